"""The model's order chosen by the check: where the user left the model to the method and the points bend
away from its linear model (a large footprint across projections, a scanned sheet), a second-order polynomial
is fitted on the same points, checked by the same independent verification, and kept only when the check
judges it better (:func:`hamta.core.verify.beats`; never by the fit's own residuals). Coordinates: target
pixels to full-resolution reference pixels.
"""
from __future__ import annotations

import math
from typing import Optional

import numpy as np

from .errors import InsufficientMatchesError
from .estimation.models import MIN_POINTS
from .estimation.robust import Estimate, FinalFit, final_fit
from .verify import error_bound

HIGHER = "polynomial-2"
LINEAR = ("similarity", "affine", "projective")
MIN_INLIERS = 30
# The points must span this share of the target's width and height: a polynomial bends freely beyond its points.
MIN_SPAN = 0.6
# The bend must be significant: the second order's extra coefficients fit the points better than noise does with this
# probability at most (an F test of the residuals)...
MAX_CHANCE = 1e-6
# ... and the two models must differ over the points' extent by this share of the tolerance (0.5 px of the default
# 3 px) before the second is worth a check (a few tenths of a second); the check then decides.
MIN_BEND_SHARE = 1 / 6


def bent_fit(kind: str, fit: FinalFit, estimate: Estimate, width: int, height: int, tolerance_px: float,
             max_gcps: int, frame) -> Optional[FinalFit]:
    """A second-order fit of ``estimate``'s points when the linear ``fit`` (of ``kind``) leaves a bend worth
    checking, else None. ``width`` and ``height``: the target's, pixels."""
    if kind not in LINEAR:
        return None
    points = fit.points
    src, dst = points.target_px[points.inlier], points.reference_px[points.inlier]
    if len(src) < MIN_INLIERS or (np.ptp(src, axis=0) / np.array([width, height], float) < MIN_SPAN).any():
        return None
    try:
        bent = final_fit(HIGHER, estimate, max_gcps, frame)
    except (InsufficientMatchesError, ValueError, np.linalg.LinAlgError):
        return None
    straight, curved = (np.sum(m.residuals(src, dst) ** 2) for m in (fit.model, bent.model))
    extra, left = 2 * (MIN_POINTS[HIGHER] - MIN_POINTS[kind]), 2 * len(src) - 2 * MIN_POINTS[HIGHER]
    if curved <= 0 or f_tail((straight - curved) / extra / (curved / left), extra, left) > MAX_CHANCE:
        return None
    gx, gy = np.meshgrid(*(np.linspace(lo, hi, 10) for lo, hi in zip(src.min(axis=0), src.max(axis=0))))
    grid = np.column_stack([gx.ravel(), gy.ravel()])
    difference = bent.model.apply(grid) - fit.model.apply(grid)
    if np.sqrt(np.mean(np.sum(difference ** 2, axis=1))) < MIN_BEND_SHARE * tolerance_px:
        return None
    return bent


def order_note(kind: str, linear, bent, kept: bool) -> str:
    """The result's note on the order tried: which model the check kept, and by what bounds."""
    bounds = (f"the check bounds {HIGHER} at {error_bound(bent):.2f} px ({bent.verdict}), {kind} at "
              f"{error_bound(linear):.2f} px ({linear.verdict})")
    if kept:
        return f"model {HIGHER} chosen by the check, the points bending away from the {kind} model: {bounds}"
    return f"model {HIGHER} tried and not kept: {bounds}"


def f_tail(f: float, d1: int, d2: int) -> float:
    """P(F > ``f``) for Fisher's F with ``d1`` (even) and ``d2`` degrees of freedom: the regularised incomplete beta
    function I_x(d2/2, d1/2), x = d2 / (d2 + d1 f), summed in closed form (its second argument is whole)."""
    if f <= 0:
        return 1.0
    a, x = d2 / 2, d2 / (d2 + d1 * f)
    terms = (math.lgamma(a + k) - math.lgamma(a) - math.lgamma(k + 1) + a * math.log(x) + k * math.log1p(-x)
             for k in range(d1 // 2))
    return min(1.0, sum(math.exp(t) for t in terms))
