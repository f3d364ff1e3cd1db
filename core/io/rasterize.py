"""Shapes drawn into a GeoTIFF: a vector layer (water, buildings, roads) made a reference raster.

Areas are filled (255 on 0), lines drawn one pixel wide through every pixel they touch, points left out (a
point symbol has no shape to match). The file is written whole or not at all.
"""
from __future__ import annotations

import os

import numpy as np

INSIDE = 255


def write_shapes(shapes, bounds, size, crs_wkt: str, path: str) -> int:
    """Draw ``shapes`` (shapely geometries in ``crs_wkt``) over ``bounds`` (xmin, ymin, xmax, ymax) at
    ``size`` (columns, rows) into the GeoTIFF ``path``; returns how many shapes were drawn."""
    import rasterio
    from rasterio.features import rasterize
    from rasterio.transform import from_bounds

    cols, rows = size
    transform = from_bounds(*bounds, cols, rows)
    areas, lines = [], []
    for shape in shapes:
        if shape is None or shape.is_empty:
            continue
        kind = shape.geom_type
        if "Polygon" in kind:
            areas.append((shape, INSIDE))
        elif "LineString" in kind or kind == "LinearRing":
            lines.append((shape, INSIDE))
    image = np.zeros((rows, cols), np.uint8)
    if areas:
        rasterize(areas, out=image, transform=transform)
    if lines:
        rasterize(lines, out=image, transform=transform, all_touched=True)
    tmp = f"{path}.{os.getpid()}.part.tif"
    profile = dict(driver="GTiff", width=cols, height=rows, count=1, dtype="uint8", crs=crs_wkt,
                   transform=transform, compress="deflate", tiled=cols >= 256 and rows >= 256)
    try:
        with rasterio.open(tmp, "w", **profile) as dst:
            dst.write(image, 1)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return len(areas) + len(lines)
