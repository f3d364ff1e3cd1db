"""The model's error as a field over the overlap.

:func:`error_field` fits sites' offsets with a field (a mean, a similarity, an affine or a quadratic
field, by how many sites there are) and gives its RMS over the overlap, an upper bound and the local
scatter. :func:`model_error` gives the agreeing sites' field and looks for an affine field that more
sites share than agree with the model (a turn or a scale the model missed). :func:`site_coverage`
measures how far the supporting sites spread.

Coordinates: sites, offsets and the ``extent`` points are full-resolution reference pixels; fields
are fitted in coordinates centred on the extent and scaled to about 1.
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np

BOUND_SE = 2.0  # standard errors above the debiased error: the bound (see FieldFit.bound)
# Site offsets read about 10 % short of a true shift (the sub-pixel peak and the resampling flatten it toward
# zero: 1.41-1.89 px measured for shifts of 1.5-2 px on the calibration study), a systematic part no number of
# sites averages away; its share of the error counts in the bound's standard error.
OFFSET_SHARE = 0.1
SHARED_MARGIN = 3  # sites a shared field must gain over the agreeing ones: three sites fit any affine field


@dataclass(frozen=True, eq=False)
class FieldFit:
    """An error field fitted to sites' offsets: its RMS over the extent (``error``), the standard error
    of that RMS (``se``: the RMS over the extent of the field's standard error), the residual scatter
    of the sites, the Bayesian information criterion of the fit, and its coefficients."""

    error: float
    se: float
    scatter: float
    bic: float
    coef: np.ndarray
    centre: np.ndarray
    scale: float
    order: int

    @property
    def bound(self) -> float:
        """An upper bound of the true RMS error: the RMS of the fitted field is inflated by the noise of the
        fit (its square's expectation is the true square plus ``se`` squared), so the debiased estimate
        plus ``BOUND_SE`` standard errors (about 97.5 % one-sided when the noise is normal), the systematic
        ``OFFSET_SHARE`` of the offsets added to the standard error."""
        se = math.hypot(self.se, OFFSET_SHARE * self.error)
        return math.sqrt(max(self.error ** 2 - self.se ** 2, 0.0)) + BOUND_SE * se

    def predict(self, xy: np.ndarray) -> np.ndarray:
        """The field's offsets (K, 2) at reference px ``xy``."""
        return (_field_design(xy, self.centre, self.scale, self.order) @ self.coef).reshape(2, -1).T


def error_field(sites: np.ndarray, offsets: np.ndarray, extent: np.ndarray):
    """(error, bound, scatter) in px of the field :func:`fit_field` fits; all None without sites."""
    fit = fit_field(sites, offsets, extent)
    return (None, None, None) if fit is None else (fit.error, fit.bound, fit.scatter)


def fit_field(sites: np.ndarray, offsets: np.ndarray, extent: np.ndarray) -> Optional[FieldFit]:
    """The error field of sites' ``offsets``: their mean with fewer than 4 sites, a similarity with 4 to
    7, an affine from 8, and from 12 a quadratic field when the Bayesian information criterion prefers it
    (a projective or polynomial model's error curves, and an affine field fitted where the sites are
    would understate it toward the overlap's edges). None without sites."""
    k = len(sites)
    if k == 0 or len(extent) == 0:
        return None
    centre = extent.mean(axis=0)
    scale = max(float(np.abs(extent - centre).max()), 1.0)
    order = 0 if k < 4 else (1 if k < 8 else 2)
    fits = [_field_fit(sites, offsets, extent, centre, scale, order)]
    if k >= 12:
        fits.append(_field_fit(sites, offsets, extent, centre, scale, 3))
    return min(fits, key=lambda f: f.bic)


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


def _field_fit(sites, offsets, extent, centre, scale: float, order: int) -> FieldFit:
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
    return FieldFit(error, se, float(np.sqrt(np.mean(resid ** 2) * 2)), bic, coef, centre, scale, order)


def model_error(sites: np.ndarray, offsets: np.ndarray, agree: np.ndarray, usable: np.ndarray, extent: np.ndarray,
                radius: float) -> Tuple[Optional[FieldFit], Optional[float]]:
    """(the error field of the sites that ``agree``, the RMS of an error field that ``usable`` sites share,
    or None).

    ``usable`` sites have an interior peak worth reading. A field that more of them share than agree
    with the model (by at least ``SHARED_MARGIN``) is the model's own error: contradicting sites that
    agree with one another show a turn or a scale the model missed, which moves the sites far from the
    overlap's centre beyond the agreement radius (where a field fitted to the agreeing sites alone
    would not see it); scattered ones are local differences (parallax, change, modality)."""
    fit = fit_field(sites[agree], offsets[agree], extent)
    shared = _shared(sites, offsets, usable, extent, radius)
    if shared is None or shared.sum() < agree.sum() + SHARED_MARGIN:
        return fit, None
    return fit, fit_field(sites[shared], offsets[shared], extent).error


def _shared(sites, offsets, usable, extent, radius) -> Optional[np.ndarray]:
    """The ``usable`` sites that share the affine field most of them share, within ``radius`` (three sites
    define one; a field is tried through every triple); None with fewer than four usable sites."""
    idx = np.nonzero(usable)[0]
    n = len(idx)
    if n < 4:
        return None
    centre = extent.mean(axis=0)
    scale = max(float(np.abs(extent - centre).max()), 1.0)
    a = np.column_stack([np.ones(n), (sites[idx] - centre) / scale])
    o = offsets[idx]
    triples = np.array(list(itertools.combinations(range(n), 3)))
    blocks = a[triples]
    ok = np.abs(np.linalg.det(blocks)) > 1e-6
    if not ok.any():
        return None
    coef = np.linalg.solve(blocks[ok], o[triples[ok]])  # (K, 3, 2) affine error fields
    support = (np.linalg.norm(o[None] - np.einsum("nj,kjc->knc", a, coef), axis=2) <= radius).sum(axis=1)
    best = coef[int(np.argmax(support))]
    out = np.zeros(len(sites), bool)
    out[idx] = np.linalg.norm(o - a @ best, axis=1) <= radius
    return out


def site_coverage(agreeing: np.ndarray, measured: np.ndarray) -> float:
    """The smaller of the two axes' spans of ``agreeing`` sites, as shares of ``measured`` sites' spans."""
    if len(agreeing) < 2 or len(measured) < 2:
        return 0.0
    span = np.ptp(measured, axis=0)
    spans = np.where(span > 0, np.ptp(agreeing, axis=0) / np.maximum(span, 1e-9), 1.0)
    return float(np.min(spans))
