"""SAR input handling: one normalisation used by every SAR-specific stage.

SAR rasters come as amplitude, intensity (power), decibels or complex (read as amplitude by
:mod:`hamta.core.io.raster`), often with heavy tails (bright point scatterers in uint16 data).
:func:`normalised_amplitude` turns any of them into amplitude divided by its 99th percentile and
clipped to [eps, 1]. ROEWA ratios, the diffusion contrast factor K, the DoG contrast threshold and
phase congruency all see this same array, so their thresholds mean the same on every sensor.
"""
from __future__ import annotations

import numpy as np

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
    values = amp[valid]
    if values.size > 250_000:
        values = values[:: values.size // 250_000]
    scale = float(np.percentile(values, percentile)) if values.size else 1.0
    out = np.clip(amp / max(scale, 1e-12), EPS, 1.0)
    out[~valid] = EPS
    return out.astype(np.float32)
