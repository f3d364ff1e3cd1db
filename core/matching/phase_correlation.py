"""Phase correlation: the translation between two images from their normalised cross-power spectrum.

Kuglin, C. D., & Hines, D. C. (1975). The phase correlation image alignment method. Proc. IEEE
Conference on Cybernetics and Society, 163-165. Sub-pixel peak by OpenCV's weighted centroid
(``cv2.phaseCorrelate``) on Hann-windowed images.
"""
from __future__ import annotations

from typing import Tuple

import cv2
import numpy as np


def phase_correlate(moving: np.ndarray, fixed: np.ndarray, valid_moving: np.ndarray,
                    valid_fixed: np.ndarray) -> Tuple[np.ndarray, float]:
    """Shift (dx, dy) such that ``fixed(p + shift) ~ moving(p)``, and the peak response (0..1).

    Both images are zero-padded to a common power-of-two-friendly size; invalid pixels are set to
    each image's valid mean so that nodata borders do not dominate the spectrum.
    """
    h = max(moving.shape[0], fixed.shape[0])
    w = max(moving.shape[1], fixed.shape[1])
    size = (cv2.getOptimalDFTSize(h), cv2.getOptimalDFTSize(w))
    a = _prepared(moving, valid_moving, size)
    b = _prepared(fixed, valid_fixed, size)
    window = cv2.createHanningWindow((size[1], size[0]), cv2.CV_64F)
    (dx, dy), response = cv2.phaseCorrelate(a, b, window)
    return np.array([dx, dy]), float(response)


def _prepared(img: np.ndarray, valid: np.ndarray, size) -> np.ndarray:
    out = np.zeros(size, np.float64)
    mean = float(img[valid].mean()) if valid.any() else 0.0
    patch = np.where(valid, img, mean).astype(np.float64) - mean
    out[: img.shape[0], : img.shape[1]] = patch
    return out
