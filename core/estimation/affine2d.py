"""2-D affine (2 x 3) and projective (3 x 3) maps between image grids, and exact rescaling.

Every map takes corner-convention pixels of one image to corner-convention pixels of another
(see :mod:`hamta.core.coords`); OpenCV's pixel-centre convention is only used inside ``warp``.
"""
from __future__ import annotations

import math
from typing import Tuple

import cv2
import numpy as np

from ..coords import apply_matrix, matrix_corner_to_opencv


def _full(m) -> np.ndarray:
    m = np.asarray(m, float)
    return m if m.shape == (3, 3) else np.vstack([m, [0.0, 0.0, 1.0]])


def apply(matrix: np.ndarray, xy: np.ndarray) -> np.ndarray:
    """Points (N, 2) through a 2 x 3 affine or a 3 x 3 homography."""
    return apply_matrix(_full(matrix), xy)


def invert(matrix: np.ndarray) -> np.ndarray:
    inv = np.linalg.inv(_full(matrix))
    return inv if np.shape(matrix) == (3, 3) else inv[:2]


def similarity(angle_deg: float, scale: float, centre_from, centre_to) -> np.ndarray:
    """Rotation (clockwise as displayed) and scale taking ``centre_from`` to ``centre_to``."""
    a = math.radians(angle_deg)
    lin = scale * np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    return np.column_stack([lin, np.asarray(centre_to, float) - lin @ np.asarray(centre_from, float)])


def warp(image: np.ndarray, valid: np.ndarray, matrix: np.ndarray, shape) -> Tuple[np.ndarray, np.ndarray]:
    """``image`` resampled onto a ``shape`` grid through ``matrix`` (2 x 3 affine or 3 x 3
    homography, image px -> grid px), with its validity."""
    h, w = shape
    m = matrix_corner_to_opencv(_full(matrix))
    m, fn = (m, cv2.warpPerspective) if np.shape(matrix) == (3, 3) else (m[:2], cv2.warpAffine)
    out = fn(image.astype(np.float32), m, (w, h), flags=cv2.INTER_LINEAR, borderValue=0)
    ok = fn(valid.astype(np.uint8), m, (w, h), flags=cv2.INTER_NEAREST, borderValue=0) > 0
    return out, ok


def compose(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The 2 x 3 affine ``a`` after ``b`` (x -> a(b(x)))."""
    return (_full(a) @ _full(b))[:2]


def scaling(fx: float, fy: float = None) -> np.ndarray:
    """A pure rescaling (no offset in the corner convention)."""
    return np.array([[fx, 0.0, 0.0], [0.0, fx if fy is None else fy, 0.0]])


def angle_scale(m: np.ndarray) -> Tuple[float, float]:
    """(rotation in degrees, scale) of the similarity closest to the affine ``m``."""
    a = np.asarray(m, float)[:2, :2]
    return math.degrees(math.atan2(a[1, 0] - a[0, 1], a[0, 0] + a[1, 1])), math.sqrt(abs(np.linalg.det(a)))


def resize(image: np.ndarray, valid: np.ndarray, f: float):
    """``image`` and its validity rescaled by ``f`` (area averaging when shrinking), with the exact
    2 x 3 map from input px to output px."""
    h, w = image.shape[:2]
    size = (max(int(round(w * f)), 8), max(int(round(h * f)), 8))
    small = cv2.resize(image.astype(np.float32), size, interpolation=cv2.INTER_AREA if f < 1 else cv2.INTER_LINEAR)
    ok = cv2.resize(valid.astype(np.uint8), size, interpolation=cv2.INTER_NEAREST) > 0
    return small, ok, scaling(size[0] / w, size[1] / h)
