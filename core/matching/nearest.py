"""Nearest-neighbour descriptor matching: Lowe's ratio test with optional cross-checks.

Lowe, D. G. (2004). Distinctive image features from scale-invariant keypoints. IJCV 60(2).
"""
from __future__ import annotations

import cv2
import numpy as np

from ..types import Features

CROSS_CHECKS = ("none", "mutual", "dual-ratio")


def match_features(a: Features, b: Features, *, ratio: float = 0.8, cross_check: str = "mutual"):
    """Match descriptors of ``a`` to ``b``.

    Parameters
    ----------
    a, b : Features
        Must use the same metric (L2 or Hamming), which selects the norm.
    ratio : float
        Keep a->b when the nearest distance is strictly below ``ratio`` times the second nearest
        (1.0 disables the test).
    cross_check : {'none', 'mutual', 'dual-ratio'}
        'mutual': b's nearest neighbour in ``a`` must be the same point. 'dual-ratio': the match
        must also pass the ratio test from b to a (the dual matching of BFSIFT).

    Returns
    -------
    index_a, index_b : (K,) int arrays
    score : (K,) float, ``1 - d1/d2`` (higher = more distinctive).
    """
    if a.metric != b.metric:
        raise ValueError(f"cannot match {a.metric} descriptors with {b.metric} descriptors")
    if cross_check not in CROSS_CHECKS:
        raise ValueError(f"cross_check must be one of {CROSS_CHECKS}, got {cross_check!r}")
    empty = (np.zeros(0, int), np.zeros(0, int), np.zeros(0))
    if len(a) < 2 or len(b) < 2:
        return empty
    ia, ib, d1, d2 = _two_nearest(a.descriptors, b.descriptors, a.metric)
    keep = d1 < ratio * d2 if ratio < 1.0 else np.ones(len(ia), bool)
    if cross_check != "none" and keep.any():
        # Only the b points some a point chose need their own nearest neighbours in a.
        cand = np.unique(ib[keep])
        jb, ja, e1, e2 = _two_nearest(b.descriptors[cand], a.descriptors, a.metric)
        back = np.full(len(b), -1)
        back_ok = np.ones(len(jb), bool) if cross_check == "mutual" or ratio >= 1.0 else e1 < ratio * e2
        back[cand[jb[back_ok]]] = ja[back_ok]
        keep &= back[ib] == ia
    ia, ib = ia[keep], ib[keep]
    with np.errstate(divide="ignore", invalid="ignore"):
        score = np.where(d2[keep] > 0, 1.0 - d1[keep] / d2[keep], 0.0)
    return ia, ib, score


def _two_nearest(query: np.ndarray, train: np.ndarray, metric: str):
    norm = cv2.NORM_HAMMING if metric == "hamming" else cv2.NORM_L2
    if metric == "l2":
        query, train = query.astype(np.float32, copy=False), train.astype(np.float32, copy=False)
    knn = cv2.BFMatcher(norm).knnMatch(query, train, k=2)
    pairs = [m for m in knn if len(m) == 2]
    qi = np.array([m[0].queryIdx for m in pairs], int)
    ti = np.array([m[0].trainIdx for m in pairs], int)
    d1 = np.array([m[0].distance for m in pairs], np.float64)
    d2 = np.array([m[1].distance for m in pairs], np.float64)
    return qi, ti, d1, d2
