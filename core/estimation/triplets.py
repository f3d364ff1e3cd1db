"""Triplet clustering, spec 003's future work: an affine transform from every triple of matches, the
densest cluster of those transforms, and the matches it explains (a robust estimator beside RANSAC)."""
from __future__ import annotations

import itertools
import math
from typing import Tuple

import numpy as np
from scipy.spatial import cKDTree

from .ransac import minimal_fits


def triplet_clustering(src, dst, *, radius_px: float, inlier_px: float, min_area_px2: float = 100.0,
                       scale_range: Tuple[float, float] = (0.01, 100.0), max_triplets: int = 5000, seed: int = 0):
    """The thesis's future work: an affine from every triple of matches (src -> dst), the transform
    with the most others within ``radius_px`` (compared by where they send three anchor points spread
    over the source points), the mean of its cluster, and the matches it maps within ``inlier_px``.

    Triples whose triangles are smaller than ``min_area_px2`` in either image, or whose scale is
    outside ``scale_range``, are skipped. Returns (2 x 3 matrix or None, inlier mask).
    """
    src, dst = np.asarray(src, float), np.asarray(dst, float)
    n = len(src)
    none = (None, np.zeros(n, bool))
    if n < 3:
        return none
    if math.comb(n, 3) <= max_triplets:
        tri = np.array(list(itertools.combinations(range(n), 3)), int)
    else:
        rng = np.random.default_rng(seed)
        tri = np.array([rng.choice(n, 3, replace=False) for _ in range(max_triplets)], int)

    def area(p):
        return 0.5 * np.abs((p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1])
                            - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1]))
    s3, d3 = src[tri], dst[tri]
    keep = (area(s3) >= min_area_px2) & (area(d3) >= min_area_px2)
    m, ok = minimal_fits("affine", s3[keep], d3[keep])
    m = m[:, :2]
    det = np.abs(m[:, 0, 0] * m[:, 1, 1] - m[:, 0, 1] * m[:, 1, 0])
    ok &= (det >= scale_range[0] ** 2) & (det <= scale_range[1] ** 2)
    m = m[ok]
    if len(m) == 0:
        return none
    lo, hi = src.min(axis=0), src.max(axis=0)
    anchors = np.array([[lo[0], lo[1], 1.0], [hi[0], lo[1], 1.0], [lo[0], hi[1], 1.0]])
    code = np.einsum("tij,aj->tai", m, anchors).reshape(len(m), 6)
    near = cKDTree(code).query_ball_point(code, radius_px, p=np.inf, return_length=True)
    best = int(np.argmax(near))
    member = np.abs(code - code[best]).max(axis=1) <= radius_px
    mean = m[member].mean(axis=0)
    err = np.linalg.norm(src @ mean[:, :2].T + mean[:, 2] - dst, axis=1)
    return mean, err <= inlier_px
