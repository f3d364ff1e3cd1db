"""Scale-normalised circular regions around keypoints, and SIFT-style dominant orientations.

A keypoint with support radius ``rho`` (working pixels) becomes a ``(2R+1+2M)`` square patch
sampled bilinearly on a grid of step ``rho / R`` (R = 20 in spec 000), optionally rotated;
``M`` extra pixels on each side leave room for neighbourhood operators. The source is
Gaussian-smoothed before downsampling so the patch does not alias. Everything is vectorised:
one ``cv2.remap`` call samples all keypoints of a scale group.
"""
from __future__ import annotations

import math
from typing import Optional

import cv2
import numpy as np


def sample_patches(image: np.ndarray, xy: np.ndarray, support_radius: np.ndarray, radius: int = 20,
                   margin: int = 2, angle_rad: Optional[np.ndarray] = None, smoothing: float = 0.0,
                   antialias: bool = True) -> np.ndarray:
    """(K, S, S) float32 patches, S = 2 * (radius + margin) + 1.

    Parameters
    ----------
    image : (H, W) float image, working pixels.
    xy : (K, 2) keypoint centres (corner convention).
    support_radius : (K,) support radius of each keypoint in ``image`` pixels.
    angle_rad : (K,) optional; the patch's x axis is turned to this direction (radians,
        counter-clockwise as displayed, i.e. from +x towards -y).
    smoothing : float
        Extra Gaussian smoothing, in patch pixels, applied (through the source) before sampling.
    antialias : bool
        Smooth the source before downsampling; off when it is already smooth at the patch scale
        (a scale-space level sampled finer than its sigma).
    """
    k = len(xy)
    half = radius + margin
    size = 2 * half + 1
    out = np.zeros((k, size, size), np.float32)
    if k == 0:
        return out
    step = np.asarray(support_radius, float) / radius
    grid = np.arange(-half, half + 1, dtype=np.float64)
    gu, gv = np.meshgrid(grid, grid)
    cos = np.ones(k) if angle_rad is None else np.cos(angle_rad)
    sin = np.zeros(k) if angle_rad is None else np.sin(angle_rad)
    img = image.astype(np.float32)
    # Each keypoint is sampled with its exact step from an image smoothed for its scale; smoothing
    # levels are shared between keypoints whose sigmas differ by less than 1/16 octave.
    sigma = np.sqrt((0.25 * np.maximum(step * step - 1.0, 0.0) if antialias else 0.0) + (smoothing * step) ** 2)
    level = np.where(sigma > 0.2, np.round(np.log2(np.maximum(sigma, 1e-6)) * 16), -10 ** 6).astype(np.int64)
    pyramid = {0: img}
    for lv in np.unique(level):
        sel = np.flatnonzero(level == lv)
        target_sigma = 2.0 ** (lv / 16.0) if lv > -10 ** 6 else 0.0
        # Large blurs run on a 2^k-times smaller copy (area-averaged), with the remaining blur there.
        k = int(max(0, np.floor(np.log2(max(target_sigma, 1e-6) / 2.0)))) if target_sigma > 4 else 0
        if k not in pyramid:
            h, w = img.shape
            pyramid[k] = cv2.resize(img, (max(1, w >> k), max(1, h >> k)), interpolation=cv2.INTER_AREA)
        base = pyramid[k]
        f = np.array([base.shape[1] / img.shape[1], base.shape[0] / img.shape[0]])
        residual = np.sqrt(max(target_sigma ** 2 - (0.5 * (2 ** k) if k else 0.0) ** 2, 0.0)) / (2 ** k)
        src = cv2.GaussianBlur(base, (0, 0), residual) if residual > 0.2 else base
        s = step[sel, None, None]
        u = gu[None] * s
        v = gv[None] * s
        # patch x axis = (cos, -sin) in image coordinates (y down); patch y axis = (sin, cos)
        c, n = cos[sel, None, None], sin[sel, None, None]
        mx = (xy[sel, 0, None, None] + c * u + n * v) * f[0] - 0.5
        my = (xy[sel, 1, None, None] - n * u + c * v) * f[1] - 0.5
        mx = mx.reshape(-1, size).astype(np.float32)
        my = my.reshape(-1, size).astype(np.float32)
        rows = (30000 // size) * size  # cv2.remap maps must stay under 32767 rows
        sampled = np.concatenate([cv2.remap(src, mx[i:i + rows], my[i:i + rows], cv2.INTER_LINEAR,
                                            borderMode=cv2.BORDER_REFLECT) for i in range(0, len(mx), rows)])
        out[sel] = sampled.reshape(len(sel), size, size)
    return out


def patch_gradients(patches: np.ndarray):
    """Central differences (unscaled) of a (K, S, S) stack over its (S-2) x (S-2) interior."""
    return patches[:, 1:-1, 2:] - patches[:, 1:-1, :-2], patches[:, 2:, 1:-1] - patches[:, :-2, 1:-1]


def dominant_orientation(patches: np.ndarray, radius: int = 20, bins: int = 36) -> np.ndarray:
    """SIFT-style dominant gradient orientation (Lowe 2004, section 5) of each patch, in radians,
    counter-clockwise as displayed: a magnitude- and Gaussian-weighted 36-bin histogram over the
    disk of ``radius``, smoothed, with a parabolic peak fit."""
    k, size, _ = patches.shape
    c = size // 2
    p = patches.astype(np.float32, copy=False)
    gx, gy = patch_gradients(p)
    yy, xx = np.mgrid[1:size - 1, 1:size - 1] - c
    disk = (xx ** 2 + yy ** 2) <= radius ** 2
    weight = (np.exp(-(xx ** 2 + yy ** 2) / (2.0 * (radius / 2.0) ** 2)) * disk).astype(np.float32)
    mag = np.hypot(gx, gy) * weight[None]
    ang = np.arctan2(-gy, gx)  # counter-clockwise as displayed (image y points down)
    b = np.floor((ang + math.pi) / (2 * math.pi) * bins).astype(int) % bins
    index = (np.arange(k)[:, None] * bins + b[:, disk]).ravel()
    hist = np.bincount(index, weights=mag[:, disk].ravel(), minlength=k * bins).reshape(k, bins)
    for _ in range(2):  # Lowe's smoothing of the orientation histogram
        hist = (np.roll(hist, 1, axis=1) + hist + np.roll(hist, -1, axis=1)) / 3.0
    peak = np.argmax(hist, axis=1)
    left = hist[np.arange(k), (peak - 1) % bins]
    mid = hist[np.arange(k), peak]
    right = hist[np.arange(k), (peak + 1) % bins]
    den = left - 2 * mid + right
    off = np.where(den < 0, 0.5 * (left - right) / np.where(den < 0, den, -1), 0.0)
    return (peak + 0.5 + off) / bins * 2 * math.pi - math.pi
