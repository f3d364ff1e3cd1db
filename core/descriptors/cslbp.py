"""The standard CS-LBP descriptor: the baseline RILBP is measured against.

Heikkilä, M., Pietikäinen, M., & Schmid, C. (2009). Description of interest regions with local
binary patterns. Pattern Recognition, 42(3), 425-436. :DOI:`10.1016/j.patcog.2008.08.014`

On a region already rotated to its dominant orientation: centre-symmetric LBP codes (N = 8
neighbours on a circle of radius 1, bilinear, threshold T on intensities scaled to [0, 1]),
16-bin histograms on a 4 x 4 grid with bilinear spatial interpolation of the votes
(256 dimensions), then L2 normalisation, clipping at 0.2 and renormalisation (Heikkilä 2009).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .normalise import l2_normalise


@dataclass(frozen=True)
class CslbpParams:
    radius: int = 20
    grid: int = 4
    neighbours: int = 8
    lbp_radius: float = 1.0
    threshold: float = 0.01  # on intensities scaled to [0, 1] (Heikkilä 2009)
    clip: float = 0.2

    @property
    def margin(self) -> int:
        return int(math.ceil(self.lbp_radius)) + 1


def cslbp_descriptors(patches: np.ndarray, params: CslbpParams = CslbpParams()) -> np.ndarray:
    """(K, grid^2 * 16) float32 descriptors of (K, S, S) oriented patches (0..255 intensities)."""
    k, size, _ = patches.shape
    c, r = size // 2, params.radius
    dim = params.grid ** 2 * 2 ** (params.neighbours // 2)
    if k == 0:
        return np.zeros((0, dim), np.float32)
    img = patches.astype(np.float32) / np.float32(255.0)
    t = 2 * math.pi * np.arange(params.neighbours) / params.neighbours
    ys, xs = np.mgrid[-r:r + 1, -r:r + 1]
    nb = []
    for a in t:
        nb.append(_shifted(img, params.lbp_radius * math.cos(a), -params.lbp_radius * math.sin(a), c, r))
    n_half = params.neighbours // 2
    codes = np.zeros((k, 2 * r + 1, 2 * r + 1), np.int64)
    for b in range(n_half):
        codes |= ((nb[b] - nb[b + n_half]) > params.threshold).astype(np.int64) << b
    # bilinear spatial interpolation over the grid cells
    g = params.grid
    fx = (xs + r + 0.5) / (2 * r + 1) * g - 0.5
    fy = (ys + r + 0.5) / (2 * r + 1) * g - 0.5
    x0, y0 = np.floor(fx).astype(int), np.floor(fy).astype(int)
    bins = 2 ** n_half
    desc = np.zeros(k * dim)
    for dx in (0, 1):
        for dy in (0, 1):
            cx, cy = x0 + dx, y0 + dy
            w = (1 - np.abs(fx - cx)) * (1 - np.abs(fy - cy))
            ok = (cx >= 0) & (cx < g) & (cy >= 0) & (cy < g) & (w > 0)
            cell = (cy * g + cx)[ok]
            index = (np.arange(k)[:, None] * dim + cell[None] * bins + codes[:, ok]).ravel()
            desc += np.bincount(index, weights=np.broadcast_to(w[ok], (k, ok.sum())).ravel(), minlength=k * dim)
    return l2_normalise(desc.reshape(k, dim), params.clip)


def _shifted(img, dx, dy, c, r):
    """Bilinear samples of every (K, S, S) patch at (x + dx, y + dy) over the (2r+1)^2 centre."""
    dx, dy = round(dx, 9), round(dy, 9)
    x0, y0 = int(math.floor(dx)), int(math.floor(dy))
    fx, fy = dx - x0, dy - y0

    def at(ox, oy):
        return img[:, c - r + oy:c + r + 1 + oy, c - r + ox:c + r + 1 + ox]

    out = None
    for ox, oy, w in ((x0, y0, (1 - fx) * (1 - fy)), (x0 + 1, y0, fx * (1 - fy)), (x0, y0 + 1, (1 - fx) * fy),
                      (x0 + 1, y0 + 1, fx * fy)):
        if w > 1e-12:
            term = at(ox, oy) * np.float32(w)
            out = term if out is None else out + term
    return out
