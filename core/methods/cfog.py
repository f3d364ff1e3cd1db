"""Across modalities (SAR, infrared, maps onto optical): a structural search, then dense CFOG matching.

The product for spec 003's task (a SAR target on an optical reference). The thesis's line
intersections (:mod:`hamta.core.methods.lines_spectral`) give about 60 % correct matches among
5-8, too few and too unreliable for a transform, so the coarse transform comes from an exhaustive
rotation, scale and shift search on CFOG structural descriptors (``coarse='lines'`` starts from the
thesis's matcher instead); CFOG template matching on a grid then gives hundreds of well-spread
correspondences, and the shared pipeline fits the model and refines decimated images with the
same similarity.

References
----------
Ye, Y., Bruzzone, L., Shan, J., Bovolo, F., & Zhu, Q. (2019). Fast and robust matching for
multimodal remote sensing image registration. IEEE TGRS 57(11), 9059-9070.
:DOI:`10.1109/TGRS.2019.2924684`
Gholami, S. (2018). Automatic registration of SAR images onto optical images (M.Sc. thesis,
Shahrood University of Technology), spec 003.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from ..estimation import triplets
from ..estimation.ransac import ransac_or_none
from ..matching import multimodal
from ..preprocess.sar import SAR_UNITS
from ..progress import Monitor
from ..refine import STRUCTURAL_REFINEMENT
from ..similarity.cfog import cfog
from ..types import Matches
from .lines_spectral import LinesParams, match_lines, sar_image
from .registry import Method, Toolbox, param, register_method, validate


@dataclass(frozen=True)
class CfogParams:
    """The structural search and the dense CFOG passes; the thesis's line stage (coarse='lines')
    runs with its own defaults."""

    units: str = param("amplitude", "What the target raster holds when it is SAR: amplitude, intensity or db "
                                    "(other images: leave amplitude).", choices=SAR_UNITS, basic=True)
    lee: bool = param(False, "No Lee filter: CFOG's smoothing already averages speckle, and the filter measured no "
                             "gain (multimodal proxy 8/8 either way; real pairs 0.85 vs 1.06 px median).")
    coarse: str = param("search", "Coarse transform: exhaustive CFOG search (default: it registers where the "
                                  "thesis's 5-8 matches cannot) or the thesis's lines.", choices=("search", "lines"))
    max_rotation_deg: float = param(30.0, "Rotations searched, +- degrees (georeferenced targets arrive "
                                          "north-up, so rotation is small).", minimum=0.0, maximum=180.0, basic=True)
    max_scale: float = param(2.0, "Scales searched, 1/max_scale .. max_scale (2 registers the scale family's 0.5-2, "
                                  "10/10 against 6/10 for 1.5, for 26 % more time on a 1000 px pair).",
                             minimum=1.0, maximum=4.0, basic=True)
    coarse_px: int = param(96, "Longest reference side at the first search level, px.", minimum=32, maximum=512)
    coarse_local_sigma: float = param(3.0, "The search compares descriptors minus their local mean over this many "
                                           "first-level px: with the global mean (0) regional orientation statistics "
                                           "favoured wrong axis-aligned candidates (overlap family 8/10; 3 px: "
                                           "10/10, 6 px: 9/10).", minimum=0.0)
    template_px: int = param(64, "Side of the CFOG templates, working px.", minimum=16)
    search_px: int = param(24, "Search radius of the first dense pass, working px (covers the coarse error).",
                           minimum=2)
    min_ncc: float = param(0.1, "Weakest accepted template correlation; RANSAC removes the rest.", minimum=-1.0,
                           maximum=1.0)
    max_points: int = param(400, "Templates per dense pass.", minimum=10)
    candidates: int = param(3, "Coarse candidates checked by dense matching when the best is not convincing.",
                            minimum=1, maximum=5)

    def __post_init__(self):
        validate(self)

    def thesis(self) -> LinesParams:
        """The thesis's parameters for the line stage, with this run's target units and filter."""
        return LinesParams(units=self.units, lee=self.lee)


def _coarse_from_lines(target, reference, params: CfogParams, monitor, seed: int):
    m = match_lines(target, reference, params.thesis(), monitor)
    diag = math.hypot(*reference.shape)
    affine, inliers = triplets.triplet_clustering(m.target_xy, m.reference_xy, radius_px=0.03 * diag,
                                                  inlier_px=0.02 * diag, seed=seed)
    if affine is None or inliers.sum() < 3:
        return None
    return affine


def _ransac_fit(found, kind, seed):
    model, inliers = ransac_or_none(found[0], found[1], kind, threshold_px=3.0, rng=seed)
    return (None, 0) if model is None else (model.matrix, int(inliers.sum()))


def _fit(found, seed, gain: float = 1.1):
    """RANSAC model of dense matches: an affine (2 x 3), or a homography (3 x 3) where it explains
    ``gain`` times as many matches plus 5, so that the second pass follows perspective without
    extrapolating a homography that the matches do not need; with its inlier count, or (None, 0)."""
    if len(found[0]) < 3:
        return None, 0
    affine, n_affine = _ransac_fit(found, "affine", seed)
    homography, n_homography = _ransac_fit(found, "projective", seed) if len(found[0]) >= 8 else (None, 0)
    if homography is not None and n_homography >= gain * n_affine + 5:
        return homography, n_homography
    return (None if affine is None else affine[:2]), n_affine


def match(target, reference, params: CfogParams, monitor: Monitor, seed: int = 0) -> Matches:
    """Coarse candidates, each checked by a dense CFOG pass and RANSAC (the first that most matches
    agree with wins, else the one with most inliers), then a second dense pass from its fit (a
    homography when the first pass gave enough matches)."""
    t0 = time.perf_counter()
    sar = sar_image(target, params.thesis())
    diag = {}
    if params.coarse == "lines":
        affine = _coarse_from_lines(target, reference, params, monitor.span(0.0, 0.4), seed)
        starts = [] if affine is None else [affine]
    else:
        cands, _ = multimodal.search_similarity(
            sar, target.valid, reference.data, reference.valid, max_rotation_deg=params.max_rotation_deg,
            max_scale=params.max_scale, coarse_px=params.coarse_px, local_sigma=params.coarse_local_sigma,
            progress=lambda f: monitor.report(0.4 * f, "coarse search"))
        starts = [c["affine"] for c in cands[:params.candidates]]
    monitor.report(0.4, "coarse transform")
    diag["coarse_s"] = round(time.perf_counter() - t0, 3)
    ref_desc = cfog(reference.data, valid=reference.valid)

    def dense(model, search):
        monitor.check()
        return multimodal.dense_matches(sar, target.valid, reference.data, reference.valid, model,
                                        template=params.template_px, search=search, limit=params.max_points,
                                        min_ncc=params.min_ncc, reference_descriptors=ref_desc)
    best = (None, 0, None, -1)
    for k, start in enumerate(starts):
        found = dense(start, params.search_px)
        model, n_in = _fit(found, seed)
        if n_in > best[1]:
            best = (model, n_in, found, k)
        if n_in >= max(20, 0.5 * len(found[0])):
            break
    model, n_in, found, k = best
    diag.update(candidate=k, dense_pass1=0 if found is None else len(found[0]), pass1_inliers=n_in)
    if model is None:
        return Matches.empty(0, 0) if found is None else Matches(found[0], found[1], found[2], 0, 0, diag)
    lin = model[:2, :2] / (model[2, 2] if model.shape == (3, 3) else 1.0)
    diag["coarse"] = {"rotation_deg": round(math.degrees(math.atan2(lin[1, 0], lin[0, 0])), 2),
                      "scale": round(math.sqrt(abs(np.linalg.det(lin))), 4)}
    monitor.report(0.7, "dense CFOG matching")
    tx, rx, peak = dense(model, 4)
    diag["dense_pass2"] = len(tx)
    diag["dense_s"] = round(time.perf_counter() - t0 - diag["coarse_s"], 3)
    monitor.report(1.0, "dense CFOG matching")
    return Matches(tx, rx, peak, len(tx), len(rx), diag)


METHOD = register_method(Method(
    name="cfog", title="Across modalities: structural search + dense CFOG (SAR, infrared, maps onto optical)",
    summary="Registers a SAR image (the target) onto an optical reference, where intensities do not correspond and "
            "contrast is often inverted: an exhaustive search over rotation (up to 30 degrees either way), scale "
            "(up to 2 times either way) and shift on CFOG structural descriptors (gradient orientations, blind to "
            "the sign of contrast), then CFOG template matching on a regular grid, seeded RANSAC, the chosen "
            "transformation on well-spread GCPs, and full-resolution refinement of decimated images with the same "
            "similarity. Widen the rotation range for targets that are not roughly north-up. The CLI method "
            "'lines-spectral-faithful' is the thesis's line-intersection matcher as written (Radon lines, "
            "eigenvector and Voronoi/Hausdorff spectral matching), which rarely finds enough correct matches to "
            "register.",
    citation="S. Gholami (2018), Automatic registration of SAR images onto optical images, M.Sc. thesis, Shahrood "
             "University of Technology; Y. Ye, L. Bruzzone, J. Shan, F. Bovolo and Q. Zhu (2019), Fast and robust "
             "matching for multimodal remote sensing image registration, IEEE Transactions on Geoscience and "
             "Remote Sensing 57(11):9059-9070, doi:10.1109/TGRS.2019.2924684", params_type=CfogParams,
    match=match, refinement=STRUCTURAL_REFINEMENT,
    use_when="SAR, infrared or a map onto an optical image that is roughly north-up",
    toolbox=Toolbox("registersaroptical", "Register SAR image onto optical image")), aliases=("lines-spectral",))
