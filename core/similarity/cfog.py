"""CFOG: channel features of orientated gradients, a dense structural descriptor for multimodal matching.

Ye, Y., Bruzzone, L., Shan, J., Bovolo, F. & Zhu, Q. (2019). Fast and robust matching for
multimodal remote sensing image registration. IEEE TGRS 57(11):9059-9070.
:DOI:`10.1109/TGRS.2019.2924684`

Per pixel, the gradient projected on ``bins`` orientations over [0, 180) degrees, its absolute
value (so a contrast inversion, common between SAR and optical, leaves it unchanged), smoothed by
a Gaussian in space and [1, 2, 1] across orientations, then L2-normalised over the channels.
The independent check (:mod:`hamta.core.verify`) and the matchers (:mod:`hamta.core.methods.cfog`,
:mod:`hamta.core.matching.multimodal`, :mod:`hamta.core.refine`) compute it here.
"""
from __future__ import annotations

from functools import lru_cache
from typing import Optional

import cv2
import numpy as np


def cfog(image: np.ndarray, bins: int = 9, sigma: float = 0.8, presmooth: float = 0.0,
         valid: Optional[np.ndarray] = None, portable: bool = False) -> np.ndarray:
    """Descriptor stack (bins, H, W) float32 of a grey ``image``; zero outside ``valid`` and within
    the smoothing support of its border.

    ``portable`` computes the gradients and the Gaussian smoothing with numpy in double
    precision instead of OpenCV's single-precision kernels, which differ in their last digits
    between OpenCV versions: the independent check uses it so that its numbers, hence its verdict,
    are the same on every library stack (same kernel size and border rule as OpenCV's)."""
    img = image.astype(np.float64 if portable else np.float32)
    if valid is not None and not valid.all():
        img = np.where(valid, img, img.dtype.type(img[valid].mean()) if valid.any() else 0)
    blur = gaussian_blur if portable else _blur_opencv
    if presmooth > 0:
        img = blur(img, presmooth)
    gx, gy = central_differences(img) if portable else (cv2.Sobel(img, cv2.CV_32F, 1, 0, ksize=1),
                                                        cv2.Sobel(img, cv2.CV_32F, 0, 1, ksize=1))
    raw = np.empty((bins,) + img.shape, img.dtype)
    for k in range(bins):
        a = k * np.pi / bins
        raw[k] = blur(np.abs(img.dtype.type(np.cos(a)) * gx + img.dtype.type(np.sin(a)) * gy), sigma)
    del gx, gy
    ch = _across_orientations(raw)
    del raw
    norm = np.sqrt(np.einsum("kij,kij->ij", ch, ch))
    norm += img.dtype.type(1e-6 + 1e-3 * float(ch.mean()))
    ch /= norm[None]
    if valid is not None:  # the edge between valid and filled pixels is not image structure
        r = 2 * int(np.ceil(2 * sigma + presmooth)) + 3
        ch *= cv2.erode(valid.astype(np.uint8), np.ones((r, r), np.uint8), borderType=cv2.BORDER_REPLICATE)[None]
    return ch.astype(np.float32, copy=False)


def _across_orientations(raw: np.ndarray) -> np.ndarray:
    """``raw`` (bins, H, W) smoothed by [1, 2, 1] / 4 across its circular orientation axis, a channel at a
    time: temporaries the size of the stack cost more than the arithmetic (fresh pages)."""
    bins = len(raw)
    out = np.empty_like(raw)
    quarter = np.empty_like(raw[0])
    for k in range(bins):
        np.multiply(raw[k], 0.5, out=out[k])
        out[k] += np.multiply(raw[k - 1], 0.25, out=quarter)
    for k in range(bins):
        out[k] += np.multiply(raw[(k + 1) % bins], 0.25, out=quarter)
    return out


def _blur_opencv(img: np.ndarray, sigma: float) -> np.ndarray:
    return cv2.GaussianBlur(img, (0, 0), sigma)


@lru_cache(maxsize=None)
def gaussian_kernel(sigma: float) -> np.ndarray:
    """OpenCV's Gaussian kernel for floating-point images: ``2 round(4 sigma) + 1`` taps, normalised (read
    only, shared)."""
    half = int(round(sigma * 8 + 1)) // 2
    x = np.arange(-half, half + 1, dtype=np.float64)
    k = np.exp(-x * x / (2.0 * sigma * sigma))
    k /= k.sum()
    k.setflags(write=False)
    return k


def gaussian_blur(img: np.ndarray, sigma: float) -> np.ndarray:
    """Separable Gaussian smoothing in double precision, borders mirrored without repeating the edge
    (OpenCV's default BORDER_REFLECT_101, scipy's 'mirror'); numpy only, as importing scipy.ndimage
    costs a third of a second per run."""
    k = gaussian_kernel(sigma)
    return _correlate(_correlate(img, k, -1), k, -2)


def _correlate(img: np.ndarray, k: np.ndarray, axis: int) -> np.ndarray:
    """``img`` correlated with the symmetric kernel ``k`` along ``axis``, borders mirrored."""
    half = len(k) // 2
    n = img.shape[axis]
    lead = (slice(None),) * (axis % img.ndim)
    padded = _mirrored(img, half, axis)

    def at(j: int) -> np.ndarray:
        return padded[lead + (slice(j, j + n),)]

    out = k[half] * at(half)
    for j in range(half):  # both taps at distance half - j at once
        out += k[j] * (at(j) + at(len(k) - 1 - j))
    return out


def _mirrored(img: np.ndarray, half: int, axis: int) -> np.ndarray:
    """``img`` padded by ``half`` along ``axis``, mirrored without repeating the edge (``np.pad``'s 'reflect',
    built directly: its general code costs more than the smoothing of a small window)."""
    n = img.shape[axis]
    if n <= half + 1:
        pad = [(0, 0)] * img.ndim
        pad[axis] = (half, half)
        return np.pad(img, pad, mode="reflect")
    lead = (slice(None),) * (axis % img.ndim)
    return np.concatenate([img[lead + (slice(half, 0, -1),)], img,
                           img[lead + (slice(n - 2, n - 2 - half, -1),)]], axis=axis)


def central_differences(img: np.ndarray):
    """Central differences ``f(x + 1) - f(x - 1)`` (OpenCV's Sobel with ksize 1), zero at the border
    (mirrored without repeating the edge)."""
    gx, gy = np.zeros_like(img), np.zeros_like(img)
    gx[:, 1:-1] = img[:, 2:] - img[:, :-2]
    gy[1:-1] = img[2:] - img[:-2]
    return gx, gy

