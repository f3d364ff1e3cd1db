"""SAR onto optical: line intersections matched spectrally (spec 003), as the thesis describes.

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

The thesis reports about 60 % correct among 5-8 matches, too few and too unreliable for a
transform; the product for SAR onto optical is :mod:`hamta.core.methods.cfog`, which can start
from this module's line matcher (``coarse='lines'``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np

from ..detectors import lines as ln
from ..matching import spectral
from ..preprocess.sar import SAR_UNITS, lee_filter, normalised_amplitude
from ..progress import Monitor
from ..refine import STRUCTURAL_REFINEMENT
from ..types import Matches
from .registry import Method, param, register_method, validate

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


def match_lines(target, reference, params: LinesParams, monitor: Monitor, seed: int = 0) -> Matches:
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


# The thesis's matches are few and imprecise: its transform comes from triplet clustering with a
# 5 px tolerance, and 3 agreeing matches are accepted (the model's own minimum still applies).
_THESIS = dict(robust="triplets", ransac_threshold_px=5.0, min_inliers=3, refinement=STRUCTURAL_REFINEMENT)

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
