"""The benchmark's summary: per family and method, and the tables ``hamta bench`` prints and writes."""
from __future__ import annotations

import math
from typing import Dict, List, Sequence

from .stats import median, p90

BASELINE = "sift"


def summarise(rows: List[dict], methods: Sequence[str]) -> Dict[str, Dict[str, dict]]:
    """Per family and method: success rate, median/p90 check-point RMSE of successes, median NCM,
    precision, time, peak memory, and the median per-case time ratio to the SIFT baseline."""
    out: Dict[str, Dict[str, dict]] = {}
    baseline = {(r["family"], r["case"]): r["time_s"] for r in rows if r["method"] == BASELINE}
    difficulty = {(r["family"], r["case"]): ((r["rmse_cp"] or 0.0) if r["success"] else float("inf"))
                  for r in rows if r["method"] == BASELINE}
    for fam in dict.fromkeys(r["family"] for r in rows):
        out[fam] = {}
        for m in methods:
            rs = [r for r in rows if r["family"] == fam and r["method"] == m]
            if not rs:
                continue
            ok = [r for r in rs if r["success"]]
            ratios = [r["time_s"] / baseline[(fam, r["case"])] for r in rs
                      if baseline.get((fam, r["case"])) and m != BASELINE]
            cases = sorted({r["case"] for r in rs}, key=lambda c: difficulty.get((fam, c), 0.0), reverse=True)
            hard = set(cases[: int(math.ceil(len(cases) / 3))])
            hard_rows = [r for r in rs if r["case"] in hard]
            out[fam][m] = {
                "n_cases": len(rs), "n_success": len(ok), "success_rate": len(ok) / len(rs),
                "hardest_third_success": sum(r["success"] for r in hard_rows) / max(len(hard_rows), 1),
                "median_rmse_cp": median([r["rmse_cp"] for r in ok]), "p90_rmse_cp": p90([r["rmse_cp"] for r in ok]),
                "median_ncm": median([r["ncm"] for r in rs]),
                "median_precision": median([r["precision"] for r in rs]),
                "median_time_s": median([r["time_s"] for r in rs]),
                "time_ratio_to_sift": 1.0 if m == BASELINE else median(ratios),
                "median_peak_rss_mb": median([r["peak_rss_mb"] for r in rs]),
                "n_verified_right": sum(bool(r.get("verified")) and r["success"] for r in rs),
                "n_false_verified": sum(bool(r.get("false_verified")) for r in rs),
                "n_false_flagged": sum(bool(r.get("false_flagged")) for r in rs),
                "n_crashed": sum(bool(r.get("crashed")) for r in rs),
                **bound_coverage(rs),
            }
    return out


def bound_coverage(rows: List[dict]) -> dict:
    """Of the verified results with an error bound and a measured error, how many bounds cover the true
    error (the check-point RMSE): the share should be at least 95 %."""
    bounded = [r for r in rows if r.get("verified") and r.get("rmse_cp") is not None
               and (r.get("quality") or {}).get("error_bound_px") is not None]
    covered = sum(r["quality"]["error_bound_px"] >= r["rmse_cp"] for r in bounded)
    return {"n_bounded": len(bounded), "n_bound_covers": covered,
            "bound_coverage": covered / len(bounded) if bounded else None}


COLUMNS = [("method", "method"), ("success", "success"), ("verified", "right+verified"),
           ("false_verified", "wrong verified"), ("false_flagged", "right flagged"), ("coverage", "bound covers"),
           ("crashed", "crashes"),
           ("hard", "hard 1/3"), ("median_rmse_cp", "RMSE_cp med"), ("p90_rmse_cp", "RMSE_cp p90"),
           ("median_ncm", "NCM med"), ("median_precision", "precision med"), ("median_time_s", "time med (s)"),
           ("time_ratio_to_sift", "time / SIFT"), ("median_peak_rss_mb", "peak MB")]


def _cells(method: str, s: dict) -> List[str]:
    def num(v, fmt):
        return "–" if v is None or (isinstance(v, float) and math.isnan(v)) else format(v, fmt)

    return [method, f"{s['n_success']}/{s['n_cases']} ({100 * s['success_rate']:.0f}%)",
            f"{s.get('n_verified_right', 0)}", f"{s.get('n_false_verified', 0)}", f"{s.get('n_false_flagged', 0)}",
            "–" if not s.get("n_bounded") else f"{s['n_bound_covers']}/{s['n_bounded']}", f"{s.get('n_crashed', 0)}",
            f"{100 * s.get('hardest_third_success', 0):.0f}%", num(s["median_rmse_cp"], ".3f"),
            num(s["p90_rmse_cp"], ".3f"), num(s["median_ncm"], ".0f"),
            num(s["median_precision"], ".2f"), num(s["median_time_s"], ".2f"), num(s["time_ratio_to_sift"], ".2f"),
            num(s["median_peak_rss_mb"], ".0f")]


def _aligned(rows) -> List[str]:
    """Rows of cells as text lines: first column left-aligned, the others right-aligned, a rule under the header."""
    rows = [[str(c) for c in r] for r in rows]
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    lines = ["  ".join(c.ljust(w) if j == 0 else c.rjust(w) for j, (c, w) in enumerate(zip(r, widths))) for r in rows]
    return lines[:1] + ["  ".join("-" * w for w in widths)] + lines[1:]


def text_tables(report: dict) -> str:
    """The summary as aligned plain-text tables, one per family."""
    lines = []
    for fam, per_method in report["summary"].items():
        n = next(iter(per_method.values()))["n_cases"]
        lines.append(f"\n{fam} ({n} case{'s' if n != 1 else ''})")
        lines.extend(_aligned([[h for _, h in COLUMNS]] + [_cells(m, s) for m, s in per_method.items()]))
    for table in report.get("reproductions", []):
        lines.append(f"\n{table['title']}")
        lines.extend(_aligned([table["columns"]] + [[_fmt_cell(v) for v in r] for r in table["rows"]]))
        if table.get("note"):
            lines.append(f"  ({table['note']})")
    meta = report["meta"]
    lines.append(f"\n{sum(len(v) for v in report['summary'].values())} method/family cells, "
                 f"{len(report['cases'])} registrations in {meta['duration_s']} s")
    lines.extend(f"note: {n}" for n in meta["notes"])
    return "\n".join(lines)


def markdown(report: dict) -> str:
    """The summary as Markdown (one table per family) with the run's settings."""
    meta = report["meta"]
    cfg = meta["config"]
    out = [f"# hamta bench — {meta['date']}", "",
           f"size {cfg['size']} px, quick={cfg['quick']}, jobs={cfg['jobs']}, methods: {', '.join(cfg['methods'])}; "
           f"{len(report['cases'])} registrations in {meta['duration_s']} s on {meta['machine']['cpus']} CPUs; "
           f"hamta {meta['versions']['hamta']}, OpenCV {meta['versions']['opencv']}, GDAL {meta['versions']['gdal']}.",
           "", "Success: the returned mapping's check-point RMSE ≤ 3 px (real pairs and the multimodal set: their "
           "own tolerance; should-fail cases: no verified result). right+verified: successes that the independent "
           "check also verified (what a user gets by default); wrong verified: confident wrong answers (verified "
           "beyond the tolerance; the goal is 0); right flagged: successes left unverified; bound covers: verified "
           "results whose error bound is at least their check-point RMSE (the goal is 95 %; on the multimodal set "
           "the truth itself is off by a few px); crashes: runs ended "
           "by an internal error (a bug in a method, never a success; the goal is 0). RMSE_cp statistics are "
           "over successful cases only. NCM: returned matches within 3 px of the truth. time / SIFT: median "
           "per-case ratio to the SIFT baseline in the same run. hard 1/3: success on the third of the family's "
           "cases where SIFT's error is largest.", ""]
    out.extend(f"> {n}" for n in meta["notes"])
    for fam, per_method in report["summary"].items():
        n = next(iter(per_method.values()))["n_cases"]
        out += ["", f"## {fam} ({n} case{'s' if n != 1 else ''})", "",
                "| " + " | ".join(h for _, h in COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
        out += ["| " + " | ".join(_cells(m, s)) + " |" for m, s in per_method.items()]
    for table in report.get("reproductions", []):
        out += ["", f"## {table['title']}", "", "| " + " | ".join(table["columns"]) + " |",
                "|" + "---|" * len(table["columns"])]
        out += ["| " + " | ".join(_fmt_cell(v) for v in r) + " |" for r in table["rows"]]
        if table.get("note"):
            out += ["", table["note"]]
    return "\n".join(out) + "\n"


def cell(value, fmt: str) -> str:
    """``value`` formatted with ``fmt`` for a table, '–' for None."""
    return "–" if value is None else format(value, fmt)


def _fmt_cell(v) -> str:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "–"
    if isinstance(v, float):
        return f"{v:.3f}" if abs(v) < 100 else f"{v:.0f}"
    return str(v)
