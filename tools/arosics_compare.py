"""Hamta's local correction against AROSICS's local co-registration on the same non-rigid cases.

Usage: python tools/arosics_compare.py OUT_DIR   (needs arosics importable; see docs/benchmarks.md)

AROSICS corrects shifts only (no rotation or scale), so these cases are its use case: a target on
the reference's own grid and georeferencing whose content is displaced by a constant shift plus a
smooth terrain-like field (and, in one case, two block patches) — the ``nonrigid`` family's field
(:mod:`hamta.bench.nonrigid`) without its global similarity. Both get the same window size (96 px)
and about the same grid spacing (32 px for AROSICS's ``grid_res``, Hamta's automatic spacing). The
error of each result is measured at the same dense check points: Hamta's returned model; for
AROSICS, a thin plate spline through the tie points it keeps (``to_GCPList``), which is what it
hands GDAL to warp with.
"""
from __future__ import annotations

import os
import sys
import time

import numpy as np

from hamta.bench.cases import Case, grid_inside, write_raster
from hamta.bench.families import default_data_dir, load_source
from hamta.bench.nonrigid import Field
from hamta.core import RegisterOptions, register
from hamta.core.coords import map_to_pixel
from hamta.core.estimation.models import ThinPlateSplineModel

CASES = (("landsat", 3.0, 0), ("multitemporal", 3.0, 0), ("landscape", 4.0, 0), ("landscape", 4.0, 2))
SHIFT = np.array([2.3, -1.7])


def make_case(folder: str, source: str, amplitude: float, patches: int, seed: int) -> Case:
    import cv2

    canvas = load_source(source, 1024, default_data_dir())
    h, w = canvas.shape
    field = Field((h, w), np.random.default_rng(seed), amplitude, patches)

    def truth(p):
        q = np.asarray(p, float).reshape(-1, 2) + SHIFT
        return q + field(q)

    gx, gy = np.meshgrid(np.arange(w) + 0.5, np.arange(h) + 0.5)
    where = truth(np.column_stack([gx.ravel(), gy.ravel()])).reshape(h, w, 2) - 0.5
    mx, my = where[..., 0].astype(np.float32), where[..., 1].astype(np.float32)
    tgt = np.stack([cv2.remap(b, mx, my, cv2.INTER_CUBIC, borderMode=cv2.BORDER_CONSTANT) for b in canvas.data])
    valid = cv2.remap(canvas.valid.astype(np.float32), mx, my, cv2.INTER_LINEAR) > 0.999
    name = f"{source}_{amplitude:g}px_{patches}patches"
    reference = write_raster(os.path.join(folder, f"{name}_reference.tif"), canvas.data, canvas.valid, canvas.dtype,
                             canvas.crs, canvas.transform)
    target = write_raster(os.path.join(folder, f"{name}_target.tif"), tgt, valid, canvas.dtype, canvas.crs,
                          canvas.transform)
    return Case(name, target, reference, truth, grid_inside((h, w), truth, canvas.valid, valid, n=40))


def _gdal_shim() -> None:
    """AROSICS's helpers use GDAL 3.7-3.8 Python API (``with`` on datasets, ``gdal.config_options``);
    Debian bookworm has 3.6. Add those to 3.6's bindings, in this process only."""
    from hamta.bench.goals.speed import GDAL_SHIM

    exec(GDAL_SHIM, {})


def _skimage_shim() -> None:
    """AROSICS calls ``skimage.measure.ransac(..., rng=)`` (scikit-image 0.20+); Debian's 0.19 names it
    ``random_state``."""
    import inspect

    import skimage.measure

    if "rng" in inspect.signature(skimage.measure.ransac).parameters:
        return
    original = skimage.measure.ransac

    def ransac(*args, rng=None, **kwargs):
        return original(*args, random_state=rng, **kwargs)

    skimage.measure.ransac = ransac
    import arosics.Tie_Point_Grid as grid

    grid.ransac = ransac


def arosics_model(case: Case, folder: str):
    _gdal_shim()
    _skimage_shim()
    from arosics import COREG_LOCAL

    out = os.path.join(folder, f"{case.name}_arosics.tif")
    cr = COREG_LOCAL(case.reference, case.target, grid_res=32, window_size=(96, 96), max_shift=10, path_out=out,
                     fmt_out="GTiff", CPUs=1, q=True, progress=False)
    cr.correct_shifts()
    gcps = cr.coreg_info["GCPList"]
    import rasterio

    with rasterio.open(case.reference) as ds:
        transform = ds.transform
    src = np.array([[g.GCPPixel, g.GCPLine] for g in gcps], float)
    dst = map_to_pixel(transform, np.array([[g.GCPX, g.GCPY] for g in gcps], float))
    return ThinPlateSplineModel.fit(src, dst, smoothing=0.0), len(gcps)


def rmse(case: Case, model) -> float:
    return float(np.sqrt(np.mean(case.errors(model) ** 2)))


def main(folder: str) -> int:
    os.makedirs(folder, exist_ok=True)
    print("| case | no correction | Hamta global (sift) | Hamta local | time s | AROSICS local | tie points | time s |")
    print("|---|---|---|---|---|---|---|---|")
    for i, (source, amplitude, patches) in enumerate(CASES):
        case = make_case(folder, source, amplitude, patches, seed=31 + i)
        none = float(np.sqrt(np.mean(np.sum((case.check_points - case.truth(case.check_points)) ** 2, axis=1))))
        glob = register(case.target, case.reference, method="sift")
        t0 = time.perf_counter()
        local = register(case.target, case.reference, method="sift", options=RegisterOptions(local=True))
        hamta_s = time.perf_counter() - t0
        t0 = time.perf_counter()
        try:
            aro, n = arosics_model(case, folder)
            aro_text = f"{rmse(case, aro):.3f}"
        except Exception as exc:  # report what AROSICS said, go on with the next case
            aro_text, n = f"failed ({type(exc).__name__}: {exc})"[:80], 0
        aro_s = time.perf_counter() - t0
        print(f"| {case.name} | {none:.3f} | {rmse(case, glob.model):.3f} | {rmse(case, local.model):.3f} | "
              f"{hamta_s:.1f} | {aro_text} | {n} | {aro_s:.1f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
