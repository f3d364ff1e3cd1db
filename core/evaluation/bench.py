"""``hamta bench``: every method and baseline on the synthetic families and the real pairs.

Each case is generated once, then every selected method registers it through the public
``register`` entry point (the one the CLI and Processing call) in the same worker process, one
after the other, so per-case time ratios to the SIFT baseline compare like with like. The
returned mapping is judged against ground truth (:mod:`hamta.core.evaluation.metrics`).
"""
from __future__ import annotations

import concurrent.futures as cf
import ctypes
import datetime
import gc
import json
import math
import multiprocessing
import os
import platform
import resource
import threading
import time
from dataclasses import asdict, dataclass
from typing import Callable, Dict, List, Optional, Sequence

import numpy as np

from ..errors import HamtaError
from ..outputs.report import clean
from ..methods import all_methods
from ..pipeline import RegisterOptions, register
from .families import DEFAULT_FAMILIES, FAMILIES, CaseSpec, available, build_case, default_data_dir, family_specs
from .metrics import judge

BASELINE = "sift"


@dataclass(frozen=True)
class BenchConfig:
    """What to run. ``size`` is the reference's longest side in pixels for synthetic cases."""

    methods: Sequence[str] = ()
    families: Sequence[str] = DEFAULT_FAMILIES
    size: int = 1024
    quick: bool = False
    jobs: int = 1
    out_dir: str = "bench-output"
    data_dir: str = ""
    reproductions: bool = True

    def resolved(self) -> "BenchConfig":
        methods = [m for m in (self.methods or default_methods(self.quick)) if m != BASELINE]
        methods.insert(0, BASELINE)  # the baseline always runs, first, so ratios have a reference
        unknown = [f for f in self.families if f not in FAMILIES]
        if unknown:
            raise ValueError(f"unknown famil{'y' if len(unknown) == 1 else 'ies'} {', '.join(unknown)}; "
                             f"choose from {', '.join(FAMILIES)}")
        for m in methods:
            parse_variant(m)  # raises on unknown methods, parameters or options
        return BenchConfig(tuple(methods), tuple(self.families), self.size, self.quick, max(1, self.jobs),
                           os.path.abspath(self.out_dir), self.data_dir or default_data_dir(), self.reproductions)


QUICK_BASELINES = ("sift", "orb", "phasecorr")


def default_methods(quick: bool) -> list:
    """Every method; for a quick run the product methods and the generic baselines only (the
    faithful versions and the papers' own baselines belong to full runs)."""
    return [name for name, m in all_methods().items()
            if not quick or m.kind == "method" or name in QUICK_BASELINES]


def parse_variant(text: str):
    """``name`` or ``name[key=value,...]`` -> (method name, method params, RegisterOptions fields).

    Keys are the method's parameters or, failing that, fields of RegisterOptions (e.g.
    ``ransac_threshold_px``); a variant is benchmarked as its own row.
    """
    import dataclasses

    name, _, rest = text.partition("[")
    if name not in all_methods():
        raise ValueError(f"unknown method {name!r}; available: {', '.join(all_methods())}")
    params, options = {}, {}
    option_fields = {f.name for f in dataclasses.fields(RegisterOptions)}
    method_fields = {f.name for f in dataclasses.fields(all_methods()[name].params_type)}
    for item in filter(None, rest.rstrip("]").split(",")):
        key, _, value = item.partition("=")
        key = key.strip()
        if key in method_fields:
            params[key] = value.strip()
        elif key in option_fields:
            options[key] = _number_or_text(value.strip())
        else:
            raise ValueError(f"{key!r} is neither a parameter of {name!r} nor a registration option")
    all_methods()[name].make_params(params)
    return name, params, options


def _number_or_text(text: str):
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def expand_sweep(methods: Sequence[str], sweeps: Sequence[str]) -> List[str]:
    """Every non-baseline method crossed with every ``key=v1,v2,...`` sweep value."""
    variants = [m for m in methods if m != BASELINE]
    for sweep in sweeps:
        key, _, values = sweep.partition("=")
        variants = [f"{m[:-1] + ',' if m.endswith(']') else m + '['}{key}={v}]"
                    for m in variants for v in values.split(",")]
    return [BASELINE] + variants


class _PeakRss:
    """Peak resident memory of this process during a block. Freed heap is first returned to the
    system and the kernel's high-water mark reset (Linux), so a case is not charged with what an
    earlier case in the same worker left behind; elsewhere the resident size is sampled every 5 ms."""

    def __enter__(self):
        gc.collect()
        self.exact = _reset_peak()
        self.peak = _rss_mb()
        self._stop = threading.Event()
        self._thread = None
        if not self.exact:
            self._thread = threading.Thread(target=self._sample, daemon=True)
            self._thread.start()
        return self

    def _sample(self):
        while not self._stop.wait(0.005):
            self.peak = max(self.peak, _rss_mb())

    def __exit__(self, *exc):
        self._stop.set()
        if self._thread is not None:
            self._thread.join()
        self.peak = _hwm_mb() if self.exact else max(self.peak, _rss_mb())
        return False


def _reset_peak() -> bool:
    """Trim the C heap and reset VmHWM; False where that is not possible."""
    try:
        ctypes.CDLL("libc.so.6").malloc_trim(0)
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
        return _hwm_mb() > 0
    except (OSError, AttributeError):
        return False


def _hwm_mb() -> float:
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024.0
    return 0.0


def _rss_mb() -> float:
    try:
        with open("/proc/self/statm") as f:
            return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2 ** 20
    except OSError:
        return _maxrss_mb()


def _maxrss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def run_case(spec: CaseSpec, config: BenchConfig) -> List[dict]:
    """Build one case and register it with every method; one result row per method."""
    folder = os.path.join(config.out_dir, "cases", spec.family)
    case = build_case(spec, folder, config.size, config.data_dir)
    rows = []
    for method in config.methods:
        name, params, overrides = parse_variant(method)
        options = RegisterOptions(**dict({"model": spec.model}, **overrides))
        result, error = None, None
        with _PeakRss() as mem:
            t0 = time.perf_counter()
            try:
                result = register(case.target, case.reference, name, params=params, options=options)
            except (HamtaError, ValueError, np.linalg.LinAlgError) as exc:
                error = exc
        wall = time.perf_counter() - t0
        row = {"family": spec.family, "case": spec.name, "method": method, "model": spec.model,
               "tolerance_px": case.tolerance_px, "n_check_points": int(len(case.check_points)),
               "time_s": result.timings["total"] if result is not None else wall,
               "timings_s": result.timings if result is not None else {"total": wall},
               "peak_rss_mb": round(mem.peak, 1),
               "diagnostics": result.diagnostics if result is not None else {}}
        row.update(judge(case, result, error))
        rows.append(row)
    return rows


def run_bench(config: BenchConfig, progress: Optional[Callable[[float, str], None]] = None) -> dict:
    """Run the benchmark; write ``bench.json`` and ``bench.md`` into ``config.out_dir``; return the report."""
    config = config.resolved()
    os.makedirs(config.out_dir, exist_ok=True)
    notes, specs = [], []
    for fam in config.families:
        if not available(fam, config.data_dir):
            notes.append(f"family '{fam}' skipped: no development data at {config.data_dir}")
            continue
        specs.extend(family_specs(fam, config.quick))
    t0 = time.perf_counter()
    rows: List[dict] = []
    done = 0
    for batch in _execute(specs, config):
        rows.extend(batch)
        done += 1
        if progress:
            progress(done / max(len(specs), 1), f"{done}/{len(specs)} cases")
    rows.sort(key=lambda r: (FAMILIES.index(r["family"]), r["case"], list(config.methods).index(r["method"])))
    reproductions = run_reproductions(config, rows, progress) if config.reproductions else []
    report = {
        "meta": {"date": datetime.datetime.now().isoformat(timespec="seconds"), "duration_s": round(
            time.perf_counter() - t0, 1), "config": {k: list(v) if isinstance(v, tuple) else v
                                                    for k, v in asdict(config).items()},
                 "machine": {"cpus": os.cpu_count(), "platform": platform.platform()}, "versions": _versions(),
                 "notes": notes},
        "summary": summarise(rows, config.methods),
        "reproductions": reproductions,
        "cases": rows,
    }
    with open(os.path.join(config.out_dir, "bench.json"), "w") as f:
        json.dump(clean(report), f, indent=1, allow_nan=False)
    with open(os.path.join(config.out_dir, "bench.md"), "w") as f:
        f.write(markdown(report))
    return report


def run_reproductions(config: BenchConfig, bench_rows: List[dict], progress=None) -> list:
    """Each paper's own evaluation whose method is benchmarked and whose families are selected.
    A reproduction without units of its own is computed from the benchmark's rows."""
    from .reproductions import all_reproductions

    tables = []
    names = {parse_variant(m)[0] for m in config.methods}
    for rep in all_reproductions():
        if not set(rep.methods) & names or not set(rep.families) & set(config.families):
            continue
        if rep.units is None:
            rows = [r for r in bench_rows if r["family"] in rep.families]
            if rows:
                tables.extend(rep.tables(rows))
            continue
        units = rep.units(config)
        rows = []
        for i, unit_rows in enumerate(_map(_run_unit, [(rep.name, u, config) for u in units], config)):
            rows.extend(unit_rows)
            if progress:
                progress((i + 1) / len(units), f"reproducing {rep.name}: {i + 1}/{len(units)}")
        if rows:
            tables.extend(rep.tables(rows))
    return tables


def _run_unit(args):
    from .reproductions import all_reproductions

    name, unit, config = args
    return next(r for r in all_reproductions() if r.name == name).run_unit(unit, config)


def _pool(jobs: int):
    method = "fork" if "fork" in multiprocessing.get_all_start_methods() else "spawn"
    return cf.ProcessPoolExecutor(jobs, mp_context=multiprocessing.get_context(method))


def _map(fn, items, config):
    """``fn`` over ``items`` in the order given, in the worker pool when ``config.jobs`` > 1."""
    if config.jobs <= 1 or len(items) <= 1:
        yield from map(fn, items)
        return
    with _pool(config.jobs) as pool:
        yield from pool.map(fn, items)


def _versions() -> dict:
    from ..result import versions

    return versions()


def _execute(specs, config):
    if config.jobs <= 1 or len(specs) <= 1:
        for spec in specs:
            yield run_case(spec, config)
        return
    with _pool(config.jobs) as pool:
        futures = [pool.submit(run_case, spec, config) for spec in specs]
        for fut in cf.as_completed(futures):
            yield fut.result()


def median(values):
    v = [x for x in values if x is not None]
    return float(np.median(v)) if v else None


def _p90(values):
    v = [x for x in values if x is not None]
    return float(np.percentile(v, 90)) if v else None


def summarise(rows: List[dict], methods: Sequence[str]) -> Dict[str, Dict[str, dict]]:
    """Per family and method: success rate, median/p90 check-point RMSE of successes, median NCM,
    precision, time, peak memory, and the median per-case time ratio to the SIFT baseline."""
    out: Dict[str, Dict[str, dict]] = {}
    baseline = {(r["family"], r["case"]): r["time_s"] for r in rows if r["method"] == BASELINE}
    difficulty = {(r["family"], r["case"]): (r["rmse_cp"] if r["success"] else float("inf"))
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
                "median_rmse_cp": median([r["rmse_cp"] for r in ok]), "p90_rmse_cp": _p90([r["rmse_cp"] for r in ok]),
                "median_ncm": median([r["ncm"] for r in rs]),
                "median_precision": median([r["precision"] for r in rs]),
                "median_time_s": median([r["time_s"] for r in rs]),
                "time_ratio_to_sift": 1.0 if m == BASELINE else median(ratios),
                "median_peak_rss_mb": median([r["peak_rss_mb"] for r in rs]),
            }
    return out


COLUMNS = [("method", "method"), ("success", "success"), ("hard", "hard 1/3"), ("median_rmse_cp", "RMSE_cp med"),
           ("p90_rmse_cp", "RMSE_cp p90"), ("median_ncm", "NCM med"), ("median_precision", "precision med"),
           ("median_time_s", "time med (s)"), ("time_ratio_to_sift", "time / SIFT"), ("median_peak_rss_mb", "peak MB")]


def _cells(method: str, s: dict) -> List[str]:
    def num(v, fmt):
        return "–" if v is None or (isinstance(v, float) and math.isnan(v)) else format(v, fmt)

    return [method, f"{s['n_success']}/{s['n_cases']} ({100 * s['success_rate']:.0f}%)",
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
           "", "Success: check-point RMSE ≤ 3 px (real pairs: their own tolerance). RMSE_cp statistics are over "
           "successful cases only. NCM: returned matches within 3 px of the truth. time / SIFT: median per-case "
           "ratio to the SIFT baseline in the same run. hard 1/3: success on the third of the family's cases "
           "where SIFT's error is largest.", ""]
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


def _fmt_cell(v) -> str:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "–"
    if isinstance(v, float):
        return f"{v:.3f}" if abs(v) < 100 else f"{v:.0f}"
    return str(v)
