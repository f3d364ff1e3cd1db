"""Phase correlation (translation only): the frequency-domain anchor for small shifts.

Kuglin, C. D., & Hines, D. C. (1975). The phase correlation image alignment method. Proc. IEEE
Conf. on Cybernetics and Society, 163-165.

The single global shift is returned as a regular grid of correspondences over the target, so the
shared robust fit and outputs apply unchanged (any model fitted to them is that translation).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..matching.phase_correlation import phase_correlate
from ..progress import Monitor
from ..types import Matches
from .registry import Method, param, register_method, validate


@dataclass(frozen=True)
class PhaseCorrelationParams:
    """Parameters of the phase-correlation baseline."""

    grid: int = param(5, "Correspondences per side of the grid that carries the shift.", minimum=3)
    min_response: float = param(0.02, "Lowest accepted normalised correlation peak.", minimum=0.0, maximum=1.0)

    def __post_init__(self):
        validate(self)


def match(target, reference, params: PhaseCorrelationParams, monitor: Monitor, seed: int = 0) -> Matches:
    """Global translation between the working images, as a grid of correspondences."""
    shift, response = phase_correlate(target.data, reference.data, target.valid, reference.valid)
    monitor.report(1.0, "phase correlation")
    if response < params.min_response:
        return Matches.empty(1, 1)
    h, w = target.shape
    gx, gy = np.meshgrid(np.linspace(0.1 * w, 0.9 * w, params.grid), np.linspace(0.1 * h, 0.9 * h, params.grid))
    t = np.column_stack([gx.ravel(), gy.ravel()])
    return Matches(t, t + shift, np.full(len(t), response), 1, 1, {"shift_working_px": shift.tolist(),
                                                                    "response": response})


METHOD = register_method(Method(
    name="phasecorr",
    title="Phase correlation (translation only)",
    summary="One global sub-pixel shift from the normalised cross-power spectrum. Right for images that "
            "differ by a small translation only (e.g. a georeferencing offset); fails under rotation or scale.",
    citation="Kuglin & Hines 1975, Proc. IEEE Conf. Cybernetics and Society",
    params_type=PhaseCorrelationParams,
    match=match,
    default_model="similarity",
    kind="baseline",
    use_when="a pure shift between two images of one grid (the fastest check)"))
