"""Synthetic registration cases written to disk with exact ground truth.

Each case is a reference raster, a target raster and the true map ``truth(target_px) ->
reference_px``; check points are a regular grid over the part of the target that shows valid
reference pixels. Used by the tests and by ``hamta bench``.
"""
from __future__ import annotations

import os
import warnings
from dataclasses import dataclass
from typing import Callable

import numpy as np
import rasterio
from affine import Affine
from rasterio.errors import NotGeoreferencedWarning
from rasterio.warp import Resampling, calculate_default_transform, reproject

from ..coords import apply_matrix, compose, map_to_pixel, pixel_to_map
from .synthetic import similarity_matrix, warp_to_target


@dataclass(frozen=True, eq=False)
class Case:
    """A target/reference pair on disk with the true target px -> reference px map."""

    name: str
    target: str
    reference: str
    truth: Callable[[np.ndarray], np.ndarray]
    check_points: np.ndarray  # (N, 2) target px

    def errors(self, model) -> np.ndarray:
        """Euclidean error (reference px) of ``model`` at every check point."""
        return np.linalg.norm(model.apply(self.check_points) - self.truth(self.check_points), axis=1)


def _read(path):
    with rasterio.open(path) as ds:
        return ds.read(), ds.read_masks(1) > 0, ds.profile


def _write(path, data, profile, **extra):
    prof = dict(driver="GTiff", width=data.shape[2], height=data.shape[1], count=data.shape[0], dtype=data.dtype.name,
                compress="deflate")
    prof.update({k: profile[k] for k in ("nodata", "photometric") if k in profile and profile[k] is not None})
    prof.update(extra)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NotGeoreferencedWarning)
        with rasterio.open(path, "w", **prof) as dst:
            dst.write(data)


def _grid_inside(target_shape, truth, ref_valid, tgt_valid=None, n: int = 25) -> np.ndarray:
    h, w = target_shape
    gx, gy = np.meshgrid((np.arange(n) + 0.5) * w / n, (np.arange(n) + 0.5) * h / n)
    pts = np.column_stack([gx.ravel(), gy.ravel()])
    ref = truth(pts)
    rh, rw = ref_valid.shape
    ok = (ref[:, 0] > 2) & (ref[:, 1] > 2) & (ref[:, 0] < rw - 2) & (ref[:, 1] < rh - 2)
    ri = np.clip(ref.astype(int), 0, [rw - 1, rh - 1])
    ok &= ref_valid[ri[:, 1], ri[:, 0]]
    if tgt_valid is not None:
        ti = pts.astype(int)
        ok &= tgt_valid[ti[:, 1], ti[:, 0]]
    return pts[ok]


def similarity_case(folder: str, reference_path: str, *, angle_deg: float, scale: float, shift_px=(0.0, 0.0),
                    target_shape=None, name: str = "similarity", matrix=None, radiometry=None) -> Case:
    """Target = reference rotated by ``angle_deg``, scaled by ``scale`` (target px per reference px)
    and shifted; no georeferencing. ``matrix`` (target px -> reference px) overrides the similarity.
    ``radiometry(array) -> array`` alters the target's values."""
    os.makedirs(folder, exist_ok=True)
    data, valid, profile = _read(reference_path)
    rh, rw = valid.shape
    shape = target_shape or (int(round(rh * scale)), int(round(rw * scale)))
    g = matrix if matrix is not None else similarity_matrix(angle_deg, scale, shape, (rh, rw), shift_px)
    tgt = warp_to_target(data.astype(np.float32), g, shape)
    if radiometry is not None:
        tgt = radiometry(tgt)
    tgt = np.clip(np.round(tgt), np.iinfo(data.dtype).min, np.iinfo(data.dtype).max).astype(data.dtype) \
        if data.dtype.kind in "ui" else tgt.astype(data.dtype)
    tgt_valid = warp_to_target(valid.astype(np.float32), g, shape) > 0.999
    if profile.get("nodata") is not None:
        tgt[:, ~tgt_valid] = profile["nodata"]
    target = os.path.join(folder, f"{name}_target.tif")
    _write(target, tgt, profile)
    truth = lambda p: apply_matrix(g, p)  # noqa: E731
    return Case(name, target, os.path.abspath(reference_path), truth, _grid_inside(shape, truth, valid, tgt_valid))


def reprojected_case(folder: str, reference_path: str, *, dst_crs: str, shift_px=(0.0, 0.0),
                     name: str = "reprojected") -> Case:
    """Target = reference reprojected to ``dst_crs``, written with a geotransform wrongly shifted
    by ``shift_px`` of its own pixels (a georeferencing error to correct)."""
    os.makedirs(folder, exist_ok=True)
    data, valid, profile = _read(reference_path)
    src_crs, src_tr = profile["crs"], profile["transform"]
    rh, rw = valid.shape
    tr, w, h = calculate_default_transform(src_crs, dst_crs, rw, rh, *rasterio.transform.array_bounds(rh, rw, src_tr))
    tgt = np.zeros((data.shape[0], h, w), data.dtype)
    reproject(data, tgt, src_transform=src_tr, src_crs=src_crs, dst_transform=tr, dst_crs=dst_crs,
              src_nodata=profile.get("nodata"), dst_nodata=profile.get("nodata") or 0, resampling=Resampling.cubic)
    tgt_valid = np.zeros((h, w), np.uint8)
    reproject(valid.astype(np.uint8), tgt_valid, src_transform=src_tr, src_crs=src_crs, dst_transform=tr,
              dst_crs=dst_crs, dst_nodata=0, resampling=Resampling.nearest)
    wrong = compose(tr, Affine.translation(shift_px[0], shift_px[1]))
    target = os.path.join(folder, f"{name}_target.tif")
    _write(target, tgt, profile, crs=dst_crs, transform=wrong)
    from pyproj import Transformer

    to_ref = Transformer.from_crs(dst_crs, src_crs, always_xy=True)

    def truth(p):
        mp = pixel_to_map(tr, p)
        x, y = to_ref.transform(mp[:, 0], mp[:, 1])
        return map_to_pixel(src_tr, np.column_stack([x, y]))

    return Case(name, target, os.path.abspath(reference_path), truth,
                _grid_inside((h, w), truth, valid, tgt_valid.astype(bool)))
