"""Lowe's SIFT orientation assignment and 128-D descriptor on any scale space.

Lowe, D. G. (2004). Distinctive image features from scale-invariant keypoints. IJCV 60(2),
91-110, sections 5-6. :DOI:`10.1023/B:VISI.0000029664.99615.94`

OpenCV's SIFT only runs on its own Gaussian pyramid; spec 002 needs the same orientation and
descriptor on a nonlinear diffusion stack, so both are written here. Instead of visiting every
pixel of a scale-dependent window, each keypoint's neighbourhood is resampled (bilinear, one
``cv2.remap`` for all keypoints) on a fixed grid in the keypoint's own frame, so the cost does not
grow with scale and every keypoint shares one set of spatial weights:

- orientation: a 31 x 31 grid over +-4.5 sigma, gradients by central differences, magnitudes
  weighted by a Gaussian of 1.5 sigma, 36 bins smoothed with [1 4 6 4 1]/16, every local peak
  above 80 % of the maximum giving an orientation refined by a parabola;
- descriptor: a 41 x 41 grid over +-7.5 sigma (the 4 x 4 cells of 3 sigma plus the half cell that
  trilinear interpolation reaches) rotated to the orientation, Gaussian weight of half the
  descriptor width, trilinear votes into 4 x 4 x 8 bins, L2 normalisation, clipping at 0.2,
  renormalisation (OpenCV's constants).

Angles are degrees, clockwise as displayed (image axes, y down), in [0, 360).
"""
from __future__ import annotations

from functools import lru_cache
from typing import Tuple

import numpy as np

from ..detectors.patches import patch_gradients, sample_patches
from .normalise import l2_normalise

ORI_BINS = 36
ORI_HALF = 15
DESCR_WIDTH = 4
DESCR_BINS = 8
DESCR_HALF = 20
DESCR_MAG_THR = 0.2
CHUNK = 256  # keypoints described at once


def orientations(level: np.ndarray, xy: np.ndarray, sigma: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Dominant orientations of keypoints on one scale level.

    Parameters
    ----------
    level : (H, W) image the keypoints were found on (its own pixels).
    xy : (K, 2) keypoint positions in ``level`` pixels (corner convention).
    sigma : (K,) keypoint scale in ``level`` pixels.

    Returns
    -------
    index : (M,) keypoint of each orientation (a keypoint may have several).
    angle : (M,) degrees.
    """
    k = len(xy)
    if k == 0:
        return np.zeros(0, int), np.zeros(0)
    support = 4.5 * sigma * (ORI_HALF + 1) / ORI_HALF  # one extra sample for the central differences
    p = sample_patches(level, xy, support, ORI_HALF + 1, 0, antialias=False)
    gx, gy = patch_gradients(p)
    off = np.arange(-ORI_HALF, ORI_HALF + 1)
    yy, xx = np.meshgrid(off, off, indexing="ij")
    spacing = 4.5 / ORI_HALF  # sigmas per grid step
    weight = np.exp(-(xx ** 2 + yy ** 2) * spacing ** 2 / (2 * 1.5 ** 2)).astype(np.float32)
    mag = np.hypot(gx, gy) * weight[None]
    b = np.round(np.degrees(np.arctan2(gy, gx)) % 360.0 * ORI_BINS / 360.0).astype(np.int64) % ORI_BINS
    hist = np.bincount((np.arange(k)[:, None, None] * ORI_BINS + b).ravel(), weights=mag.ravel(),
                       minlength=k * ORI_BINS).reshape(k, ORI_BINS)
    hist = (np.roll(hist, 2, 1) + np.roll(hist, -2, 1)) / 16 + (np.roll(hist, 1, 1) + np.roll(hist, -1, 1)) * 4 / 16 \
        + hist * 6 / 16
    left, right = np.roll(hist, 1, axis=1), np.roll(hist, -1, axis=1)
    peak = (hist > left) & (hist > right) & (hist >= 0.8 * hist.max(axis=1, keepdims=True))
    ki, bi = np.nonzero(peak)
    lo, c, hi = left[ki, bi], hist[ki, bi], right[ki, bi]
    angle = ((bi + 0.5 * (lo - hi) / (lo - 2 * c + hi)) * 360.0 / ORI_BINS) % 360.0
    return ki, angle


@lru_cache(maxsize=1)
def _spatial_weights() -> np.ndarray:
    """(samples, 16) weights of every descriptor grid sample into the 4 x 4 cells: bilinear in the
    cell coordinates times the Gaussian window (the same for every keypoint)."""
    d = DESCR_WIDTH
    off = np.arange(-DESCR_HALF, DESCR_HALF + 1)
    yy, xx = np.meshgrid(off, off, indexing="ij")
    cells_per_step = (d / 2 + 0.5) / DESCR_HALF  # the grid spans +-(d/2 + 1/2) cells
    c_rot, r_rot = (xx * cells_per_step).ravel(), (yy * cells_per_step).ravel()
    rbin, cbin = r_rot + d / 2 - 0.5, c_rot + d / 2 - 0.5
    gauss = np.exp(-(c_rot ** 2 + r_rot ** 2) / (2 * (0.5 * d) ** 2))
    weights = np.zeros((len(rbin), d * d))
    for r in range(d):
        wr = np.maximum(1 - np.abs(rbin - r), 0)
        for c in range(d):
            weights[:, r * d + c] = wr * np.maximum(1 - np.abs(cbin - c), 0) * gauss
    return weights.astype(np.float32)


def descriptors(level: np.ndarray, xy: np.ndarray, sigma: np.ndarray, angle_deg: np.ndarray) -> np.ndarray:
    """(K, 128) float32 SIFT descriptors of keypoints on one scale level (same units as
    :func:`orientations`)."""
    d, n = DESCR_WIDTH, DESCR_BINS
    k = len(xy)
    if k == 0:
        return np.zeros((0, d * d * n), np.float32)
    half_width = 3.0 * sigma * (d / 2 + 0.5) * (DESCR_HALF + 1) / DESCR_HALF
    # sample_patches turns the patch x axis to angle_rad counter-clockwise as displayed
    p = sample_patches(level, xy, half_width, DESCR_HALF + 1, 0, angle_rad=-np.radians(angle_deg), antialias=False)
    gx, gy = patch_gradients(p)
    mag = np.hypot(gx, gy).reshape(k, -1)
    obin = (np.degrees(np.arctan2(gy, gx)) % 360.0).reshape(k, -1) * (n / 360.0)
    o0 = np.floor(obin).astype(np.int64) % n
    fo = (obin - np.floor(obin)).astype(np.float32)
    hist = np.empty((k, n, d * d), np.float32)
    votes = np.zeros((min(k, CHUNK), n, mag.shape[1]), np.float32)
    for a in range(0, k, CHUNK):  # chunks bound the (keypoints, bins, samples) vote array
        b = min(a + CHUNK, k)
        v = votes[: b - a]
        v[:] = 0
        kk, ss = np.arange(b - a)[:, None], np.arange(mag.shape[1])[None, :]
        v[kk, o0[a:b], ss] = mag[a:b] * (1 - fo[a:b])  # each (keypoint, sample) votes into two adjacent bins
        v[kk, (o0[a:b] + 1) % n, ss] += mag[a:b] * fo[a:b]
        hist[a:b] = v @ _spatial_weights()
    return l2_normalise(hist.transpose(0, 2, 1).reshape(k, -1), DESCR_MAG_THR)  # (cell, orientation) order
