"""Dense structural descriptors for template matching across speckle and modalities.

Ye, Y., Bruzzone, L., Shan, J., Bovolo, F., & Zhu, Q. (2019). Fast and robust matching for
multimodal remote sensing image registration. IEEE TGRS 57(11), 9059-9070.
:DOI:`10.1109/TGRS.2019.2924684` (CFOG: channel features of orientated gradients), compared as
in HOPC (Ye, Shan, Bruzzone & Shen 2017, IEEE TGRS 55(5):2941-2958) by normalised correlation.

Every pixel gets ``orientations`` channels, the absolute gradient projected on directions
k * 180 / orientations degrees (absolute, so that contrast reversal between sensors does not
matter), smoothed by a Gaussian in space and by [1 2 1] / 4 across (circular) orientation, then
normalised to unit length. Speckled images are compared on log amplitude, where a ratio of
brightness becomes a difference (the gradient then measures ratios, as ROEWA does).
"""
from __future__ import annotations

import math
from typing import Optional, Tuple

import cv2
import numpy as np

EPS = 1e-6


def cfog(image: np.ndarray, orientations: int = 9, sigma: float = 0.8, presmooth: float = 0.0,
         log: bool = False) -> np.ndarray:
    """(orientations, H, W) float32 descriptor image of a 2-D ``image``.

    ``presmooth`` (px, 0 = none) blurs the image before the gradients (for speckle); ``log`` takes
    the log of a positive amplitude first.
    """
    img = image.astype(np.float32)
    if log:
        img = np.log(np.maximum(img, np.float32(max(float(np.percentile(img, 1)), 1e-3))))
    if presmooth > 0:
        img = cv2.GaussianBlur(img, (0, 0), presmooth)
    gx = cv2.Sobel(img, cv2.CV_32F, 1, 0, ksize=1)
    gy = cv2.Sobel(img, cv2.CV_32F, 0, 1, ksize=1)
    angles = np.arange(orientations) * math.pi / orientations
    ch = np.empty((orientations,) + img.shape, np.float32)
    for k, a in enumerate(angles):
        ch[k] = cv2.GaussianBlur(np.abs(gx * math.cos(a) + gy * math.sin(a)), (0, 0), sigma)
    ch = 0.5 * ch + 0.25 * (np.roll(ch, 1, axis=0) + np.roll(ch, -1, axis=0))
    ch /= np.sqrt((ch * ch).sum(axis=0)) + EPS
    return ch


def match_descriptor(search: np.ndarray, template: np.ndarray) -> np.ndarray:
    """Zero-mean normalised correlation of a (C, h, w) ``template`` at every position of a
    (C, H, W) ``search`` (all channels together): a (H - h + 1, W - w + 1) surface in [-1, 1]."""
    c, h, w = template.shape
    n = float(c * h * w)
    t = template - template.mean()
    t_norm = math.sqrt(float((t * t).sum()))
    corr = sum(cv2.matchTemplate(search[k], t[k], cv2.TM_CCORR) for k in range(c))
    box_sum = sum(cv2.boxFilter(search[k], -1, (w, h), normalize=False, anchor=(0, 0),
                                borderType=cv2.BORDER_CONSTANT) for k in range(c))
    box_sq = sum(cv2.boxFilter(search[k] * search[k], -1, (w, h), normalize=False, anchor=(0, 0),
                               borderType=cv2.BORDER_CONSTANT) for k in range(c))
    rows, cols = corr.shape
    s_var = box_sq[:rows, :cols] - box_sum[:rows, :cols] ** 2 / n
    return (corr / (t_norm * np.sqrt(np.maximum(s_var, EPS)) + EPS)).astype(np.float32)


def peak_offset(surface: np.ndarray, centre: Tuple[int, int]) -> Tuple[Optional[np.ndarray], float, float]:
    """Sub-pixel peak of a correlation ``surface`` relative to ``centre`` (x, y), its value and the
    second-highest value outside the peak's 3 x 3 neighbourhood (for a distinctiveness test).
    The offset is None when the peak lies on the border."""
    _, peak, _, (u, v) = cv2.minMaxLoc(surface)
    rows, cols = surface.shape
    if not (0 < u < cols - 1 and 0 < v < rows - 1) or not np.isfinite(peak):
        return None, float(peak), float(peak)
    masked = surface.copy()
    masked[v - 1: v + 2, u - 1: u + 2] = -np.inf
    second = float(masked.max()) if masked.size > 9 else -1.0
    dx = _parabola(surface[v, u - 1], surface[v, u], surface[v, u + 1])
    dy = _parabola(surface[v - 1, u], surface[v, u], surface[v + 1, u])
    return np.array([u + dx - centre[0], v + dy - centre[1]]), float(peak), second


def _parabola(a: float, b: float, c: float) -> float:
    den = a - 2 * b + c
    return 0.0 if den >= 0 else float(np.clip(0.5 * (a - c) / den, -0.5, 0.5))
