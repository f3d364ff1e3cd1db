"""Scanned sheets drawn at random (:mod:`hamta.bench.random_sheets`), georeferenced by their printed grid:
``hamta bench --methods auto --families scanned-random`` (held-out seeds 1000-1099) or ``scanned-random-tune``
(seeds 0-99, the ones the grid reader's constants were chosen on).

Each sheet is run as a user runs it (:func:`hamta.core.run`, method 'grid', no reference, the CRS of the printed
coordinates given): with 2 hints on crossings placed within 3 px (sheets with a printed grid), and with none
(the labels read). Right within 2 scan px over every crossing on the sheet (exact truth); a verified result
beyond that, or on a sheet with no grid, is a confident wrong answer.
"""
from __future__ import annotations

import os
import time

import numpy as np

from ..study import Study

HELD_OUT = range(1000, 1100)
TUNE = range(0, 100)
HINTS = (2, 0)
RIGHT_PX = 2.0


def _units(seeds):
    def units(config):
        chosen = list(seeds)[:4] if config.quick else seeds
        return [("random", str(seed), k, seed) for seed in chosen for k in HINTS]

    return units


def run_unit(unit, config) -> list:
    from ...core import run
    from ...core.errors import HamtaError
    from ...core.options import OutputOptions
    from ..memory import PeakRss
    from ..random_sheets import render_random

    _, _, k, seed = unit
    folder = os.path.join(config.out_dir, "cases", "scanned-random", f"{seed}-{k}")
    os.makedirs(folder, exist_ok=True)
    sheet = render_random(seed, folder, config.data_dir)
    spec = sheet.spec
    nodes = sheet.nodes()
    row = {"kind": "random", "sheet": str(seed), "hints": k, "seed": seed, "style": spec.style,
           "printed": spec.sheet_crs, "labelled": bool(spec.labelled), "verdict": "skipped", "rms_px": None,
           "time_s": 0.0, "peak_mb": 0.0, "why": ""}
    hints = sheet.hints(k, seed) if k else None
    if k and (spec.style == "none" or len(nodes) < k):
        return [dict(row, why="no crossings to hint", confident_wrong=False)]
    t0 = time.perf_counter()
    with PeakRss() as peak:
        try:
            result, _ = run(sheet.path, None, None, method="grid", params={"hints": hints, "sheet_crs": spec.sheet_crs},
                            output=OutputOptions(), accept_unverified=True)
        except HamtaError as exc:
            result, row["verdict"], row["why"] = None, "refused", str(exc)[:200]
        except Exception as exc:  # a bug: counted, and the other sheets still run
            result, row["verdict"], row["why"] = None, "crashed", f"{type(exc).__name__}: {exc}"[:200]
    row["time_s"], row["peak_mb"] = time.perf_counter() - t0, peak.peak
    if result is not None:
        row["verdict"] = result.verification.verdict
        row["why"] = "; ".join(result.verification.reasons)[:200]
        row["rms_px"] = _rms(result, spec.sheet_crs, nodes, sheet.to_scan(nodes)) if len(nodes) else None
    row["confident_wrong"] = row["verdict"] == "verified" and (row["rms_px"] is None or row["rms_px"] > RIGHT_PX)
    return [row]


def _rms(result, printed_crs, nodes, truth_px) -> float:
    """RMS (scan px) of every crossing from where ``result``'s model puts its printed coordinates."""
    from pyproj import CRS, Transformer

    from ...core.estimation.inverse import invert_model

    to_map = Transformer.from_crs(CRS.from_user_input(printed_crs), CRS.from_user_input(result.reference.crs.to_wkt()),
                                  always_xy=True)
    xy = np.column_stack(to_map.transform(nodes[:, 0], nodes[:, 1]))
    frame_px = np.column_stack((~result.reference.transform) * (xy[:, 0], xy[:, 1]))
    got, _ = invert_model(result.model, frame_px, (result.target.width, result.target.height))
    return float(np.sqrt(np.nanmean(np.sum((got - truth_px) ** 2, axis=1))))


def tables(rows) -> list:
    out = []
    for k, title in ((2, "2 hints on crossings within 3 px"), (0, "no hints: the labels read")):
        body = []
        for style in sorted({r["style"] for r in rows if r["hints"] == k}):
            mine = [r for r in rows if r["hints"] == k and r["style"] == style and r["verdict"] != "skipped"]
            if not mine:
                continue
            right = [r for r in mine if r["verdict"] == "verified" and not r["confident_wrong"]]
            rms = [r["rms_px"] for r in right]
            body.append([style, len(mine), sum(r["labelled"] for r in mine), len(right),
                         sum(r["confident_wrong"] for r in mine), sum(r["verdict"] == "refused" for r in mine),
                         sum(r["verdict"] not in ("verified", "refused", "crashed") for r in mine),
                         sum(r["verdict"] == "crashed" for r in mine),
                         "–" if not rms else f"{np.median(rms):.2f}",
                         f"{np.median([r['time_s'] for r in mine]):.1f}", f"{max(r['time_s'] for r in mine):.0f}",
                         f"{max(r['peak_mb'] for r in mine):.0f}"])
        if body:
            out.append({"title": f"scanned, random sheets: {title}", "rows": body,
                        "columns": ["grid printed as", "sheets", "labelled", "verified right", "confident wrong",
                                    "refused", "suspect/unverified", "crashed", "median RMS px", "median s", "max s",
                                    "max peak MB"],
                        "note": "RMS over every crossing on the sheet (exact truth), scan px; right within 2 px."})
    odd = [r for r in rows if r.get("confident_wrong") or r["verdict"] in ("suspect", "failed", "crashed")]
    if odd:
        out.append({"title": "scanned, random sheets: every confident wrong, suspect, not verified or crashed run",
                    "columns": ["seed", "hints", "grid printed as", "printed in", "verdict", "RMS px", "why"],
                    "rows": [[r["seed"], r["hints"], r["style"], r["printed"], r["verdict"],
                              "–" if r["rms_px"] is None else f"{r['rms_px']:.2f}", r["why"][:120]]
                             for r in sorted(odd, key=lambda r: (r["seed"], r["hints"]))],
                    "note": "hamta.bench.random_sheets.render_random(seed, ...) draws the sheet again."})
    return out


STUDY = Study("scanned-random", ("auto",), ("scanned-random",), _units(HELD_OUT), run_unit, tables)
TUNE_STUDY = Study("scanned-random-tune", ("auto",), ("scanned-random-tune",), _units(TUNE), run_unit, tables)
