"""The bundled demo: a self-generated georeferenced scene and a rotated, rescaled, shifted target
without georeferencing, registered back with the true check-point error reported."""
from __future__ import annotations

import json
import os
import warnings

import numpy as np
import rasterio
from affine import Affine
from rasterio.errors import NotGeoreferencedWarning

from ..core.coords import apply_matrix
from .synthetic import make_landscape, similarity_matrix, warp_to_target

DEMO_CRS = "EPSG:32639"  # WGS 84 / UTM zone 39N
DEMO_TRANSFORM = Affine(10.0, 0.0, 552000.0, 0.0, -10.0, 3620000.0)  # 10 m pixels
DEMO_TRUTH = {"angle_deg": 12.0, "scale": 0.8, "shift_px": [37.0, -21.0]}
TARGET_SHAPE = (700, 760)


def make_demo_pair(folder: str, side: int = 1000):
    """Write ``reference.tif``, ``target.tif`` and ``truth.json`` into ``folder``; return their paths.

    The target shows the reference rotated by 12 degrees at 12.5 m pixels (scale 0.8), shifted,
    with a gamma change and sensor noise, and carries no georeferencing. ``side`` (reference px) gives a
    smaller pair of the same make, target and shift scaled alike (the tests' quick pair).
    """
    os.makedirs(folder, exist_ok=True)
    factor = side / 1000.0
    shape = (round(TARGET_SHAPE[0] * factor), round(TARGET_SHAPE[1] * factor))
    shift = [v * factor for v in DEMO_TRUTH["shift_px"]]
    ref = make_landscape((side, side), seed=7)
    g = similarity_matrix(DEMO_TRUTH["angle_deg"], DEMO_TRUTH["scale"], shape, ref.shape[1:], shift)
    tgt = warp_to_target(ref, g, shape)
    rng = np.random.default_rng(11)
    tgt = 255.0 * (np.clip(tgt, 0, 255) / 255.0) ** 0.8 + rng.normal(0, 3.0, tgt.shape)
    tgt = np.clip(tgt, 0, 255).astype(np.uint8)
    paths = {k: os.path.join(folder, v) for k, v in
             (("reference", "reference.tif"), ("target", "target.tif"), ("truth", "truth.json"))}
    with rasterio.open(paths["reference"], "w", driver="GTiff", width=side, height=side, count=3, dtype="uint8",
                       crs=DEMO_CRS, transform=DEMO_TRANSFORM, photometric="RGB", compress="deflate") as dst:
        dst.write(ref)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NotGeoreferencedWarning)
        with rasterio.open(paths["target"], "w", driver="GTiff", width=shape[1], height=shape[0],
                           count=3, dtype="uint8", photometric="RGB", compress="deflate") as dst:
            dst.write(tgt)
    with open(paths["truth"], "w") as f:
        json.dump(dict(DEMO_TRUTH, shift_px=shift, target_px_to_reference_px=g.tolist()), f, indent=1)
    return paths


def check_point_error(model, truth_matrix: np.ndarray, target_shape, reference_shape, n: int = 20):
    """RMSE and max (reference px) of ``model`` against the true map on a regular grid of check
    points over the part of the target that lies inside the reference."""
    h, w = target_shape
    gx, gy = np.meshgrid((np.arange(n) + 0.5) * w / n, (np.arange(n) + 0.5) * h / n)
    pts = np.column_stack([gx.ravel(), gy.ravel()])
    true = apply_matrix(truth_matrix, pts)
    inside = ((true >= 0) & (true <= [reference_shape[1], reference_shape[0]])).all(axis=1)
    pts, true = pts[inside], true[inside]
    err = np.linalg.norm(model.apply(pts) - true, axis=1)
    return float(np.sqrt(np.mean(err ** 2))), float(err.max())
