"""The model's error as a field over the overlap: :func:`error_field` fits the agreeing sites'
offsets (a mean, a similarity, an affine or a quadratic field, by how many sites there are) and
gives its RMS over the overlap, an upper bound and the local scatter; :func:`shared_error` finds an
error field that contradicting clear sites share; :func:`site_coverage` measures how far the
supporting sites spread. Coordinates: sites, offsets and the ``extent`` points are full-resolution
reference pixels; fields are fitted in coordinates centred on the extent and scaled to about 1.
"""
from __future__ import annotations

import itertools
import math

import numpy as np


def error_field(sites: np.ndarray, offsets: np.ndarray, extent: np.ndarray):
    """(error, bound, scatter) in px from agreeing sites' offsets: the RMS over ``extent`` of an
    error field fitted to them (the mean offset with fewer than 4 sites, a similarity with 4 to 7,
    an affine from 8, and from 12 a quadratic field when the Bayesian information criterion prefers
    it: a projective or polynomial model's error curves, and an affine field fitted where the sites
    are would understate it toward the overlap's edges), the same plus two standard errors of the
    fit, and the residual scatter; all None without sites."""
    k = len(sites)
    if k == 0 or len(extent) == 0:
        return None, None, None
    centre = extent.mean(axis=0)
    scale = max(float(np.abs(extent - centre).max()), 1.0)
    order = 0 if k < 4 else (1 if k < 8 else 2)
    fits = [_field_fit(sites, offsets, extent, centre, scale, order)]
    if k >= 12:
        fits.append(_field_fit(sites, offsets, extent, centre, scale, 3))
    error, bound, scatter, _ = min(fits, key=lambda f: f[3])
    return error, bound, scatter


def _field_design(xy: np.ndarray, centre, scale: float, order: int) -> np.ndarray:
    """Rows (all x, then all y) of an error field's design: 0 a shift, 1 a similarity, 2 an affine,
    3 a quadratic field."""
    u = (xy - centre) / scale
    one, zero = np.ones(len(xy)), np.zeros(len(xy))
    cols = [(one, zero), (zero, one)]
    if order == 1:
        cols += [(u[:, 0], u[:, 1]), (-u[:, 1], u[:, 0])]
    elif order >= 2:
        terms = [u[:, 0], u[:, 1]] + ([u[:, 0] ** 2, u[:, 0] * u[:, 1], u[:, 1] ** 2] if order == 3 else [])
        cols += [(t, zero) for t in terms] + [(zero, t) for t in terms]
    return np.stack([np.concatenate(c) for c in cols], axis=1)


def _field_fit(sites, offsets, extent, centre, scale: float, order: int):
    """(error, bound, scatter, BIC) of one error field fitted to the sites' offsets."""
    a = _field_design(sites, centre, scale, order)
    b = np.concatenate([offsets[:, 0], offsets[:, 1]])
    coef, *_ = np.linalg.lstsq(a, b, rcond=None)
    resid = b - a @ coef
    rss = float(resid @ resid)
    dof = max(len(b) - a.shape[1], 1)
    sigma = max(math.sqrt(rss / dof), 0.1)
    e = _field_design(extent, centre, scale, order)
    field_xy = (e @ coef).reshape(2, -1).T
    error = float(np.sqrt(np.mean(np.sum(field_xy ** 2, axis=1))))
    cov = sigma ** 2 * np.linalg.pinv(a.T @ a)
    var = np.einsum("ij,jk,ik->i", e, cov, e).reshape(2, -1).sum(axis=0)  # per point, x + y
    se = float(np.sqrt(np.mean(var)))
    bic = len(b) * math.log(max(rss, 1e-6 * len(b)) / len(b)) + a.shape[1] * math.log(len(b))
    return error, error + 2.0 * se, float(np.sqrt(np.mean(resid ** 2) * 2)), bic


def shared_error(sites: np.ndarray, offsets: np.ndarray, extent: np.ndarray, radius: float):
    """RMS over ``extent`` of the affine error field that most clear sites share (within ``radius``
    of their offsets), when more sites share it than share no error at all; None otherwise.

    Contradicting sites scattered at random are local differences (parallax, change); contradicting
    sites that agree with one another are the model's own error (a turn or scale it missed)."""
    n = len(sites)
    if n < 4 or len(extent) == 0:
        return None
    support0 = int((np.linalg.norm(offsets, axis=1) <= radius).sum())
    centre = extent.mean(axis=0)
    scale = max(float(np.abs(extent - centre).max()), 1.0)
    a = np.column_stack([np.ones(n), (sites - centre) / scale])
    e = np.column_stack([np.ones(len(extent)), (extent - centre) / scale])
    triples = np.array(list(itertools.combinations(range(n), 3)))
    blocks = a[triples]
    ok = np.abs(np.linalg.det(blocks)) > 1e-6
    if not ok.any():
        return None
    coef = np.linalg.solve(blocks[ok], offsets[triples[ok]])  # (K, 3, 2) affine error fields
    support = (np.linalg.norm(offsets[None] - np.einsum("nj,kjc->knc", a, coef), axis=2) <= radius).sum(axis=1)
    k = int(np.argmax(support))
    if support[k] <= max(support0, 3):  # three sites fit any field: a shared one needs a fourth
        return None
    best_field = coef[k]
    inliers = np.linalg.norm(offsets - a @ best_field, axis=1) <= radius
    coef = np.linalg.lstsq(a[inliers], offsets[inliers], rcond=None)[0]
    return float(np.sqrt(np.mean(np.sum((e @ coef) ** 2, axis=1))))


def site_coverage(agreeing: np.ndarray, measured: np.ndarray) -> float:
    """The smaller of the two axes' spans of ``agreeing`` sites, as shares of ``measured`` sites' spans."""
    if len(agreeing) < 2 or len(measured) < 2:
        return 0.0
    span = np.ptp(measured, axis=0)
    spans = np.where(span > 0, np.ptp(agreeing, axis=0) / np.maximum(span, 1e-9), 1.0)
    return float(np.min(spans))
