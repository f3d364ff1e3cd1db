"""The target pixels that a model maps onto given reference pixels.

Linear models invert exactly; the others (polynomial, thin plate spline, CRS-framed) are solved by
Newton's method from the least-squares affine inverse over the target. With ``fixed_jacobian`` the
steps use that affine inverse throughout (the chord method: one model evaluation per step, which
converges as fast for a smooth model that departs little from affine, such as a local
correction's spline); otherwise the Jacobian is taken at every point and step.

Coordinates: reference px in, target px out (corner convention).
"""
from __future__ import annotations

from typing import Tuple

import numpy as np

from ..coords import as_xy
from .models import local_jacobian

TOLERANCE_PX = 1e-3  # stop when every point maps within this (reference px) or moves less


def invert_model(model, reference_xy, target_size, tolerance: float = 0.05, iterations: int = 12,
                 fixed_jacobian: bool = False) -> Tuple[np.ndarray, np.ndarray]:
    """(target px, ok): where ``model`` maps onto ``reference_xy``, and where that inverse holds (the
    model maps the solution back within ``tolerance`` reference px). A solution may lie off the
    target (``target_size`` = width, height); callers mask those pixels."""
    p = as_xy(reference_xy)
    if hasattr(model, "inverse"):
        q = model.inverse().apply(p)
        with np.errstate(invalid="ignore", over="ignore"):
            back = np.linalg.norm(model.apply(np.nan_to_num(q)) - p, axis=1)
    else:
        q, back = _newton(model, p, target_size, iterations, fixed_jacobian)
    with np.errstate(invalid="ignore"):
        ok = np.isfinite(q).all(axis=1) & (back < tolerance)
    return q, ok


def _newton(model, p: np.ndarray, target_size, iterations: int, fixed_jacobian: bool):
    """(q, |model(q) - p|) after Newton (or chord) steps from the least-squares affine inverse."""
    w, h = target_size
    gx, gy = np.meshgrid(np.linspace(0, w, 9), np.linspace(0, h, 9))
    src = np.column_stack([gx.ravel(), gy.ravel()])
    approx = np.linalg.lstsq(np.column_stack([model.apply(src), np.ones(len(src))]), src, rcond=None)[0]
    q = np.column_stack([p, np.ones(len(p))]) @ approx
    with np.errstate(all="ignore"):
        for _ in range(iterations):
            r = p - model.apply(q)
            finite = np.isfinite(r).all(axis=1)
            if not finite.any() or np.abs(r[finite]).max() < TOLERANCE_PX:
                return q, np.where(finite, np.linalg.norm(r, axis=1), np.inf)
            if fixed_jacobian:
                step = r @ approx[:2]
            else:
                j = local_jacobian(model, q)
                det = j[:, 0, 0] * j[:, 1, 1] - j[:, 0, 1] * j[:, 1, 0]
                good = np.abs(det) > 1e-12
                step = np.zeros_like(q)
                step[good] = np.linalg.solve(j[good], r[good][..., None])[..., 0]
            q = q + step
            if np.abs(step[np.isfinite(step)]).max(initial=0.0) < TOLERANCE_PX:
                break
        back = np.linalg.norm(model.apply(np.nan_to_num(q)) - p, axis=1)
    return q, back
