"""OpenCV ORB + ratio test: the fast binary-descriptor baseline.

Rublee, E., Rabaud, V., Konolige, K., & Bradski, G. (2011). ORB: an efficient alternative to SIFT
or SURF. ICCV 2011. :DOI:`10.1109/ICCV.2011.6126544`
"""
from __future__ import annotations

from dataclasses import dataclass

from ..descriptors.orb import OrbDetector, orb_features
from ..matching.nearest import CROSS_CHECKS
from ..preprocess.normalize import detection_mask, stretch_to_uint8
from .registry import Method, match_with, param, register_method, validate


@dataclass(frozen=True)
class OrbParams:
    """Parameters of the ORB baseline."""

    n_features: int = param(8000, "Strongest keypoints kept per image.", minimum=1)
    fast_threshold: int = param(20, "FAST corner threshold (OpenCV default).", minimum=1)
    n_levels: int = param(8, "Pyramid levels, scale factor 1.2 (OpenCV default).", minimum=1)
    ratio: float = param(0.8, "Nearest/second-nearest Hamming distance ratio.", minimum=0.0, maximum=1.0)
    cross_check: str = param("mutual", "Cross-check of matches: none, mutual or dual-ratio.", choices=CROSS_CHECKS)

    def __post_init__(self):
        validate(self)


def orb_image_features(img, params: OrbParams):
    """OpenCV ORB on a working image (8-bit percentile stretch)."""
    detector = OrbDetector(n_features=params.n_features, fast_threshold=params.fast_threshold,
                           n_levels=params.n_levels)
    return orb_features(stretch_to_uint8(img.data, img.valid), detection_mask(img.valid, 16), detector)


METHOD = register_method(Method(
    name="orb",
    title="ORB baseline (OpenCV)",
    summary="OpenCV ORB keypoints with rBRIEF descriptors, Hamming ratio test with a mutual check, robust fit. "
            "Fast; weaker under large scale changes.",
    citation="Rublee et al. 2011, ICCV, doi:10.1109/ICCV.2011.6126544",
    params_type=OrbParams,
    match=match_with(orb_image_features, "ORB keypoints"),
    kind="baseline",
))
