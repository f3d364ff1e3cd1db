"""Modality-robust area matching on CFOG descriptors: a global search and dense template matching.

``search_similarity`` finds rotation, scale and shift between two images of different modality
without any features: at a coarse level it scores a grid of rotations and scales, each with every
shift at once (masked normalised cross-correlation of CFOG channels by FFT, as Ye et al. 2019
match by FFT), then refines the best candidates at twice the resolution. ``dense_matches`` then
places templates on a regular grid of the reference and finds each one in the target warped by
the current model, which gives many well-spread correspondences.

Transforms are 2 x 3 affine matrices (3 x 3 homographies where said) from target px to reference
px (corner convention) of the images passed in.
"""
from __future__ import annotations

import math
from typing import Callable, List, Optional, Tuple

import cv2
import numpy as np
from scipy import fft as sfft

from ..descriptors.cfog import ncc_surface
from ..estimation.affine2d import apply, invert, similarity, warp
from ..similarity.cfog import cfog
from ..similarity.peak import peak_offset


def _centred(desc: np.ndarray, valid: np.ndarray, local_sigma: float = 0.0) -> np.ndarray:
    """Channels minus their mean over valid pixels (a Gaussian-weighted local mean when ``local_sigma``
    > 0), zero elsewhere: zero padding is then neutral, and with a local mean regional orientation
    statistics (texture, compression blocks) stop correlating regardless of position."""
    if not valid.any():
        return np.zeros_like(desc)
    m = valid.astype(np.float32)
    if local_sigma > 0:
        weight = np.maximum(cv2.GaussianBlur(m, (0, 0), local_sigma), 1e-6)
        mean = np.stack([cv2.GaussianBlur(c * m, (0, 0), local_sigma) / weight for c in desc])
    else:
        mean = desc[:, valid].mean(axis=1)[:, None, None]
    return ((desc - mean) * m[None]).astype(np.float32)


class _Scorer:
    """Masked NCC of a fixed reference descriptor against warped targets, for shifts up to ``pad`` px."""

    def __init__(self, reference, r_valid, pad: int, bins: int, sigma: float, min_overlap: float,
                 local_sigma: float = 0.0):
        h, w = reference.shape
        self.shape, self.pad = (h + 2 * pad, w + 2 * pad), pad
        self.n = (sfft.next_fast_len(self.shape[0] + pad), sfft.next_fast_len(self.shape[1] + pad))
        self.bins, self.sigma, self.local_sigma = bins, sigma, local_sigma
        self.origin = np.array([[1, 0, pad], [0, 1, pad]], float)
        ref, ok = warp(reference, r_valid, self.origin, self.shape)
        d = _centred(cfog(ref, bins, sigma, valid=ok), ok, local_sigma)
        self.fr = sfft.rfft2(d, self.n, axes=(1, 2))
        self.fe = sfft.rfft2((d ** 2).sum(axis=0), self.n)
        self.fm = sfft.rfft2(ok.astype(np.float32), self.n)
        self.area = max(float(ok.sum()), 1.0)
        self.min_count = max(min_overlap * self.area, 1.0)

    def best(self, target, t_valid, affine) -> Tuple[float, float, np.ndarray]:
        """(significance, NCC, affine with its shift) at the most significant shift of the target
        warped by ``affine``. Significance is Fisher's z of the NCC times the square root of the
        overlap (as a fraction of the reference): a high NCC over a small overlap is likelier chance."""
        full = np.vstack([self.origin, [0, 0, 1]]) @ np.vstack([affine, [0, 0, 1]])
        img, ok = warp(target, t_valid, full[:2], self.shape)
        if ok.sum() < self.min_count:
            return -np.inf, -1.0, affine
        d = _centred(cfog(img, self.bins, self.sigma, valid=ok), ok, self.local_sigma)
        ft = np.conj(sfft.rfft2(d, self.n, axes=(1, 2)))
        fmt = np.conj(sfft.rfft2(ok.astype(np.float32), self.n))
        num = sfft.irfft2((self.fr * ft).sum(axis=0), self.n)
        er = sfft.irfft2(self.fe * fmt, self.n)
        et = sfft.irfft2(self.fm * np.conj(sfft.rfft2((d ** 2).sum(axis=0), self.n)), self.n)
        count = sfft.irfft2(self.fm * fmt, self.n)
        ncc = num / np.sqrt(np.maximum(er * et, 1e-12))
        p = self.pad
        idx = np.r_[0:p + 1, -p:0]
        ncc, count = ncc[np.ix_(idx, idx)], count[np.ix_(idx, idx)]
        z = np.arctanh(np.clip(ncc, -0.999, 0.999)) * np.sqrt(np.maximum(count, 0) / self.area)
        z[count < self.min_count] = -np.inf
        r, c = np.unravel_index(int(np.argmax(z)), z.shape)
        shifted = affine.copy()
        shifted[:, 2] += (idx[c], idx[r])
        return float(z[r, c]), float(ncc[r, c]), shifted


def _downsampled(image, valid, f):
    h, w = image.shape
    size = (max(int(round(w * f)), 8), max(int(round(h * f)), 8))
    small = cv2.resize(image.astype(np.float32), size, interpolation=cv2.INTER_AREA)
    ok = cv2.resize(valid.astype(np.uint8), size, interpolation=cv2.INTER_NEAREST) > 0
    return small, ok, np.diag([size[0] / w, size[1] / h])


def _rescaled(affine, s_src, s_dst):
    """``affine`` between images rescaled by the 2 x 2 diagonal ``s_src`` (its source) and ``s_dst`` (its
    destination): S_dst A S_src^-1."""
    a, b = np.eye(3), np.eye(3)
    a[:2, :2], b[:2, :2] = s_dst, np.linalg.inv(s_src)
    return (a @ np.vstack([affine, [0, 0, 1]]) @ b)[:2]


def search_similarity(target, t_valid, reference, r_valid, *, max_rotation_deg: float = 30.0,
                      max_scale: float = 1.5, coarse_px: int = 96, rotation_step_deg: float = 5.0,
                      scale_step: float = 1.1, max_offset: float = 0.5, keep: int = 5, bins: int = 9,
                      min_overlap: float = 0.2, local_sigma: float = 3.0,
                      progress: Optional[Callable[[float], None]] = None) -> Tuple[List[dict], List[dict]]:
    """Rotation, scale and shift of ``target`` onto ``reference``, found by exhaustive search.

    Level 1: both images decimated by one factor so that the reference's longest side is
    ``coarse_px``; every rotation within +-``max_rotation_deg`` (step ``rotation_step_deg``) and
    scale within [1/max_scale, max_scale] (ratio ``scale_step``), each with every shift of up to
    ``max_offset`` x the reference size. Level 2: the ``keep`` best at twice the resolution with
    half steps and a few pixels of shift. Candidates and shifts are ranked by significance (see
    ``_Scorer.best``). Descriptors are compared after removing their local mean over
    ``local_sigma`` level-1 px (0: the global mean), so that only the positions of structures count.
    ``progress(fraction)`` is called before each trial (and may raise to cancel).

    Returns
    -------
    candidates : list of dict
        The best level-2 result of each level-1 candidate, best first: 'affine' (target px ->
        reference px), 'ncc', 'z', 'rotation_deg', 'scale'.
    tried : list of dict
        Every level-1 trial with its scores.
    """
    f = coarse_px / max(reference.shape)
    tried, seeds, out = [], [], []
    for level in (0, 1):
        fl = f * (2 ** level)
        tgt, tok, st = _downsampled(target, t_valid, fl)
        ref, rok, sr = _downsampled(reference, r_valid, fl)
        ct, cr = np.array(tgt.shape[::-1]) / 2.0, np.array(ref.shape[::-1]) / 2.0
        back = (np.linalg.inv(st), np.linalg.inv(sr))
        if level == 0:
            scorer = _Scorer(ref, rok, int(math.ceil(max_offset * max(ref.shape))), bins, 0.8, min_overlap,
                             local_sigma)
            top = max_rotation_deg - (1e-9 if max_rotation_deg >= 180 else -1e-9)  # -180 and 180 are one
            rot = np.arange(-max_rotation_deg, top, rotation_step_deg) if max_rotation_deg > 0 else np.zeros(1)
            n = int(math.ceil(math.log(max_scale) / math.log(scale_step))) if max_scale > 1 else 0
            grid = [(a, scale_step ** k) for k in range(-n, n + 1) for a in rot]
            for i, (a, s) in enumerate(grid):
                if progress is not None:
                    progress(0.8 * i / len(grid))
                z, ncc, shifted = scorer.best(tgt, tok, similarity(a, s, ct, cr))
                tried.append({"rotation_deg": float(a), "scale": float(s), "ncc": ncc, "z": z,
                              "affine": _rescaled(shifted, *back)})
            seeds = _distinct(sorted(tried, key=lambda d: -d["z"]), keep, rotation_step_deg, scale_step,
                              4.0 / fl, np.array(target.shape[::-1]) / 2.0)
            continue
        scorer = _Scorer(ref, rok, 4, bins, 0.8, min_overlap, 2 * local_sigma)
        da, ds = rotation_step_deg / 2.0, math.sqrt(scale_step)
        for i, seed in enumerate(seeds):
            if progress is not None:
                progress(0.8 + 0.2 * i / len(seeds))
            centre = apply(_rescaled(seed["affine"], st, sr), ct[None])[0]
            trials = []
            for a in (seed["rotation_deg"] - da, seed["rotation_deg"], seed["rotation_deg"] + da):
                for s in (seed["scale"] / ds, seed["scale"], seed["scale"] * ds):
                    z, ncc, shifted = scorer.best(tgt, tok, similarity(a, s, ct, centre))
                    trials.append({"rotation_deg": float(a), "scale": float(s), "ncc": ncc, "z": z,
                                   "affine": _rescaled(shifted, *back)})
            out.append(max(trials, key=lambda d: d["z"]))
    return sorted(out, key=lambda d: -d["z"]), [{k: v for k, v in d.items() if k != "affine"} for d in tried]


def _distinct(ranked: List[dict], keep: int, rotation_step: float, scale_step: float, shift_px: float,
              centre) -> List[dict]:
    """The first ``keep`` trials of ``ranked`` that are not neighbours of a better one: within one
    rotation step, one scale step and ``shift_px`` of where they send the target's ``centre``."""
    kept = []
    for d in ranked:
        at = apply(d["affine"], np.asarray(centre, float)[None])[0]
        if not any(abs(d["rotation_deg"] - k["rotation_deg"]) <= rotation_step + 1e-9
                   and abs(math.log(d["scale"] / k["scale"])) <= math.log(scale_step) + 1e-9
                   and np.linalg.norm(at - k["_at"]) <= shift_px for k in kept):
            kept.append(dict(d, _at=at))
        if len(kept) == keep:
            break
    return [{k: v for k, v in d.items() if k != "_at"} for d in kept]


def grid(shape, valid, half: int, limit: int) -> np.ndarray:
    """Up to ``limit`` px centres on a regular grid whose ``half``-px windows lie in valid pixels."""
    h, w = shape
    if h <= 2 * half + 2 or w <= 2 * half + 2:
        return np.zeros((0, 2))
    area = max(float(valid[half:h - half, half:w - half].sum()), 1.0)
    step = max(math.sqrt(area / limit), 4.0)
    xs = np.arange(half + 1, w - half, step)
    ys = np.arange(half + 1, h - half, step)
    gx, gy = np.meshgrid(np.floor(xs), np.floor(ys))
    x, y = gx.ravel().astype(int), gy.ravel().astype(int)
    ii = cv2.integral(valid.astype(np.uint8))  # window sums of valid[y - half:y + half, x - half:x + half]
    count = ii[y + half, x + half] - ii[y - half, x + half] - ii[y + half, x - half] + ii[y - half, x - half]
    pts = np.column_stack([x, y])
    ok = count >= 0.95 * (2 * half) ** 2
    return pts[ok]


def dense_matches(target, t_valid, reference, r_valid, model, *, template: int = 64, search: int = 8,
                  limit: int = 400, min_ncc: float = 0.2, bins: int = 9, sigma: float = 0.8,
                  reference_descriptors: Optional[np.ndarray] = None):
    """Correspondences on a reference grid: each CFOG template found in the target warped by
    ``model`` (2 x 3 affine or 3 x 3 homography, target px -> reference px) within +-``search`` px.
    Returns (target px, reference px, NCC peak), weak peaks dropped.
    ``reference_descriptors`` (``cfog(reference, bins, sigma, valid=r_valid)``) saves recomputing them."""
    warped, wok = warp(target, t_valid, model, reference.shape)
    dt = cfog(warped, bins, sigma, valid=wok)
    dr = cfog(reference, bins, sigma, valid=r_valid) if reference_descriptors is None else reference_descriptors
    half = template // 2
    pts = grid(reference.shape, r_valid & wok, half + search, limit)
    inv = invert(model)
    tx, rx, pk = [], [], []
    for x, y in pts:
        x0, y0 = x - half, y - half
        tmpl = dr[:, y0:y0 + template, x0:x0 + template]
        area = dt[:, y0 - search:y0 + template + search, x0 - search:x0 + template + search]
        offset, peak = peak_offset(ncc_surface(area, tmpl), search)
        if offset is None or peak < min_ncc:
            continue
        centre = np.array([x0 + template / 2.0, y0 + template / 2.0])
        tx.append(apply(inv, (centre + offset)[None])[0])
        rx.append(centre)
        pk.append(peak)
    if not tx:
        return np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0)
    return np.array(tx), np.array(rx), np.array(pk)
