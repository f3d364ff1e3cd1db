"""Regions as control points: a scanned map onto a layer of its areas by the places of its lakes and blocks.

Goshtasby, A., Stockman, G. C., & Page, C. V. (1986). A region-based approach to digital image registration
with subpixel accuracy. IEEE TGRS 24(3), 390-399. :DOI:`10.1109/TGRS.1986.289597`

A scanned map, a rasterized layer (water, buildings) and a photo share few local textures but many of the
same closed shapes. The regions of each image (:mod:`hamta.core.detectors.regions`) are matched as a
constellation (:mod:`hamta.core.matching.constellation`): any rotation, any scale. Their centroids are the
correspondences; the full-resolution refinement and the independent check follow as for every method.

Deviations from the paper: regions are cut at many grey levels rather than by one segmentation
(``levels``: which level shows a map's lakes or a photo's fields is not known beforehand), and matched by
where they lie together rather than by shape alone (a lake drawn on a map and the same lake photographed in
another year differ in shape); the paper's iterative re-segmentation for subpixel centroids is replaced by
the shared full-resolution refinement.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..detectors.regions import find_regions
from ..matching.constellation import match_constellation
from ..progress import Monitor
from ..refine import STRUCTURAL_REFINEMENT
from ..types import Matches
from .registry import Method, Toolbox, param, register_method, validate


@dataclass(frozen=True)
class RegionsParams:
    """Parameters of the region matcher."""

    levels: int = param(12, "Grey levels (percentiles) at which regions are cut from each image.", minimum=2)
    min_area_px: int = param(25, "Smallest region kept, working px.", minimum=4)
    max_pixels: int = param(1_500_000, "Each image is matched at most this size (the larger of the two is "
                            "brought to the smaller's pixel count first).", minimum=100_000)
    anchors: int = param(60, "Largest target regions each paired with every large reference region to "
                         "propose a similarity.", minimum=3)
    max_regions: int = param(3000, "At most this many target regions, the largest, score a similarity: a bound "
                             "on the search's time where a scan holds tens of thousands (letters, specks).",
                             minimum=10)

    def __post_init__(self):
        validate(self)


def match(target, reference, params: RegionsParams, monitor: Monitor, seed: int = 0) -> Matches:
    """Region centroids brought together by the best constellation (target and reference working px)."""
    t_img, t_factor = _matched_size(target, reference, params.max_pixels)
    r_img, r_factor = _matched_size(reference, target, params.max_pixels)
    t_regions = find_regions(*t_img, levels=params.levels, min_area=params.min_area_px)
    monitor.report(0.3, "target regions")
    r_regions = find_regions(*r_img, levels=params.levels, min_area=params.min_area_px)
    monitor.report(0.6, "reference regions")
    natural = np.flatnonzero(~t_regions.blocky)
    t_regions = t_regions.subset(natural[np.argsort(-t_regions.area[natural], kind="stable")][:params.max_regions])
    found = match_constellation(t_regions, r_regions, anchors_target=params.anchors)
    monitor.report(1.0, "constellation")
    diagnostics = {"target_regions": len(t_regions), "reference_regions": len(r_regions)}
    if found is None:
        return Matches(np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0), len(t_regions), len(r_regions), diagnostics)
    diagnostics["constellation_score"] = round(found.score, 1)
    return Matches(t_regions.xy[found.target] * t_factor, r_regions.xy[found.reference] * r_factor,
                   np.log(np.maximum(t_regions.area[found.target], 2.0)), len(t_regions), len(r_regions), diagnostics)


def _matched_size(image, other, max_pixels: int):
    """``image`` ((grey, valid) at a size no larger than ``other``'s valid pixel count nor ``max_pixels``),
    and its working px per px of the result."""
    import cv2

    budget = min(max_pixels, max(int(other.valid.sum()), 1))
    factor = max(1.0, float(np.sqrt(image.valid.sum() / budget)))
    if factor < 1.25:
        return (image.data, image.valid), 1.0
    size = (max(1, round(image.shape[1] / factor)), max(1, round(image.shape[0] / factor)))
    grey = cv2.resize(image.data.astype(np.float32), size, interpolation=cv2.INTER_AREA)
    valid = cv2.resize(image.valid.astype(np.uint8), size, interpolation=cv2.INTER_NEAREST) > 0
    return (grey, valid), (image.shape[1] / size[0] + image.shape[0] / size[1]) / 2


METHOD = register_method(Method(
    name="regions",
    title="Regions as control points (a map onto imagery or a layer)",
    summary="Registers a target whose closed shapes (lakes, blocks, fields) the reference shows too, in another "
            "look: a scanned map onto a layer of the areas it shows (a vector layer of water or buildings, drawn "
            "as a raster), at any rotation and scale. The regions of each image, cut at many grey levels, are "
            "matched by where they lie together; their centroids are refined at full resolution with CFOG and "
            "the result checked independently.",
    citation="A. Goshtasby, G. C. Stockman and C. V. Page (1986), A region-based approach to digital image "
             "registration with subpixel accuracy, IEEE TGRS 24(3):390-399, doi:10.1109/TGRS.1986.289597",
    params_type=RegionsParams,
    match=match,
    ransac_threshold_px=3.0,
    min_inliers=6,
    refine="always",
    refinement=STRUCTURAL_REFINEMENT,
    use_when="a scanned map onto a layer of its areas (lakes, blocks) drawn as a raster, any rotation and scale",
    toolbox=Toolbox("registerregions", "Register a scanned map onto a layer of areas (regions)")))
