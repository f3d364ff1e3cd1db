"""Writing the warped output against ``gdalwarp``, and the fixed cost of one run (issue 15's goals).

Not a paper's evaluation but measured the same way: ``hamta bench --families writing``. One case: a
16.5 Mpx RGB target (a rotated, shifted crop of a generated scene, no georeferencing) registered onto
a georeferenced reference with SIFT (not timed); then, in the same process and one after the other,
Hamta's writer (:func:`hamta.core.outputs.warp.write_warped`) and the ``gdalwarp`` program warp the
same model VRT onto the same grid with the same creation options (tiled, DEFLATE) — ``gdalwarp``
single-threaded (its default) and with ``-multi -wo NUM_THREADS`` as Hamta's warp uses. Peak memory:
Hamta's is the process's high-water mark during the write (with the engine loaded); ``gdalwarp``'s
is its own, measured by spawning it from a small process. The fixed cost: ``hamta register
--method sift`` on the demo pair (760 x 700 px target) as a fresh process, wall time minus its reading and matching.
"""
from __future__ import annotations

import json
import math
import os
import shutil
import subprocess
import sys
import time

import numpy as np

from ..memory import PeakRss, measured
from ..study import Study

TARGET_SIDE = 4064  # 16.5 Mpx


def units(config):
    """The two output formats Hamta's writer is timed in, and the fixed cost."""
    return ["gtiff", "cog", "fixed-cost"]


def _pair(folder: str):
    """A 16.5 Mpx target (rotated 7 degrees, shifted) and its reference (10 m UTM grid)."""
    import cv2
    import rasterio
    from affine import Affine

    from ..synthetic import make_landscape

    target, reference = os.path.join(folder, "writing_target.tif"), os.path.join(folder, "writing_reference.tif")
    if os.path.exists(target):
        return target, reference
    side = TARGET_SIDE + 400
    scene = make_landscape((side, side), seed=11)
    tr = Affine(10.0, 0, 500000.0, 0, -10.0, 4000000.0)
    with rasterio.open(reference, "w", driver="GTiff", width=side, height=side, count=3, dtype="uint8",
                       crs="EPSG:32639", transform=tr, tiled=True, compress="deflate") as dst:
        dst.write(scene)
    rot = cv2.getRotationMatrix2D((side / 2.0, side / 2.0), 7.0, 1.0)
    rot[:, 2] += (31.0, -17.0)
    turned = np.stack([cv2.warpAffine(b, rot, (side, side), flags=cv2.INTER_LINEAR) for b in scene])
    crop = turned[:, 200:200 + TARGET_SIDE, 200:200 + TARGET_SIDE]
    with rasterio.open(target, "w", driver="GTiff", width=TARGET_SIDE, height=TARGET_SIDE, count=3, dtype="uint8",
                       tiled=True, compress="deflate") as dst:
        dst.write(crop)
    return target, reference


def _writing(unit: str, folder: str) -> list:
    """Rows for the format ``unit`` ('gtiff' or 'cog'): Hamta's writer, then ``gdalwarp`` single- and
    multi-threaded, on the same model VRT: seconds and peak MB; Hamta's row also its ratios to the best."""
    from ...core import OutputOptions, RegisterOptions, register
    from ...core.outputs.model_vrt import write_model_vrt
    from ...core.outputs.warp import GTIFF_OPTIONS, THREADS, output_grid, write_warped

    target, reference = _pair(folder)
    result = register(target, reference, method="sift", options=RegisterOptions(model="affine"))
    out = os.path.join(folder, f"hamta.{unit}.tif")
    with PeakRss() as mem:
        t0 = time.perf_counter()
        write_warped(out, result, OutputOptions(format=unit))
        ours = time.perf_counter() - t0
    vrt = os.path.join(folder, "model.vrt")
    write_model_vrt(vrt, result)
    transform, width, height, crs = output_grid(result)
    extent = [transform.c, transform.f + height * transform.e, transform.c + width * transform.a, transform.f]
    creation = ["COMPRESS=DEFLATE"] if unit == "cog" else [f"{k}={v}" for k, v in GTIFF_OPTIONS.items()]
    cmd = ["gdalwarp", "-q", "-overwrite", "-r", "bilinear", "-te", *map(repr, extent), "-ts", str(width),
           str(height), "-t_srs", crs.to_wkt(), "-dstalpha", "-of", "COG" if unit == "cog" else "GTiff"]
    cmd += [a for c in creation for a in ("-co", c)]
    rows = []
    for label, extra in (("gdalwarp", []), (f"gdalwarp -multi ({THREADS} threads)",
                                            ["-multi", "-wo", f"NUM_THREADS={THREADS}"])):
        seconds, peak, code = measured(cmd + extra + [vrt, os.path.join(folder, f"gdal.{unit}.tif")])
        rows.append({"unit": unit, "writer": label, "time_s": seconds, "peak_mb": peak, "ok": code == 0})
    fastest = min(r["time_s"] for r in rows)
    leanest = min(r["peak_mb"] for r in rows)
    rows.insert(0, {"unit": unit, "writer": "hamta", "time_s": ours, "peak_mb": mem.peak, "ok": True,
                    "time_ratio": ours / fastest, "memory_ratio": mem.peak / leanest, "pixels": width * height})
    return rows


def _fixed_cost(folder: str) -> list:
    """Rows of three fresh ``hamta register --method sift`` runs on the demo pair: wall seconds, of which
    reading and matching, and the rest (the fixed cost)."""
    from ..sample import make_demo_pair

    pair = make_demo_pair(os.path.join(folder, "small"))
    beside = os.path.join(os.path.dirname(sys.executable), "hamta")  # this environment's command, not another one
    hamta = beside if os.path.exists(beside) else shutil.which("hamta")
    rows = []
    for i in range(3):
        out = os.path.join(folder, f"small-out-{i}")
        t0 = time.perf_counter()
        subprocess.run([hamta, "register", "--reference", pair["reference"], "--target", pair["target"], "--out", out,
                        "--method", "sift", "--quiet"], check=True, capture_output=True)
        wall = time.perf_counter() - t0
        with open(os.path.join(out, "report.json")) as f:
            timings = json.load(f)["timings_s"]
        work = timings.get("read", 0) + timings.get("open", 0) + timings.get("match", 0)
        rows.append({"unit": "fixed-cost", "writer": f"run {i + 1}", "time_s": wall, "reading_matching_s": work,
                     "fixed_s": wall - work})
    return rows


def run_unit(unit, config) -> list:
    folder = os.path.join(config.out_dir, "cases", "writing")
    os.makedirs(folder, exist_ok=True)
    return _fixed_cost(folder) if unit == "fixed-cost" else _writing(unit, folder)


def tables(rows) -> list:
    def fmt(v, digits=2):
        return "–" if v is None or (isinstance(v, float) and not math.isfinite(v)) else f"{v:.{digits}f}"

    body = [[r["unit"], r["writer"], fmt(r["time_s"]), fmt(r["peak_mb"], 0), fmt(r.get("time_ratio")),
             fmt(r.get("memory_ratio"))] for r in rows if r["unit"] != "fixed-cost"]
    fixed = [[r["writer"], fmt(r["time_s"]), fmt(r["reading_matching_s"]), fmt(r["fixed_s"])]
             for r in rows if r["unit"] == "fixed-cost"]
    return [{"title": f"writing the warped output ({TARGET_SIDE} x {TARGET_SIDE} RGB target, 16.5 Mpx): hamta vs "
                      "gdalwarp, same model VRT, grid and creation options",
             "columns": ["format", "writer", "time s", "peak MB", "time / fastest gdalwarp",
                         "memory / leanest gdalwarp"], "rows": body,
             "note": "Goal: time <= 1.5x and memory <= 2x gdalwarp's. Hamta's peak is its whole process during the "
                     "write (engine loaded, registration done); gdalwarp's is its own process. gdalwarp writes an "
                     "alpha band (-dstalpha) as Hamta does for uint8 data without nodata."},
            {"title": "fixed cost of one run: 'hamta register --method sift' on the demo pair (760 x 700 target), "
                      "fresh process",
             "columns": ["run", "wall s", "reading + matching s", "fixed s (start-up, fit, verify, outputs)"],
             "rows": fixed, "note": "Goal: fixed cost <= 1 s."}]


STUDY = Study("writing", ("sift",), ("writing",), units, run_unit, tables)
