"""RIFT features: FAST corners on the phase-congruency moment map, described by Maximum Index Map
histograms, rotation-invariant (RIFT2) or plain.

Li, J., Hu, Q., & Ai, M. (2020). RIFT: multi-modal image matching based on radiation-variation
insensitive feature transform. IEEE TIP 29, 3296-3310. :DOI:`10.1109/TIP.2019.2959244`
Li, J., Shi, P., Hu, Q., & Zhang, Y. (2023). RIFT2: speeding-up RIFT with a new rotation-invariance
technique. arXiv:2303.00319.

Keypoints: FAST (threshold 1 of 255 on the moment map rescaled to [0, 1], non-maximum suppression),
strongest first, away from invalid pixels. Orientation (RIFT2): the peaks (>= 0.8 of the highest)
of a 24-bin, Gaussian-weighted histogram of the moment map's gradient directions in the patch
radius. Rotation-invariant descriptor (RIFT2): the MIM sampled on a 96-px patch turned to the
keypoint's orientation, its indexes shifted so that the patch's most frequent one becomes 0 (a
rotation of the image shifts every index by the rotation / 30 degrees), then 6 x 6 cells x 6-bin
histograms, L2-normalised (216-D). Plain descriptor (RIFT without rotation invariance): the same
histograms over an axis-aligned window, computed with integral images of the one-hot MIM.
Coordinates are corner-convention pixels of the image described.
"""
from __future__ import annotations

import cv2
import numpy as np

from ..detectors.phase_congruency import RIFT_PARAMS, log_gabor_maps
from ..types import Features, Keypoints

NORIENT = RIFT_PARAMS.norient  # MIM values = histogram bins
PATCH = 96  # RIFT's descriptor patch, px
GRID = 6  # 6 x 6 cells
ORI_BINS = 24  # RIFT2's orientation histogram
ORI_PEAK = 0.8  # secondary orientation peaks kept above this share of the highest


def maps(image: np.ndarray, valid: np.ndarray) -> dict:
    """RIFT's maps (see :func:`log_gabor_maps`) of ``image`` with invalid pixels filled by the mean;
    the MIM holds -1 there, and ``M`` is rescaled to [0, 1]."""
    filled = np.where(valid, image, image[valid].mean() if valid.any() else 0).astype(np.float32)
    out = log_gabor_maps(filled, RIFT_PARAMS)
    m = out["M"]
    out["M"] = (m - m.min()) / max(float(m.max() - m.min()), 1e-12)
    mim = out["mim"].astype(np.int16)
    mim[~valid] = -1
    out["mim"] = mim
    return out


def corners(moment: np.ndarray, valid: np.ndarray, n_points: int, margin: int = 0) -> np.ndarray:
    """FAST corners (K, 2) of the [0, 1] moment map, strongest first, at least 4 px inside valid
    pixels and ``margin`` px inside the image; corner-convention px."""
    detector = cv2.FastFeatureDetector_create(threshold=1, nonmaxSuppression=True)
    kps = sorted(detector.detect((moment * 255).astype(np.uint8), None), key=lambda k: -k.response)
    xy = np.array([k.pt for k in kps], float).reshape(-1, 2)
    h, w = valid.shape
    xi = np.round(xy).astype(int)
    keep = (xi[:, 0] >= margin) & (xi[:, 0] < w - margin) & (xi[:, 1] >= margin) & (xi[:, 1] < h - margin)
    xy, xi = xy[keep], xi[keep]
    inner = cv2.erode(valid.astype(np.uint8), np.ones((9, 9), np.uint8)) > 0
    xi = np.clip(xi, 0, [w - 1, h - 1])
    return xy[inner[xi[:, 1], xi[:, 0]]][:n_points] + 0.5


def orientations(moment: np.ndarray, xy: np.ndarray):
    """RIFT2 orientations (rad): every peak >= ``ORI_PEAK`` x the highest of a Gaussian-weighted
    (sigma = radius / 3) histogram of gradient directions of the moment map; returns (keypoints
    repeated per orientation, orientations)."""
    r = PATCH // 2
    gx = cv2.Sobel(moment, cv2.CV_32F, 1, 0, ksize=3)
    gy = cv2.Sobel(moment, cv2.CV_32F, 0, 1, ksize=3)
    mag = np.sqrt(gx ** 2 + gy ** 2)
    b = np.round(np.mod(np.arctan2(gy, gx), 2 * np.pi) * ORI_BINS / (2 * np.pi)).astype(int) % ORI_BINS
    xi = np.clip(np.floor(xy).astype(int), 0, [moment.shape[1] - 1, moment.shape[0] - 1])
    hist = np.empty((len(xy), ORI_BINS), np.float32)
    for k in range(ORI_BINS):  # the disc-limited Gaussian sum is a blur of each bin's magnitudes
        blurred = cv2.GaussianBlur(np.where(b == k, mag, 0).astype(np.float32), (2 * r + 1, 2 * r + 1), r / 3.0,
                                   borderType=cv2.BORDER_CONSTANT)
        hist[:, k] = blurred[xi[:, 1], xi[:, 0]]
    w = np.array([1, 4, 6, 4, 1], np.float32) / 16
    hist = sum(w[j] * np.roll(hist, j - 2, axis=1) for j in range(5))
    left, right = np.roll(hist, 1, axis=1), np.roll(hist, -1, axis=1)
    peak = (hist > left) & (hist > right) & (hist >= ORI_PEAK * hist.max(axis=1, keepdims=True))
    i, k = np.nonzero(peak)
    den = left[i, k] + right[i, k] - 2 * hist[i, k]
    off = np.where(np.abs(den) > 1e-12, 0.5 * (left[i, k] - right[i, k]) / np.where(den == 0, 1, den), 0)
    return xy[i], ((k + off) % ORI_BINS) * 2 * np.pi / ORI_BINS


def describe_rotated(mim: np.ndarray, xy: np.ndarray, angle: np.ndarray, step: int = 1,
                     chunk: int = 64) -> np.ndarray:
    """(K, 216) rotation-invariant MIM descriptors (see the module docstring); ``step`` > 1 samples
    the patch every ``step`` px; ``chunk`` keypoints at a time (their sample maps stay in cache)."""
    norient = NORIENT
    size = PATCH // step
    cs = size // GRID
    g = (np.arange(size, dtype=np.float32) - (size - 1) / 2) * step
    u, v = np.meshgrid(g, g)
    cell = ((np.arange(size) // cs)[:, None] * GRID + (np.arange(size) // cs)[None, :]).ravel().astype(np.int32)
    out = np.zeros((len(xy), GRID, GRID, norient), np.float32)
    mimf = mim.astype(np.float32)
    cell_keys = (np.arange(chunk, dtype=np.int32)[:, None] * (GRID * GRID) + cell[None]) * (norient + 1)
    scratch = np.empty((min(chunk, len(xy)), size, size), np.float32)
    for s in range(0, len(xy), chunk):
        p, a = (xy[s:s + chunk] - 0.5).astype(np.float32), angle[s:s + chunk]  # OpenCV px for remap
        c, si = np.cos(a)[:, None, None].astype(np.float32), np.sin(a)[:, None, None].astype(np.float32)
        n = len(p)
        mx, my, t = c * u, si * u, scratch[:n]  # in place: x + c u - s v and y + s u + c v, as written
        mx += p[:, 0, None, None]
        mx -= np.multiply(si, v, out=t)
        my += p[:, 1, None, None]
        my += np.multiply(c, v, out=t)
        vals = cv2.remap(mimf, mx.reshape(n * size, size), my.reshape(n * size, size), cv2.INTER_NEAREST,
                         borderMode=cv2.BORDER_CONSTANT, borderValue=-1).reshape(n, -1).astype(np.int32)
        vals[vals < 0] = norient  # invalid or outside: an extra bin, dropped
        vals += cell_keys[:n]  # each sample's histogram bin: (keypoint, cell, index)
        h = np.bincount(vals.ravel(), minlength=n * GRID * GRID * (norient + 1))
        h = h.reshape(n, GRID, GRID, norient + 1)[..., :norient]
        dominant = h.sum(axis=(1, 2)).argmax(axis=1)
        roll = (np.arange(norient)[None] + dominant[:, None]) % norient
        out[s:s + chunk] = np.take_along_axis(h, roll[:, None, None, :], axis=3)
    return _normalised(out.reshape(len(xy), GRID * GRID * norient))


def describe_plain(mim: np.ndarray, xy: np.ndarray, patch: int, norient: int = NORIENT) -> np.ndarray:
    """(K, 36 x norient) MIM histograms of axis-aligned ``patch``-px windows (integral images)."""
    h, w = mim.shape
    ii = np.stack([cv2.integral((mim == k).astype(np.uint8)) for k in range(norient)], axis=-1).astype(np.int32)
    x0 = np.floor(xy[:, 0] - patch / 2).astype(int)
    y0 = np.floor(xy[:, 1] - patch / 2).astype(int)
    edges = np.round(np.arange(GRID + 1) * patch / GRID).astype(int)
    out = np.zeros((len(xy), GRID, GRID, norient), np.float32)
    for i in range(GRID):
        ya, yb = np.clip(y0 + edges[i], 0, h), np.clip(y0 + edges[i + 1], 0, h)
        for j in range(GRID):
            xa, xb = np.clip(x0 + edges[j], 0, w), np.clip(x0 + edges[j + 1], 0, w)
            out[:, i, j] = ii[yb, xb] - ii[ya, xb] - ii[yb, xa] + ii[ya, xa]
    return _normalised(out.reshape(len(xy), GRID * GRID * norient))


def _normalised(d: np.ndarray) -> np.ndarray:
    if len(d) == 0:
        return d.astype(np.float32)
    return d / np.maximum(np.linalg.norm(d, axis=1, keepdims=True), 1e-12)


def rotated_features(image: np.ndarray, valid: np.ndarray, n_points: int = 5000, step: int = 1) -> Features:
    """RIFT2 features of one image: keypoints (with orientation, in degrees) and rotation-invariant
    MIM descriptors; ``Keypoints.size`` is the patch side."""
    m = maps(image, valid)
    xy, angle = orientations(m["M"], corners(m["M"], valid, n_points))
    d = describe_rotated(m["mim"], xy, angle, step)
    kp = Keypoints(xy, np.full(len(xy), float(PATCH)), np.degrees(angle), np.zeros(len(xy)))
    return Features(kp, d.astype(np.float32), "l2")


def plain_features(image: np.ndarray, valid: np.ndarray, n_points: int, patch: int, margin: int = 4) -> Features:
    """RIFT features without rotation invariance (for images already in a common orientation)."""
    m = maps(image, valid)
    xy = corners(m["M"], valid, n_points, margin)
    d = describe_plain(m["mim"], xy, patch)
    kp = Keypoints(xy, np.full(len(xy), float(patch)), np.full(len(xy), np.nan), np.zeros(len(xy)))
    return Features(kp, d, "l2")
