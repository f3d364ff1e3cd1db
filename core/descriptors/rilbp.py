"""RILBP: the rotation-invariant LBP descriptor of Sedaghat & Mohammadi (2019).

Sedaghat, A., & Mohammadi, N. (2019). Rotation invariant local binary pattern descriptor for
remote sensing image matching (in Persian). Journal of Geospatial Information Technology, 7(2),
223-239. Specification: ``../shared/specs/000_rilbp.md``.

A scale-normalised disk of radius R (20 px) is split into n rings (Eq. 3); each ring's pixels are
ranked by intensity and split into m_i equal-count sub-regions with m_i = round(A_i / a_1)
(Eqs. 4-5). Every pixel gets a centre-symmetric LBP code (N = 8 neighbours, 16 codes) sampled
bilinearly in its own radial frame (y axis from the centre to the pixel), so no dominant
orientation is needed; it votes into its sub-region's 16-bin histogram with the weight
w = w_Gaussian(sigma = R) x w_ring (Eqs. 6-8). The histograms are concatenated ring by ring,
brightest group first (Eqs. 9-10): 16 x (2 + 3 + 3) = 128 dimensions with the defaults.

Gaps the paper leaves are parameters with the spec's suggested defaults: ring radii
(0.5R, 0.8R, R), the only simple radii that give the paper's 128-D; LBP radius 1 (the paper's
figure); threshold T = 0 (exact gain/offset invariance); the centre pixel excluded (it has no
radial direction); the literal ring weight 1 - (d/h)^2; L2 normalisation.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Tuple

import numpy as np
from scipy import sparse

from .normalise import l2_normalise


@dataclass(frozen=True)
class RilbpParams:
    """RILBP settings (see the module docstring for which are the paper's and which fill gaps)."""

    radius: int = 20
    ring_fractions: Tuple[float, ...] = (0.5, 0.8, 1.0)
    m1: int = 2
    neighbours: int = 8
    lbp_radius: float = 1.0
    threshold: float = 0.0
    ring_weight: str = "literal"  # 'literal': 1 - (d/h)^2 ; 'border': 1 - (2d/h)^2 (zero at every border)
    exclude_center: bool = True
    clip: float = 0.0  # SIFT-style clipping after L2 normalisation (0 = off; not in the paper)

    @property
    def margin(self) -> int:
        return int(math.ceil(self.lbp_radius)) + 1


def round_half_away(x: float) -> int:
    """MATLAB-style rounding (the paper's), not numpy's round-half-to-even."""
    return int(math.floor(abs(x) + 0.5) * (1 if x >= 0 else -1))


def sub_region_counts(params: RilbpParams) -> Tuple[int, ...]:
    """m_i per ring by Eq. 4 from continuous ring areas: (2, 3, 3) with the defaults."""
    b = [0.0] + [f * params.radius for f in params.ring_fractions]
    areas = [math.pi * (b[i + 1] ** 2 - b[i] ** 2) for i in range(len(b) - 1)]
    a1 = areas[0] / params.m1
    return (params.m1,) + tuple(round_half_away(a / a1) for a in areas[1:])


def dimension(params: RilbpParams) -> int:
    return 2 ** (params.neighbours // 2) * sum(sub_region_counts(params))


@lru_cache(maxsize=8)
def _geometry(params: RilbpParams):
    """Per-pixel ring, weight and the sparse bilinear sampler of all polar neighbours."""
    r = params.radius
    half = r + params.margin
    size = 2 * half + 1
    ys, xs = np.mgrid[-r:r + 1, -r:r + 1]
    inside = xs ** 2 + ys ** 2 <= r * r
    if params.exclude_center:
        inside &= (xs != 0) | (ys != 0)
    x, y = xs[inside].astype(float), ys[inside].astype(float)
    rho = np.hypot(x, y)
    bounds = np.array([0.0] + [f * r for f in params.ring_fractions])
    ring = np.minimum(np.searchsorted(bounds, rho, side="right") - 1, len(bounds) - 2)
    ring[rho >= bounds[-1]] = len(bounds) - 2
    w_gauss = np.exp(-rho ** 2 / (2.0 * r * r)) / (2 * math.pi * r * r)
    inner, outer = bounds[ring], bounds[ring + 1]
    h = outer - inner
    d = np.where(ring == 0, rho, np.abs(rho - 0.5 * (inner + outer)))
    w_ring = 1 - (d / h) ** 2 if params.ring_weight == "literal" else 1 - (2 * d / h) ** 2
    weight = w_gauss * np.maximum(w_ring, 0.0)
    # polar frame: y axis from the centre to the pixel, x axis perpendicular (fixed handedness)
    with np.errstate(invalid="ignore", divide="ignore"):
        ey = np.column_stack([x / rho, y / rho])
    ey[~np.isfinite(ey)] = 0.0
    ex = np.column_stack([ey[:, 1], -ey[:, 0]])
    t = 2 * math.pi * np.arange(params.neighbours) / params.neighbours
    px = x[:, None] + params.lbp_radius * (np.cos(t)[None] * ex[:, :1] + np.sin(t)[None] * ey[:, :1])
    py = y[:, None] + params.lbp_radius * (np.cos(t)[None] * ex[:, 1:] + np.sin(t)[None] * ey[:, 1:])
    sampler = _bilinear_sampler(px.ravel() + half, py.ravel() + half, size)
    flat_index = ((y + half) * size + (x + half)).astype(int)
    return ring, weight, sampler, flat_index


def _bilinear_sampler(col: np.ndarray, row: np.ndarray, size: int):
    """Sparse (n, size*size) matrix interpolating a flattened patch at (col, row) (pixel indices)."""
    c0, r0 = np.floor(col).astype(int), np.floor(row).astype(int)
    fc, fr = col - c0, row - r0
    n = len(col)
    rows = np.repeat(np.arange(n), 4)
    cols = np.column_stack([r0 * size + c0, r0 * size + c0 + 1, (r0 + 1) * size + c0, (r0 + 1) * size + c0 + 1])
    vals = np.column_stack([(1 - fc) * (1 - fr), fc * (1 - fr), (1 - fc) * fr, fc * fr])
    return sparse.csr_matrix((vals.ravel(), (rows, cols.ravel())), shape=(n, size * size))


def rilbp_descriptors(patches: np.ndarray, params: RilbpParams = RilbpParams()) -> np.ndarray:
    """(K, D) float32 RILBP descriptors of (K, S, S) patches from :func:`sample_patches`
    (S = 2 (R + margin) + 1, centre at the middle pixel, not rotated)."""
    k = len(patches)
    ring, weight, sampler, flat_index = _geometry(params)
    m = sub_region_counts(params)
    dim = dimension(params)
    if k == 0:
        return np.zeros((0, dim), np.float32)
    flat = patches.reshape(k, -1).astype(np.float32)
    values = flat[:, flat_index]  # (K, P) each pixel's own intensity, for ranking
    n_half = params.neighbours // 2
    nb = (sampler.astype(np.float32) @ flat.T).T.reshape(k, len(ring), params.neighbours)
    codes = np.zeros((k, len(ring)), np.int64)
    for b in range(n_half):
        codes |= ((nb[:, :, b] - nb[:, :, b + n_half]) >= params.threshold).astype(np.int64) << b
    group = np.zeros((k, len(ring)), np.int64)
    offset = np.cumsum((0,) + m)
    for i, mi in enumerate(m):
        members = np.flatnonzero(ring == i)
        order = np.argsort(-values[:, members], axis=1)  # descending intensity
        rank = np.empty_like(order)
        np.put_along_axis(rank, order, np.arange(len(members))[None].repeat(k, 0), axis=1)
        group[:, members] = offset[i] + rank * mi // len(members)
    bins = 2 ** n_half
    index = (np.arange(k)[:, None] * dim + group * bins + codes).ravel()
    desc = np.bincount(index, weights=np.broadcast_to(weight, (k, len(ring))).ravel(), minlength=k * dim)
    return l2_normalise(desc.reshape(k, dim), params.clip)


