"""From correspondences to a linear model: outlier rejection with the run's rules, and the final fit.

Both stages take and return :class:`hamta.core.types.Correspondences` (full-resolution target and
reference pixels, corner convention) with the fit's inlier flags.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Optional

import numpy as np

from ..errors import InsufficientMatchesError
from ..types import Correspondences
from .framed import CrsFrame, fit_framed
from .models import MIN_POINTS, LinearModel, fit_model
from .ransac import ransac_or_none
from .spread import spread_subset


@dataclass(frozen=True)
class RobustRules:
    """How a run rejects outliers: the linear ``kind`` fitted, the fewest agreeing correspondences
    ``need``ed, the rule ('ransac', 'none' or 'triplets') and its ``seed``; ``method`` and
    ``target_path`` name the run in error messages."""

    kind: str
    need: int
    robust: str
    seed: int
    method: str
    target_path: str

    @classmethod
    def for_run(cls, model: str, options, method: str, target_path: str) -> "RobustRules":
        kind = model if model in ("similarity", "affine") else ("affine" if model == "linear" else "projective")
        need = max(options.min_inliers, MIN_POINTS[model] + 2)
        return cls(kind, need, options.robust, options.seed, method, target_path)


@dataclass(frozen=True, eq=False)
class Estimate:
    """A linear model (target px -> reference px), the correspondences it was fitted among (inlier
    flags set), the inlier tolerance in reference px, and whether the points were refined at full
    resolution."""

    model: LinearModel
    points: Correspondences
    threshold_px: float
    refined: bool = False


def robust_linear(points: Correspondences, threshold_px: float, rules: RobustRules, robust: Optional[str] = None,
                  refined: bool = False) -> Estimate:
    """Reject outliers among ``points`` and fit ``rules.kind`` on the rest.

    Raises
    ------
    InsufficientMatchesError
        Too few correspondences, or too few agreeing on one transform; it carries ``points``.
    """
    robust = robust or rules.robust
    tgt, ref, n = points.target_px, points.reference_px, len(points)
    if n < rules.need:
        raise _insufficient(
            f"Method '{rules.method}' found only {n} candidate correspondences for '{rules.target_path}' (at least "
            f"{rules.need} are needed). The images may not overlap, or differ too much for this method.",
            n, rules.need, points)
    if robust == "none":
        model, inliers = LinearModel.fit(rules.kind, tgt, ref), np.ones(n, bool)
    elif robust == "triplets":
        from .triplets import triplet_clustering  # scipy.spatial: loaded only when asked for

        _, inliers = triplet_clustering(tgt, ref, radius_px=4 * threshold_px, inlier_px=threshold_px, seed=rules.seed)
        model = LinearModel.fit(rules.kind, tgt[inliers], ref[inliers]) if inliers.sum() >= rules.need else None
    else:
        model, inliers = ransac_or_none(tgt, ref, rules.kind, threshold_px=threshold_px, rng=rules.seed)
    if model is None or inliers.sum() < rules.need:
        raise _insufficient(
            f"Only {int(inliers.sum())} of {n} correspondences found by '{rules.method}' for '{rules.target_path}' "
            f"agree on one {rules.kind} transform (at least {rules.need} are needed). The images may not overlap, "
            "or differ too much for this method.", int(inliers.sum()), rules.need, points)
    return Estimate(model, replace(points, inlier=inliers), threshold_px, refined)


def _insufficient(message: str, found: int, needed: int, points: Correspondences) -> InsufficientMatchesError:
    exc = InsufficientMatchesError(message, found, needed)
    exc.correspondences = replace(points, inlier=np.zeros(len(points), bool))
    return exc


@dataclass(frozen=True, eq=False)
class FinalFit:
    """The requested model fitted on well-spread inliers: ``used`` indexes ``points`` (the GCPs)."""

    model: object
    points: Correspondences
    used: np.ndarray
    refined: bool


def final_fit(kind: str, estimate: Estimate, max_gcps: int, frame: Optional[CrsFrame]) -> FinalFit:
    """Fit ``kind`` on at most ``max_gcps`` well-spread inliers of ``estimate``; for the polynomial
    models the inlier set is first re-selected with their own residuals (they bend where a linear
    model cannot). With a ``frame``, the model is fitted in the target's own CRS frame."""
    p, inliers = estimate.points, estimate.points.inlier
    if kind not in ("similarity", "affine", "projective", "tps") and not inliers.all():
        for _ in range(5):
            model = _fit(kind, p.target_px[inliers], p.reference_px[inliers], frame)
            new = model.residuals(p.target_px, p.reference_px) < estimate.threshold_px
            if np.array_equal(new, inliers) or new.sum() < MIN_POINTS[kind]:
                break
            inliers = new
    idx = distinct(np.flatnonzero(inliers), p)
    if len(idx) < MIN_POINTS[kind]:
        raise InsufficientMatchesError(f"only {len(idx)} distinct agreeing points; the {kind} model needs "
                                       f"{MIN_POINTS[kind]}", len(idx), MIN_POINTS[kind])
    used = idx[spread_subset(p.reference_px[idx], p.score[idx], max_gcps)]
    model = _fit(kind, p.target_px[used], p.reference_px[used], frame)
    return FinalFit(model, replace(p, inlier=inliers), used, estimate.refined)


def distinct(idx: np.ndarray, points) -> np.ndarray:
    """``idx`` without repeated places: where several points share a target pixel or a reference
    pixel (matches of one keypoint at several orientations, or refined onto one spot), the best
    scored is kept, so no GCP is listed twice. Returns sorted indexes into ``points``."""
    idx = idx[np.argsort(-points.score[idx], kind="stable")]
    for xy in (points.target_px, points.reference_px):
        _, first = np.unique(np.round(xy[idx], 6), axis=0, return_index=True)
        idx = idx[np.sort(first)]
    return np.sort(idx)


def _fit(kind, src, dst, frame):
    if frame is None:
        return fit_model(kind, src, dst)
    return fit_framed(lambda s, d: fit_model(kind, s, d), frame, src, dst)
