"""Difference-of-Gaussian keypoints (Lowe's SIFT detector) on any stack of scale levels.

Lowe, D. G. (2004). Distinctive image features from scale-invariant keypoints. IJCV 60(2),
91-110, sections 3-4. :DOI:`10.1023/B:VISI.0000029664.99615.94`

The detector is separate from the scale space so that the same code runs on Gaussian stacks
(:func:`gaussian_octaves`) and on other scale spaces, such as the nonlinear diffusion of spec 002.
Per octave: differences of adjacent levels, extrema over 3x3x3 neighbourhoods (vectorised with
grey-level dilation/erosion), a preliminary contrast test, up to five Newton steps of the 3-D
quadratic fit for sub-pixel and sub-level position, the final contrast test and the principal
curvature (edge) test, as OpenCV implements Lowe's method. Positions are corner-convention
pixels of the input image; octave o samples every 2^o-th input pixel.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import List, Tuple

import cv2
import numpy as np

from ..types import Keypoints
from .extrema import scale_space_extrema


@dataclass(frozen=True)
class DogParams:
    """Lowe's detector settings (OpenCV defaults). Images are expected in [0, 1]."""

    layers: int = 3
    sigma: float = 1.6
    contrast_threshold: float = 0.04
    edge_threshold: float = 10.0
    max_keypoints: int = 0  # 0 = all
    border: int = 5

    def level_sigmas(self) -> np.ndarray:
        """sigma_k = sigma 2^(k / layers), k = 0 .. layers + 2, in octave-local pixels."""
        return self.sigma * 2.0 ** (np.arange(self.layers + 3) / self.layers)


def build_octaves(base: np.ndarray, layers: int, next_levels, max_octaves: int = 0, min_size: int = 16):
    """Octave stacks: ``next_levels(base, octave) -> list of levels``; each next octave starts from
    level ``layers`` decimated by 2 (Lowe's convention), until ``max_octaves`` (0 = no limit) or
    the image is smaller than ``min_size``."""
    octaves = []
    while (max_octaves <= 0 or len(octaves) < max_octaves) and min(base.shape) >= min_size:
        levels = next_levels(base, len(octaves))
        octaves.append(np.stack(levels))
        base = levels[layers][::2, ::2].copy()
    return octaves


def gaussian_octaves(image: np.ndarray, params: DogParams = DogParams(), assumed_blur: float = 0.5,
                     min_size: int = 16, max_octaves: int = 0) -> List[np.ndarray]:
    """Gaussian scale space without Lowe's initial doubling: per octave a (layers + 3, H, W)
    float32 stack with sigma_k = sigma * 2^(k / layers) relative to the octave's pixels."""
    sig = params.level_sigmas()
    base = cv2.GaussianBlur(image.astype(np.float32), (0, 0), math.sqrt(max(sig[0] ** 2 - assumed_blur ** 2, 0.01)))

    def levels(b, _):
        out = [b]
        for k in range(1, len(sig)):
            out.append(cv2.GaussianBlur(out[-1], (0, 0), math.sqrt(sig[k] ** 2 - sig[k - 1] ** 2)))
        return out
    return build_octaves(base, params.layers, levels, max_octaves, min_size)


def dog_keypoints(octaves: List[np.ndarray],
                  params: DogParams = DogParams()) -> Tuple[Keypoints, np.ndarray, np.ndarray]:
    """Keypoints of the difference of adjacent levels of each octave stack.

    Parameters
    ----------
    octaves : list of (L, H, W) arrays, octave o at 1 / 2^o of the input resolution; level k has
        scale ``params.level_sigmas()[k]`` in its octave's pixels (used for the keypoint size).

    Returns
    -------
    Keypoints
        ``size`` = 2 x sigma in input pixels, ``response`` = |interpolated DoG|, angle NaN.
    octave : (N,) int
    level : (N,) float, interpolated level within the octave (the DoG between levels s and s + 1
        is indexed s).
    """
    s = params.layers
    rows = []
    for o, stack in enumerate(octaves):
        dog = stack[1:] - stack[:-1]  # (L - 1, H, W)
        cand = scale_space_extrema(dog, 0.5 * params.contrast_threshold / s, end_layers=False, border=params.border)
        found = _refine(dog, cand, params)
        if len(found):
            sig = params.level_sigmas()
            layer_sigma = np.interp(found[:, 2], np.arange(len(sig)), sig)
            f = 2 ** o  # octave pixel centre i sits on input pixel centre f * i
            x = f * found[:, 0] + 0.5
            y = f * found[:, 1] + 0.5
            rows.append(np.column_stack([x, y, 2 * layer_sigma * f, found[:, 3], np.full(len(found), o), found[:, 2]]))
    if not rows:
        return Keypoints.empty(), np.zeros(0, int), np.zeros(0)
    allk = np.concatenate(rows)
    order = np.argsort(-allk[:, 3], kind="stable")
    if params.max_keypoints > 0:
        order = order[: params.max_keypoints]
    allk = allk[order]
    kp = Keypoints(allk[:, :2], allk[:, 2], np.full(len(allk), np.nan), allk[:, 3])
    return kp, allk[:, 4].astype(int), allk[:, 5]


def _refine(dog: np.ndarray, cand, params: DogParams) -> np.ndarray:
    """Newton steps of the 3-D quadratic fit; rows (x, y, level, |D|) of the surviving extrema."""
    layer, row, col = (a.astype(np.int64) for a in cand)
    n_layers, h, w = dog.shape
    alive = np.ones(len(layer), bool)
    active = alive.copy()  # still moving
    offset = np.zeros((len(layer), 3))
    for _ in range(5):
        idx = np.flatnonzero(active)
        if len(idx) == 0:
            break
        g, hess = _derivatives(dog, layer[idx], row[idx], col[idx])
        det = np.linalg.det(hess)
        ok = np.abs(det) > 1e-12
        step = np.zeros((len(idx), 3))
        step[ok] = -np.linalg.solve(hess[ok], g[ok][..., None])[..., 0]
        alive[idx[~ok]] = False
        offset[idx] = step
        done = np.all(np.abs(step) < 0.5, axis=1)
        move = ok & ~done
        active[idx[~move]] = False
        m = idx[move]
        col[m] += np.round(step[move, 0]).astype(np.int64)
        row[m] += np.round(step[move, 1]).astype(np.int64)
        layer[m] += np.round(step[move, 2]).astype(np.int64)
        inside = (layer[m] >= 1) & (layer[m] <= n_layers - 2) & (row[m] >= params.border) & \
                 (row[m] < h - params.border) & (col[m] >= params.border) & (col[m] < w - params.border)
        alive[m[~inside]] = False
        active[m[~inside]] = False
    idx = np.flatnonzero(alive & np.all(np.abs(offset) < 0.5, axis=1))
    if len(idx) == 0:
        return np.zeros((0, 4))
    g, hess = _derivatives(dog, layer[idx], row[idx], col[idx])
    value = dog[layer[idx], row[idx], col[idx]] + 0.5 * np.einsum("ni,ni->n", g, offset[idx])
    keep = np.abs(value) * params.layers >= params.contrast_threshold
    dxx, dyy, dxy = hess[:, 0, 0], hess[:, 1, 1], hess[:, 0, 1]
    tr, det2 = dxx + dyy, dxx * dyy - dxy * dxy
    r = params.edge_threshold
    keep &= (det2 > 0) & (tr * tr * r < (r + 1) ** 2 * det2)
    idx, value = idx[keep], value[keep]
    return np.column_stack([col[idx] + offset[idx, 0], row[idx] + offset[idx, 1], layer[idx] + offset[idx, 2],
                            np.abs(value)])


def _derivatives(dog, layer, row, col):
    """Central-difference gradient (x, y, s) and Hessian at integer positions."""
    def at(dl, dr, dc):
        return dog[layer + dl, row + dr, col + dc].astype(np.float64)

    c = at(0, 0, 0)
    dx = (at(0, 0, 1) - at(0, 0, -1)) / 2
    dy = (at(0, 1, 0) - at(0, -1, 0)) / 2
    ds = (at(1, 0, 0) - at(-1, 0, 0)) / 2
    dxx = at(0, 0, 1) + at(0, 0, -1) - 2 * c
    dyy = at(0, 1, 0) + at(0, -1, 0) - 2 * c
    dss = at(1, 0, 0) + at(-1, 0, 0) - 2 * c
    dxy = (at(0, 1, 1) - at(0, 1, -1) - at(0, -1, 1) + at(0, -1, -1)) / 4
    dxs = (at(1, 0, 1) - at(1, 0, -1) - at(-1, 0, 1) + at(-1, 0, -1)) / 4
    dys = (at(1, 1, 0) - at(1, -1, 0) - at(-1, 1, 0) + at(-1, -1, 0)) / 4
    g = np.column_stack([dx, dy, ds])
    hess = np.stack([np.column_stack([dxx, dxy, dxs]), np.column_stack([dxy, dyy, dys]),
                     np.column_stack([dxs, dys, dss])], axis=1)
    return g, hess
