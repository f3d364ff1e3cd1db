"""Across modalities at any rotation and scale: RIFT feature votes, a dense pose check, local RIFT.

For image pairs that differ in modality (optical onto SAR, infrared, depth, maps, night lights)
*and* by an arbitrary rotation and a scale between 1/2 and 2, where SIFT finds nothing and an
exhaustive structural search is slow and fragile.

1. Features: both images rescaled by one factor (the reference's longest side at most
   ``feat_px``); on a pyramid of each (factors 1, 2^-1/2, 1/2) RIFT2 keypoints with rotation-
   invariant MIM descriptors (:mod:`hamta.core.descriptors.rift`); every target descriptor takes its
   nearest reference descriptor.
2. Hypotheses: each match votes for a rotation (difference of the keypoints' orientations) and a
   scale (ratio of their pyramid factors); the strongest (rotation, scale) cells each give a
   similarity by RANSAC on the matches that voted near them.
3. Dense check: each hypothesis is scored by the masked NCC of CFOG descriptors of the target seen
   through it against the reference's (:mod:`hamta.core.matching.pose_check`), over shifts and a few
   scale factors around it, and ranked by the significance of the best.
4. Local RIFT: the best few are refined twice by matching plain (not rotation-invariant) MIM
   descriptors near their predicted positions; the hypothesis with most inliers wins, and its
   matches are returned for the shared robust fit, full-resolution CFOG refinement and check.

References
----------
Li, J., Hu, Q., & Ai, M. (2020). RIFT. IEEE TIP 29, 3296-3310. :DOI:`10.1109/TIP.2019.2959244`
Li, J., Shi, P., Hu, Q., & Zhang, Y. (2023). RIFT2. arXiv:2303.00319.
Li, J., Hu, Q., & Zhang, Y. (2023). Multimodal image matching: a scale-invariant algorithm and an
open dataset. ISPRS J. Photogramm. Remote Sens. 204, 77-88 (scale by pyramids; the data set).
Ye, Y., Bruzzone, L., Shan, J., Bovolo, F., & Zhu, Q. (2019). CFOG. IEEE TGRS 57(11), 9059-9070.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import List

import cv2
import numpy as np

from ..blas import reference_blas
from ..descriptors import rift
from ..estimation.affine2d import angle_scale, apply, compose, invert, resize, scaling, similarity, warp
from ..estimation.ransac import ransac_or_none
from ..matching.pose_check import ShiftCorrelator, TargetPyramid, oriented_channels
from ..parallel import threaded
from ..progress import Monitor
from ..refine import STRUCTURAL_REFINEMENT
from ..types import Matches
from .registry import Method, Toolbox, param, register_method, validate

CITATION = ("Li, Hu & Ai 2020, IEEE TIP 29:3296 (RIFT); Li et al. 2023, arXiv:2303.00319 (RIFT2); Li, Hu & Zhang "
            "2023, ISPRS J. 204:77 (scale, data set); Ye et al. 2019, IEEE TGRS 57(11):9059 (CFOG)")


@dataclass(frozen=True)
class XmodalParams:
    """The four stages; defaults chosen on the odd-numbered pairs of the real multimodal set and
    confirmed on the even-numbered ones (``hamta bench --families multimodal-set``)."""

    feat_px: int = param(320, "Longest reference side for feature extraction, px: enough detail for RIFT features, "
                              "and their cost.", minimum=64)
    levels: int = param(3, "Pyramid levels (factors 2^-k/2) per image; 3 covers scales 1/2 to 2.", minimum=1,
                         maximum=5)
    points: int = param(1000, "Keypoints kept at the first level (0.7 and 0.5 times that at the next two).",
                        minimum=50)
    hypotheses: int = param(6, "Rotation-scale hypotheses checked densely (10 gave nothing more).", minimum=1)
    refine_best: int = param(3, "Hypotheses refined by local RIFT (5 gave nothing more).", minimum=1)
    check_px: int = param(128, "Longest reference side for the dense check, px: keeps its 30 FFT trials per "
                               "hypothesis cheap; where CFOG separated right from wrong poses best.", minimum=32)
    local_px: int = param(384, "Longest reference side for local RIFT matching, px.", minimum=64)
    min_inliers: int = param(8, "Fewest local-RIFT inliers for a refined hypothesis.", minimum=3)

    def __post_init__(self):
        validate(self)


VOTE_ANGLE_DEG = 10.0  # rotation bin of the votes
CHECK_SCALES = (2 ** -0.5, 2 ** -0.25, 1.0, 2 ** 0.25, 2 ** 0.5)  # the vote's scale is quantised to half octaves
CHECK_SHIFT_PX = 12
LOCAL_RADII = (0.08, 0.03)  # local search radius, share of the working size: coarse, then fine
LOCAL_PATCH_PX = 72
DESCRIPTOR_STEP = 2  # rotated patches sampled every 2 px: 4x cheaper, 64 samples per cell


def _level_features(image, valid, f0: float, k: int, points: int):
    """(keypoints full-res px, orientations rad, descriptors, level factors) at pyramid level ``k``."""
    f = f0 * 2 ** (-k / 2)
    img, ok, s = resize(image, valid, f)
    feats = rift.rotated_features(img, ok, int(points * (1.0, 0.7, 0.5, 0.4, 0.3)[k]), DESCRIPTOR_STEP)
    xy = apply(invert(s), feats.keypoints.xy)
    return xy, np.radians(feats.keypoints.angle), feats.descriptors, np.full(len(xy), f)


def _pyramid_features(images, f0: float, levels: int, points: int) -> list:
    """For each (image, valid) of ``images``, its features over the pyramid (see :func:`_level_features`); every
    level of every image on the threads at once, the largest first."""
    jobs = [(k, i) for k in range(levels) for i in range(len(images))]
    found = dict(zip(jobs, threaded(lambda job: _level_features(*images[job[1]], f0, job[0], points), jobs)))
    return [[np.concatenate([found[k, i][c] for k in range(levels)]) for c in range(4)] for i in range(len(images))]


def nearest(a: np.ndarray, b: np.ndarray, rows: int = 512) -> np.ndarray:
    """For each row of ``a``, the index of its nearest row of ``b`` (Euclidean): the largest
    ``a.b - |b|^2 / 2`` (``|a|^2`` is the same along a row), a block of ``rows`` rows at a time, so that
    the distances stay in cache instead of filling hundreds of MB (the same indexes, in half the time)."""
    if reference_blas():  # OpenCV's brute force (:mod:`hamta.core.blas`)
        _, index = cv2.batchDistance(a.astype(np.float32), b.astype(np.float32), cv2.CV_32F,
                                     normType=cv2.NORM_L2SQR, K=1)
        return index[:, 0].astype(np.intp)
    half = (b * b).sum(1) * -0.5  # exact: a power of two
    out = np.empty(len(a), np.intp)
    for i in range(0, len(a), rows):
        d = a[i:i + rows] @ b.T
        d += half
        out[i:i + rows] = d.argmax(axis=1)
    return out


def squared_distances(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(len(a), len(b)) squared Euclidean distances between rows, formed in place (scipy's loops where
    numpy's matrix products run on a reference BLAS: twice as fast there)."""
    if reference_blas():
        from scipy.spatial.distance import cdist

        return cdist(a, b, "sqeuclidean").astype(np.float32)
    d = a @ b.T
    d *= -2
    d += (a * a).sum(1)[:, None]
    d += (b * b).sum(1)[None]
    return d


def _far(p: np.ndarray, q: np.ndarray, radius: float) -> np.ndarray:
    """(len(p), len(q)) True where points p and q are more than ``radius`` apart (in single precision)."""
    p, q = p.astype(np.float32, copy=False), q.astype(np.float32, copy=False)
    dx = p[:, None, 0] - q[None, :, 0]
    dx *= dx
    dy = p[:, None, 1] - q[None, :, 1]
    dy *= dy
    dx += dy
    return dx > np.float32(radius * radius)


def mutual_nearest_within(d2: np.ndarray, p: np.ndarray, q: np.ndarray, radius: float, rows: int = 128):
    """For squared descriptor distances ``d2`` (len(p), len(q)) between points ``p`` and ``q``: each row's
    nearest column among the points within ``radius`` of its own (``j``), and whether that pair is mutual and
    that near (``ok``). ``d2`` is masked in place, ``rows`` rows at a time (the masks stay in cache); the
    columns' nearest rows are kept as the blocks go (first of equals, as ``argmin``)."""
    n, m = d2.shape
    p, q = p.astype(np.float32), q.astype(np.float32)  # once, not per block
    j = np.empty(n, np.intp)
    column_min, column_arg = np.full(m, np.inf, d2.dtype), np.zeros(m, np.intp)
    for i in range(0, n, rows):
        block = d2[i:i + rows]
        block[_far(p[i:i + rows], q, radius)] = np.inf
        j[i:i + rows] = block.argmin(axis=1)
        low = block.argmin(axis=0)
        value = block[low, np.arange(m)]
        better = value < column_min
        column_min[better], column_arg[better] = value[better], low[better] + i
    ok = np.isfinite(d2[np.arange(n), j]) & (column_arg[j] == np.arange(n))
    return j, ok


def vote_hypotheses(t_feat, r_feat, n: int, seed: int) -> List[np.ndarray]:
    """Similarity hypotheses (2 x 3) from nearest-neighbour matches voting in a (rotation, log2 scale)
    histogram (``VOTE_ANGLE_DEG`` x half octaves, circularly smoothed over rotation); each of the
    ``n`` strongest cells runs a similarity RANSAC on the matches within one bin of it."""
    txy, tori, td, tf = t_feat
    rxy, rori, rd, rf = r_feat
    if len(txy) < 3 or len(rxy) < 3:
        return []
    j = nearest(td, rd)
    turn = np.degrees(rori[j] - tori) % 360
    na, ns = int(round(360 / VOTE_ANGLE_DEG)), 5
    ai = np.floor(turn / VOTE_ANGLE_DEG).astype(int) % na
    si = np.clip(np.round(np.log2(tf / rf[j]) * 2).astype(int) + 2, 0, ns - 1)
    h = np.zeros((na, ns))
    np.add.at(h, (ai, si), 1.0)
    h = 0.5 * h + 0.25 * np.roll(h, 1, 0) + 0.25 * np.roll(h, -1, 0)
    size = float(np.ptp(rxy, axis=0).max())
    out, used = [], np.zeros_like(h, bool)
    for o in np.argsort(-h.ravel(), kind="stable"):
        a, s = divmod(int(o), ns)
        if used[a, s]:
            continue
        used[[(a - 1) % na, a, (a + 1) % na], max(s - 1, 0):s + 2] = True
        near = (np.abs((ai - a + na // 2) % na - na // 2) <= 1) & (np.abs(si - s) <= 1)
        if near.sum() < 3:
            continue
        model, _ = ransac_or_none(txy[near], rxy[j[near]], "similarity", threshold_px=0.02 * size, rng=seed,
                                  scale_range=(0.4, 2.5))
        if model is not None:
            out.append(model.matrix[:2])
        if len(out) == n:
            break
    return out


def _check(corr: ShiftCorrelator, pyr: TargetPyramid, m: np.ndarray, f_ref: float):
    """Best (z, affine full-res target px -> full-res reference px) over ``CHECK_SCALES`` around ``m``."""
    angle, scale = angle_scale(m)
    sr = scaling(f_ref)
    centre = np.array(pyr.shape_full[::-1]) / 2.0
    to = apply(compose(sr, m), centre[None])[0]
    best = (-np.inf, m)
    for ds in CHECK_SCALES:
        z, _, shifted = corr.best(pyr, similarity(angle, scale * ds * f_ref, centre, to), CHECK_SHIFT_PX)
        if z > best[0]:
            best = (z, compose(invert(sr), shifted))
    return best


def local_rift(target, t_valid, reference_local, m, radius: float, seed: int):
    """Refine ``m`` by plain MIM matching between the reference (its :func:`local_reference`) and the target
    warped by ``m`` at that size: mutual nearest neighbours within ``radius`` x the working size, then a
    similarity RANSAC (3 px). Returns (refined m or None, target px (K, 2), reference px (K, 2) of
    its inliers) in full-resolution working px."""
    shape, sr, rfeat = reference_local
    fwd = compose(sr, m)
    tw, tok = warp(target, t_valid, fwd, shape)
    none = (None, np.zeros((0, 2)), np.zeros((0, 2)))
    if tok.sum() < 0.05 * tok.size:
        return none
    tfeat = rift.plain_features(tw, tok, 1500, LOCAL_PATCH_PX)
    txy, td, rxy, rd = tfeat.keypoints.xy, tfeat.descriptors, rfeat.keypoints.xy, rfeat.descriptors
    if len(txy) < 4 or len(rxy) < 4:
        return none
    j, ok = mutual_nearest_within(squared_distances(td, rd), txy, rxy, radius * max(shape))
    src, dst = txy[ok], rxy[j[ok]]
    if len(src) < 4:
        return none
    model, inliers = ransac_or_none(src, dst, "similarity", threshold_px=3.0, rng=seed)
    if model is None:
        return none
    back = invert(sr)
    refined = compose(back, compose(model.matrix[:2], fwd))
    return refined, apply(invert(fwd), src[inliers]), apply(back, dst[inliers])


def local_reference(reference, r_valid, params: XmodalParams) -> tuple:
    """(shape, scaling, plain RIFT features) of the reference at ``params.local_px``, for :func:`local_rift`."""
    f = min(1.0, params.local_px / max(reference.shape))
    ref, rok, sr = resize(reference, r_valid, f)
    return ref.shape, sr, rift.plain_features(ref, rok, 1500, LOCAL_PATCH_PX)


def _refined(t_img, t_ok, reference_local, m, params: XmodalParams, seed: int, monitor: Monitor):
    """Hypothesis ``m`` refined by local RIFT at each of ``LOCAL_RADII`` while it keeps enough inliers:
    (model, target px, reference px)."""
    found = (m, np.zeros((0, 2)), np.zeros((0, 2)))
    for radius in LOCAL_RADII:
        monitor.check()
        new, src, dst = local_rift(t_img, t_ok, reference_local, found[0], radius, seed)
        if new is None or len(src) < params.min_inliers:
            break
        found = (new, src, dst)
    return found


def match(target, reference, params: XmodalParams, monitor: Monitor, seed: int = 0) -> Matches:
    """Working-pixel correspondences of the winning hypothesis' local RIFT inliers."""
    t0 = time.perf_counter()
    t_img, t_ok, r_img, r_ok = target.data, target.valid, reference.data, reference.valid
    f = min(1.0, params.feat_px / max(r_img.shape))
    t_feat, r_feat = _pyramid_features([(t_img, t_ok), (r_img, r_ok)], f, params.levels, params.points)
    monitor.report(0.55, "RIFT features")
    hyps = vote_hypotheses(t_feat, r_feat, params.hypotheses, seed)
    diag = {"n_hypotheses": len(hyps), "features_s": round(time.perf_counter() - t0, 3)}
    if not hyps:
        return Matches.empty(len(t_feat[0]), len(r_feat[0]))
    f_c = params.check_px / max(r_img.shape)
    ref_c, rok_c, _ = resize(r_img, r_ok, f_c)
    corr = ShiftCorrelator(oriented_channels(ref_c, rok_c, 9, 1), rok_c, pad=CHECK_SHIFT_PX)
    need = [angle_scale(h)[1] * f_c for h in hyps]
    spread = max(CHECK_SCALES) / min(CHECK_SCALES)
    hi, lo = max(need) * 2 ** 0.25 * spread ** 0.5, min(need) * 2 ** -0.25 / spread ** 0.5
    pyr = TargetPyramid(t_img, t_ok, min(hi, 1.0), int(math.ceil(2 * math.log2(hi / lo))) + 2, bins=9, sub=4,
                        min_factor=lo * 0.7)
    # the reference's local features beside the pose checks
    jobs = [lambda: local_reference(r_img, r_ok, params)] + [lambda h=h: _check(corr, pyr, h, f_c) for h in hyps]
    reference_local, *checks = threaded(lambda job: job(), jobs)
    checked = sorted(checks, key=lambda c: -c[0])
    monitor.report(0.75, "pose check")
    refine = lambda m: _refined(t_img, t_ok, reference_local, m, params, seed, monitor)  # noqa: E731
    best = (0, None, None, None)
    for found in threaded(refine, [m for _, m in checked[:params.refine_best]]):  # in order: ties go to the first
        if len(found[1]) > best[0]:
            best = (len(found[1]), found[0], found[1], found[2])
    monitor.report(1.0, "local RIFT")
    n, m, src, dst = best
    diag.update(z_best=round(float(checked[0][0]), 3), local_inliers=n, time_s=round(time.perf_counter() - t0, 3))
    if m is not None:
        diag["rotation_deg"], diag["scale"] = (round(v, 4) for v in angle_scale(m))
    if n == 0:
        return Matches(np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0), len(t_feat[0]), len(r_feat[0]), diag)
    return Matches(src, dst, np.ones(n), len(t_feat[0]), len(r_feat[0]), diag)


METHOD = register_method(Method(
    name="xmodal", title="Across modalities at any rotation and scale (RIFT votes + CFOG check + local RIFT)",
    summary="Registers a target of another modality than the reference (SAR, infrared, a depth rendering, a web "
            "map, night lights onto optical imagery) at any rotation and at scales from 1/2 to 2: phase-congruency "
            "(RIFT) features vote for rotation and scale, each hypothesis is checked densely with CFOG structural "
            "descriptors, the best are refined by matching RIFT descriptors near their predicted positions, and "
            "the result is refined at full resolution with CFOG and checked independently. Its baseline, the "
            "published RIFT2 matcher, is the CLI method 'rift'.",
    citation="J. Li, Q. Hu and M. Ai (2020), RIFT, IEEE Transactions on Image Processing 29:3296-3310; J. Li, Q. "
             "Hu and Y. Zhang (2023), Multimodal image matching: a scale-invariant algorithm and an open dataset, "
             "ISPRS Journal of Photogrammetry and Remote Sensing 204:77-88; Y. Ye et al. (2019), CFOG, IEEE TGRS "
             "57(11):9059-9070.", params_type=XmodalParams, match=match, ransac_threshold_px=4.0, refine="always",
    refinement=STRUCTURAL_REFINEMENT,
    use_when="different modalities at any rotation and scale 1/2-2 (SAR, infrared, depth, maps, night lights)",
    toolbox=Toolbox("registercrossmodal", "Register across modalities at any rotation and scale")))
