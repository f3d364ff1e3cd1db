"""Registration cases written to disk with exact ground truth.

A case is a reference raster, a target raster and the true map ``truth(target_px) ->
reference_px``. Synthetic cases cut the reference from a *canvas* image and resample the target
from the same canvas through a known map, so every target pixel has a known true position; check
points are a regular grid over the part of the target that shows valid reference pixels. Real
pairs carry hand-picked check points instead. Used by the tests and by ``hamta bench``.
"""
from __future__ import annotations

import os
import warnings
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np
import rasterio
from affine import Affine
from rasterio.errors import NotGeoreferencedWarning
from rasterio.warp import Resampling, calculate_default_transform, reproject

from ..core.coords import apply_matrix, compose, map_to_pixel, pixel_to_map
from .synthetic import similarity_matrix, warp_to_target


@dataclass(frozen=True, eq=False)
class Canvas:
    """A source image: ``data`` (bands, H, W) float32, ``valid`` (H, W), optional georeferencing."""

    data: np.ndarray
    valid: np.ndarray
    crs: Optional[str] = None
    transform: Optional[Affine] = None
    dtype: str = "uint8"

    @property
    def shape(self):
        return self.valid.shape


@dataclass(frozen=True, eq=False)
class Case:
    """A target/reference pair on disk with the true target px -> reference px map.

    ``check_truth`` (optional) holds measured reference positions of the check points (real
    pairs); otherwise ``truth`` gives them. ``tolerance_px`` is the success threshold.
    """

    name: str
    target: str
    reference: str
    truth: Callable[[np.ndarray], np.ndarray]
    check_points: np.ndarray  # (N, 2) target px
    check_truth: Optional[np.ndarray] = None
    tolerance_px: float = 3.0
    info: dict = field(default_factory=dict)

    def errors(self, model) -> np.ndarray:
        """Euclidean error (reference px) of ``model`` at every check point."""
        true = self.check_truth if self.check_truth is not None else self.truth(self.check_points)
        return np.linalg.norm(model.apply(self.check_points) - true, axis=1)


def read_canvas(path: str) -> Canvas:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NotGeoreferencedWarning)
        with rasterio.open(path) as ds:
            georef = ds.crs is not None
            return Canvas(ds.read().astype(np.float32), np.all(ds.read_masks() > 0, axis=0),
                          ds.crs.to_wkt() if georef else None, ds.transform if georef else None, ds.dtypes[0])


def write_raster(path: str, data: np.ndarray, valid: np.ndarray, dtype: str, crs=None, transform=None) -> str:
    """Write (bands, H, W) ``data``; invalid pixels become nodata (0 for integers, NaN for floats)."""
    nodata = float("nan") if dtype.startswith("float") else 0
    if dtype.startswith("float"):
        out = data.astype(dtype)
    else:
        info = np.iinfo(dtype)
        out = np.clip(np.round(data), info.min + 1, info.max).astype(dtype)  # 0 stays free for nodata
    out[:, ~valid] = nodata
    prof = dict(driver="GTiff", width=out.shape[2], height=out.shape[1], count=out.shape[0], dtype=dtype,
                nodata=nodata, compress="deflate", tiled=True)
    if out.shape[0] == 3:
        prof["photometric"] = "RGB"
    if crs is not None:
        prof.update(crs=crs, transform=transform)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NotGeoreferencedWarning)
        with rasterio.open(path, "w", **prof) as dst:
            dst.write(out)
    return path


def grid_inside(target_shape, truth, ref_valid, tgt_valid=None, n: int = 25) -> np.ndarray:
    """Regular ``n x n`` grid of target pixels whose true position shows valid reference pixels."""
    h, w = target_shape
    gx, gy = np.meshgrid((np.arange(n) + 0.5) * w / n, (np.arange(n) + 0.5) * h / n)
    pts = np.column_stack([gx.ravel(), gy.ravel()])
    ref = truth(pts)
    rh, rw = ref_valid.shape
    ok = (ref[:, 0] > 2) & (ref[:, 1] > 2) & (ref[:, 0] < rw - 2) & (ref[:, 1] < rh - 2)
    ri = np.clip(np.nan_to_num(ref).astype(int), 0, [rw - 1, rh - 1])
    ok &= ref_valid[ri[:, 1], ri[:, 0]]
    if tgt_valid is not None:
        ti = pts.astype(int)
        ok &= tgt_valid[ti[:, 1], ti[:, 0]]
    return pts[ok]


def warped_case(folder: str, name: str, canvas: Canvas, g: np.ndarray, target_shape, *, ref_window=None,
                reference_radiometry=None, target_radiometry=None, dtype: Optional[str] = None,
                seed: int = 0, info: Optional[dict] = None) -> Case:
    """Reference = ``canvas`` (or its ``ref_window`` = (col, row, width, height)); target pixel p
    shows canvas position ``g(p)`` (3x3, target px -> canvas px). Radiometry functions take
    ``(array, rng)`` and return the altered float array. The target has no georeferencing."""
    os.makedirs(folder, exist_ok=True)
    rng = np.random.default_rng(seed)
    c0, r0, rw, rh = ref_window or (0, 0, canvas.shape[1], canvas.shape[0])
    ref_data = canvas.data[:, r0:r0 + rh, c0:c0 + rw]
    ref_valid = canvas.valid[r0:r0 + rh, c0:c0 + rw]
    if reference_radiometry is not None:
        ref_data = reference_radiometry(ref_data, rng)
    tgt = warp_to_target(canvas.data, g, target_shape)
    tgt_valid = warp_to_target(canvas.valid.astype(np.float32), g, target_shape) > 0.999
    if target_radiometry is not None:
        tgt = target_radiometry(tgt, rng)
    dtype = dtype or canvas.dtype
    ref_tr = None if canvas.transform is None else compose(canvas.transform, Affine.translation(c0, r0))
    reference = write_raster(os.path.join(folder, f"{name}_reference.tif"), ref_data, ref_valid, dtype, canvas.crs,
                             ref_tr)
    target = write_raster(os.path.join(folder, f"{name}_target.tif"), tgt, tgt_valid, dtype)
    shift = np.array([[1.0, 0, -c0], [0, 1.0, -r0], [0, 0, 1.0]])
    g_ref = shift @ g
    truth = lambda p: apply_matrix(g_ref, p)  # noqa: E731
    return Case(name, target, reference, truth, grid_inside(target_shape, truth, ref_valid, tgt_valid),
                info=dict(info or {}, target_px_to_reference_px=g_ref.tolist()))


def similarity_case(folder: str, reference_path: str, *, angle_deg: float, scale: float, shift_px=(0.0, 0.0),
                    target_shape=None, name: str = "similarity", radiometry=None) -> Case:
    """Target = the reference rotated by ``angle_deg``, scaled by ``scale`` (target px per
    reference px) and shifted; no georeferencing."""
    canvas = read_canvas(reference_path)
    rh, rw = canvas.shape
    shape = target_shape or (int(round(rh * scale)), int(round(rw * scale)))
    g = similarity_matrix(angle_deg, scale, shape, (rh, rw), shift_px)
    return warped_case(folder, name, canvas, g, shape, target_radiometry=radiometry)


def reprojected_case(folder: str, reference_path: str, *, dst_crs: str, shift_px=(0.0, 0.0),
                     name: str = "reprojected", canvas: Optional[Canvas] = None) -> Case:
    """Target = the reference reprojected to ``dst_crs``, written with a geotransform wrongly shifted
    by ``shift_px`` of its own pixels (a georeferencing error to correct)."""
    os.makedirs(folder, exist_ok=True)
    canvas = canvas or read_canvas(reference_path)
    if reference_path is None:
        reference_path = write_raster(os.path.join(folder, f"{name}_reference.tif"), canvas.data, canvas.valid,
                                      canvas.dtype, canvas.crs, canvas.transform)
    src_crs, src_tr = canvas.crs, canvas.transform
    rh, rw = canvas.shape
    tr, w, h = calculate_default_transform(src_crs, dst_crs, rw, rh, *rasterio.transform.array_bounds(rh, rw, src_tr))
    src = np.where(canvas.valid, canvas.data, np.nan).astype(np.float32)
    tgt = np.full((canvas.data.shape[0], h, w), np.nan, np.float32)
    reproject(src, tgt, src_transform=src_tr, src_crs=src_crs, dst_transform=tr, dst_crs=dst_crs,
              src_nodata=np.nan, dst_nodata=np.nan, resampling=Resampling.cubic)
    tgt_valid = np.all(np.isfinite(tgt), axis=0)
    wrong = compose(tr, Affine.translation(shift_px[0], shift_px[1]))
    target = write_raster(os.path.join(folder, f"{name}_target.tif"), np.nan_to_num(tgt), tgt_valid, canvas.dtype,
                          dst_crs, wrong)
    from pyproj import Transformer

    to_ref = Transformer.from_crs(dst_crs, src_crs, always_xy=True)

    def truth(p):
        mp = pixel_to_map(tr, p)
        x, y = to_ref.transform(mp[:, 0], mp[:, 1])
        return map_to_pixel(src_tr, np.column_stack([x, y]))

    return Case(name, target, os.path.abspath(reference_path), truth,
                grid_inside((h, w), truth, canvas.valid, tgt_valid), info={"dst_crs": dst_crs,
                                                                           "shift_px": list(shift_px)})
