"""The report's previews: both rasters read once at preview size, and the target warped onto the
reference preview through the model.

A raster is decimated to a preview whose longest side is :data:`PREVIEW_PX` pixels
(:func:`hamta.core.io.raster.read_image` with an output shape), so time and memory do not grow with
the raster size. Coordinates follow :mod:`hamta.core.coords`: full-resolution pixel ``(x, y)``
(corner origin; target px or reference px) is preview pixel ``(x / sx, y / sy)``, and OpenCV draws at
that minus one half, since OpenCV puts pixel centres at integers (:meth:`Preview.to_opencv`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Tuple

import cv2
import numpy as np

from ..coords import as_xy
from ..estimation.inverse import invert_model
from ..io.raster import RasterInfo, read_image, resolve_bands
from ..io.windows import read_whole

PREVIEW_PX = 800  # longest side of the previews
GRID_STEP_PX = 20  # preview px between the nodes where the model is inverted exactly


@dataclass(frozen=True)
class Preview:
    """A raster read at preview size, contrast-stretched to uint8.

    ``scale`` is (sx, sy), full-resolution pixels per preview pixel.
    """

    image: np.ndarray
    valid: np.ndarray
    scale: Tuple[float, float]

    @property
    def shape(self) -> Tuple[int, int]:
        return self.image.shape[:2]

    def to_opencv(self, xy) -> np.ndarray:
        """Full-resolution pixels (corner origin) -> OpenCV coordinates of the preview."""
        return as_xy(xy) / np.asarray(self.scale) - 0.5

    def to_full(self, xy) -> np.ndarray:
        """Preview pixels (corner origin) -> full-resolution pixels (corner origin)."""
        return as_xy(xy) * np.asarray(self.scale)


def preview_shape(width: int, height: int, longest: int = PREVIEW_PX) -> Tuple[int, int]:
    """(rows, cols) of a preview of a ``width x height`` raster with the longest side ``longest``."""
    f = longest / float(max(width, height))
    return max(1, int(round(height * f))), max(1, int(round(width * f)))


def read_preview(info: RasterInfo, band: Optional[int]) -> Preview:
    """Read ``info`` (the band or RGB luminance the registration used) at preview size.

    Larger rasters are decimated by the read; smaller ones are read whole and enlarged bilinearly,
    so that the drawings keep their size whatever the raster's.
    """
    rows, cols = preview_shape(info.width, info.height)
    bands = resolve_bands(info, band)
    if rows >= info.height and cols >= info.width:  # read whole: within a run, the read the check made
        image, valid = read_whole(info, bands)
    else:
        image, valid = read_image(info, bands, out_shape=(min(rows, info.height), min(cols, info.width)))
    if image.shape != (rows, cols):
        image = cv2.resize(image, (cols, rows), interpolation=cv2.INTER_LINEAR)
        valid = cv2.resize(valid.astype(np.uint8), (cols, rows), interpolation=cv2.INTER_NEAREST) > 0
    return Preview(stretch(image, valid), valid, (info.width / cols, info.height / rows))


def stretch(image: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """Linear 2-98 % stretch of the valid pixels to uint8; invalid pixels are black."""
    values = image[valid]
    if values.size == 0:
        return np.zeros(image.shape, np.uint8)
    lo, hi = np.percentile(values, [2.0, 98.0])
    hi = hi if hi > lo else lo + 1.0
    out = np.clip((image - lo) * (255.0 / (hi - lo)), 0, 255).astype(np.uint8)
    out[~valid] = 0
    return out


def warp_to_reference(model, tgt: Preview, ref: Preview) -> Tuple[np.ndarray, np.ndarray]:
    """The target preview resampled onto the reference preview grid through ``model``.

    The model (target px -> reference px) is inverted exactly at nodes every
    :data:`GRID_STEP_PX` preview pixels and bilinearly in between (an inverse map is smooth); the
    target's edge and mask are then applied pixel by pixel.

    Returns
    -------
    warped : (rows, cols) uint8
    valid : (rows, cols) bool
        False where the target does not cover the reference, or the model could not be inverted.
    """
    rows, cols = ref.shape
    nx, ny = max(2, math.ceil(cols / GRID_STEP_PX) + 1), max(2, math.ceil(rows / GRID_STEP_PX) + 1)
    node_x, node_y = np.linspace(0.5, cols - 0.5, nx), np.linspace(0.5, rows - 0.5, ny)
    gx, gy = np.meshgrid(node_x, node_y)
    full = ref.to_full(np.column_stack([gx.ravel(), gy.ravel()]))
    tgt_size = tgt.scale[0] * tgt.shape[1], tgt.scale[1] * tgt.shape[0]
    q, ok = invert_model(model, full, tgt_size, tolerance=0.1 * min(ref.scale))
    wx, wy = _hat_matrix(cols, node_x), _hat_matrix(rows, node_y)
    q = np.where(ok[:, None], q, 0.0)
    map_x = wy @ q[:, 0].reshape(ny, nx) @ wx.T
    map_y = wy @ q[:, 1].reshape(ny, nx) @ wx.T
    covered = (wy @ ok.reshape(ny, nx).astype(float) @ wx.T) > 0.999
    map_x = (map_x / tgt.scale[0] - 0.5).astype(np.float32)
    map_y = (map_y / tgt.scale[1] - 0.5).astype(np.float32)
    warped = cv2.remap(tgt.image, map_x, map_y, cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    inside = cv2.remap(tgt.valid.astype(np.uint8), map_x, map_y, cv2.INTER_NEAREST,
                       borderMode=cv2.BORDER_CONSTANT, borderValue=0) > 0
    return warped, inside & covered


def _hat_matrix(n: int, nodes: np.ndarray) -> np.ndarray:
    """(n, len(nodes)) weights of linear interpolation between evenly spaced ``nodes`` at pixel
    centres ``i + 0.5``."""
    x = np.arange(n) + 0.5
    spacing = nodes[1] - nodes[0]
    return np.maximum(0.0, 1.0 - np.abs(x[:, None] - nodes[None, :]) / spacing)
