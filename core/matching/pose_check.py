"""Scoring a pose hypothesis densely: CFOG of the target turned and scaled onto the reference,
correlated with the reference's for every shift at once (FFT).

Recomputing CFOG (Ye et al. 2019, IEEE TGRS 57(11):9059) for every trial pose would dominate the
cost, so the target's descriptor is computed once per pyramid level for ``bins * sub``
orientations (5 degrees apart by default): a rotation by theta turns the gradient field, so the
reference-frame channel of orientation a is the target's channel of orientation a - theta, a
channel permutation (rounded to 5 degrees) followed by a spatial warp of the stack. Gaussian
smoothing commutes with rotation; the scale left to the warp stays within [2^-1/4, 2^1/4] by
choosing the pyramid level. Shifts are scored by masked normalised cross-correlation and ranked by
its significance z = atanh(NCC) sqrt(overlap / reference area).

All transforms are 2 x 3 affines, corner-convention px, target -> reference.
"""
from __future__ import annotations

import math
from typing import Optional

import cv2
import numpy as np

from ..coords import matrix_corner_to_opencv
from ..estimation.affine2d import compose, invert, resize
from ..fourier import fast_length, irfft2, rfft2


def _erode(valid: np.ndarray, r: int) -> np.ndarray:
    return cv2.erode(valid.astype(np.uint8), np.ones((2 * r + 1, 2 * r + 1), np.uint8),
                     borderType=cv2.BORDER_CONSTANT, borderValue=1) > 0


def oriented_channels(image: np.ndarray, valid: np.ndarray, bins: int = 9, sub: int = 4,
                      sigma: float = 0.8) -> np.ndarray:
    """(H, W, bins * sub) CFOG channels at orientations k * 180 / (bins * sub) degrees.

    Channel m is |gradient . u(m)|, Gaussian-smoothed (``sigma``), smoothed across orientation with
    its neighbours 180 / bins degrees away ([1, 2, 1] / 4, as CFOG) and L2-normalised over the
    ``bins`` channels {m + j sub} that form one CFOG stack (a floor of 5 % of the mean norm keeps flat
    areas near zero); zero within the smoothing support of invalid pixels. ``sub`` = 1 is CFOG.
    """
    img = image.astype(np.float32)
    if not valid.all():
        img = np.where(valid, img, np.float32(img[valid].mean()) if valid.any() else 0)
    gx = cv2.Scharr(img, cv2.CV_32F, 1, 0)
    gy = cv2.Scharr(img, cv2.CV_32F, 0, 1)
    d = bins * sub
    raw = np.empty(img.shape + (d,), np.float32)
    for m in range(d):
        a = m * math.pi / d
        raw[..., m] = cv2.GaussianBlur(np.abs(np.float32(math.cos(a)) * gx + np.float32(math.sin(a)) * gy),
                                       (0, 0), sigma)
    ch = 0.5 * raw + 0.25 * np.roll(raw, sub, axis=2) + 0.25 * np.roll(raw, -sub, axis=2)
    for o in range(sub):
        sl = ch[..., o::sub]
        norm = np.sqrt((sl ** 2).sum(axis=2))
        norm += np.float32(1e-6 + 0.05 * float(norm.mean()))
        ch[..., o::sub] = sl / norm[..., None]
    ch *= _erode(valid, int(math.ceil(2 * sigma)) + 1)[..., None]
    return ch


class TargetPyramid:
    """Target CFOG stacks at levels ``f0 * 2^(-l/2)`` (within [``min_factor``, 1]), each with
    ``bins * sub`` orientations."""

    def __init__(self, target, t_valid, f0: float, n_levels: int, bins: int = 9, sub: int = 4, sigma: float = 0.8,
                 min_factor: float = 0.0):
        self.bins, self.sub, self.shape_full = bins, sub, target.shape
        self.levels = []
        for level in range(n_levels):
            f = f0 * 2 ** (-level / 2)
            if f > 1.0 or f < min_factor:
                continue
            img, ok, s = resize(target, t_valid, f)
            self.levels.append((s, oriented_channels(img, ok, bins, sub, sigma), _erode(ok, 2)))

    def warped(self, affine: np.ndarray, shape):
        """Descriptor (H, W, bins) and validity of the target seen through ``affine`` (full-resolution
        target px -> grid px) on a ``shape`` grid: the level whose remaining scale is nearest 1,
        channels permuted for the rotation, then warped."""
        lin = np.asarray(affine)[:2, :2]
        scale = math.sqrt(abs(np.linalg.det(lin)))
        ang = math.degrees(math.atan2(lin[1, 0] - lin[0, 1], lin[0, 0] + lin[1, 1]))
        s_lvl, ch, ok = min(self.levels, key=lambda lv: abs(math.log(scale / lv[0][0, 0])))
        d = self.bins * self.sub
        idx = np.round((np.arange(self.bins) * 180.0 / self.bins - ang) / (180.0 / d)).astype(int) % d
        m = matrix_corner_to_opencv(np.vstack([compose(affine, invert(s_lvl)), [0, 0, 1.0]]))[:2]
        h, w = shape
        out = cv2.warpAffine(np.ascontiguousarray(ch[..., idx]), m, (w, h), flags=cv2.INTER_LINEAR, borderValue=0)
        okw = cv2.warpAffine(ok.astype(np.uint8), m, (w, h), flags=cv2.INTER_NEAREST, borderValue=0) > 0
        return (out[..., None] if out.ndim == 2 else out), okw


class ShiftCorrelator:
    """Masked NCC of a fixed reference descriptor with warped target descriptors for every shift up
    to ``pad`` px (FFT), and its significance.

    Parameters
    ----------
    ref_desc : (H, W, C) reference descriptor; ``r_valid`` its validity.
    pad : largest shift (px); the reference sits at (pad, pad) in a zero canvas.
    min_overlap : shifts overlapping less than this share of the reference's valid area are
        ignored (spurious peaks on slivers).
    """

    def __init__(self, ref_desc: np.ndarray, r_valid: np.ndarray, pad: int, min_overlap: float = 0.25):
        h, w = r_valid.shape
        self.pad = pad
        self.shape = (fast_length(h + 2 * pad), fast_length(w + 2 * pad))
        self.origin = np.array([[1.0, 0, pad], [0, 1.0, pad]])
        canvas = np.zeros(self.shape + (ref_desc.shape[2],), np.float32)
        ok = np.zeros(self.shape, bool)
        canvas[pad:pad + h, pad:pad + w] = ref_desc
        ok[pad:pad + h, pad:pad + w] = r_valid
        d = self._centre(canvas, ok)
        self.fr = rfft2(d, axes=(0, 1))
        self.fe = rfft2((d ** 2).sum(axis=2))
        self.fm = rfft2(ok.astype(np.float32))
        self.area = max(float(r_valid.sum()), 1.0)
        self.min_count = max(min_overlap * self.area, 1.0)
        self.idx = np.r_[0:pad + 1, -pad:0]

    @staticmethod
    def _centre(desc, ok):
        if not ok.any():
            return desc
        return (desc - desc[ok].mean(axis=0)) * ok[..., None]

    def surface(self, desc: np.ndarray, ok: np.ndarray):
        """(z, ncc) over shifts (rows dy, columns dx in ``self.idx`` order) for a target descriptor
        on the canvas grid; the target content at x matches the reference at x + d."""
        if ok.sum() < self.min_count:
            return None
        d = self._centre(desc, ok)
        ft = np.conj(rfft2(d, axes=(0, 1)))
        fmt = np.conj(rfft2(ok.astype(np.float32)))
        num = irfft2((self.fr * ft).sum(axis=2), self.shape)
        er = irfft2(self.fe * fmt, self.shape)
        et = irfft2(self.fm * np.conj(rfft2((d ** 2).sum(axis=2))), self.shape)
        count = irfft2(self.fm * fmt, self.shape)
        ix = np.ix_(self.idx, self.idx)
        num, er, et, count = num[ix], er[ix], et[ix], count[ix]
        ncc = num / np.sqrt(np.maximum(er * et, 1e-12))
        z = np.arctanh(np.clip(ncc, -0.999, 0.999)) * np.sqrt(np.maximum(count, 0) / self.area)
        z[count < self.min_count] = -np.inf
        return z, ncc

    def best(self, pyramid: TargetPyramid, affine: np.ndarray, radius: Optional[int] = None):
        """(z, ncc, ``affine`` with the best shift added) for the target seen through ``affine``
        (full-resolution target px -> reference grid px); shifts within +-``radius`` when given."""
        desc, ok = pyramid.warped(compose(self.origin, affine), self.shape)
        s = self.surface(desc, ok)
        if s is None:
            return -np.inf, -1.0, affine
        z, ncc = s
        if radius is not None and radius < self.pad:
            far = np.abs(self.idx) > radius
            z = z.copy()
            z[far, :] = -np.inf
            z[:, far] = -np.inf
        r, c = np.unravel_index(int(np.argmax(z)), z.shape)
        out = np.array(affine, float)
        out[:, 2] += (self.idx[c], self.idx[r])
        return float(z[r, c]), float(ncc[r, c]), out
