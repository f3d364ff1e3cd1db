"""SAR input handling: one normalisation used by every SAR-specific stage.

SAR rasters come as amplitude, intensity (power), decibels or complex (read as amplitude by
:mod:`hamta.core.io.raster`), often with heavy tails (bright point scatterers in uint16 data).
:func:`normalised_amplitude` turns any of them into amplitude divided by its 99th percentile and
clipped to [eps, 1]. ROEWA ratios, the diffusion contrast factor K, the DoG contrast threshold and
phase congruency all see this same array, so their thresholds mean the same on every sensor.
"""
from __future__ import annotations

import cv2
import numpy as np

from .normalize import valid_sample

SAR_UNITS = ("amplitude", "intensity", "db")
EPS = 1e-3


def to_amplitude(data: np.ndarray, units: str) -> np.ndarray:
    """Amplitude from ``units``: amplitude (as is), intensity (square root), db (10 log10 intensity)."""
    if units not in SAR_UNITS:
        raise ValueError(f"SAR units must be one of {SAR_UNITS}, got {units!r}")
    if units == "intensity":
        return np.sqrt(np.maximum(data, 0.0))
    if units == "db":
        return np.power(10.0, data / 20.0)
    return np.abs(data)


def normalised_amplitude(data: np.ndarray, valid: np.ndarray, units: str = "amplitude",
                         percentile: float = 99.0) -> np.ndarray:
    """float32 amplitude / its ``percentile`` over valid pixels, clipped to [EPS, 1]; invalid -> EPS."""
    amp = to_amplitude(data.astype(np.float64), units)
    values = valid_sample(amp, valid)
    scale = float(np.percentile(values, percentile)) if values.size else 1.0
    out = np.clip(amp / max(scale, 1e-12), EPS, 1.0)
    out[~valid] = EPS
    return out.astype(np.float32)


def log_scaled(amplitude: np.ndarray) -> np.ndarray:
    """log of a :func:`normalised_amplitude` array mapped to [0, 1] (EPS -> 0, 1 -> 1): multiplicative
    speckle becomes additive noise of the same strength in dark and bright areas."""
    return (np.log(amplitude) / -np.log(EPS) + 1.0).astype(np.float32)


def lee_filter(image: np.ndarray, looks: float = 1.0, window: int = 7, units: str = "intensity") -> np.ndarray:
    """Lee's local-statistics speckle filter (Lee 1980, IEEE TPAMI 2(2):165-168, eqs. 18-21).

    Multiplicative model z = x u with E[u] = 1 and var(u) = 1/L for L-look intensity or
    (4 - pi) / (pi L) for L-look amplitude. With local mean m and variance v over ``window`` x
    ``window`` (box filters): Q = max(0, (v + m^2) / (1 + s^2) - m^2), k = Q / (m^2 s^2 + Q),
    x = m + k (z - m). Homogeneous areas go to their mean, edges and point targets keep z.
    """
    if units not in ("intensity", "amplitude"):
        raise ValueError(f"Lee filter works on intensity or amplitude, got {units!r}")
    s2 = 1.0 / looks if units == "intensity" else (4.0 - np.pi) / (np.pi * looks)
    z = image.astype(np.float64)
    m = cv2.blur(z, (window, window), borderType=cv2.BORDER_REFLECT)
    v = np.maximum(cv2.blur(z * z, (window, window), borderType=cv2.BORDER_REFLECT) - m * m, 0.0)
    q = np.maximum((v + m * m) / (1.0 + s2) - m * m, 0.0)
    k = q / np.maximum(m * m * s2 + q, 1e-30)
    return (m + k * (z - m)).astype(np.float32)
