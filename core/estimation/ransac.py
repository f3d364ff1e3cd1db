"""Seeded LO-RANSAC for similarity, affine and projective models.

Fischler, M. A., & Bolles, R. C. (1981). Random sample consensus. Communications of the ACM,
24(6), 381-395. :DOI:`10.1145/358669.358692`; hypotheses are scored with MSAC (Torr & Zisserman
2000) and the best one is polished by iterated least squares on its inliers (LO-RANSAC, Chum et
al. 2003).

Hypotheses are generated and scored in vectorised batches; the generator is seeded, so a run is
reproducible. OpenCV's estimators are not used because ``estimateAffinePartial2D`` takes no
seed and none of them lets us score with the same truncated loss across all three models.
"""
from __future__ import annotations

import math
from typing import Optional, Tuple

import numpy as np

from ..coords import apply_matrix, as_xy
from ..errors import NoConsensusError
from .models import MIN_POINTS, LinearModel

RANSAC_KINDS = ("similarity", "affine", "projective")
_BATCH = 256


def _minimal_similarity(s: np.ndarray, d: np.ndarray):
    zs = s[..., 0] + 1j * s[..., 1]
    zd = d[..., 0] + 1j * d[..., 1]
    dz = zs[:, 1] - zs[:, 0]
    ok = np.abs(dz) > 1e-9
    a = np.where(ok, (zd[:, 1] - zd[:, 0]) / np.where(ok, dz, 1), 1)
    b = zd[:, 0] - a * zs[:, 0]
    m = np.zeros((len(s), 3, 3))
    m[:, 0, 0], m[:, 0, 1], m[:, 0, 2] = a.real, -a.imag, b.real
    m[:, 1, 0], m[:, 1, 1], m[:, 1, 2] = a.imag, a.real, b.imag
    m[:, 2, 2] = 1
    return m, ok


def _minimal_affine(s: np.ndarray, d: np.ndarray):
    a = np.concatenate([s, np.ones(s.shape[:2] + (1,))], axis=2)  # (K, 3, 3)
    det = np.linalg.det(a)
    ok = np.abs(det) > 1e-6
    a[~ok] = np.eye(3)
    coef = np.linalg.solve(a, d)  # (K, 3, 2)
    m = np.zeros((len(s), 3, 3))
    m[:, :2, :] = np.transpose(coef, (0, 2, 1))
    m[:, 2, 2] = 1
    return m, ok


def _minimal_projective(s: np.ndarray, d: np.ndarray):
    k = len(s)
    a = np.zeros((k, 8, 8))
    b = np.zeros((k, 8))
    x, y, u, v = s[..., 0], s[..., 1], d[..., 0], d[..., 1]
    a[:, 0::2, 0], a[:, 0::2, 1], a[:, 0::2, 2] = x, y, 1
    a[:, 0::2, 6], a[:, 0::2, 7] = -x * u, -y * u
    a[:, 1::2, 3], a[:, 1::2, 4], a[:, 1::2, 5] = x, y, 1
    a[:, 1::2, 6], a[:, 1::2, 7] = -x * v, -y * v
    b[:, 0::2], b[:, 1::2] = u, v
    ok = np.abs(np.linalg.det(a)) > 1e-10
    a[~ok] = np.eye(8)
    h = np.linalg.solve(a, b[..., None])[..., 0]
    m = np.concatenate([h, np.ones((k, 1))], axis=1).reshape(k, 3, 3)
    return m, ok


_MINIMAL = {"similarity": _minimal_similarity, "affine": _minimal_affine, "projective": _minimal_projective}


def minimal_fits(kind: str, src: np.ndarray, dst: np.ndarray):
    """Exact 3 x 3 transforms (K, 3, 3) of K minimal samples (K, m, 2) -> (K, m, 2), and a
    well-conditioned flag per sample."""
    return _MINIMAL[kind](np.asarray(src, float), np.asarray(dst, float))


def _squared_errors(m: np.ndarray, src: np.ndarray, dst: np.ndarray) -> np.ndarray:
    """(K, N) squared transfer errors of K hypotheses on N points, one ufunc at a time in place (a third of
    the time of ``einsum`` over a two-long axis, the same values); affine hypotheses skip the division."""
    x, y = src[:, 0], src[:, 1]

    def row(i: int) -> np.ndarray:
        out = m[:, i, 0, None] * x
        out += m[:, i, 1, None] * y
        out += m[:, i, 2, None]
        return out

    px, py = row(0), row(1)
    projective = bool(np.any(m[:, 2, :2]) or np.any(m[:, 2, 2] != 1.0))
    if projective:
        w = row(2)
        with np.errstate(divide="ignore", invalid="ignore"):  # points on a hypothesis' horizon: inf, below
            px /= w
            py /= w
    px -= dst[:, 0]
    py -= dst[:, 1]
    with np.errstate(over="ignore", invalid="ignore"):
        px *= px
        py *= py
        px += py
    if projective:
        px[~np.isfinite(px) | (w <= 0)] = np.inf
    return px


def ransac(src, dst, kind: str, *, threshold_px: float, max_trials: int = 5000,
           confidence: float = 0.999, rng=0, scale_range: Optional[Tuple[float, float]] = None
           ) -> Tuple[LinearModel, np.ndarray]:
    """Robustly fit a linear model from ``src`` (target px) to ``dst`` (reference px).

    Parameters
    ----------
    threshold_px : float
        Inlier tolerance on the transfer error, in ``dst`` pixels.
    max_trials : int
        Upper bound on hypotheses; fewer are drawn once ``confidence`` is reached.
    rng : int or numpy.random.Generator
        Seed; the same seed gives the same result.
    scale_range : (low, high), optional
        Minimal-sample hypotheses whose scale (sqrt |det| of the linear part) lies outside are
        discarded: a prior on scale.

    Returns
    -------
    model : LinearModel
        Least-squares fit on the final inliers.
    inliers : (N,) bool
        Raises :class:`NoConsensusError` (a ValueError too) when there are fewer points than a
        minimal sample or no hypothesis reaches the minimal inlier count.
    """
    if kind not in RANSAC_KINDS:
        raise ValueError(f"RANSAC supports {RANSAC_KINDS}, not {kind!r}")
    src0, dst0 = as_xy(src), as_xy(dst)
    n, m = len(src0), MIN_POINTS[kind]
    if n < m:
        raise NoConsensusError(f"{kind} RANSAC needs at least {m} correspondences, got {n}", n, m)
    rng = np.random.default_rng(rng)
    # Isotropic normalisation keeps the minimal solves well conditioned for any pixel range and
    # maps each model class onto itself.
    ts, td = _isotropic(src0), _isotropic(dst0)
    src, dst = apply_matrix(ts, src0), apply_matrix(td, dst0)
    t2 = (threshold_px * td[0, 0]) ** 2
    best_score, best_inliers = np.inf, None
    trials, needed = 0, max_trials
    while trials < min(needed, max_trials):
        idx = np.argsort(rng.random((_BATCH, n)), axis=1)[:, :m] if n <= 64 else _sample(rng, n, m)
        hyp, ok = _MINIMAL[kind](src[idx], dst[idx])
        if scale_range is not None:
            scale = np.sqrt(np.abs(np.linalg.det(hyp[:, :2, :2]))) * ts[0, 0] / td[0, 0]
            ok &= (scale >= scale_range[0]) & (scale <= scale_range[1])
        trials += _BATCH
        if not ok.any():
            continue
        hyp = hyp[ok]
        err = _squared_errors(hyp, src, dst)
        score = np.minimum(err, t2).sum(axis=1)
        k = int(np.argmin(score))
        if score[k] < best_score:
            best_score, best_inliers = score[k], err[k] < t2
            w = best_inliers.mean()
            needed = _trials_needed(w, m, confidence)
    if best_inliers is None or best_inliers.sum() < m:
        found = 0 if best_inliers is None else int(best_inliers.sum())
        raise NoConsensusError(f"no {kind} hypothesis gathered {m} inliers within {threshold_px:g} px", found, m)
    return polish(src0, dst0, kind, best_inliers, threshold_px)


def ransac_or_none(src, dst, kind: str, *, threshold_px: float, rng=0, **kwargs):
    """:func:`ransac`, or (None, no inliers) where no hypothesis gathers a minimal sample."""
    try:
        return ransac(src, dst, kind, threshold_px=threshold_px, rng=rng, **kwargs)
    except NoConsensusError:  # only that: a bug inside is not "no model"
        return None, np.zeros(len(src), bool)


def _isotropic(xy: np.ndarray) -> np.ndarray:
    c = xy.mean(axis=0)
    d = np.sqrt(((xy - c) ** 2).sum(axis=1)).mean()
    s = 1.0 / d if d > 0 else 1.0
    return np.array([[s, 0, -s * c[0]], [0, s, -s * c[1]], [0, 0, 1.0]])


def _sample(rng, n: int, m: int) -> np.ndarray:
    """Batch of m-subsets of range(n) without repeated indexes inside a row."""
    idx = rng.integers(0, n, size=(_BATCH, m))
    for _ in range(8):
        srt = np.sort(idx, axis=1)
        dup = (np.diff(srt, axis=1) == 0).any(axis=1)
        if not dup.any():
            break
        idx[dup] = rng.integers(0, n, size=(int(dup.sum()), m))
    return idx


def _trials_needed(inlier_ratio: float, m: int, confidence: float) -> int:
    good = inlier_ratio ** m
    if good <= 0:
        return 10 ** 9
    if good >= 1:
        return 1
    return int(math.ceil(math.log(1 - confidence) / math.log(1 - good)))


def polish(src, dst, kind: str, inliers: np.ndarray, threshold_px: float, iterations: int = 10):
    """Iterate least squares on the inliers and re-select inliers until the set is stable."""
    src, dst = as_xy(src), as_xy(dst)
    model = LinearModel.fit(kind, src[inliers], dst[inliers])
    for _ in range(iterations):
        new = model.residuals(src, dst) < threshold_px
        if new.sum() < MIN_POINTS[kind] or np.array_equal(new, inliers):
            break
        inliers = new
        model = LinearModel.fit(kind, src[inliers], dst[inliers])
    return model, inliers
