"""OpenCV SIFT + ratio test: the classic baseline every method is measured against.

Lowe, D. G. (2004). Distinctive image features from scale-invariant keypoints. IJCV 60(2),
91-110. :DOI:`10.1023/B:VISI.0000029664.99615.94`
"""
from __future__ import annotations

from dataclasses import dataclass

from ..descriptors.sift import SiftDetector, sift_features
from ..matching.nearest import CROSS_CHECKS
from ..preprocess.normalize import detection_mask, stretch_to_uint8
from .registry import Method, Toolbox, match_with, param, register_method, validate


@dataclass(frozen=True)
class SiftParams:
    """Parameters of the SIFT baseline."""

    n_features: int = param(8000, "Strongest keypoints kept per image (0 = all).", minimum=0)
    contrast_threshold: float = param(0.04, "DoG contrast threshold (OpenCV default, Lowe 2004).", minimum=0.0)
    edge_threshold: float = param(10.0, "Edge-response ratio limit (Lowe 2004).", minimum=1.0)
    ratio: float = param(0.8, "Lowe's nearest/second-nearest distance ratio.", minimum=0.0, maximum=1.0)
    cross_check: str = param("mutual", "Cross-check of matches: none, mutual or dual-ratio.", choices=CROSS_CHECKS)

    def __post_init__(self):
        validate(self)


def sift_image_features(img, params: SiftParams):
    """OpenCV SIFT on a working image (8-bit percentile stretch)."""
    detector = SiftDetector(n_features=params.n_features, contrast_threshold=params.contrast_threshold,
                            edge_threshold=params.edge_threshold)
    return sift_features(stretch_to_uint8(img.data, img.valid), detection_mask(img.valid), detector)


METHOD = register_method(Method(
    name="sift",
    title="SIFT baseline (OpenCV)",
    summary="Registers the target raster onto the reference raster automatically: OpenCV SIFT keypoints, Lowe's "
            "ratio test with a mutual check, seeded RANSAC, full-resolution refinement, and the chosen "
            "transformation fitted on well-spread GCPs. Writes the georeferenced raster, the GCPs as a point layer "
            "and, on request, a QGIS Georeferencer .points file, a VRT carrying the GCPs and a JSON report.",
    citation="D. G. Lowe (2004), Distinctive image features from scale-invariant keypoints, IJCV 60(2):91-110, "
             "doi:10.1023/B:VISI.0000029664.99615.94",
    params_type=SiftParams,
    match=match_with(sift_image_features, "SIFT keypoints"),
    kind="baseline",
    use_when="same sensor or similar optical images, any rotation and scale (what auto tries first)",
    toolbox=Toolbox("registersift", "Register raster (SIFT baseline)")))
