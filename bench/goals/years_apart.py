"""Co-registering dates years apart (issue 37): ``hamta bench --families years-apart``.

Real imagery of several dates (``timeseries/``: NAIP orthophotos of North Dakota farmland, 2009-2016, 5 m;
Landsat over Pucallpa, 1990 and 2005, about 90 m). A target is one date's file with its georeferencing moved
by 20-30 px (the pixels untouched), registered onto another date's file; the truth is the file's own
georeferencing. The error is the RMS distance, in reference px, between where the model and the truth put a
20 x 20 grid of target points; the mean offset says in which direction. Each product's georeferencing is the
producer's, good to a fraction of a pixel between dates of one sensor (about 0.4 px on NAIP 2015 against
2009, docs/benchmarks.md), which limits what the error can show.

Goal: every answer verified and within 0.5 px of the truth.
"""
from __future__ import annotations

import os
import time

import numpy as np

from ..study import Study
from ..tables import cell
from .basemap_real import FOLDER

PAIRS = (  # target date, reference date, the target's georeferencing moved by (x, y) target px
    ("naip_20090818.tif", "naip_20160816.tif", (23, -27)),
    ("naip_20100629.tif", "naip_20150926.tif", (-25, 21)),
    ("naip_20140720.tif", "naip_20100629.tif", (28, 20)),
    ("naip_20150926.tif", "naip_20090818.tif", (-21, -29)),
    ("naip_20160816.tif", "naip_20140720.tif", (30, -22)),
    ("landsat_1990.tif", "landsat_2005.tif", (-24, 26)),
    ("landsat_2005.tif", "landsat_1990.tif", (27, 22)),
)
GOAL_PX = 0.5
GRID = 20


def available(data_dir: str) -> bool:
    return all(os.path.exists(os.path.join(data_dir, FOLDER, f)) for t, r, _ in PAIRS for f in (t, r))


def units(config):
    """(pair index, method) for each case (pairs 3 and 5 with ``--quick``)."""
    methods = [m for m in config.methods if "[" not in m] or ["auto"]
    pairs = range(len(PAIRS)) if not config.quick else (3, 5)
    return [(i, m) for i in pairs for m in methods]


def moved_target(i: int, data_dir: str, folder: str) -> str:
    """Pair ``i``'s target date in ``folder``: the file copied byte for byte, then its geotransform moved by the
    pair's offset (band descriptions, colour interpretation and tags as the producer wrote them, so that Hamta
    reads it as it reads the original)."""
    import shutil

    import rasterio
    from affine import Affine

    name, _, (dx, dy) = PAIRS[i]
    path = os.path.join(folder, f"moved_{dx:+d}_{dy:+d}_{name}")
    if not os.path.exists(path):
        os.makedirs(folder, exist_ok=True)
        part = f"{path}.{os.getpid()}.part"  # units of one pair may run side by side
        shutil.copyfile(os.path.join(data_dir, FOLDER, name), part)
        with rasterio.open(part, "r+", IGNORE_COG_LAYOUT_BREAK="YES") as dst:
            dst.transform = dst.transform * Affine.translation(dx, dy)
        os.replace(part, path)
    return path


def truth_points(target: str, reference: str, n: int = GRID):
    """(target px (n * n, 2), reference px (n * n, 2)): an ``n`` x ``n`` grid over the target file ``target``
    (with its own georeferencing) and where that georeferencing puts it on ``reference`` (same CRS)."""
    import rasterio

    with rasterio.open(target) as t, rasterio.open(reference) as r:
        width, height, to_map, from_map = t.width, t.height, t.transform, ~r.transform
    gx, gy = np.meshgrid((np.arange(n) + 0.5) * width / n, (np.arange(n) + 0.5) * height / n)
    pts = np.column_stack([gx.ravel(), gy.ravel()])
    return pts, np.column_stack(from_map * (to_map * (pts[:, 0], pts[:, 1])))


def run_unit(unit, config) -> list:
    """One row: the pair's moved target registered onto the other date: verdict, RMS error and mean offset
    in reference px against the file's own georeferencing, and the check's bound."""
    from ...core import RegisterOptions, run
    from ...core.errors import HamtaError
    from ..memory import PeakRss

    i, method = unit
    name, reference_name, move = PAIRS[i]
    case = f"{os.path.splitext(name)[0]}-onto-{os.path.splitext(reference_name)[0].split('_')[-1]}"
    reference = os.path.join(config.data_dir, FOLDER, reference_name)
    target = moved_target(i, config.data_dir, os.path.join(config.out_dir, "cases", "years-apart"))
    pts, truth = truth_points(os.path.join(config.data_dir, FOLDER, name), reference)
    row = {"case": case, "method": method, "moved_px": list(move)}
    t0 = time.perf_counter()
    result, failure = None, None
    with PeakRss() as peak:
        try:
            result, _ = run(target, reference, None, method=method, options=RegisterOptions(),
                            accept_unverified=True)
        except Exception as exc:  # a HamtaError is an honest failure (no model); anything else a bug
            failure = "no model" if isinstance(exc, HamtaError) else "crash"
            row["error"] = f"{type(exc).__name__}: {exc}"
    row.update(time_s=time.perf_counter() - t0, peak_mb=peak.peak)
    if result is None:
        return [dict(row, method_used=None, verdict=failure, rms_px=None, offset_px=None, bound_px=None)]
    off = result.model.apply(pts) - truth
    return [dict(row, method_used=result.method, verdict=result.verification.verdict,
                 rms_px=float(np.sqrt(np.mean(np.sum(off ** 2, axis=1)))), offset_px=off.mean(axis=0).tolist(),
                 bound_px=result.verification.error_bound_px)]


def tables(rows) -> list:
    body, met = [], {}
    for r in sorted(rows, key=lambda r: (r["case"], r["method"])):
        within = r["verdict"] == "verified" and r["rms_px"] is not None and r["rms_px"] <= GOAL_PX
        done, n = met.get(r["method"], (0, 0))
        met[r["method"]] = (done + within, n + 1)
        body.append([r["case"], r["method"], "{:+d}, {:+d}".format(*r["moved_px"]), r["method_used"] or "–",
                     r["verdict"], cell(r["rms_px"], ".2f"),
                     "–" if r["offset_px"] is None else "{:+.2f}, {:+.2f}".format(*r["offset_px"]),
                     cell(r["bound_px"], ".2f"), "yes" if within else "no", f"{r['time_s']:.1f}",
                     f"{r['peak_mb']:.0f}"])
    counts = "; ".join(f"{m} {done} of {n}" for m, (done, n) in sorted(met.items()))
    return [{"title": f"years-apart: one date's file, its georeferencing moved, onto another date; verified within "
                      f"{GOAL_PX:g} px: {counts}",
             "columns": ["case", "method", "moved px", "via", "verdict", "err rms px", "mean offset px", "bound px",
                         f"<= {GOAL_PX:g} px", "time s", "peak MB"], "rows": body,
             "note": "Error: RMS over a 20 x 20 grid of target points against the file's own georeferencing, in "
                     "reference px; mean offset: (x, y), x right, y down; bound: the check's bound on the error. Goal "
                     "(issue 37): every answer verified and within 0.5 px. The products' own georeferencing agrees "
                     "between dates to a fraction of a pixel only."}]


STUDY = Study("years-apart", ("auto",), ("years-apart",), units, run_unit, tables)
