"""Pixel and map coordinate conventions, fixed once for the whole package.

Hamta's pixel coordinates are continuous ``(x, y)`` = (column, row) with the origin at the
top-left *corner* of the top-left pixel, as GDAL geotransforms and GCPs use them: the centre of
pixel (row r, col c) is (c + 0.5, r + 0.5). OpenCV puts pixel centres at integers; every +0.5
shift between the two lives here. Arrays of points are ``(N, 2)`` float64 named ``*_xy``.
"""
from __future__ import annotations

import threading
from typing import Optional

import numpy as np
from affine import Affine


def as_xy(points) -> np.ndarray:
    """Return ``points`` as a C-contiguous ``(N, 2)`` float64 array."""
    xy = np.asarray(points, dtype=np.float64)
    if xy.ndim == 1 and xy.size == 2:
        xy = xy[None, :]
    if xy.ndim != 2 or xy.shape[1] != 2:
        raise ValueError(f"expected points of shape (N, 2), got {xy.shape}")
    return np.ascontiguousarray(xy)


def raster_outline(width: float, height: float, n: int, ends: bool = False) -> np.ndarray:
    """Points along the border of a ``width`` x ``height`` raster (pixels, corner convention),
    clockwise from the top-left corner: ``n`` per side (the side's last point left out unless
    ``ends``, so each corner appears once)."""
    s = np.linspace(0.0, 1.0, n) if ends else np.linspace(0.0, 1.0, n)[:-1]
    w, h = float(width), float(height)
    return np.concatenate([np.column_stack([s * w, 0 * s]), np.column_stack([0 * s + w, s * h]),
                           np.column_stack([w - s * w, 0 * s + h]), np.column_stack([0 * s, h - s * h])])


def opencv_to_corner(xy) -> np.ndarray:
    """OpenCV pixel coordinates (centres at integers) -> corner-origin pixel coordinates."""
    return as_xy(xy) + 0.5


def corner_to_opencv(xy) -> np.ndarray:
    """Corner-origin pixel coordinates -> OpenCV pixel coordinates (centres at integers)."""
    return as_xy(xy) - 0.5


def matrix_corner_to_opencv(h: np.ndarray) -> np.ndarray:
    """A 3x3 map between corner-origin pixel spaces, re-expressed between OpenCV pixel spaces.

    Use it to hand a corner-convention homography to ``cv2.warpPerspective`` / ``warpAffine``.
    """
    shift = np.array([[1.0, 0.0, 0.5], [0.0, 1.0, 0.5], [0.0, 0.0, 1.0]])
    unshift = np.array([[1.0, 0.0, -0.5], [0.0, 1.0, -0.5], [0.0, 0.0, 1.0]])
    return unshift @ np.asarray(h, dtype=np.float64) @ shift


def apply_matrix(h: np.ndarray, xy) -> np.ndarray:
    """Apply a 3x3 projective matrix to ``(N, 2)`` points (same space convention in and out)."""
    xy = as_xy(xy)
    h = np.asarray(h, dtype=np.float64)
    w = xy @ h[2, :2] + h[2, 2]
    out = (xy @ h[:2, :2].T + h[:2, 2]) / w[:, None]
    return out


def xy_bounds(xy) -> tuple:
    """(lowest x and y, highest x and y) of ``(N, 2)`` points (any one space), column by column: the
    same values as ``min(axis=0)``, which numpy reduces some 20 times slower across two columns."""
    xy = as_xy(xy)
    x, y = xy[:, 0], xy[:, 1]
    return np.array([x.min(), y.min()]), np.array([x.max(), y.max()])


def affine_to_matrix(transform: Affine) -> np.ndarray:
    """A rasterio/GDAL geotransform as a 3x3 matrix (pixel corner coordinates -> map)."""
    t = transform
    return np.array([[t.a, t.b, t.c], [t.d, t.e, t.f], [0.0, 0.0, 1.0]])


def pixel_to_map(transform: Affine, xy) -> np.ndarray:
    """Pixel (corner convention) -> map coordinates of a raster with geotransform ``transform``."""
    return apply_matrix(affine_to_matrix(transform), xy)


def map_to_pixel(transform: Affine, xy) -> np.ndarray:
    """Map coordinates -> pixel (corner convention) of a raster with geotransform ``transform``."""
    return apply_matrix(np.linalg.inv(affine_to_matrix(transform)), xy)


def gdal_coefficients(transform: Affine) -> list:
    """The 6 GDAL geotransform coefficients ``[c, a, b, f, d, e]`` of a rasterio ``Affine``."""
    return [float(v) for v in transform.to_gdal()]


def compose(*transforms: Affine) -> Affine:
    """Product of affine transforms, left to right as ``t1 * t2 * ...`` (works with affine 2 and 3,
    whose operators differ)."""
    m = np.eye(3)
    for t in transforms:
        m = m @ affine_to_matrix(t)
    return Affine(m[0, 0], m[0, 1], m[0, 2], m[1, 0], m[1, 1], m[1, 2])


def continue_longitudes(xy: np.ndarray, centre: Optional[float]) -> np.ndarray:
    """Longitudes (column 0) moved by whole turns to within half a turn of ``centre`` (a geographic
    raster's central longitude), so that a raster across the antimeridian, written as 179..181 or as
    -181..-179, stays in one piece; unchanged when ``centre`` is None (a projected CRS)."""
    if centre is None:
        return xy
    out = np.array(xy, dtype=np.float64)
    out[:, 0] += 360.0 * np.round((centre - out[:, 0]) / 360.0)
    return out


def transformer(src, dst):
    """A pyproj ``Transformer`` from ``src`` to ``dst`` (CRS objects or strings), x = easting or longitude.
    Built once per pair and thread: building one costs a few milliseconds (a verification places
    hundreds of points one site at a time), and pyproj's transformers are not shared across threads."""
    cache = _transformers.__dict__.setdefault("by_pair", {})
    key = (_crs_key(src), _crs_key(dst))
    found = cache.get(key)
    if found is None:
        from pyproj import Transformer  # imported when needed: pixel-mode runs never are

        if len(cache) >= 32:
            cache.clear()
        found = cache[key] = Transformer.from_crs(src, dst, always_xy=True)
    return found


def _crs_key(crs) -> str:
    return crs if isinstance(crs, str) else crs.to_wkt()


_transformers = threading.local()
