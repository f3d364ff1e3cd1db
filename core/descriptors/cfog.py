"""CFOG: channel features of orientated gradients, a dense structural descriptor for multimodal matching.

Ye, Y., Bruzzone, L., Shan, J., Bovolo, F. & Zhu, Q. (2019). Fast and robust matching for
multimodal remote sensing image registration. IEEE TGRS 57(11):9059-9070.
:DOI:`10.1109/TGRS.2019.2924684`

Per pixel, the gradient projected on ``bins`` orientations over [0, 180) degrees, its absolute
value (so a contrast inversion, common between SAR and optical, leaves it unchanged), smoothed by
a Gaussian in space and [1, 2, 1] across orientations, then L2-normalised over the channels.
Matching compares descriptor windows by normalised cross-correlation over all channels at once.
"""
from __future__ import annotations

from typing import Optional, Tuple

import cv2
import numpy as np


def cfog(image: np.ndarray, bins: int = 9, sigma: float = 0.8, presmooth: float = 0.0,
         valid: Optional[np.ndarray] = None) -> np.ndarray:
    """Descriptor stack (bins, H, W) float32 of a grey ``image``; zero outside ``valid`` and within
    the smoothing support of its border."""
    img = image.astype(np.float32)
    if valid is not None and not valid.all():
        img = np.where(valid, img, np.float32(img[valid].mean()) if valid.any() else 0)
    if presmooth > 0:
        img = cv2.GaussianBlur(img, (0, 0), presmooth)
    gx = cv2.Sobel(img, cv2.CV_32F, 1, 0, ksize=1)
    gy = cv2.Sobel(img, cv2.CV_32F, 0, 1, ksize=1)
    raw = np.empty((bins,) + img.shape, np.float32)
    for k in range(bins):
        a = k * np.pi / bins
        oriented = np.abs(np.float32(np.cos(a)) * gx + np.float32(np.sin(a)) * gy)
        cv2.GaussianBlur(oriented, (0, 0), sigma, dst=raw[k])
    del gx, gy
    ch = 0.5 * raw
    ch[1:] += 0.25 * raw[:-1]
    ch[0] += 0.25 * raw[-1]
    ch[:-1] += 0.25 * raw[1:]
    ch[-1] += 0.25 * raw[0]
    del raw
    norm = np.sqrt(np.einsum("kij,kij->ij", ch, ch))
    norm += np.float32(1e-6 + 1e-3 * float(ch.mean()))
    ch /= norm[None]
    if valid is not None:  # the edge between valid and filled pixels is not image structure
        r = 2 * int(np.ceil(2 * sigma + presmooth)) + 3
        ch *= cv2.erode(valid.astype(np.uint8), np.ones((r, r), np.uint8), borderType=cv2.BORDER_REPLICATE)[None]
    return ch


def ncc_surface(search: np.ndarray, template: np.ndarray) -> np.ndarray:
    """Normalised cross-correlation of a (C, h, w) ``template`` at every position in a (C, H, W)
    ``search`` stack, with one mean and one norm over all channels."""
    c, h, w = template.shape
    t = template - template.mean()
    tn = float(np.sqrt((t ** 2).sum()))
    num = sum(cv2.matchTemplate(search[k], t[k], cv2.TM_CCORR) for k in range(c))
    ones = np.ones((h, w), np.float32)
    s1 = cv2.matchTemplate(search.sum(axis=0), ones, cv2.TM_CCORR)
    s2 = cv2.matchTemplate((search ** 2).sum(axis=0), ones, cv2.TM_CCORR)
    var = np.maximum(s2 - s1 ** 2 / (c * h * w), 0.0)
    return num / np.maximum(np.sqrt(var) * tn, 1e-9)


def peak_offset(surface: np.ndarray, radius: int) -> Tuple[Optional[np.ndarray], float]:
    """Sub-pixel (dx, dy) of the highest interior peak of ``surface`` relative to its centre
    (``radius`` px from each side), and the peak value; None where the peak is on the border."""
    _, peak, _, (u, v) = cv2.minMaxLoc(surface)
    if not (0 < u < surface.shape[1] - 1 and 0 < v < surface.shape[0] - 1) or not np.isfinite(peak):
        return None, float(peak)
    dx = _parabola(surface[v, u - 1], surface[v, u], surface[v, u + 1])
    dy = _parabola(surface[v - 1, u], surface[v, u], surface[v + 1, u])
    return np.array([u + dx - radius, v + dy - radius]), float(peak)


def _parabola(a: float, b: float, c: float) -> float:
    den = a - 2 * b + c
    return 0.0 if den >= 0 else float(np.clip(0.5 * (a - c) / den, -0.5, 0.5))
