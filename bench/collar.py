"""The ``collar`` family: a georeferenced SAR scene with a turned footprint inside an untagged zero
collar, onto a georeferenced optical scene, their georeferencing 100-300 px apart.

Built from the real SAR-optical development pair (``../shared/data/pairs``): the reference is the
optical image, the target the SAR image, both upsampled twice so that a georeferencing error of a
few hundred pixels leaves a partial overlap, as on a full scene. The target keeps its own pixel grid
(about north-up, like a geocoded product); its footprint is a turned rectangle and everything outside
it is 0, without a nodata value. Both carry an EPSG:4326 geotransform; the target's is shifted by the
case's error. Some targets are coarser than the reference (a 1.5 m SAR product onto 1 m optical).

Ground truth: the pair's hand-picked affine map H (SAR px -> optical px), conjugated by the upsampling
and the target's window and pixel size. H is good to about 2 px of the original images (see the pair's
``confidence_px``), so the success tolerance is the pair's own (5 px) times the upsampling: 10 reference
px. Coordinates: corner convention, as everywhere in the bench.
"""
from __future__ import annotations

import json
import math
import os
from typing import List

import cv2
import numpy as np
from affine import Affine

from ..core.coords import apply_matrix
from .cases import Case, grid_inside, read_canvas, write_raster
from .synthetic import warp_to_target

UPSAMPLE = 2
ORIGIN = (116.30, 39.95)  # lon, lat of the reference's top-left corner
DEGREES_PER_PX = 5e-6
# name: (georeferencing error in reference px, footprint angle in degrees, target px per reference px)
CASES = {"off100": ((100, -70), 12.0, 1.0), "off200": ((-160, 130), 28.0, 1.0), "off300": ((230, 190), 35.0, 1.0),
         "off200-coarse": ((-150, -140), 20.0, 1.5)}


def names(quick: bool) -> List[str]:
    return list(CASES)[:1] if quick else list(CASES)


def build(folder: str, name: str, data_dir: str) -> Case:
    """Write the case ``name`` into ``folder`` and return it."""
    error, angle, coarse = CASES[name]
    pairs = os.path.join(data_dir, "pairs")
    with open(os.path.join(pairs, "ground_truth.json")) as f:
        pair = next(p for p in json.load(f)["pairs"] if p["id"] == "sar_optical")
    up = np.diag([UPSAMPLE, UPSAMPLE, 1.0])
    h = up @ np.asarray(pair["H_a_to_b"], float) @ np.linalg.inv(up)  # upsampled SAR px -> reference px
    sar, optical = read_canvas(os.path.join(pairs, pair["a"])), read_canvas(os.path.join(pairs, pair["b"]))
    ref = _grey(optical.data, UPSAMPLE)
    sar_up = _grey(sar.data, UPSAMPLE)
    rh, rw = ref.shape
    # The target: a window of the upsampled SAR image, at ``coarse`` times the reference's pixel size.
    c0, r0 = 0.15 * rw, 0.12 * rh
    shape = (int(0.75 * rh / coarse), int(0.72 * rw / coarse))
    to_sar = np.array([[coarse, 0, c0], [0, coarse, r0], [0, 0, 1.0]])  # target px -> upsampled SAR px
    tgt = warp_to_target(sar_up, to_sar, shape)
    inside = _turned_rectangle(shape, angle, 0.78)
    tgt = np.where(inside, np.clip(tgt, 1, 255), 0)
    g = h @ to_sar  # target px -> reference px
    ref_tr = Affine(DEGREES_PER_PX, 0, ORIGIN[0], 0, -DEGREES_PER_PX, ORIGIN[1])
    # The target's geotransform as the truth gives it near its centre (scale and offset), then shifted.
    centre = np.array([shape[1] / 2.0, shape[0] / 2.0])
    scale = math.sqrt(abs(np.linalg.det(g[:2, :2])))
    corner = apply_matrix(g, centre[None])[0] - scale * centre + np.asarray(error, float)
    tgt_tr = ref_tr * Affine(scale, 0, corner[0], 0, scale, corner[1])
    os.makedirs(folder, exist_ok=True)
    full = f"collar_{name}"
    reference = write_raster(os.path.join(folder, f"{full}_reference.tif"), ref[None], np.ones(ref.shape, bool),
                             "uint8", "EPSG:4326", ref_tr)
    target = write_raster(os.path.join(folder, f"{full}_target.tif"), tgt[None], np.ones(shape, bool), "uint8",
                          "EPSG:4326", tgt_tr)
    _zero_collar(target, inside)
    truth = lambda p: apply_matrix(g, p)  # noqa: E731
    return Case(full, target, reference, truth, grid_inside(shape, truth, np.ones(ref.shape, bool), inside),
                tolerance_px=float(pair.get("success_tol_px", 5.0)) * UPSAMPLE,
                info={"family": "collar", "georeferencing_error_px": list(error), "footprint_angle_deg": angle,
                      "target_px_per_reference_px": coarse, "target_px_to_reference_px": g.tolist()})


def _grey(data: np.ndarray, factor: int) -> np.ndarray:
    grey = data.mean(axis=0).astype(np.float32)
    return cv2.resize(grey, None, fx=factor, fy=factor, interpolation=cv2.INTER_CUBIC)


def _turned_rectangle(shape, angle_deg: float, fill: float) -> np.ndarray:
    """A rectangle turned by ``angle_deg`` about the image centre, as large as fits (sides ``fill`` of
    what would fit unturned, shrunk until its corners are inside)."""
    h, w = shape
    a = math.radians(angle_deg)
    c, s = abs(math.cos(a)), abs(math.sin(a))
    k = fill * min(w / (w * c + h * s), h / (w * s + h * c))
    corners = np.array([[-w, -h], [w, -h], [w, h], [-w, h]], float) * k / 2.0
    rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    poly = corners @ rot.T + [w / 2.0, h / 2.0]
    mask = np.zeros(shape, np.uint8)
    cv2.fillPoly(mask, [np.round(poly * 16).astype(np.int32)], 1, shift=4)
    return mask > 0


def _zero_collar(path: str, inside: np.ndarray) -> None:
    """Rewrite ``path`` with 0 outside ``inside`` and no nodata value (write_raster keeps 0 for nodata)."""
    import rasterio

    with rasterio.open(path) as src:
        data, prof = src.read(), src.profile
    prof.update(nodata=None)
    with rasterio.open(path, "w", **prof) as dst:
        dst.write(np.where(inside, data, 0).astype(data.dtype))
