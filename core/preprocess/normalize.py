"""Radiometric normalisation of working images before feature detection."""
from __future__ import annotations

import numpy as np

_SAMPLE = 250_000  # valid pixels (an even stride through the image) used to estimate percentiles


def valid_sample(data: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """The valid pixels, or an even stride through them when there are many (for percentiles)."""
    values = data[valid]
    return values[:: values.size // _SAMPLE] if values.size > _SAMPLE else values


def percentile_range(data: np.ndarray, valid: np.ndarray, low: float = 0.5, high: float = 99.5):
    """Robust value range of the valid pixels (percentiles on a deterministic subsample)."""
    values = valid_sample(data, valid)
    lo, hi = np.percentile(values, [low, high])
    if hi <= lo:
        lo, hi = float(values.min()), float(values.max())
    return float(lo), float(hi)


def stretch_to_uint8(data: np.ndarray, valid: np.ndarray, low: float = 0.5, high: float = 99.5) -> np.ndarray:
    """Linear stretch of the [low, high] percentiles of valid pixels onto 0..255; invalid -> 0.

    Parameters
    ----------
    data : (H, W) float array, working pixels.
    valid : (H, W) bool mask.
    low, high : float
        Percentiles mapped to 0 and 255; clipping the tails makes uint16 and SAR-like data with
        heavy tails usable by 8-bit detectors.
    """
    lo, hi = percentile_range(data, valid, low, high)
    scale = 255.0 / max(hi - lo, 1e-12)
    out = np.clip((data - lo) * scale, 0, 255)
    out[~valid] = 0
    return (out + 0.5).astype(np.uint8)


def detection_mask(valid: np.ndarray, border_px: int = 3) -> np.ndarray:
    """uint8 mask (255 = usable) for OpenCV detectors: valid pixels away from invalid edges."""
    import cv2

    mask = valid.astype(np.uint8) * 255
    if border_px > 0:
        kernel = np.ones((2 * border_px + 1, 2 * border_px + 1), np.uint8)
        mask = cv2.erode(mask, kernel, borderType=cv2.BORDER_CONSTANT, borderValue=0)
    return mask
