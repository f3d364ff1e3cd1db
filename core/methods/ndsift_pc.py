"""SAR registration with nonlinear-diffusion SIFT and phase-congruency pruning (spec 002).

Fan, J., Wu, Y., Wang, F., Zhang, Q., Liao, G., & Li, M. (2015). SAR image registration using
phase congruency and nonlinear diffusion-based SIFT. IEEE Geoscience and Remote Sensing Letters
12(3), 562-566. :DOI:`10.1109/LGRS.2014.2351396`

Pipeline: SAR amplitude normalised once (:mod:`hamta.core.preprocess.sar`) -> nonlinear diffusion
scale space (O = 4 octaves, S = 3, t = sigma^2 / 2; Perona-Malik c2 conductance of the ROEWA
gradient with contrast factor K; one AOS step per level) -> SIFT detection on differences of
adjacent levels -> keypoints with phase congruency < 0.01 (Kovesi, on the full-resolution image)
dropped -> SIFT orientation and 128-D descriptor on the nonlinear levels -> dual (mutual) ratio
test at 0.8 -> similarity transform. The paper fits all matches (``ndsift-pc-faithful``); the
product adds RANSAC and the shared refinement.

The paper's comparisons are methods too: ``ndss-sift`` (no phase congruency), ``gss-sift`` (the
same detector and descriptor on a Gaussian scale space) and ``bfsift`` (bilateral-filter scale
space, finest octave skipped, RANSAC; Wang, You & Fu 2012, IEEE GRSL 9(4):649-653).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import List

import cv2
import numpy as np

from ..descriptors.sift_descriptor import descriptors, orientations
from ..detectors.dog import DogParams, build_octaves, dog_keypoints, gaussian_octaves
from ..detectors.nonlinear import aos_step, contrast_factor, pm_conductance
from ..detectors.phase_congruency import PhaseCongruencyParams, phase_congruency
from ..detectors.roewa import roewa_magnitude
from ..matching.nearest import CROSS_CHECKS, match_features
from ..preprocess.sar import SAR_UNITS, log_scaled, normalised_amplitude
from ..progress import Monitor
from ..refine import RefineParams
from ..types import Features, Keypoints, Matches
from .registry import Method, Toolbox, param, register_method, validate

CITATION = ("Fan et al. 2015, SAR image registration using phase congruency and nonlinear diffusion-based SIFT, "
            "IEEE GRSL 12(3):562-566, doi:10.1109/LGRS.2014.2351396 (spec 002)")
SCALE_SPACES = ("nonlinear", "gaussian", "bilateral")


@dataclass(frozen=True)
class NdsiftParams:
    """Parameters of spec 002's method as published, shared by its baselines."""

    units: str = param("amplitude", "What the SAR raster holds: amplitude, intensity or db (complex is read as "
                                    "amplitude).", choices=SAR_UNITS)
    scale_space: str = param("nonlinear", "Scale space: nonlinear (the paper), gaussian or bilateral (baselines).",
                             choices=SCALE_SPACES)
    log_amplitude: bool = param(False, "Run on log amplitude, where speckle is additive and of one strength "
                                       "everywhere (not in the paper).")
    presmooth: bool = param(False, "Gaussian pre-smoothing to sigma_0 before the diffusion, as KAZE does (the paper "
                                   "starts from the original image).")
    octaves: int = param(4, "Octaves O (the paper: 4).", minimum=1, maximum=8)
    layers: int = param(3, "Sub-levels S per octave (the paper: 3; S + 3 images per octave).", minimum=1)
    sigma0: float = param(1.6, "Base scale sigma_0 (gap; Lowe's 1.6).", minimum=0.5)
    roewa_alpha: float = param(2.0, "ROEWA exponential weight alpha (gap; SAR-SIFT's 2).", minimum=0.5)
    k_percentile: float = param(70.0, "Contrast factor K = this percentile of the ROEWA gradient (gap; KAZE's 70).",
                                minimum=1.0, maximum=99.0)
    k_octave_factor: float = param(0.75, "K is multiplied by this at each new octave (the paper: 'change K'; "
                                         "AKAZE's 0.75).", minimum=0.1, maximum=2.0)
    conductance_gradient: str = param("roewa", "Gradient inside the conductance: roewa (the paper) or difference.",
                                      choices=("roewa", "difference"))
    contrast_threshold: float = param(0.03, "DoG contrast threshold on the [0, 1] amplitude (gap; Lowe's 0.03).",
                                      minimum=0.0)
    edge_threshold: float = param(10.0, "DoG edge ratio r (Lowe's 10).", minimum=1.0)
    phase_congruency: bool = param(True, "Drop keypoints whose phase congruency is below pc_threshold (the paper).")
    pc_threshold: float = param(0.01, "Phase congruency threshold (the paper: 0.01).", minimum=0.0, maximum=1.0)
    pc_noise_k: float = param(2.0, "Kovesi's noise multiplier k (gap; his default 2).", minimum=0.0)
    bilateral_range: float = param(0.1, "Range sigma of the bilateral scale space on the [0, 1] amplitude (BFSIFT "
                                        "baseline; not given).", minimum=0.001)
    skip_first_octave: bool = param(False, "Ignore keypoints of the finest octave (BFSIFT does).")
    ratio: float = param(0.8, "Nearest/second-nearest ratio (the paper: 0.8).", minimum=0.0, maximum=1.0)
    cross_check: str = param("dual-ratio", "Dual matching: both directions pass the ratio test (the paper).",
                             choices=CROSS_CHECKS)

    def __post_init__(self):
        validate(self)


@dataclass(frozen=True)
class ProductParams(NdsiftParams):
    """The product's defaults: where they differ from the paper, the docstring says why."""

    presmooth: bool = param(True, "Gaussian pre-smoothing to sigma_0 before the diffusion, as KAZE does: on 1-look "
                                  "speckle it turns 3 of 24 failures into successes (the paper starts from the "
                                  "original image).")
    cross_check: str = param("none", "One-way ratio test: dual ratio matching keeps too few matches on 1-look "
                                     "speckle, and RANSAC removes the extra outliers (the paper: dual-ratio).",
                             choices=CROSS_CHECKS)


@dataclass(frozen=True)
class GaussianParams(NdsiftParams):
    scale_space: str = param("gaussian", "Gaussian scale space (the paper's SIFT baseline).", choices=SCALE_SPACES)
    phase_congruency: bool = param(False, "No phase congruency in the baseline.")


@dataclass(frozen=True)
class NdssParams(NdsiftParams):
    phase_congruency: bool = param(False, "NDSS+SIFT: the paper's ablation without phase congruency.")


@dataclass(frozen=True)
class BilateralParams(NdsiftParams):
    scale_space: str = param("bilateral", "Bilateral-filter scale space (BFSIFT).", choices=SCALE_SPACES)
    phase_congruency: bool = param(False, "No phase congruency in BFSIFT.")
    skip_first_octave: bool = param(True, "BFSIFT skips the finest scale.")


def level_sigmas(params: NdsiftParams) -> np.ndarray:
    """sigma_s = sigma_0 2^(s / S), s = 0 .. S + 2, in octave-local pixels (eq. 5)."""
    return DogParams(layers=params.layers, sigma=params.sigma0).level_sigmas()


def nonlinear_octaves(image: np.ndarray, valid: np.ndarray, params: NdsiftParams) -> List[np.ndarray]:
    """Algorithm 1: per octave S + 3 levels, each one AOS step of tau = t_s - t_(s-1) from the
    previous with the c2 conductance of the (ROEWA) gradient; the next octave starts from level S
    decimated by 2 (SIFT's convention) with K multiplied by ``k_octave_factor``."""
    sig = level_sigmas(params)
    times = sig ** 2 / 2.0
    base = image.astype(np.float32)
    presmooth = float(np.sqrt(max(sig[0] ** 2 - 0.25, 0.0)))  # the input already has sigma 0.5
    if params.presmooth and presmooth > 0.05:
        base = cv2.GaussianBlur(base, (0, 0), presmooth)
    grad = _gradient(base, params)
    k = np.cumprod([contrast_factor(grad, valid, params.k_percentile)] + [params.k_octave_factor] * params.octaves)

    def levels(b, octave):
        out = [b]
        for s in range(1, len(sig)):
            g = grad if s == 1 and octave == 0 else _gradient(out[-1], params)
            out.append(aos_step(out[-1], pm_conductance(g, k[octave], "c2"), float(times[s] - times[s - 1])))
        return out
    return build_octaves(base, params.layers, levels, params.octaves)


def _gradient(img: np.ndarray, params: NdsiftParams) -> np.ndarray:
    if params.conductance_gradient == "roewa":
        return roewa_magnitude(np.maximum(img, 1e-4), params.roewa_alpha)
    gy, gx = np.gradient(img.astype(np.float32))
    return np.hypot(gx, gy)


def bilateral_octaves(image: np.ndarray, params: NdsiftParams) -> List[np.ndarray]:
    """BFSIFT's anisotropic scale space: every level a bilateral filtering of the octave's base
    (not iterated) with spatial sigma_s and a fixed range sigma."""
    sig = level_sigmas(params)
    return build_octaves(image.astype(np.float32), params.layers,
                         lambda b, _: [cv2.bilateralFilter(b, -1, params.bilateral_range, float(s)) for s in sig],
                         params.octaves)


def scale_space(image, valid, params: NdsiftParams) -> List[np.ndarray]:
    if params.scale_space == "nonlinear":
        return nonlinear_octaves(image, valid, params)
    if params.scale_space == "bilateral":
        return bilateral_octaves(image, params)
    dog = DogParams(layers=params.layers, sigma=params.sigma0)
    return gaussian_octaves(image, dog, max_octaves=params.octaves)


def sar_features(img, params: NdsiftParams, info: dict = None, check=lambda: None) -> Features:
    """Keypoints, phase-congruency pruning and SIFT descriptors of one working image.

    ``info`` (optional dict) receives diagnostics: keypoints before and after pruning; ``check()``
    is called between stages (it raises to stop, see :meth:`hamta.core.progress.Monitor.check`).
    """
    amp = normalised_amplitude(img.data, img.valid, params.units)
    if params.log_amplitude:
        amp = log_scaled(amp)
    octaves = scale_space(amp, img.valid, params)
    check()
    dog = DogParams(layers=params.layers, sigma=params.sigma0, contrast_threshold=params.contrast_threshold,
                    edge_threshold=params.edge_threshold)
    kp, octave, level = dog_keypoints(octaves, dog)
    keep = img.valid[np.clip(kp.xy[:, 1].astype(int), 0, img.valid.shape[0] - 1),
                     np.clip(kp.xy[:, 0].astype(int), 0, img.valid.shape[1] - 1)]
    if params.skip_first_octave:
        keep &= octave > 0
    kp, octave, level = kp.subset(keep), octave[keep], level[keep]
    n_before = len(kp)
    check()
    if params.phase_congruency and len(kp):
        pc = phase_congruency(amp, PhaseCongruencyParams(k=params.pc_noise_k))
        check()
        r = np.clip(kp.xy[:, 1].astype(int), 0, pc.shape[0] - 1)
        c = np.clip(kp.xy[:, 0].astype(int), 0, pc.shape[1] - 1)
        keep = pc[r, c] >= params.pc_threshold
        kp, octave, level = kp.subset(keep), octave[keep], level[keep]
    if info is not None:
        info["before_pc"], info["after_pc"] = n_before, len(kp)
    return describe(octaves, kp, octave, level)


def describe(octaves, kp: Keypoints, octave: np.ndarray, level: np.ndarray) -> Features:
    """SIFT orientations (one keypoint per dominant orientation) and descriptors on each keypoint's level."""
    xy_all, size_all, ang_all, resp_all, desc_all = [], [], [], [], []
    lvl = np.clip(np.round(level).astype(int), 0, None)
    for o in np.unique(octave):
        f = 2.0 ** o
        for lv in np.unique(lvl[octave == o]):
            sel = np.flatnonzero((octave == o) & (lvl == lv))
            stack = octaves[o]
            image = stack[min(lv, len(stack) - 1)]
            xy = (kp.xy[sel] - 0.5) / f + 0.5
            sigma = kp.size[sel] / 2.0 / f
            ki, angle = orientations(image, xy, sigma)
            if len(ki) == 0:
                continue
            desc_all.append(descriptors(image, xy[ki], sigma[ki], angle))
            xy_all.append(kp.xy[sel][ki])
            size_all.append(kp.size[sel][ki])
            ang_all.append(angle)
            resp_all.append(kp.response[sel][ki])
    if not desc_all:
        return Features(Keypoints.empty(), np.zeros((0, 128), np.float32), "l2")
    keypoints = Keypoints(np.concatenate(xy_all), np.concatenate(size_all), np.concatenate(ang_all),
                          np.concatenate(resp_all))
    return Features(keypoints, np.concatenate(desc_all), "l2")


def match(target, reference, params: NdsiftParams, monitor: Monitor, seed: int = 0) -> Matches:
    info_t, info_r = {}, {}
    ft = sar_features(target, params, info_t, monitor.check)
    monitor.report(0.45, "scale space, keypoints, descriptors")
    fr = sar_features(reference, params, info_r, monitor.check)
    monitor.report(0.9, "scale space, keypoints, descriptors")
    it, ir, score = match_features(ft, fr, ratio=params.ratio, cross_check=params.cross_check)
    monitor.report(1.0, "matching")
    diag = {"keypoints_target": info_t, "keypoints_reference": info_r}
    return Matches(ft.keypoints.xy[it], fr.keypoints.xy[ir], score, len(ft), len(fr), diag)


# Speckle makes feature positions noisy, but correlation over a large window averages it out:
# on 1-look pairs 64 px templates place 87-98 % of grid points within 1 px (32 px: 42-61 %), with
# correlation peaks around 0.35, so the acceptance threshold is low and RANSAC removes the rest.
SAR_REFINEMENT = RefineParams(template_px=64, search_px=8, min_ncc=0.2, points="grid", passes=2)

_SUMMARY = ("Nonlinear diffusion scale space (ROEWA conductance, AOS) with SIFT, keypoints pruned by phase "
            "congruency, ratio-test matching. For SAR-to-SAR registration (other date, band, polarisation).")

METHOD = register_method(Method(
    name="ndsift-pc", title="ND-SIFT + phase congruency (SAR)",
    summary="Registers a SAR image onto a SAR reference (another date, band or polarisation) despite speckle: a "
            "nonlinear diffusion scale space whose conductance uses the speckle-robust ROEWA gradient, SIFT "
            "keypoints and descriptors on it, keypoints kept only where phase congruency shows real structure, "
            "ratio-test matching, seeded RANSAC, then correlation refinement on a grid at full resolution. Set "
            "what the rasters hold (amplitude, intensity or dB; complex data is read as amplitude). Product "
            "defaults pre-smooth and use a one-way ratio test; the CLI method 'ndsift-pc-faithful' is the paper as "
            "written.",
    citation="J. Fan, Y. Wu, F. Wang, Q. Zhang, G. Liao and M. Li (2015), SAR image registration using phase "
             "congruency and nonlinear diffusion-based SIFT, IEEE Geoscience and Remote Sensing Letters "
             "12(3):562-566, doi:10.1109/LGRS.2014.2351396",
    params_type=ProductParams, match=match, default_model="similarity", refine="always",
    refinement=SAR_REFINEMENT,
    use_when="SAR onto SAR (another date, band or polarisation), any rotation",
    toolbox=Toolbox("registerndsift", "Register SAR image onto SAR image (ND-SIFT + phase congruency)")))

FAITHFUL = register_method(Method(
    name="ndsift-pc-faithful", title="ND-SIFT + phase congruency, as published",
    summary="The paper's pipeline and parameters: dual ratio matching, a least-squares similarity on all "
            "matches, no outlier rejection.",
    citation=CITATION, params_type=NdsiftParams, match=match, default_model="similarity", kind="faithful",
    robust="none", min_inliers=4))

NDSS = register_method(Method(
    name="ndss-sift", title="NDSS + SIFT without phase congruency (spec 002 ablation)",
    summary="The paper's nonlinear scale space and SIFT without the phase-congruency pruning.",
    citation=CITATION, params_type=NdssParams, match=match, default_model="similarity", kind="baseline",
    robust="none", min_inliers=4))

GSS = register_method(Method(
    name="gss-sift", title="Gaussian-scale-space SIFT (spec 002 baseline)",
    summary="The same SIFT detector, descriptor and dual matching on a Gaussian scale space (no upsampling).",
    citation="Lowe 2004; " + CITATION, params_type=GaussianParams, match=match, default_model="similarity",
    kind="baseline", robust="none", min_inliers=4))

BFSIFT = register_method(Method(
    name="bfsift", title="BFSIFT: bilateral-filter SIFT (spec 002 baseline)",
    summary="Anisotropic scale space by bilateral filters (not iterated), finest octave skipped, dual matching "
            "and RANSAC.",
    citation="Wang, You & Fu 2012, IEEE GRSL 9(4):649-653; " + CITATION, params_type=BilateralParams, match=match,
    default_model="similarity", kind="baseline", min_inliers=4))

