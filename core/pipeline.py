"""``register``: the one entry point the CLI, Processing, Python users and the benchmark call.

Data flow (pixels are corner-convention, see :mod:`hamta.core.coords`):
open both rasters -> plan the overlap and read working images -> the method matches them
(working pixels) -> correspondences become full-resolution target/reference pixel pairs ->
seeded RANSAC with a linear model -> optional full-resolution refinement -> the requested model
is fitted on well-spread inliers, which become the GCPs.
"""
from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, replace
from typing import Optional

import numpy as np

from .coords import pixel_to_map
from .errors import InsufficientMatchesError
from .estimation.framed import CrsFrame, fit_framed
from .estimation.models import MIN_POINTS, LinearModel, canonical_model, fit_model
from .estimation.ransac import ransac_or_none
from .io.raster import open_raster, resolve_bands
from .io.working import TARGET_GEOREF_CHOICES, prepare_working_images
from .matching.spectral import triplet_clustering
from .methods import get_method
from .progress import Monitor
from .refine import grid_points, refine_points, spread_subset
from .result import Correspondences, Gcp, RegistrationResult, params_dict

REFINE_CHOICES = ("auto", "on", "off")
ROBUST_CHOICES = ("ransac", "none", "triplets")


@dataclass(frozen=True)
class RegisterOptions:
    """Settings shared by every method.

    Attributes
    ----------
    model : str, optional
        Transform model (see ``hamta.core.estimation.MODEL_CHOICES``); None = the method's default.
    max_working_pixels : int
        Pixel budget of each working image; bounds memory and matching time.
    ransac_threshold_px : float, optional
        Inlier tolerance in working reference pixels; None = the method's default.
    seed : int
        Seed of every random choice (RANSAC), for reproducible runs.
    refine : {'auto', 'on', 'off'}
        Full-resolution refinement; 'auto' refines when a working image was decimated or the method
        always refines (see :class:`hamta.core.methods.Method`).
    max_gcps : int
        Well-spread inliers kept as GCPs; the model is fitted on exactly these.
    min_inliers : int, optional
        Fewest agreeing correspondences accepted as a registration (at least the model minimum + 2);
        None = the method's default.
    robust : {'ransac', 'none', 'triplets'}, optional
        Outlier rejection before the fit; 'none' fits every correspondence (as some papers do);
        'triplets' clusters the affine transforms of all match triples (spec 003's future work);
        None = the method's default.
    target_georef : {'auto', 'use', 'ignore'}
        Whether the target's own georeferencing is used as a starting point.
    target_band, reference_band : int, optional
        1-based band to match; None = luminance of RGB images, else band 1.
    """

    model: Optional[str] = None
    max_working_pixels: int = 4_000_000
    ransac_threshold_px: Optional[float] = None
    seed: int = 0
    refine: str = "auto"
    max_gcps: int = 500
    min_inliers: Optional[int] = None
    robust: Optional[str] = None
    target_georef: str = "auto"
    target_band: Optional[int] = None
    reference_band: Optional[int] = None

    def __post_init__(self):
        if self.model is not None:
            object.__setattr__(self, "model", canonical_model(self.model))
        if self.refine not in REFINE_CHOICES:
            raise ValueError(f"refine must be one of {REFINE_CHOICES}, got {self.refine!r}")
        if self.target_georef not in TARGET_GEOREF_CHOICES:
            raise ValueError(f"target_georef must be one of {TARGET_GEOREF_CHOICES}, got {self.target_georef!r}")
        if self.max_working_pixels < 4096:
            raise ValueError("max_working_pixels must be at least 4096")
        if self.robust not in (None,) + ROBUST_CHOICES:
            raise ValueError(f"robust must be one of {ROBUST_CHOICES}, got {self.robust!r}")
        if self.ransac_threshold_px is not None and self.ransac_threshold_px <= 0:
            raise ValueError("ransac_threshold_px must be positive")


def register(target, reference, method: str = "sift", params=None, options: RegisterOptions = RegisterOptions(),
             progress=None, is_canceled=None) -> RegistrationResult:
    """Register the ``target`` raster onto the ``reference`` raster.

    Parameters
    ----------
    target, reference : str or os.PathLike
        Raster files. The reference defines the map (its CRS and geotransform), or, without
        georeferencing, its pixel grid is the map.
    method : str
        A name from :func:`hamta.core.methods.all_methods`.
    params : mapping or the method's parameter dataclass, optional
        Method parameters; missing ones take their documented defaults.
    options : RegisterOptions
    progress : callable(fraction, message), optional
    is_canceled : callable() -> bool, optional

    Returns
    -------
    RegistrationResult
        Nothing is written; see :func:`hamta.core.outputs.write_outputs`.

    Raises
    ------
    HamtaError
        Subclasses name the file and the problem (missing input, no overlap, too few matches...).
    """
    monitor = Monitor(progress, is_canceled)
    clock = _Clock()
    spec = get_method(method)
    if params is None or isinstance(params, dict):
        params = spec.make_params(params)
    options = replace(options, model=options.model or spec.default_model,
                      ransac_threshold_px=options.ransac_threshold_px or spec.ransac_threshold_px,
                      min_inliers=options.min_inliers or spec.min_inliers, robust=options.robust or spec.robust)
    model_kind, robust, tolerance = options.model, options.robust, options.ransac_threshold_px

    tgt_info = open_raster(target, "target")
    ref_info = open_raster(reference, "reference")
    tgt_bands = resolve_bands(tgt_info, options.target_band)
    ref_bands = resolve_bands(ref_info, options.reference_band)
    clock.lap("open")
    monitor.report(0.02, "reading")

    tgt, ref, plan = prepare_working_images(tgt_info, ref_info, target_bands=tgt_bands, reference_bands=ref_bands,
                                            max_pixels=options.max_working_pixels,
                                            target_georef=options.target_georef)
    clock.lap("read")
    monitor.report(0.1, "matching")

    matches = spec.match(tgt, ref, params, monitor.span(0.1, 0.7))
    clock.lap("match")
    tgt_px = tgt.to_source.forward(matches.target_xy) if len(matches) else np.zeros((0, 2))
    ref_px = ref.to_source.forward(matches.reference_xy) if len(matches) else np.zeros((0, 2))
    score = np.asarray(matches.score, float)

    need = max(options.min_inliers, MIN_POINTS[model_kind] + 2)
    linear_kind = model_kind if model_kind in ("similarity", "affine") else "projective"
    threshold = tolerance * ref.source_px_per_working_px
    try:
        linear, inliers = _robust_linear(tgt_px, ref_px, linear_kind, threshold, options.seed, need, spec.name,
                                         tgt_info.path, robust)
    except InsufficientMatchesError as exc:
        exc.correspondences = Correspondences(tgt_px, ref_px, score, np.zeros(len(tgt_px), bool))
        raise
    raw = Correspondences(tgt_px, ref_px, score, inliers)
    clock.lap("estimate")
    monitor.report(0.75, "refining")

    notes = list(plan.notes)
    decimation = max(tgt.source_px_per_working_px, ref.source_px_per_working_px)
    refined = options.refine == "on" or (options.refine == "auto" and (spec.refine == "always" or decimation > 1.25))
    if refined:
        rp = replace(spec.refinement, search_px=max(spec.refinement.search_px, int(math.ceil(2.5 * decimation)) + 4))
        fit_threshold = max(1.0, tolerance)
        for i in range(rp.passes):
            if rp.points == "grid":
                points = grid_points(linear, tgt_info, ref_info, rp)
            else:
                kept = ref_px[inliers]
                points = kept[spread_subset(kept, score[inliers], rp.max_points)]
            span = monitor.span(0.75 + 0.15 * i / rp.passes, 0.75 + 0.15 * (i + 1) / rp.passes)
            r_tgt, r_ref, r_score = refine_points(linear, points, tgt_info, tgt_bands, ref_info, ref_bands, rp, span)
            fallback = "working-resolution matches" if i == 0 else "previous pass"
            if len(r_tgt) < need:
                notes.append(f"refinement kept only {len(r_tgt)} points; using the {fallback}")
                refined = i > 0
                break
            try:
                linear, inliers = _robust_linear(r_tgt, r_ref, linear_kind, fit_threshold, options.seed, need,
                                                 spec.name, tgt_info.path, "ransac" if robust == "triplets" else robust)
            except InsufficientMatchesError as exc:
                notes.append(f"refinement pass {i + 1} found no consistent model ({exc}); using the {fallback}")
                refined = i > 0
                break
            threshold = fit_threshold
            tgt_px, ref_px, score = r_tgt, r_ref, r_score
            rp = replace(rp, search_px=min(rp.search_px, 3))  # later passes start from the refined model
    clock.lap("refine")
    monitor.report(0.9, "fitting")

    frame = _crs_frame(plan, tgt_info, ref_info)
    model, used, inliers = _final_fit(model_kind, tgt_px, ref_px, score, inliers, threshold, options.max_gcps, frame)
    clock.lap("fit")

    result = _assemble(spec, params, options, model, tgt_info, ref_info, plan, tgt_px, ref_px, score,
                       inliers, used, matches, raw, refined, notes, clock)
    monitor.report(1.0, "done")
    return result


def _robust_linear(tgt_px, ref_px, kind, threshold, seed, need, method, target_path, robust="ransac"):
    n = len(tgt_px)
    if n < need:
        raise InsufficientMatchesError(
            f"Method '{method}' found only {n} candidate correspondences for '{target_path}' (at least "
            f"{need} are needed). The images may not overlap, or differ too much for this method.", n, need)
    if robust == "none":
        return LinearModel.fit(kind, tgt_px, ref_px), np.ones(n, bool)
    if robust == "triplets":
        _, inliers = triplet_clustering(tgt_px, ref_px, radius_px=4 * threshold, inlier_px=threshold, seed=seed)
        model = LinearModel.fit(kind, tgt_px[inliers], ref_px[inliers]) if inliers.sum() >= need else None
    else:
        model, inliers = ransac_or_none(tgt_px, ref_px, kind, threshold_px=threshold, rng=seed)
    if model is None or inliers.sum() < need:
        raise InsufficientMatchesError(
            f"Only {int(inliers.sum())} of {n} correspondences found by '{method}' for '{target_path}' agree "
            f"on one {kind} transform (at least {need} are needed). The images may not overlap, or differ "
            "too much for this method.", int(inliers.sum()), need)
    return model, inliers


def _crs_frame(plan, tgt_info, ref_info) -> Optional[CrsFrame]:
    """The target's own CRS frame when its georeferencing was used and its CRS differs."""
    if plan.mode != "georeferenced" or tgt_info.crs is None or tgt_info.crs == ref_info.crs:
        return None
    return CrsFrame(tgt_info.transform, tgt_info.crs.to_wkt(), ref_info.transform, ref_info.crs.to_wkt())


def _fit(kind, src, dst, frame):
    if frame is None:
        return fit_model(kind, src, dst)
    return fit_framed(lambda s, d: fit_model(kind, s, d), frame, src, dst)


def _final_fit(kind, tgt_px, ref_px, score, inliers, threshold, max_gcps, frame):
    """Fit ``kind`` on well-spread inliers; widen the inlier set for the non-linear models."""
    if kind not in ("similarity", "affine", "projective", "tps") and not inliers.all():
        for _ in range(5):
            model = _fit(kind, tgt_px[inliers], ref_px[inliers], frame)
            new = model.residuals(tgt_px, ref_px) < threshold
            if np.array_equal(new, inliers) or new.sum() < MIN_POINTS[kind]:
                break
            inliers = new
    idx = np.flatnonzero(inliers)
    used = idx[spread_subset(ref_px[idx], score[idx], max_gcps)]
    return _fit(kind, tgt_px[used], ref_px[used], frame), used, inliers


def _assemble(spec, params, options, model, tgt_info, ref_info, plan, tgt_px, ref_px, score, inliers, used,
              matches, raw, refined, notes, clock):
    pixel_mode = not ref_info.georeferenced
    to_map = (lambda xy: xy) if pixel_mode else (lambda xy: pixel_to_map(ref_info.transform, xy))
    res = model.apply(tgt_px) - ref_px if len(tgt_px) else np.zeros((0, 2))
    outliers = np.flatnonzero(~inliers)
    outliers = outliers[np.argsort(-score[outliers], kind="stable")][: len(used)]
    gcps = []
    for i, enabled in [(i, True) for i in used] + [(i, False) for i in outliers]:
        gcps.append(Gcp(tuple(map(float, tgt_px[i])), tuple(map(float, ref_px[i])),
                        tuple(map(float, to_map(ref_px[i:i + 1])[0])), tuple(map(float, res[i])),
                        float(score[i]), enabled))
    used_res = np.linalg.norm(res[used], axis=1)
    loo = model.loo_residuals(tgt_px[used], ref_px[used])
    stats = {
        "n_keypoints_target": int(matches.n_target), "n_keypoints_reference": int(matches.n_reference),
        "n_matches": int(len(matches)), "n_inliers": int(raw.inlier.sum()), "n_gcps": int(len(used)),
        "n_refined": int(len(tgt_px)) if refined else 0,
        "rmse_px": float(np.sqrt(np.mean(used_res ** 2))),
        "rms_loo_px": float(np.sqrt(np.nanmean(loo ** 2))) if np.isfinite(loo).any() else None,
        "max_residual_px": float(used_res.max()),
        "refined": bool(refined),
        "peak_rss_mb": _peak_rss_mb(),
    }
    return RegistrationResult(
        method=spec.name, params=params_dict(params), options=dataclasses.asdict(options), model=model, target=tgt_info,
        reference=ref_info, plan=plan, gcps=gcps, stats=stats, timings=clock.as_dict(), notes=notes,
        diagnostics=dict(matches.diagnostics or {}), correspondences=raw,
    )


def _peak_rss_mb() -> Optional[float]:
    """Peak resident memory of this process so far (None where the OS does not say)."""
    try:
        import resource
    except ImportError:
        return None
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


class _Clock:
    def __init__(self):
        self.start = self.last = time.perf_counter()
        self.laps = {}

    def lap(self, name: str) -> None:
        now = time.perf_counter()
        self.laps[name] = round(now - self.last, 4)
        self.last = now

    def as_dict(self) -> dict:
        return dict(self.laps, total=round(time.perf_counter() - self.start, 4))
