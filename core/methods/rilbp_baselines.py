"""The baselines of spec 000 on the same CenSurE keypoints: CS-LBP and SIFT descriptors.

Both need a dominant orientation: a SIFT-style gradient-orientation histogram (Lowe 2004) turns
each region before description, as Sedaghat & Mohammadi (2019) describe for their baselines.

- CS-LBP: Heikkilä, Pietikäinen & Schmid (2009), Pattern Recognition 42(3):425-436,
  doi:10.1016/j.patcog.2008.08.014 — 4 x 4 grid of 16-bin CS-LBP histograms, 256-D.
- SIFT descriptor: Lowe (2004), IJCV 60(2):91-110, computed by OpenCV at the CenSurE keypoints.
"""
from __future__ import annotations

from dataclasses import dataclass

from ..descriptors.cslbp import CslbpParams, cslbp_descriptors
from ..descriptors.sift import sift_descriptors
from ..detectors.patches import dominant_orientation, sample_patches
from ..types import Features, Keypoints
from .registry import Method, match_with, param, register_method
from .rilbp import CITATION, CensureRegionParams, censure_regions


def oriented(img, params):
    """CenSurE keypoints on the 8-bit image, with SIFT-style dominant orientations."""
    u8, kp, support = censure_regions(img, params)
    angle = dominant_orientation(sample_patches(u8, kp.xy, support, 20, 2), 20)
    return u8, Keypoints(kp.xy, kp.size, angle, kp.response), support


def cslbp_features(img, params) -> Features:
    u8, kp, support = oriented(img, params)
    p = CslbpParams()
    patches = sample_patches(u8, kp.xy, support, p.radius, p.margin, angle_rad=kp.angle)
    return Features(kp, cslbp_descriptors(patches, p), "l2")


def censure_sift_features(img, params) -> Features:
    u8, kp, support = oriented(img, params)
    return Features(kp, sift_descriptors(u8.astype("uint8"), kp.xy, support, kp.angle), "l2")


@dataclass(frozen=True)
class CensureBaselineParams(CensureRegionParams):
    """The spec 000 baselines as compared in the paper: whole-pixel CenSurE positions."""

    subpixel: bool = param(False, "Faithful: whole-pixel CenSurE positions, as in the paper's comparison.")


CSLBP = register_method(Method(
    name="cslbp",
    title="CS-LBP on CenSurE keypoints (spec 000 baseline)",
    summary="Standard CS-LBP descriptor (4x4 grid, 256-D) on CenSurE regions turned to a SIFT-style "
            "dominant orientation: the baseline RILBP is compared with.",
    citation="Heikkilä et al. 2009, Pattern Recognition 42(3), doi:10.1016/j.patcog.2008.08.014; " + CITATION,
    params_type=CensureBaselineParams, match=match_with(cslbp_features), kind="baseline"))

CENSURE_SIFT = register_method(Method(
    name="censure-sift",
    title="SIFT descriptor on CenSurE keypoints (spec 000 baseline)",
    summary="OpenCV SIFT descriptors computed at CenSurE regions with a dominant orientation.",
    citation="Lowe 2004, IJCV 60(2); " + CITATION,
    params_type=CensureBaselineParams, match=match_with(censure_sift_features), kind="baseline"))
