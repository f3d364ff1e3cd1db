"""SAR onto optical: line intersections matched spectrally (spec 003), and the product built on it.

Gholami, S. (2018). Automatic registration of synthetic aperture radar images onto optical images
(in Persian). M.Sc. thesis, supervisor A. Ahmadyfard, Shahrood University of Technology. Its
matchers: Shapiro & Brady 1992 (Image Vis. Comput. 10(5):283-288) and VSPM of Sui, Xu, Liu & Hua
2015 (IEEE TGRS 53(11):6058-6072).

Thesis pipeline (``lines-spectral-faithful``): Lee filter on the SAR (target) image -> GGS
bi-window ratio edges on both images -> components under 65 px removed, thinning -> Radon lines,
clustered in (theta, rho) -> intersections of lines crossing at 10 degrees or more -> eigenvector
matching, VSPM, or their fusion -> (the thesis's future work) an affine from every matched
triplet, the densest cluster of those transforms, and the matches it explains. Its baselines are
the single matchers (``lines-eigen``, ``lines-vspm``).

Product (``lines-spectral``): the thesis reports about 60 % correct among 5-8 matches, too few
and too unreliable for a transform, so the coarse transform comes from an exhaustive rotation,
scale and shift search on CFOG structural descriptors (``coarse='lines'`` uses the thesis's stage
instead), then CFOG template matching on a grid gives hundreds of well-spread correspondences;
the shared pipeline fits the model and refines decimated images with the same similarity.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import cv2
import numpy as np

from ..area import multimodal
from ..area.cfog import cfog
from ..estimation.ransac import ransac_or_none
from ..features import lines as ln
from ..matching import spectral
from ..preprocess.sar import SAR_UNITS, lee_filter, normalised_amplitude
from ..progress import Monitor
from ..refine import RefineParams
from ..types import Matches
from . import Method, param, register_method, validate

CITATION = ("Gholami 2018, Automatic registration of SAR images onto optical images (M.Sc. thesis, Shahrood "
            "University of Technology), with Shapiro & Brady 1992 and Sui et al. 2015, IEEE TGRS 53(11):6058-6072 "
            "(spec 003)")
MATCHERS = ("eigenvector", "vspm", "fusion")


@dataclass(frozen=True)
class LinesParams:
    """The thesis pipeline; the thesis gives few values, the gaps are filled as spec 003 section 6 suggests."""

    units: str = param("amplitude", "What the SAR (target) raster holds: amplitude, intensity or db.",
                       choices=SAR_UNITS)
    lee: bool = param(True, "Lee speckle filter on the SAR image (the thesis).")
    lee_window: int = param(7, "Lee window side, px (not given; 7).", minimum=3)
    looks: float = param(1.0, "Equivalent number of looks of the SAR image (not given; 1).", minimum=0.1)
    ggs_alpha: float = param(3.0, "GGS window shape alpha (Shui & Cheng's practical setting).", minimum=1.0)
    ggs_beta: float = param(1.5, "GGS window width beta, px.", minimum=0.1)
    ggs_sigma_x: float = param(6.5 / math.sqrt(math.pi), "GGS window length sigma_x, px (l_f = 13).", minimum=0.5)
    orientations: int = param(8, "GGS orientations P (not given; 8).", minimum=2)
    low: float = param(0.15, "Hysteresis low threshold on 1 - ratio (not given).", minimum=0.0, maximum=1.0)
    high: float = param(0.30, "Hysteresis high threshold on 1 - ratio (not given).", minimum=0.0, maximum=1.0)
    min_component_px: int = param(65, "Edge components smaller than this are removed (the thesis: 65).", minimum=0)
    peaks: int = param(40, "Radon peaks taken before clustering (not given; 40).", minimum=2)
    theta_step_deg: float = param(1.0, "Radon angle step, degrees (MATLAB's default 1).", minimum=0.1)
    min_votes: int = param(0, "Fewest edge pixels on a line; 0 = Sui et al.'s 15 px per 256 px of image side.",
                           minimum=0)
    cluster_theta_deg: float = param(5.0, "Lines closer than this in angle ... (not given; 5).", minimum=0.0)
    cluster_rho_px: float = param(10.0, "... and this in offset are one line (not given; 10).", minimum=0.0)
    min_crossing_deg: float = param(10.0, "Line pairs crossing at less than this are not intersected (Sui et al.).",
                                    minimum=0.0, maximum=90.0)
    matcher: str = param("fusion", "Eigenvector matching, VSPM, or their fusion (the thesis).", choices=MATCHERS)
    fusion: str = param("score", "Fusion rule (not given): score-level sum, or cascade (VSPM's proximity inside "
                                 "eigenvector matching).", choices=spectral.FUSIONS)
    fusion_weight: float = param(0.5, "Weight of the eigenvector score in the score-level fusion.", minimum=0.0,
                                 maximum=1.0)
    sigma_factor: float = param(0.5, "Eigenvector proximity sigma as a fraction of each point set's RMS spread "
                                     "(not given).", minimum=0.01)
    vspm_proximity: str = param("printed", "VSPM proximity matrix: as printed (eq. 2-73), laplacian or gaussian.",
                                choices=spectral.VSPM_PROXIMITIES)
    angle_tolerance_deg: float = param(5.0, "Crossing angles of matched intersections differ by less (the thesis).",
                                       minimum=0.0)

    def __post_init__(self):
        validate(self)


@dataclass(frozen=True)
class EigenParams(LinesParams):
    matcher: str = param("eigenvector", "Shapiro-Brady eigenvector matching alone (the thesis's baseline).",
                         choices=MATCHERS)


@dataclass(frozen=True)
class VspmParams(LinesParams):
    matcher: str = param("vspm", "VSPM alone (the thesis's baseline).", choices=MATCHERS)


@dataclass(frozen=True)
class ProductParams(LinesParams):
    """The product: coarse transform, then dense CFOG matching. Line parameters apply with coarse='lines'."""

    lee: bool = param(False, "No Lee filter: CFOG's smoothing already averages speckle, and the filter measured no "
                             "gain (multimodal proxy 8/8 either way; real pairs 0.85 vs 1.06 px median).")
    coarse: str = param("search", "Coarse transform: exhaustive CFOG search (default: it registers where the "
                                  "thesis's 5-8 matches cannot) or the thesis's lines.", choices=("search", "lines"))
    max_rotation_deg: float = param(30.0, "Rotations searched, +- degrees (georeferenced targets arrive "
                                          "north-up, so rotation is small).", minimum=0.0, maximum=180.0)
    max_scale: float = param(2.0, "Scales searched, 1/max_scale .. max_scale (2 registers the scale family's 0.5-2, "
                                  "10/10 against 6/10 for 1.5, for 26 % more time on a 1000 px pair).",
                             minimum=1.0, maximum=4.0)
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


def sar_image(img, params: LinesParams) -> np.ndarray:
    """The SAR (target) working image as normalised amplitude, Lee-filtered when asked."""
    amp = normalised_amplitude(img.data, img.valid, params.units)
    if params.lee:
        amp = lee_filter(amp, looks=params.looks, window=params.lee_window, units="amplitude")
    return amp


def line_features(image: np.ndarray, valid: np.ndarray, params: LinesParams, info: dict = None):
    """Edges, lines and intersections of one working image (spec 003 sections 2.3-2.7)."""
    strength, arg, normals = ln.ggs_strength(image, params.ggs_alpha, params.ggs_beta, params.ggs_sigma_x,
                                             params.orientations)
    side = 2 * ln.ggs_radius(params.ggs_alpha, params.ggs_beta, params.ggs_sigma_x) + 1
    inner = cv2.erode(valid.astype(np.uint8), np.ones((side, side), np.uint8), borderType=cv2.BORDER_REPLICATE)
    strength[inner == 0] = 0.0  # windows reaching into invalid pixels see the footprint's border, not an edge
    edges = ln.hysteresis(ln.non_maximum_suppression(strength, arg, normals), params.low, params.high)
    edges = ln.thin(ln.remove_small(edges, params.min_component_px))
    side = min(image.shape)
    min_votes = params.min_votes or (15 if side < 256 else 15 * (side // 256))
    lines = ln.cluster_lines(ln.radon_lines(edges, params.peaks, params.theta_step_deg, min_votes),
                             params.cluster_theta_deg, params.cluster_rho_px)
    points = ln.intersections(lines, image.shape, params.min_crossing_deg)
    if info is not None:
        info.update(edge_pixels=int(edges.sum()), lines=len(lines), intersections=len(points))
    return points


def match_intersections(pt, pr, shape_t, shape_r, params: LinesParams):
    """Index pairs (target, reference) and scores from the chosen matcher."""
    if len(pt) < 3 or len(pr) < 3:
        return np.zeros(0, int), np.zeros(0, int), np.zeros(0)
    if params.matcher == "eigenvector":
        return spectral.eigenvector_match(pt.xy, pr.xy, params.sigma_factor)
    ct, cr = spectral.voronoi_cells(pt.xy, shape_t), spectral.voronoi_cells(pr.xy, shape_r)
    if params.matcher == "vspm":
        return spectral.vspm_match(ct, cr, pt.angle, pr.angle, params.angle_tolerance_deg, params.vspm_proximity)
    return spectral.fused_match(pt.xy, pr.xy, ct, cr, pt.angle, pr.angle, rule=params.fusion,
                                weight=params.fusion_weight, sigma_factor=params.sigma_factor,
                                tolerance_deg=params.angle_tolerance_deg, proximity=params.vspm_proximity)


def match_lines(target, reference, params: LinesParams, monitor: Monitor) -> Matches:
    """The thesis pipeline up to its matched intersection pairs (working px)."""
    info_t, info_r = {}, {}
    pt = line_features(sar_image(target, params), target.valid, params, info_t)
    monitor.report(0.45, "edges, lines, intersections")
    pr = line_features(reference.data, reference.valid, params, info_r)
    monitor.report(0.9, "edges, lines, intersections")
    i, j, score = match_intersections(pt, pr, target.shape, reference.shape, params)
    monitor.report(1.0, "spectral matching")
    return Matches(pt.xy[i], pr.xy[j], np.asarray(score, float), len(pt), len(pr),
                   {"target": info_t, "reference": info_r})


def _coarse_from_lines(target, reference, params, monitor) -> np.ndarray:
    m = match_lines(target, reference, params, monitor)
    diag = math.hypot(*reference.shape)
    affine, inliers = spectral.triplet_clustering(m.target_xy, m.reference_xy, radius_px=0.03 * diag,
                                                  inlier_px=0.02 * diag)
    if affine is None or inliers.sum() < 3:
        return None
    return affine


def _ransac_fit(found, kind):
    model, inliers = ransac_or_none(found[0], found[1], kind, threshold_px=3.0, rng=0)
    return (None, 0) if model is None else (model.matrix, int(inliers.sum()))


def _fit(found, gain: float = 1.1):
    """RANSAC model of dense matches: an affine (2 x 3), or a homography (3 x 3) where it explains
    ``gain`` times as many matches plus 5, so that the second pass follows perspective without
    extrapolating a homography that the matches do not need; with its inlier count, or (None, 0)."""
    if len(found[0]) < 3:
        return None, 0
    affine, n_affine = _ransac_fit(found, "affine")
    homography, n_homography = _ransac_fit(found, "projective") if len(found[0]) >= 8 else (None, 0)
    if homography is not None and n_homography >= gain * n_affine + 5:
        return homography, n_homography
    return (None if affine is None else affine[:2]), n_affine


def match_product(target, reference, params: ProductParams, monitor: Monitor) -> Matches:
    """Coarse candidates, each checked by a dense CFOG pass and RANSAC (the first that most matches
    agree with wins, else the one with most inliers), then a second dense pass from its fit (a
    homography when the first pass gave enough matches)."""
    t0 = time.perf_counter()
    sar = sar_image(target, params)
    diag = {}
    if params.coarse == "lines":
        affine = _coarse_from_lines(target, reference, params, monitor.span(0.0, 0.4))
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
        model, n_in = _fit(found)
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


# Decimated images are refined at full resolution with the same structural similarity.
CFOG_REFINEMENT = RefineParams(template_px=64, search_px=4, min_ncc=0.1, points="grid", similarity="cfog")

METHOD = register_method(Method(
    name="lines-spectral", title="SAR onto optical (structural search + dense CFOG)",
    summary="Exhaustive rotation/scale/shift search on CFOG structural descriptors, then CFOG template matching "
            "on a grid, RANSAC and the chosen model. For SAR targets on optical references (and other "
            "modality pairs, contrast inversion included). The thesis's line matcher is coarse='lines'.",
    citation=CITATION + "; Ye et al. 2019, IEEE TGRS 57(11):9059-9070 (CFOG)", params_type=ProductParams,
    match=match_product, refinement=CFOG_REFINEMENT))

# The thesis's matches are few and imprecise: its transform comes from triplet clustering with a
# 5 px tolerance, and 3 agreeing matches are accepted (the model's own minimum still applies).
_THESIS = dict(robust="triplets", ransac_threshold_px=5.0, min_inliers=3, refinement=CFOG_REFINEMENT)

FAITHFUL = register_method(Method(
    name="lines-spectral-faithful", title="Line intersections + eigenvector/VSPM fusion, as in the thesis",
    summary="Lee, GGS edges, Radon lines, intersections, fused eigenvector and VSPM matching; the thesis's future "
            "work (transform clustering over matched triplets) gives the transform.",
    citation=CITATION, params_type=LinesParams, match=match_lines, kind="faithful", **_THESIS))

EIGEN = register_method(Method(
    name="lines-eigen", title="Line intersections + Shapiro-Brady eigenvector matching (spec 003 baseline)",
    summary="The thesis pipeline with eigenvector matching alone.", citation=CITATION, params_type=EigenParams,
    match=match_lines, kind="baseline", **_THESIS))

VSPM = register_method(Method(
    name="lines-vspm", title="Line intersections + VSPM (spec 003 baseline)",
    summary="The thesis pipeline with Voronoi/Hausdorff spectral matching alone.", citation=CITATION,
    params_type=VspmParams, match=match_lines, kind="baseline", **_THESIS))
