"""Where in a large search area a small target lies: SIFT matches voting for a pose.

Lowe, D. G. (2004). Distinctive image features from scale-invariant keypoints. IJCV 60(2), 91-110,
section 7 (object recognition: a Hough transform over pose, then a least-squares fit).
:DOI:`10.1023/B:VISI.0000029664.99615.94`

A target covering 1/900 of the area has few keypoints among the area's tens of thousands, so
Lowe's ratio test against the *area's* second-nearest neighbour throws most right matches away
(another field looks alike). Here each area keypoint is matched to the *target's* two nearest
descriptors instead (``ratio`` against the target's own second best, where distractors are few),
every match votes for the similarity it implies (a keypoint's position, scale and orientation fix
one), and the places where many votes agree are the candidates, each fitted by least squares on the
matches that agree with it. Only the independent check of a later registration decides which, if
any, is right: a candidate is where to look, never a result.

Pixels: target working pixels and area working pixels, corner convention.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import List

import numpy as np

from ..descriptors.sift import SiftDetector, sift_features
from ..preprocess.normalize import detection_mask, stretch_to_uint8

NEIGHBOURS = 1
RATIO = 0.9  # against the target's own second-nearest descriptor (a loose test: votes do the rest)
ANGLE_BIN_DEG = 30.0  # Lowe's bins: 30 degrees, a factor of 2 in scale, a quarter of the projected size
LOCATION_BIN = 0.25
MIN_VOTES = 4
CONTRAST = 0.015  # below OpenCV's 0.04: images of other dates are often flat (water, bare fields), and votes
# tolerate the weaker keypoints this admits
MARGIN = 48  # px around each detection block: keypoints near its edge see their whole neighbourhood


@dataclass(frozen=True)
class Candidate:
    """A place the target may be: ``matrix`` (2 x 3) maps target working px to area working px."""

    matrix: np.ndarray
    inliers: int
    votes: int
    score: float = 0.0  # a correlation's (structure_places), where there are no features to count

    @property
    def scale(self) -> float:
        return float(math.sqrt(abs(np.linalg.det(self.matrix[:, :2]))))

    @property
    def angle_deg(self) -> float:
        return float(math.degrees(math.atan2(self.matrix[1, 0], self.matrix[0, 0])))

    def apply(self, xy: np.ndarray) -> np.ndarray:
        return np.asarray(xy, float) @ self.matrix[:, :2].T + self.matrix[:, 2]


def features(image: np.ndarray, valid: np.ndarray, per_block: int = 3000, block: int = 1024):
    """SIFT keypoints (working pixels) with RootSIFT descriptors (Arandjelovic and Zisserman 2012:
    L1-normalised square roots compared by L2, which separate true from false matches better under
    radiometric change), detected block by block so that a large area costs bounded memory (OpenCV
    builds its scale space on the image doubled: 16 Mpx whole would take about 1.5 GB)."""
    from ..parallel import threaded
    from ..types import Keypoints

    stretched = stretch_to_uint8(image, valid)
    mask = detection_mask(valid)
    h, w = image.shape
    detector = SiftDetector(n_features=per_block, contrast_threshold=CONTRAST)
    jobs = [(r, c) for r in range(0, h, block) for c in range(0, w, block)]

    def detect(job):
        r, c = job
        r0, c0 = max(0, r - MARGIN), max(0, c - MARGIN)
        r1, c1 = min(h, r + block + MARGIN), min(w, c + block + MARGIN)
        if not mask[r0:r1, c0:c1].any():
            return None
        found = sift_features(np.ascontiguousarray(stretched[r0:r1, c0:c1]), np.ascontiguousarray(mask[r0:r1, c0:c1]),
                              detector)
        xy = found.keypoints.xy + (c0, r0)
        inside = (xy[:, 0] >= c) & (xy[:, 0] < c + block) & (xy[:, 1] >= r) & (xy[:, 1] < r + block)
        k = found.keypoints
        return xy[inside], k.size[inside], k.angle[inside], k.response[inside], found.descriptors[inside]

    parts = [p for p in threaded(detect, jobs) if p is not None and len(p[0])]
    if not parts:
        return Keypoints.empty(), np.zeros((0, 128), np.float32)
    xy, size, angle, response, desc = (np.concatenate(col) for col in zip(*parts))
    desc = desc.astype(np.float32)
    desc /= np.maximum(desc.sum(axis=1, keepdims=True), 1e-9)
    return Keypoints(xy, size, angle, response), np.sqrt(desc)


def locate(target_kp, target_desc, area_kp, area_desc, target_shape, limit: int = 5) -> List[Candidate]:
    """Up to ``limit`` candidate places of the target in the area, best first (most inliers)."""
    import cv2

    if len(target_kp) < MIN_VOTES or len(area_kp) < MIN_VOTES:
        return []
    k = NEIGHBOURS
    pairs = cv2.BFMatcher(cv2.NORM_L2).knnMatch(area_desc, target_desc, k=k + 1)
    a_idx, t_idx = [], []
    for m in pairs:
        if len(m) == k + 1:
            for near in m[:k]:
                if near.distance < RATIO * m[k].distance:
                    a_idx.append(near.queryIdx)
                    t_idx.append(near.trainIdx)
    if len(a_idx) < MIN_VOTES:
        return []
    a_idx, t_idx = np.asarray(a_idx), np.asarray(t_idx)
    pose = _poses(target_kp, area_kp, t_idx, a_idx, target_shape)
    return places(target_kp.xy[t_idx], area_kp.xy[a_idx], pose, target_shape, limit)


def places(target_xy, area_xy, pose, target_shape, limit: int = 5) -> List[Candidate]:
    """Up to ``limit`` places where matches (``target_xy`` <-> ``area_xy``, each with the ``pose`` it
    predicts, see :func:`_poses`) agree, most inliers first, none within a quarter of the target's size
    of a better one."""
    size = math.hypot(*target_shape)
    candidates: List[Candidate] = []
    for members, votes in _clusters(pose, size):
        if len(candidates) >= limit:
            break
        fit = _fit(target_xy, area_xy, pose, members)
        if fit is None:
            continue
        matrix, inliers = fit
        centre = np.array([target_shape[1] / 2.0, target_shape[0] / 2.0])
        here = centre @ matrix[:, :2].T + matrix[:, 2]
        scale = math.sqrt(abs(np.linalg.det(matrix[:, :2])))
        if any(np.hypot(*(here - c.apply(centre[None])[0])) < 0.25 * size * max(scale, c.scale)
               for c in candidates):
            continue
        candidates.append(Candidate(matrix, inliers, votes))
    return sorted(candidates, key=lambda c: -c.inliers)


def learned_locate(turned, area, target_shape, limit: int = 5, min_cossim: float = 0.82) -> List[Candidate]:
    """:func:`locate` with XFeat's upright features (:mod:`hamta.core.descriptors.xfeat`): ``turned`` holds
    the target's features at each turn and scale tried (keypoints in target working pixels; the turn in
    ``Keypoints.angle``, degrees counter-clockwise as displayed, the scale as 8 / ``Keypoints.size``),
    ``area`` the area's. Mutual nearest neighbours within each turn vote for the pose that turn implies."""
    from .nearest import mutual_nearest

    txy, axy, pose = [], [], []
    for f in turned:
        it, ia, _ = mutual_nearest(f.descriptors, area.descriptors, min_cossim)
        if len(it) == 0:
            continue
        t, a = f.keypoints.xy[it], area.keypoints.xy[ia]
        pose.append(_pose(t, a, math.radians(f.keypoints.angle[0]), 8.0 / f.keypoints.size[0], target_shape))
        txy.append(t)
        axy.append(a)
    if sum(map(len, txy)) < MIN_VOTES:
        return []
    return places(np.concatenate(txy), np.concatenate(axy), np.concatenate(pose), target_shape, limit)


def _poses(target_kp, area_kp, t_idx, a_idx, target_shape) -> np.ndarray:
    """(N, 4): log2 scale, angle (radians, counter-clockwise as displayed) and the target centre's
    position in the area, as each match predicts them."""
    scale = area_kp.size[a_idx] / target_kp.size[t_idx]
    turn = np.radians(target_kp.angle[t_idx] - area_kp.angle[a_idx])  # OpenCV's angles are clockwise
    return _pose(target_kp.xy[t_idx], area_kp.xy[a_idx], turn, scale, target_shape)


def _pose(target_xy, area_xy, turn, scale, target_shape) -> np.ndarray:
    """The poses (see :func:`_poses`) of matches under their ``turn`` (radians) and ``scale``."""
    centre = np.array([target_shape[1] / 2.0, target_shape[0] / 2.0])
    d = centre - target_xy
    cos, sin = np.cos(turn) * scale, np.sin(turn) * scale
    cx = area_xy[:, 0] + cos * d[:, 0] + sin * d[:, 1]
    cy = area_xy[:, 1] - sin * d[:, 0] + cos * d[:, 1]
    return np.column_stack([np.broadcast_to(np.log2(scale), cx.shape), np.broadcast_to(np.mod(turn, 2 * np.pi),
                                                                                       cx.shape), cx, cy])


def _clusters(pose: np.ndarray, size: float):
    """Hough bins with at least :data:`MIN_VOTES` votes, most first: (indices of their matches, votes).
    Each match votes for the two nearest bins in every dimension, as Lowe does."""
    s = pose[:, 0]
    step = np.column_stack([np.ones(len(pose)), np.full(len(pose), math.radians(ANGLE_BIN_DEG)),
                            LOCATION_BIN * size * 2.0 ** np.round(s), LOCATION_BIN * size * 2.0 ** np.round(s)])
    scaled = pose / step
    base = np.floor(scaled - 0.5).astype(np.int64)
    keys, owners = [], []
    n_angle = int(round(360 / ANGLE_BIN_DEG))
    for corner in range(16):
        offs = np.array([(corner >> k) & 1 for k in range(4)])
        b = base + offs
        b[:, 1] %= n_angle
        b[:, 0] = b[:, 0] * 64 + np.round(s).astype(np.int64) + 32  # location bins differ with the scale
        keys.append(b)
        owners.append(np.arange(len(pose)))
    keys, owners = np.concatenate(keys), np.concatenate(owners)
    _, inverse, counts = np.unique(keys, axis=0, return_inverse=True, return_counts=True)
    by_bin = owners[np.argsort(inverse.ravel(), kind="stable")]  # the votes grouped by bin, bins in order
    starts = np.concatenate([[0], np.cumsum(counts)])
    for b in np.argsort(-counts, kind="stable"):
        if counts[b] < MIN_VOTES:
            break
        yield np.unique(by_bin[starts[b]:starts[b + 1]]), int(counts[b])


def _fit(txy, axy, pose, members, rounds: int = 4):
    """A similarity fitted to a cluster's matches, then to every match it predicts within a tolerance;
    (matrix, distinct inliers) or None when fewer than :data:`MIN_VOTES` agree."""
    chosen = members
    matrix = None
    for _ in range(rounds):
        if len(chosen) < 3:
            return None
        matrix = _similarity(txy[chosen], axy[chosen])
        scale = math.sqrt(abs(np.linalg.det(matrix[:, :2])))
        tol = max(3.0, 0.02 * scale * np.ptp(txy[:, 0]))
        residual = np.hypot(*(txy @ matrix[:, :2].T + matrix[:, 2] - axy).T)
        agree = np.flatnonzero(residual < tol)
        if np.array_equal(agree, chosen):
            break
        chosen = agree
    distinct = len(np.unique(txy[chosen], axis=0))
    return (matrix, distinct) if distinct >= MIN_VOTES else None


def _similarity(src: np.ndarray, dst: np.ndarray) -> np.ndarray:
    """Least-squares similarity (2 x 3) mapping ``src`` onto ``dst`` (Umeyama without reflection)."""
    ms, md = src.mean(0), dst.mean(0)
    s, d = src - ms, dst - md
    a = (s * d).sum()
    b = (s[:, 0] * d[:, 1] - s[:, 1] * d[:, 0]).sum()
    norm = (s ** 2).sum()
    c, sn = a / max(norm, 1e-12), b / max(norm, 1e-12)
    lin = np.array([[c, -sn], [sn, c]])
    return np.column_stack([lin, md - lin @ ms])
