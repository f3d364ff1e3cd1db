"""The sub-pixel peak of a correlation surface: the highest interior value, refined by a parabola
through it and its neighbours along each axis."""
from __future__ import annotations

from typing import Optional, Tuple

import numpy as np


def peak_offset(surface: np.ndarray, radius: int) -> Tuple[Optional[np.ndarray], float]:
    """Sub-pixel (dx, dy) of the highest interior peak of ``surface`` relative to its centre
    (``radius`` px from each side), and the peak value; None where the peak is on the border."""
    v, u = np.unravel_index(int(np.argmax(surface)), surface.shape)
    peak = surface[v, u]
    if not (0 < u < surface.shape[1] - 1 and 0 < v < surface.shape[0] - 1) or not np.isfinite(peak):
        return None, float(peak)
    dx = _parabola(surface[v, u - 1], surface[v, u], surface[v, u + 1])
    dy = _parabola(surface[v - 1, u], surface[v, u], surface[v + 1, u])
    return np.array([u + dx - radius, v + dy - radius]), float(peak)


def _parabola(a: float, b: float, c: float) -> float:
    den = a - 2 * b + c
    return 0.0 if den >= 0 else float(np.clip(0.5 * (a - c) / den, -0.5, 0.5))
