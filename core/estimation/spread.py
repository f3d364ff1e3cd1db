"""Choosing well-spread points: GCPs and refinement sites should cover the overlap, not cluster."""
from __future__ import annotations

import numpy as np

from ..coords import as_xy


def spread_subset(xy: np.ndarray, score: np.ndarray, limit: int) -> np.ndarray:
    """Indexes of at most ``limit`` points spread over their bounding box, best ``score`` per cell."""
    xy = as_xy(xy)
    n = len(xy)
    if n <= limit:
        return np.arange(n)
    cells = max(1, int(np.ceil(np.sqrt(limit))))
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    span = np.maximum(hi - lo, 1e-9)
    cx = np.minimum((cells * (xy[:, 0] - lo[0]) / span[0]).astype(int), cells - 1)
    cy = np.minimum((cells * (xy[:, 1] - lo[1]) / span[1]).astype(int), cells - 1)
    cell = cy * cells + cx
    order = np.lexsort((-score, cell))
    first = order[np.r_[True, cell[order][1:] != cell[order][:-1]]]
    rest = np.setdiff1d(order, first, assume_unique=True)
    rest = rest[np.argsort(-score[rest], kind="stable")]
    chosen = np.concatenate([first[np.argsort(-score[first], kind="stable")], rest])[:limit]
    return np.sort(chosen)
