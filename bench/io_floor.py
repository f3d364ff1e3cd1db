"""The IO floor of a large case: reading both rasters once and one ``gdalwarp`` of the target.

What no registration can beat on this machine: every pixel of both files read once (in blocks), and
the target warped once onto its own north-up grid by GDAL's own program with the creation options
Hamta uses (tiled, DEFLATE) and as many threads. Hamta's time on the case, outputs included, is
quoted as a multiple of it (issue 16: within 3x).
"""
from __future__ import annotations

import os
import time
import warnings

from .memory import measured


def io_floor(case, folder: str) -> dict:
    """Seconds to read both rasters once, seconds and peak MB of one gdalwarp of the target, and their sum."""
    import rasterio
    from rasterio.errors import NotGeoreferencedWarning

    from ..core.outputs.warp import GTIFF_OPTIONS, THREADS

    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NotGeoreferencedWarning)
        for path in (case.target, case.reference):
            with rasterio.open(path) as ds:
                for _, window in ds.block_windows(1):
                    ds.read(window=window)
    read_s = time.perf_counter() - t0
    out = os.path.join(folder, "io-floor-gdalwarp.tif")
    cmd = ["gdalwarp", "-q", "-overwrite", "-r", "bilinear", "-multi", "-wo", f"NUM_THREADS={THREADS}"]
    cmd += [a for k, v in GTIFF_OPTIONS.items() for a in ("-co", f"{k}={v}")]
    warp_s, warp_mb, code = measured(cmd + [case.target, out])
    if os.path.exists(out):
        os.remove(out)
    return {"read_s": round(read_s, 2), "gdalwarp_s": round(warp_s, 2), "gdalwarp_peak_mb": round(warp_mb),
            "floor_s": round(read_s + warp_s, 2), "gdalwarp_ok": code == 0}
