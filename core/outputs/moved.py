"""The target's own pixels under a corrected georeferencing (output grid 'target'): no resampling.

Where the registration is a shift (and a scale per axis), writing the target's pixels unchanged under
the geotransform the model gives is exact, faster than a warp and free of its blur, as AROSICS writes a
shift by default. A model that turns, shears or bends the target beyond :data:`MAX_DEPARTURE_PX` needs a
warp, and is refused with that said. Coordinates: the model maps target px to reference px.
"""
from __future__ import annotations

import os

import numpy as np
import rasterio
import rasterio.shutil
from affine import Affine

from ..coords import compose, raster_outline
from ..errors import OutputError
from ..progress import Monitor
from .tags import verdict_tags

MAX_DEPARTURE_PX = 0.1  # reference px: how far a north-up geotransform may leave the model at the target's edges


def moved_transform(result) -> Affine:
    """The north-up geotransform (reference CRS) that puts the target's pixels where the model does.

    Raises OutputError where the model departs from a north-up one (scale and shift per axis) by more than
    :data:`MAX_DEPARTURE_PX` reference px anywhere on the target's outline and centre."""
    t, ref = result.target, result.reference
    if result.pixel_mode or ref.crs is None:
        raise OutputError(f"The output grid 'target' needs a georeferenced reference with a CRS; '{ref.path}' "
                          "has none: choose the reference grid.")
    uv = np.vstack([raster_outline(t.width, t.height, 9, ends=True), [[t.width / 2.0, t.height / 2.0]]])
    xy = result.model.apply(uv)
    fit = [np.polyfit(uv[:, k], xy[:, k], 1) for k in (0, 1)]
    departure = float(np.max(np.hypot(*(np.polyval(fit[k], uv[:, k]) - xy[:, k] for k in (0, 1)))))
    if not np.isfinite(departure) or departure > MAX_DEPARTURE_PX:
        raise OutputError(f"The model turns or bends '{t.path}' by up to {departure:.2f} reference px against a "
                          "north-up grid, so its pixels cannot be kept unchanged: fit the model 'linear' (a scale and "
                          "shift per axis), or choose the reference or native grid (resampled).")
    (sx, ox), (sy, oy) = fit
    return compose(ref.transform, Affine(sx, 0.0, ox, 0.0, sy, oy))


def write_moved(path: str, result, creation: dict, cog: bool, monitor: Monitor) -> None:
    """The target's bands copied to ``path`` (GeoTIFF with ``creation``; a COG when ``cog``) under
    :func:`moved_transform`, in the reference CRS, with the verdict's tags."""
    transform = moved_transform(result)
    monitor.report(0.05, "writing raster")
    staged = path + ".moved.tif" if cog else path
    try:
        rasterio.shutil.copy(result.target.path, staged, driver="GTiff", **({} if cog else creation))
        monitor.check()
        with rasterio.open(staged, "r+") as dst:
            dst.transform = transform
            dst.crs = result.reference.crs
            dst.update_tags(**verdict_tags(result))
        if cog:
            monitor.report(0.6, "writing overviews")
            rasterio.shutil.copy(staged, path, driver="COG", **creation)
    finally:
        if cog and os.path.exists(staged):
            os.remove(staged)
    monitor.report(1.0, "writing raster")
