"""SIBRIF: fast aerial-to-satellite matching (spec 001).

Safdari, M., Moallem, P., & Sattari, M. Robust and fast aerial and satellite image matching based
on selective scale and rotation (in Persian; SIBRIF, "Scale Invariant and Binary Rotation
Invariant Feature"). Specification: ``../shared/specs/001_selective.md``.

Pipeline: Sobel gradient magnitude thresholded to zero at T -> SIFT difference-of-Gaussian
keypoints detected on that edge image -> rBRIEF descriptors (256 bits, 31 x 31) of the grey
image steered by the intensity-centroid angle of Eq. 4 -> removal of self-similar keypoints
within each image (Hamming) -> bidirectional (mutual) nearest neighbours -> RANSAC with affine
3-point samples (the shared robust fit) -> GCPs.

The paper leaves T, the similarity threshold and the RANSAC tolerance unspecified; they are
parameters with documented defaults (``hamta bench --methods sibrif --sweep KEY=V1,V2`` compares values).
"Selective angle and scale" in the title names the pipeline, not a voting step; the literal vote of the spec's
Appendix B (histograms of angle and log-scale differences) is an option, off by default.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np

from ..descriptors.rbrief import intensity_centroid_angle, rbrief_descriptors
from ..descriptors.sift import SiftDetector, sift_keypoints
from ..matching.nearest import match_features, self_similar
from ..preprocess.edges import sobel_edge_image
from ..preprocess.normalize import detection_mask, stretch_to_uint8
from ..progress import Monitor
from ..types import Features, Keypoints, Matches
from .registry import Method, Toolbox, param, register_method, validate

CITATION = ("Safdari, Moallem & Sattari, Robust and fast aerial and satellite image matching based on selective "
            "scale and rotation (SIBRIF, in Persian; spec 001)")


@dataclass(frozen=True)
class SibrifParams:
    """Parameters of SIBRIF (product defaults; see SibrifFaithfulParams for the paper's)."""

    edge_threshold: float = param(10.0, "Sobel magnitude threshold T (0..255; gap in the paper, default from a "
                                        "sweep).", minimum=0.0, maximum=254.0)
    similarity_threshold: float = param(10.0, "Hamming distance under which a keypoint with a near-duplicate in its "
                                              "own image is removed (gap; from a sweep).", minimum=0.0)
    magnitude: str = param("l2", "Gradient magnitude: l1 = 0.5|Gx|+0.5|Gy| (OpenCV tutorial, the spec's reading) or "
                                 "l2 = sqrt(Gx^2+Gy^2)/sqrt(2), which does not change with edge direction.",
                           choices=("l1", "l2"))
    threshold_mode: str = param("soft", "to-zero keeps magnitudes above T (the paper); soft subtracts T, so the edge "
                                        "image has no jumps at the threshold for the DoG to fire on.",
                                choices=("to-zero", "soft"))
    detection_scale: float = param(1.0, "Resolution at which the DoG pyramid starts (2 = OpenCV SIFT's upsampled "
                                         "base, the paper's; 1 = full resolution, 4x less work).",
                                   minimum=0.25, maximum=2.0)
    max_keypoints: int = param(1500, "Strongest DoG keypoints kept per image (0 = all, as the paper).", minimum=0)
    contrast_threshold: float = param(0.04, "SIFT DoG contrast threshold on the edge image (OpenCV default).",
                                      minimum=0.0)
    scale_levels: bool = param(True, "Describe each keypoint on the pyramid level matching its SIFT size (the paper "
                                     "uses a fixed 31-px patch, which breaks beyond ~1.5x scale).")
    ratio: float = param(0.8, "Lowe ratio on Hamming distances (1 = off, as the paper).", minimum=0.0, maximum=1.0)
    selective_vote: bool = param(False, "Spec Appendix B (not in the paper): keep matches at the peaks of the angle "
                                        "and log-scale difference histograms.")

    def __post_init__(self):
        validate(self)


@dataclass(frozen=True)
class SibrifFaithfulParams(SibrifParams):
    """The paper as written (and, for its gaps, the spec's readings)."""

    edge_threshold: float = param(80.0, "Sobel magnitude threshold T (0..255; gap in the paper, default from a "
                                        "sweep).", minimum=0.0, maximum=254.0)
    magnitude: str = param("l1", "Faithful: OpenCV tutorial magnitude 0.5|Gx|+0.5|Gy|.", choices=("l1", "l2"))
    threshold_mode: str = param("to-zero", "Faithful: threshold-to-zero.", choices=("to-zero", "soft"))
    detection_scale: float = param(2.0, "Faithful: OpenCV SIFT as is (upsampled base).", minimum=0.25, maximum=2.0)
    max_keypoints: int = param(0, "Faithful: every DoG keypoint.", minimum=0)
    scale_levels: bool = param(False, "Faithful: one 31-px patch at full resolution for every keypoint.")
    ratio: float = param(1.0, "Faithful: mutual nearest neighbours without a ratio test.", minimum=0.0, maximum=1.0)


LEVEL_STEP = 1.25  # scale between description levels
LEVEL_BASE_SIZE = 4.0  # SIFT keypoint size (px) described on the full-resolution image


def edge_image(gray: np.ndarray, params: SibrifParams) -> np.ndarray:
    """The thresholded Sobel edge image (uint8) the keypoints are detected on."""
    if params.magnitude == "l1" and params.threshold_mode == "to-zero":
        return sobel_edge_image(gray, params.edge_threshold)
    gx = cv2.Sobel(gray, cv2.CV_32F, 1, 0, ksize=3)
    gy = cv2.Sobel(gray, cv2.CV_32F, 0, 1, ksize=3)
    if params.magnitude == "l1":
        mag = cv2.addWeighted(np.abs(gx), 0.5, np.abs(gy), 0.5, 0)
    else:
        mag = np.hypot(gx, gy) * np.float32(1 / math.sqrt(2))  # cv2.magnitude is not deterministic
    t = np.float32(params.edge_threshold)
    if params.threshold_mode == "soft":
        return cv2.convertScaleAbs(cv2.max(mag - t, 0))  # rounds and saturates at 255
    _, edges = cv2.threshold(cv2.convertScaleAbs(mag), float(t), 255, cv2.THRESH_TOZERO)
    return edges


def edge_keypoints(edges: np.ndarray, mask: np.ndarray, params: SibrifParams) -> Keypoints:
    """SIFT DoG keypoints of the edge image, in its corner-convention pixels."""
    sift = SiftDetector(n_features=params.max_keypoints, contrast_threshold=params.contrast_threshold)
    if params.detection_scale >= 2.0:
        return sift_keypoints(edges, mask, sift)
    # OpenCV always doubles its input first; shrinking it by detection_scale / 2 beforehand starts the
    # pyramid at detection_scale.
    h, w = edges.shape
    f = params.detection_scale / 2.0
    small = cv2.resize(edges, (max(1, int(round(w * f))), max(1, int(round(h * f)))), interpolation=cv2.INTER_AREA)
    small_mask = cv2.resize(mask, (small.shape[1], small.shape[0]), interpolation=cv2.INTER_NEAREST)
    kp = sift_keypoints(small, small_mask, sift)
    sx, sy = w / small.shape[1], h / small.shape[0]
    return Keypoints(kp.xy * [sx, sy], kp.size * sx, kp.angle, kp.response)


def sibrif_features(img, params: SibrifParams) -> Features:
    """Edge keypoints described by rBRIEF on the grey image; self-similar keypoints removed."""
    gray = stretch_to_uint8(img.data, img.valid)
    kp = edge_keypoints(edge_image(gray, params), detection_mask(img.valid, 3), params)
    if len(kp) == 0:
        return Features(Keypoints.empty(), np.zeros((0, 32), np.uint8), "hamming")
    levels = _levels(kp.size) if params.scale_levels else np.zeros(len(kp), int)
    index, desc, angle = [], [], np.zeros(len(kp))
    level_img = gray
    for lv in range(int(levels.max()) + 1):
        if lv > 0:  # each level from the previous one: a cheap pyramid
            f = LEVEL_STEP ** lv
            size = (max(1, int(round(gray.shape[1] / f))), max(1, int(round(gray.shape[0] / f))))
            level_img = cv2.resize(level_img, size, interpolation=cv2.INTER_AREA)
        sel = np.flatnonzero(levels == lv)
        if len(sel) == 0:
            continue
        xy = kp.xy[sel] * [level_img.shape[1] / gray.shape[1], level_img.shape[0] / gray.shape[0]]
        ang = intensity_centroid_angle(level_img, xy)
        kept, d = rbrief_descriptors(level_img, xy, ang)
        index.append(sel[kept])
        desc.append(d)
        angle[sel] = ang
    index = np.concatenate(index) if index else np.zeros(0, int)
    feats = Features(Keypoints(kp.xy[index], kp.size[index], angle[index], kp.response[index]),
                     np.concatenate(desc) if desc else np.zeros((0, 32), np.uint8), "hamming")
    return feats.subset(~self_similar(feats, params.similarity_threshold))


def _levels(size: np.ndarray) -> np.ndarray:
    lv = np.floor(np.log(np.maximum(size, 1e-6) / LEVEL_BASE_SIZE) / math.log(LEVEL_STEP) + 0.5)
    return np.clip(lv, 0, 12).astype(int)


def selective_vote(ft: Features, fr: Features, it, ir, angle_bin_deg: float = 10.0, scale_bin_octaves: float = 0.25):
    """Spec 001 Appendix B (an extension, not the paper): keep matches whose orientation difference
    and log2 size ratio fall within one bin of the histogram peaks."""
    if len(it) == 0:
        return np.zeros(0, bool)
    d_angle = (fr.keypoints.angle[ir] - ft.keypoints.angle[it]) % 360.0
    d_scale = np.log2(fr.keypoints.size[ir] / ft.keypoints.size[it])
    a_bins = np.floor(d_angle / angle_bin_deg).astype(int)
    n_a = int(round(360.0 / angle_bin_deg))
    peak_a = np.bincount(a_bins % n_a, minlength=n_a).argmax()
    near_a = np.minimum((a_bins - peak_a) % n_a, (peak_a - a_bins) % n_a) <= 1
    s_bins = np.floor(d_scale / scale_bin_octaves).astype(int)
    values, counts = np.unique(s_bins, return_counts=True)
    near_s = np.abs(s_bins - values[np.argmax(counts)]) <= 1
    return near_a & near_s


def match(target, reference, params: SibrifParams, monitor: Monitor, seed: int = 0) -> Matches:
    ft = sibrif_features(target, params)
    monitor.report(0.45, "edge keypoints and rBRIEF")
    fr = sibrif_features(reference, params)
    monitor.report(0.9, "edge keypoints and rBRIEF")
    it, ir, score = match_features(ft, fr, ratio=params.ratio, cross_check="mutual")
    diagnostics = {"n_after_self_similarity": [len(ft), len(fr)]}
    if params.selective_vote:
        keep = selective_vote(ft, fr, it, ir)
        diagnostics["selective_vote_kept"] = int(keep.sum())
        it, ir, score = it[keep], ir[keep], score[keep]
    monitor.report(1.0, "matching")
    return Matches(ft.keypoints.xy[it], fr.keypoints.xy[ir], score, len(ft), len(fr), diagnostics)


METHOD = register_method(Method(
    name="sibrif",
    title="SIBRIF (fast aerial-to-satellite)",
    summary="Registers an aerial (or any optical) image onto a satellite reference quickly: SIFT "
            "difference-of-Gaussian keypoints detected on a thresholded Sobel edge image, rBRIEF binary "
            "descriptors steered by the intensity centroid, removal of self-similar keypoints, mutual Hamming "
            "matching and RANSAC with affine samples. Few, strong keypoints make it several times faster than "
            "SIFT. Product defaults describe each keypoint at its own scale and add a ratio test; the CLI method "
            "'sibrif-faithful' is the paper as written.",
    citation="M. Safdari, P. Moallem and M. Sattari, Robust and fast aerial and satellite image matching based on "
             "selective scale and rotation (SIBRIF).", params_type=SibrifParams, match=match,
    ransac_threshold_px=2.0,  # the paper gives none
    use_when="aerial or drone frames onto satellite imagery, when speed matters",
    toolbox=Toolbox("registersibrif", "Register aerial image onto satellite image (SIBRIF, fast)")))

FAITHFUL = register_method(Method(
    name="sibrif-faithful",
    title="SIBRIF, as published",
    summary="The paper's pipeline: fixed 31-px rBRIEF patches at full resolution.",
    citation=CITATION, params_type=SibrifFaithfulParams, match=match, kind="faithful", ransac_threshold_px=2.0))

