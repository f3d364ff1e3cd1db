"""PCA-SIFT: SIFT keypoints with PCA-projected gradient patches (a spec 001 baseline).

Ke, Y., & Sukthankar, R. (2004). PCA-SIFT: a more distinctive representation for local image
descriptors. CVPR 2004. :DOI:`10.1109/CVPR.2004.1315206`
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..descriptors.pca_sift import pca_sift_descriptors
from ..descriptors.sift import SiftDetector, sift_keypoints
from ..matching.nearest import CROSS_CHECKS
from ..preprocess.normalize import detection_mask, stretch_to_uint8
from ..types import Features, Keypoints
from .registry import Method, match_with, param, register_method, validate


@dataclass(frozen=True)
class PcaSiftParams:
    n_features: int = param(8000, "Strongest SIFT keypoints kept per image (0 = all).", minimum=0)
    ratio: float = param(0.8, "Nearest/second-nearest distance ratio (as the SIFT baseline).", minimum=0.0,
                         maximum=1.0)
    cross_check: str = param("mutual", "Cross-check of matches: none, mutual or dual-ratio.", choices=CROSS_CHECKS)

    def __post_init__(self):
        validate(self)


def pca_sift_features(img, params: PcaSiftParams) -> Features:
    gray = stretch_to_uint8(img.data, img.valid)
    kp = sift_keypoints(gray, detection_mask(img.valid), SiftDetector(n_features=params.n_features))
    if len(kp) == 0:
        return Features(Keypoints.empty(), np.zeros((0, 36), np.float32), "l2")
    angle = -np.radians(kp.angle)  # OpenCV's angle is clockwise in degrees
    return Features(kp, pca_sift_descriptors(gray, kp.xy, kp.size, angle), "l2")


METHOD = register_method(Method(
    name="pca-sift",
    title="PCA-SIFT (spec 001 baseline)",
    summary="SIFT keypoints described by 41x41 gradient patches projected on a 36-D principal subspace learnt "
            "from real imagery (shipped with the package).",
    citation="Ke & Sukthankar 2004, CVPR, doi:10.1109/CVPR.2004.1315206",
    params_type=PcaSiftParams, match=match_with(pca_sift_features, "SIFT keypoints, PCA-SIFT"), kind="baseline"))
