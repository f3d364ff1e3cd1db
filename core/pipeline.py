"""``register``: the one registration entry point; :func:`hamta.core.run.run` adds the outputs.

Data flow (pixels are corner-convention, see :mod:`hamta.core.coords`): open both rasters ->
plan the overlap and read working images -> the method matches them (working pixels) -> the
correspondences become full-resolution target/reference pixel pairs -> outlier rejection with a
linear model -> optional full-resolution refinement -> the requested model is fitted on
well-spread inliers, which become the GCPs.
"""
from __future__ import annotations

import dataclasses
from typing import Optional

from .coords import pixel_to_map
from .estimation.framed import CrsFrame
from .estimation.robust import RobustRules, final_fit, robust_linear
from .io.raster import open_raster, resolve_bands
from .io.working import Plan, prepare_working_images
from .methods import get_method
from .options import RegisterOptions, resolve_options
from .progress import Clock, Monitor
from .refine import refine_estimate
from .result import RegistrationResult, make_gcps, make_stats, params_dict
from .types import Correspondences


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
        Settings left open (None) take the method's defaults.
    progress : callable(fraction, message), optional
    is_canceled : callable() -> bool, optional

    Returns
    -------
    RegistrationResult
        Nothing is written; see :func:`hamta.core.run.run`.

    Raises
    ------
    HamtaError
        Subclasses name the file and the problem (missing input, no overlap, too few matches...).
    """
    monitor, clock = Monitor(progress, is_canceled), Clock()
    spec = get_method(method)
    params = spec.make_params(params)
    options = resolve_options(options, spec)
    tgt_info, ref_info = open_raster(target, "target"), open_raster(reference, "reference")
    bands = resolve_bands(tgt_info, options.target_band), resolve_bands(ref_info, options.reference_band)
    clock.lap("open")
    monitor.report(0.02, "reading")

    tgt, ref, plan = prepare_working_images(tgt_info, ref_info, target_bands=bands[0], reference_bands=bands[1],
                                            max_pixels=options.max_working_pixels,
                                            target_georef=options.target_georef)
    clock.lap("read")
    monitor.report(0.1, "matching")

    matches = spec.match(tgt, ref, params, monitor.span(0.1, 0.7), seed=options.seed)
    clock.lap("match")
    rules = RobustRules.for_run(options.model, options, spec.name, tgt_info.path)
    threshold = options.ransac_threshold_px * ref.source_px_per_working_px
    first = robust_linear(Correspondences.from_matches(matches, tgt, ref), threshold, rules)
    clock.lap("estimate")
    monitor.report(0.75, "refining")

    estimate, notes = refine_estimate(first, spec, options.refine, options.ransac_threshold_px, tgt, ref, rules,
                                      monitor.span(0.75, 0.9))
    clock.lap("refine")
    monitor.report(0.9, "fitting")

    fit = final_fit(options.model, estimate, options.max_gcps, crs_frame(plan, tgt_info, ref_info))
    clock.lap("fit")
    to_map = (lambda xy: xy) if not ref_info.georeferenced else (lambda xy: pixel_to_map(ref_info.transform, xy))
    result = RegistrationResult(
        method=spec.name, params=params_dict(params), options=dataclasses.asdict(options), model=fit.model,
        target=tgt_info, reference=ref_info, plan=plan, gcps=make_gcps(fit, to_map),
        stats=make_stats(matches, first.points, fit), timings=clock.as_dict(), notes=list(plan.notes) + notes,
        diagnostics=dict(matches.diagnostics or {}), correspondences=first.points)
    monitor.report(1.0, "done")
    return result


def crs_frame(plan: Plan, target, reference) -> Optional[CrsFrame]:
    """The target's own CRS frame when its georeferencing was used and its CRS differs."""
    if plan.mode != "georeferenced" or target.crs is None or target.crs == reference.crs:
        return None
    return CrsFrame(target.transform, target.crs.to_wkt(), reference.transform, reference.crs.to_wkt())
