"""Warping through a thin plate spline model here instead of GDAL's ``GCP_TPS`` transformer.

GDAL re-solves the spline for every warp call and evaluates every basis function wherever its
approximate transformer samples: with the ~2000 grid points of a local correction that costs tens
of seconds per scene. Here the exact inverse of the model (output pixel -> target pixel, by chord
steps on the model itself, :mod:`hamta.core.estimation.inverse`; GDAL fits a second spline the
other way) is computed on a lattice of output pixels (:func:`lattice_px`; once per strip of rows,
in chunks on threads) and interpolated bilinearly in between, and the target is resampled tile by
tile (bounded memory; tiles side by side on threads) with exact weights by
``scipy.ndimage.map_coordinates`` (OpenCV 4's ``remap`` rounds positions to 1/32 px).

Used for nearest neighbour and bilinear (the default), the kernels GDAL computes the same way;
any other choice goes through GDAL as before. Pixels are valid where the sample point falls inside
the target and the kernel touches no invalid target pixel (its nodata or collar value, NaN); an
alpha band takes GDAL's values (the type's maximum for integers, 255 for floats).

Coordinates: output pixels (corner convention) of the output grid; target pixels (corner
convention; array index ``i`` is the pixel centre ``i + 0.5``).
"""
from __future__ import annotations

import threading
from typing import Optional

import numpy as np
from affine import Affine
from rasterio.warp import transform as transform_points
from rasterio.windows import Window

from ..coords import map_to_pixel
from ..estimation.inverse import invert_model
from ..io.raster import numpy_dtype
from ..parallel import threaded

TILE_PX = 512
LATTICE_CHUNK = 2048  # lattice nodes inverted per thread task
KERNELS = {"nearest": 0, "bilinear": 1}  # spline order in scipy.ndimage; the same kernels as GDAL's
DTYPES = ("uint8", "uint16", "int16", "uint32", "int32", "float32", "float64")


def spline_applies(result, dtype: str, resampling: str) -> bool:
    """Whether this module warps ``result``'s model with ``resampling`` for pixel type ``dtype``."""
    return getattr(result.model, "kind", None) == "tps" and resampling in KERNELS and dtype in DTYPES


def spline_rows(src, bands, result, grid, fill, resampling: str, r0: int, n: int) -> np.ndarray:
    """Rows ``r0 .. r0 + n`` of the warped output: (bands [+ alpha], n, width), like GDAL's warp of
    ``src`` (the model VRT over the target) onto ``grid`` = (transform, width, height, crs, _)."""
    transform, width, _, crs, _ = grid
    dtype = numpy_dtype(src.dtypes[0])
    count = len(bands) + (1 if fill.alpha else 0)
    out = np.zeros((count, n, width), dtype=dtype)
    if fill.nodata is not None:
        out[:len(bands)] = fill.nodata
    alpha = np.iinfo(dtype).max if np.issubdtype(dtype, np.integer) else 255  # as GDAL's warper
    step = lattice_px(result.model)
    lattice = strip_lattice(result, transform, crs, r0, n, width, step)
    tiles = [(t0, c0, min(TILE_PX, n - t0), min(TILE_PX, width - c0))
             for t0 in range(0, n, TILE_PX) for c0 in range(0, width, TILE_PX)]
    reading = threading.Lock()  # ``src`` is read by one thread at a time

    def one(tile):  # each tile writes its own part of ``out``
        t0, c0, h, w = tile
        xs, ys = interpolate(lattice, step, c0, t0, w, h)
        resampled, valid = _resample(src, bands, xs, ys, fill, resampling, reading)
        if resampled is None:
            return
        view = out[:, t0:t0 + h, c0:c0 + w]
        whole = valid.all()
        for b in range(len(bands)):
            if whole:
                view[b] = resampled[b]
            else:
                view[b][valid] = resampled[b][valid]
        if fill.alpha:
            view[-1][valid] = alpha

    threaded(one, tiles)
    return out


def strip_lattice(result, transform: Affine, crs, r0: int, n: int, width: int, step: int) -> np.ndarray:
    """Target pixel positions (rows, cols, 2) of the centres of the output pixels every ``step``
    pixels from the strip's first pixel (column 0, row ``r0``), far enough to bracket every pixel of
    its ``n`` rows; through the exact inverse of the model (``nan`` where it has none), in chunks
    of :data:`LATTICE_CHUNK` nodes on threads (each chunk is solved until all its nodes are within Newton's
    tolerance, so a node's last digits depend on its chunk, never on the number of threads)."""
    cols = np.arange(0, width + step, step, dtype=float)
    rows = np.arange(0, n + step, step, dtype=float)
    cc, rr = np.meshgrid(cols + 0.5, r0 + rows + 0.5)
    mx, my = transform * (cc.ravel(), rr.ravel())
    if not result.pixel_mode and crs is not None and crs != result.reference.crs:
        mx, my = transform_points(crs, result.reference.crs, mx, my)
    mp = np.column_stack([mx, my])
    ref_px = mp if result.pixel_mode else map_to_pixel(result.reference.transform, mp)
    t = result.target

    def invert(start):
        q, ok = invert_model(result.model, ref_px[start:start + LATTICE_CHUNK], (t.width, t.height),
                             tolerance=0.01, fixed_jacobian=True)
        q[~ok] = np.nan  # not invertible there: those pixels stay empty
        return q

    q = np.concatenate(threaded(invert, range(0, len(ref_px), LATTICE_CHUNK)))
    return q.reshape(len(rows), len(cols), 2)


def interpolate(lattice: np.ndarray, step: int, c0: int, t0: int, w: int, h: int):
    """Target positions (x, y arrays of shape (h, w)) of the output pixels ``c0 .. c0 + w`` x
    ``t0 .. t0 + h`` of a strip, bilinear between the nodes of its :func:`strip_lattice`."""
    fx, fy = (c0 + np.arange(w)) / step, (t0 + np.arange(h)) / step
    j = np.minimum(fx.astype(int), lattice.shape[1] - 2)
    i = np.minimum(fy.astype(int), lattice.shape[0] - 2)
    tx, ty = (fx - j)[None, :], (fy - i)[:, None]
    lo, hi = i.min(), i.max() + 2
    part = lattice[lo:hi]
    i = i - lo
    positions = []
    for k in (0, 1):
        along = part[:, j, k] * (1 - tx) + part[:, j + 1, k] * tx  # (lattice rows, w)
        rise = np.diff(along, axis=0)
        pos = along[i]
        pos += rise[i] * ty
        positions.append(pos)
    return positions[0], positions[1]


def lattice_px(model) -> int:
    """Lattice spacing: a quarter of the spline's control spacing (bilinear interpolation error far
    below 0.01 px for a spline that bends at that scale), 8 to 64 px."""
    from scipy.spatial import cKDTree

    control = model.control
    if len(control) < 2:
        return 32
    gap = float(np.median(cKDTree(control).query(control, k=2)[0][:, 1]))
    return int(np.clip(gap / 4.0, 8, 64))


def _resample(src, bands, xs, ys, fill, resampling: str, reading) -> tuple:
    """(tile (bands, h, w), valid (h, w)) for the target positions ``xs``, ``ys``; (None, None) when
    no position falls inside the target."""
    from scipy.ndimage import map_coordinates

    order = KERNELS[resampling]
    with np.errstate(invalid="ignore"):
        inside = (xs >= 0) & (xs <= src.width) & (ys >= 0) & (ys <= src.height)
    whole = inside.all()
    if not whole and not inside.any():
        return None, None
    x_in, y_in = (xs, ys) if whole else (xs[inside], ys[inside])
    x0 = max(int(np.floor(x_in.min())) - 2, 0)
    y0 = max(int(np.floor(y_in.min())) - 2, 0)
    x1 = min(int(np.ceil(x_in.max())) + 2, src.width)
    y1 = min(int(np.ceil(y_in.max())) + 2, src.height)
    with reading:
        data = src.read(list(bands), window=Window(x0, y0, x1 - x0, y1 - y0))
    coords = np.empty((2,) + xs.shape)
    np.subtract(ys, y0 + 0.5, out=coords[0])
    np.subtract(xs, x0 + 0.5, out=coords[1])
    if not whole:
        coords[:, ~inside] = 0.0
    valid = inside
    bad = _invalid(data, fill.source)
    if bad is not None:
        hit = map_coordinates(bad.astype(np.float32), coords, order=order, mode="nearest", output=np.float32)
        valid = valid & (hit <= 0)
    tile = np.empty((len(data),) + xs.shape)
    for b, band in enumerate(data):
        map_coordinates(band, coords, order=order, mode="nearest", output=tile[b])
    if np.issubdtype(data.dtype, np.integer):
        limits = np.iinfo(data.dtype)
        np.rint(tile, out=tile)
        np.clip(tile, limits.min, limits.max, out=tile)
    return tile.astype(data.dtype), valid


def _invalid(data: np.ndarray, source: Optional[float]) -> Optional[np.ndarray]:
    """Target pixels (any band) that are not data, or None when all are."""
    bad = np.zeros(data.shape[1:], bool)
    if np.issubdtype(data.dtype, np.floating):
        bad |= np.isnan(data).any(axis=0)
    if source is not None and not np.isnan(source):
        bad |= (data == source).any(axis=0)
    return bad if bad.any() else None
