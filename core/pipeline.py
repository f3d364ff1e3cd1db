"""``register``: the one registration entry point; :func:`hamta.core.runner.run` adds the outputs.

Data flow (pixels are corner-convention, see :mod:`hamta.core.coords`): open both rasters ->
plan the overlap and read working images -> the method matches them (working pixels) -> the
correspondences become full-resolution target/reference pixel pairs -> outlier rejection with a
linear model -> optional full-resolution refinement -> the requested model is fitted on
well-spread inliers, which become the GCPs -> an independent check of the model against the
pixels (:mod:`hamta.core.verify`) gives the verdict.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Optional, Tuple

from .auto import AUTO, chain_for, register_auto
from .coords import pixel_to_map
from .errors import ReferenceNotGeoreferenced, UsageError, method_crashes
from .estimation.framed import CrsFrame
from .estimation.robust import RobustRules, final_fit, robust_linear
from .io.raster import RasterInfo, check_on_earth, open_raster, resolve_bands
from .io.scope import run_scope
from .io.working import Plan, WorkingImage, central_longitude, prepare_working_images
from .local import LocalParams, local_correction
from .methods import get_method
from .options import RegisterOptions, resolve_options
from .order import HIGHER, bent_fit, order_note
from .outcome import Timings
from .progress import Clock, Monitor
from .refine import refine_estimate
from .result import RegistrationResult, make_gcps, make_stats, params_dict
from .types import Correspondences
from .verify import VerifyParams, beats, error_bound, verify


@run_scope()
def register(target, reference, method: str = AUTO, params=None, options: RegisterOptions = RegisterOptions(),
             progress=None, is_canceled=None, map_chunks=None, target_pixels=None, placed=None,
             short=False) -> RegistrationResult:
    """Register the ``target`` raster onto the ``reference`` raster, and verify the result.

    Parameters
    ----------
    target, reference : str or os.PathLike
        Raster files. The reference defines the map (its CRS and geotransform); one without
        georeferencing is refused unless ``options.pixel_mode``, and then its pixel grid is the map.
    method : str
        'auto' (methods from fast to robust until one's result verifies, see :mod:`hamta.core.auto`)
        or a name from :func:`hamta.core.methods.all_methods`.
    params : mapping or the method's parameter dataclass, optional
        Method parameters; missing ones take their documented defaults (not with 'auto').
    options : RegisterOptions
        Settings left open (None) take the method's defaults.
    progress : callable(fraction, message), optional
    is_canceled : callable() -> bool, optional
    map_chunks : callable(fn, chunks) -> list, optional
        Where the local correction's windows are measured (a Dask client's workers for big scenes,
        see :mod:`hamta.core.batch`); here by default.
    target_pixels : int, optional
        A smaller pixel budget for a target searched without its georeferencing: its expected size
        in the reference (see :mod:`hamta.core.remote`).
    placed : affine.Affine, optional
        Where a search already placed the target: its pixels (corner convention) -> the reference's
        map coordinates. It stands in for the target's own georeferencing as the prior (the result
        keeps the target as opened).
    short : bool
        'auto' tries its fast steps only (up to ``cfog``, see :func:`hamta.core.auto.chain_for`): the
        basemap search's candidate places, each bounded by work rather than time.

    Returns
    -------
    RegistrationResult
        Nothing is written; see :func:`hamta.core.runner.run`. ``result.verification`` says whether
        the result verified; an unverified result is returned too (front ends decide).

    Raises
    ------
    HamtaError
        Subclasses name the file and the problem (missing input, no overlap, too few matches...).
    MethodCrashed
        Anything else raised while a method matched, fitted or verified: a bug, naming the method
        (the original exception is its ``__cause__``).
    """
    monitor = Monitor(progress, is_canceled)
    inputs = read_inputs(target, reference, options, monitor.span(0.0, 0.1), target_pixels, placed)
    rest = monitor.span(0.1, 1.0)
    if method == AUTO:
        if params:
            raise UsageError("method 'auto' takes no method parameters; choose a method to set them")
        return _unplaced(_register_by_auto(inputs, options, rest, map_chunks, short), placed, target)
    params = get_method(method).make_params(params)  # a wrong name or parameter is the caller's, not a crash
    with method_crashes(method):
        return _unplaced(match_and_fit(inputs, method, params, options, rest, map_chunks), placed, target)


def _register_by_auto(inputs: Inputs, options: RegisterOptions, monitor: Monitor, map_chunks, short: bool
                      ) -> RegistrationResult:
    """'auto' on the rasters read: each attempt is :func:`match_and_fit` with one method of its chain, refined as
    the attempt asks unless ``options.refine`` says how."""
    def attempt(name, p, mon, refine):
        step_options = options if options.refine != "auto" else dataclasses.replace(options, refine=refine)
        return match_and_fit(inputs, name, p, step_options, mon, map_chunks)

    return register_auto(attempt, options, monitor, chain_for(inputs.plan.mode, short))


def _unplaced(result: RegistrationResult, placed, target) -> RegistrationResult:
    """A result registered from a ``placed`` prior, with the target as opened and the plan a search's."""
    if placed is None:
        return result
    return dataclasses.replace(result, target=open_raster(target, "target"),
                               plan=dataclasses.replace(result.plan, mode="search"))


@dataclass(frozen=True, eq=False)
class Inputs:
    """Both rasters, opened and read at working resolution once per registration (``auto``'s
    attempts share them). ``timings`` holds the 'open' and 'read' stages."""

    target: RasterInfo
    reference: RasterInfo
    target_bands: Tuple[int, ...]
    reference_bands: Tuple[int, ...]
    target_image: WorkingImage
    reference_image: WorkingImage
    plan: Plan
    timings: dict


def read_inputs(target, reference, options: RegisterOptions, monitor: Monitor, target_pixels=None,
                placed=None) -> Inputs:
    """Open both rasters, choose their bands, plan the overlap and read the working images (``placed``:
    see :func:`register`)."""
    clock = Clock()
    tgt_info, ref_info = open_raster(target, "target"), open_raster(reference, "reference")
    if placed is not None:
        tgt_info = dataclasses.replace(tgt_info, transform=placed, crs=ref_info.crs, georef_source="geotransform")
        options = dataclasses.replace(options, target_georef="use")
    if not ref_info.georeferenced and not options.pixel_mode:
        raise ReferenceNotGeoreferenced(
            f"reference '{ref_info.path}' has no georeferencing (no geotransform or GCPs), so the result could not "
            "be placed on a map. Use a georeferenced reference, or ask for pixel-to-pixel registration, whose "
            "outputs are in the reference's pixels without a CRS")
    check_on_earth(ref_info, "reference")
    bands = resolve_bands(tgt_info, options.target_band), resolve_bands(ref_info, options.reference_band)
    clock.lap("open")
    monitor.report(0.2, "reading")
    tgt, ref, plan = prepare_working_images(tgt_info, ref_info, target_bands=bands[0], reference_bands=bands[1],
                                            max_pixels=options.max_working_pixels,
                                            target_georef=options.target_georef, extent=options.extent,
                                            target_pixels=target_pixels)
    clock.lap("read")
    monitor.report(1.0, "reading")
    return Inputs(tgt_info, ref_info, bands[0], bands[1], tgt, ref, plan, clock.laps)


def match_and_fit(inputs: Inputs, method: str, params, options: RegisterOptions, monitor: Monitor,
                  map_chunks=None) -> RegistrationResult:
    """Match the working images with ``method``, fit and refine the model, and verify it."""
    clock = Clock()
    spec = get_method(method)
    params = spec.make_params(params)
    model_left_open = options.model is None and not options.local
    options = resolve_options(options, spec)
    matches = spec.match(inputs.target_image, inputs.reference_image, params, monitor.span(0.0, 0.65),
                         seed=options.seed)
    clock.lap("match")
    first, estimate, notes = _estimate(matches, inputs, spec, options, monitor, clock)
    monitor.report(0.85, "fitting")
    fit, bent = _fits(estimate, inputs, options, model_left_open)
    clock.lap("fit")
    grid = None
    check = VerifyParams(tolerance_px=options.tolerance_px)
    verification = None
    if options.local:
        fit, grid, verification, note = _local_kept(fit, estimate, inputs, spec, options, check, monitor, map_chunks,
                                                    clock)
        notes += [note] if note else []
    if verification is None:
        verification = checked(fit.model, inputs, check, monitor.span(0.9, 0.95 if bent else 1.0))
    if bent is not None:
        second = checked(bent.model, inputs, check, monitor.span(0.95, 1.0))
        kept = beats(second, verification)
        notes.append(order_note(options.model, verification, second, kept))
        if kept:
            fit, verification, options = bent, second, dataclasses.replace(options, model=HIGHER)
    clock.lap("verify")
    ref_info = inputs.reference
    to_map = (lambda xy: xy) if not ref_info.georeferenced else (lambda xy: pixel_to_map(ref_info.transform, xy))
    timings = Timings.from_laps(dict(inputs.timings, **clock.laps))
    return RegistrationResult(
        method=spec.name, params=params_dict(params), options=dataclasses.asdict(options), model=fit.model,
        target=inputs.target, reference=ref_info, plan=inputs.plan, gcps=make_gcps(fit, to_map),
        stats=make_stats(matches, first.points, fit), timings=timings, notes=list(inputs.plan.notes) + notes,
        diagnostics=dict(matches.diagnostics or {}), correspondences=first.points, verification=verification,
        local=grid)


def _estimate(matches, inputs: Inputs, spec, options: RegisterOptions, monitor: Monitor, clock: Clock):
    """(first, estimate, notes) from the method's ``matches``: the linear model their outliers were rejected
    with, then that estimate refined at full resolution as ``options.refine`` says, and the refinement's notes."""
    tgt, ref = inputs.target_image, inputs.reference_image
    rules = RobustRules.for_run(options.model, options, spec.name, inputs.target.path)
    threshold = options.ransac_threshold_px * ref.source_px_per_working_px
    first = robust_linear(Correspondences.from_matches(matches, tgt, ref), threshold, rules)
    clock.lap("estimate")
    monitor.report(0.7, "refining")
    estimate, notes = refine_estimate(first, spec, options.refine, options.ransac_threshold_px, tgt, ref, rules,
                                      monitor.span(0.7, 0.85))
    clock.lap("refine")
    return first, estimate, notes


def _fits(estimate, inputs: Inputs, options: RegisterOptions, model_left_open: bool):
    """(fit, bent): the requested model fitted on the estimate's inliers, and where the model was left open the
    higher-order fit to check against it (else None)."""
    frame = crs_frame(inputs.plan, inputs.target, inputs.reference)
    fit = final_fit(options.model, estimate, options.max_gcps, frame)
    bent = None if not model_left_open else bent_fit(options.model, fit, estimate, inputs.target.width,
                                                     inputs.target.height, options.tolerance_px, options.max_gcps,
                                                     frame)
    return fit, bent


def _local_kept(fit, estimate, inputs: Inputs, spec, options: RegisterOptions, check: VerifyParams,
                monitor: Monitor, map_chunks, clock: Clock):
    """The local correction measured around ``estimate``, then :func:`keep_local` between it and the global
    ``fit``: (fit, grid, verification, note)."""
    similarity = spec.refinement.similarity
    local_fit, grid = local_correction(estimate, inputs.target, inputs.target_bands, inputs.reference,
                                       inputs.reference_bands, local_params(options, similarity), similarity,
                                       monitor.span(0.85, 0.9), map_chunks)
    clock.lap("local")
    return keep_local(fit, local_fit, grid, inputs, check, monitor.span(0.9, 1.0))


def keep_local(global_fit, local_fit, grid, inputs: Inputs, check: VerifyParams, monitor: Monitor):
    """(fit, grid, verification, note): the local correction, unless the check bounds the global model's
    error more tightly (a flat field, a shift: the spline would only add the windows' noise); then the global
    model, the grid None and a note saying why."""
    local = checked(local_fit.model, inputs, check, monitor.span(0.0, 0.5))
    whole = checked(global_fit.model, inputs, check, monitor.span(0.5, 1.0))
    if beats(local, whole, ties=True):
        return local_fit, grid, local, None
    return global_fit, None, whole, (
        f"local correction not kept: the check bounds the global model's error at {error_bound(whole):.2f} px, the "
        f"local correction's at {error_bound(local):.2f} px ({local.verdict})")


def checked(model, inputs: Inputs, check: VerifyParams, monitor: Monitor):
    """The independent check of ``model`` (target px -> reference px) on the run's rasters."""
    return verify(model, inputs.target, inputs.target_bands, inputs.reference, inputs.reference_bands, check, monitor)


def local_params(options: RegisterOptions, similarity: str) -> LocalParams:
    """The local correction's settings; an automatic window by what is correlated (see RegisterOptions)."""
    window = options.local_window_px or (64 if similarity == "ncc" else 96)
    return LocalParams(window_px=window, spacing_px=options.local_spacing_px)


def crs_frame(plan: Plan, target, reference) -> Optional[CrsFrame]:
    """The target's own CRS frame when its georeferencing was used and its CRS differs."""
    if plan.mode != "georeferenced" or target.crs is None or target.crs == reference.crs:
        return None
    return CrsFrame(target.transform, target.crs.to_wkt(), reference.transform, reference.crs.to_wkt(),
                    central_longitude(reference), central_longitude(target))
