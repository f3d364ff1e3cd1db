"""A scanned sheet georeferenced by its own grid, as a :class:`hamta.core.result.RegistrationResult`: the same
outputs (report, GCP layer, ``.points``, the georeferenced raster), ``hamta map-points`` and batch as any
registration.

The reference of such a result is a frame: a north-up raster in the sheet's CRS over the sheet's footprint,
at the scan's pixel size (or coarser, at most :data:`FRAME_SIDE_PX` a side), on which the grid lines are
drawn (what the report shows beside the scan). Its pixels are the result's reference px; GCPs are the
crossings found (scan px -> frame px, and their coordinates). The check is the grid's own: each crossing
predicted by the model fitted without its grid line (:func:`hamta.core.grid.sheet.fit_sheet`).
"""
from __future__ import annotations

import dataclasses
import math
import os
import time
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np
from affine import Affine
from rasterio.windows import Window

from ..errors import InputError
from ..io.raster import open_raster, resolve_bands
from ..io.scope import run_scope
from ..io.working import Plan
from ..options import RegisterOptions
from ..outcome import Stats, Timings
from ..progress import Monitor
from ..result import Gcp, RegistrationResult, peak_rss_mb
from ..scratch import process_folder
from ..verify import Verification
from .crossings import lines_held_out
from .scan import LineSource
from .sheet import SheetFit, fit_sheet

FRAME_SIDE_PX = 2048
METHOD = "grid"


@dataclass(frozen=True)
class GridParams:
    """What a run by the grid is given beside the scan: ``hints`` (a QGIS ``.points`` file, or rows of scan x,
    y, grid x, y; None: read from the labels printed in the margins), the grid's ``step`` and ``grid_crs``
    (where the hints do not tell them) and ``crs``, the sheet's (the output CRS option)."""

    hints: object
    crs: str
    step: Optional[float] = None
    grid_crs: Optional[str] = None

    @classmethod
    def make(cls, params, output) -> "GridParams":
        """From a run's ``params`` (a mapping: hints, step, grid_crs) and output options (their ``crs``)."""
        if isinstance(params, cls):
            return params
        params = dict(params or {})
        unknown = sorted(set(params) - {"hints", "step", "grid_crs"})
        if unknown:
            raise ValueError(f"georeferencing by the grid takes no parameter {', '.join(unknown)}; it takes hints, "
                             "step and grid_crs")
        if not getattr(output, "crs", None):
            raise InputError("Georeferencing a sheet by its printed grid needs the sheet's CRS (the output CRS): "
                             "the coordinates printed on it rarely say which it is.")
        step, hints = params.get("step"), params.get("hints")
        if hints is None or (isinstance(hints, str) and not hints):
            hints = None
        elif isinstance(hints, os.PathLike):
            hints = os.fspath(hints)
        elif not isinstance(hints, str):  # rows: kept as plain numbers (a run's request is JSON)
            hints = np.asarray(hints, float).reshape(-1, 4).tolist()
        return cls(hints, output.crs, None if step in (None, "") else float(step),
                   params.get("grid_crs") or None)


@run_scope()
def register_grid(target, crs: str, hints: Optional[Sequence] = None, *, grid_crs: Optional[str] = None,
                  step: Optional[float] = None, options: RegisterOptions = RegisterOptions(), progress=None,
                  is_canceled=None) -> RegistrationResult:
    """Georeference the scan ``target`` in ``crs`` by its printed grid, from ``hints``: rows of (scan x, y, grid x,
    y) or a QGIS ``.points`` file (mapX, mapY = the grid's coordinates; sourceX, -sourceY = the scan's px); None:
    from the labels printed in its margins (:mod:`hamta.core.grid.labels`). ``grid_crs``: what the printed
    coordinates count in (see :func:`hints_crs`); ``step`` the grid's, where the hints do not tell it. Nothing
    is written (see :func:`hamta.core.runner.run`)."""
    from pyproj import CRS

    monitor = Monitor(progress, is_canceled)
    t0 = time.perf_counter()
    info = open_raster(target, "target")
    try:
        frame_crs = CRS.from_user_input(crs)
    except Exception as exc:
        raise InputError(f"The sheet's CRS '{crs}' is not one PROJ knows: {exc}") from None
    notes, labels = [], None
    with LineSource.from_raster(info, resolve_bands(info, options.target_band)) as source:
        if hints is None:
            monitor.report(0.0, "grid: reading the labels")
            rows, grid_crs, labels = _hints_from_labels(source, info, frame_crs, grid_crs, monitor.span(0.0, 0.5))
            notes.append("no hints: the coordinates printed in the margins gave the crossings "
                         + ", ".join(f"({gx:g}, {gy:g})" for gx, gy in rows[:, 2:]))
            if labels["contradicting"]:
                notes.append(f"labels that contradict the others, left out: {', '.join(labels['contradicting'][:8])}")
        else:
            rows, file_crs = read_hints(hints, info.path)
            grid_crs = grid_crs or file_crs or hints_crs(rows[:, 2:], frame_crs)
        monitor.report(0.5 if hints is None else 0.05, "grid: reading the scan")
        opened = time.perf_counter()
        fit = fit_sheet(source, rows, frame_crs.to_wkt(), grid_crs, step, options.tolerance_px,
                        progress=monitor.span(0.5 if hints is None else 0.05, 0.9))
    fitted = time.perf_counter()
    fit = dataclasses.replace(fit, notes=fit.notes + notes)
    result = _result(info, fit, frame_crs, grid_crs, rows, options, {"open": opened - t0, "match": fitted - opened})
    if labels is not None:
        result.diagnostics["grid"]["labels"] = labels
    monitor.report(1.0, "grid: done")
    return result


def _hints_from_labels(source, info, frame_crs, grid_crs, monitor):
    """(hints, what the printed coordinates count in, {"used": texts, "contradicting": texts}) from the labels
    in the sheet's margins."""
    from pyproj import CRS, Transformer

    from .labels import hints_from_labels, read_labels

    labels = read_labels(source.grey, info.width, info.height, monitor.check)
    degrees = sum(lab.kind == "degrees" for lab in labels)
    metres = sum(lab.kind == "metres" and lab.value >= 1e5 for lab in labels)
    geographic = CRS.from_user_input(grid_crs).is_geographic if grid_crs else degrees >= metres
    if not geographic and frame_crs.is_geographic:
        raise InputError(f"The labels printed on '{info.path}' look like metres of a projected grid, but the "
                         f"sheet's CRS '{frame_crs.name}' is in degrees: give the CRS of the grid printed on it.")
    grid_crs = grid_crs or (frame_crs.geodetic_crs.to_wkt() if geographic else frame_crs.to_wkt())
    to_crs = Transformer.from_crs(CRS.from_user_input(grid_crs), frame_crs, always_xy=True)
    rows, contradicting = hints_from_labels(labels, info.width, info.height, geographic, to_crs)
    return rows, grid_crs, {"used": [lab.text for lab in labels], "contradicting": contradicting}


def read_hints(hints, scan_path: str):
    """(rows (n, 4) of scan x, y, grid x, y; the CRS a ``.points`` file names, or None) of ``hints``."""
    if isinstance(hints, (str, os.PathLike)):
        from ..outputs.points import read_points

        try:
            crs, points = read_points(os.fspath(hints))
        except (OSError, ValueError) as exc:
            raise InputError(f"The hints '{os.fspath(hints)}' cannot be read as a QGIS .points file: {exc}") from None
        rows = np.array([[sx, -sy, mx, my] for mx, my, sx, sy, on in points if on], float).reshape(-1, 4)
        return rows, crs
    return np.asarray(hints, float).reshape(-1, 4), None


def hints_crs(coords: np.ndarray, crs) -> str:
    """What printed coordinates count in where no file says: the geographic CRS of ``crs``'s datum when they
    look like degrees and ``crs`` is projected, else ``crs`` itself. Coordinates that cannot be degrees in a
    geographic ``crs`` are refused, saying so."""
    degrees = bool(np.all(np.abs(coords[:, 0]) <= 360) and np.all(np.abs(coords[:, 1]) <= 90))
    if crs.is_geographic and not degrees:
        raise InputError("The hints' coordinates look like metres of a projected grid, but the sheet's CRS "
                         f"'{crs.name}' is in degrees: give the CRS of the grid printed on the sheet.")
    if not crs.is_geographic and degrees:
        return crs.geodetic_crs.to_wkt()
    return crs.to_wkt()


def _result(info, fit: SheetFit, frame_crs, grid_crs: str, hints, options: RegisterOptions, laps) -> RegistrationResult:
    from ..estimation.models import fit_model

    t0 = time.perf_counter()
    frame = _frame(info, fit, frame_crs, grid_crs)
    scan_px, map_xy = fit.gcps[:, :2], fit.gcps[:, 2:4]
    frame_px = np.column_stack((~frame.transform) * (map_xy[:, 0], map_xy[:, 1]))
    scale = _frame_per_scan(fit_model("affine", scan_px, frame_px), info)
    kind, held_out = _model_by_check(options.model, fit, scan_px, frame_px, info)
    fit = dataclasses.replace(fit, model=kind, held_out=held_out / scale,
                              loo_px=float(np.sqrt(np.mean(np.sum((held_out / scale) ** 2, axis=1)))))
    fit = dataclasses.replace(fit, verified=fit.sound and fit.loo_px <= options.tolerance_px, notes=[
        f"{len(scan_px)} crossings of the printed grid found (step {fit.step:g}), covering {fit.spread:.0%} of the "
        f"sheet; the {kind} model{'' if options.model else ', chosen by the check'}: each grid line predicted from "
        f"the others is off by {fit.loo_px:.2f} scan px RMS; the lattice of whole lines holds {fit.contrast:.2f} "
        f"times the ink of its lines moved by part of a step, and is within {fit.apart_px:.1f} px of the "
        "crossings"] + fit.notes[1:])
    model = fit_model(kind, scan_px, frame_px)
    residual = model.apply(scan_px) - frame_px
    gcps = [Gcp(tuple(map(float, s)), tuple(map(float, f)), tuple(map(float, m)), tuple(map(float, r)), 1.0, True)
            for s, f, m, r in zip(scan_px, frame_px, map_xy, residual)]
    res = np.hypot(*residual.T)
    loo = model.loo_residuals(scan_px, frame_px)
    stats = Stats(n_keypoints_target=fit.nodes, n_keypoints_reference=0, n_matches=len(gcps), n_inliers=len(gcps),
                  n_gcps=len(gcps), n_refined=0, rmse_px=float(np.sqrt(np.mean(res ** 2))),
                  rms_loo_px=float(np.sqrt(np.nanmean(loo ** 2))) if np.isfinite(loo).any() else None,
                  max_residual_px=float(res.max()), refined=False, peak_rss_mb=peak_rss_mb())
    verification = _check(fit, frame_px, scale, options.tolerance_px, time.perf_counter() - t0)
    laps = dict(laps, fit=time.perf_counter() - t0)
    timings = Timings.from_laps(laps)
    plan = Plan("grid", Window(0, 0, frame.width, frame.height), Window(0, 0, info.width, info.height),
                ("the sheet's own printed grid",))
    params = {"step": fit.step, "grid_crs": grid_crs, "hints": hints.tolist()}
    return RegistrationResult(METHOD, params, {"model": options.model, "tolerance_px": options.tolerance_px,
                                               "target_band": options.target_band}, model, info, frame, plan, gcps,
                              stats, timings, notes=list(fit.notes), verification=verification,
                              diagnostics={"grid": {"step": fit.step, "model": fit.model, "held_out_rms_px": fit.loo_px,
                                                    "coverage": fit.spread, "crossings": len(gcps),
                                                    "lattice_contrast": fit.contrast,
                                                    "frame_px_per_scan_px": scale}})


KINDS = (("affine", 0.0), ("polynomial-2", 0.5), ("polynomial-3", 0.8), ("tps", 0.5))  # the sheet's models, with
# the share of the sheet the crossings must cover for each (a polynomial or a spline bends wildly beyond them)
BETTER = 0.9  # a model after the affine is taken when its lines held out are this much closer


def _model_by_check(asked: Optional[str], fit: SheetFit, scan_px, frame_px, info):
    """(the model kind, each crossing's error in frame px predicted by it fitted without the crossing's grid
    line): the one asked for, else the one the check finds best (:data:`KINDS`, :data:`BETTER`)."""
    from ..estimation.models import MIN_POINTS

    lines = fit.gcps[:, 4:6]
    kinds = [asked] if asked else [k for k, cover in KINDS if fit.spread >= cover and len(scan_px) >= 2 * MIN_POINTS[k]]
    best = None
    for kind in kinds or ["affine"]:
        errors = held_out_lines(kind, scan_px, frame_px, lines)
        rms = float(np.sqrt(np.mean(np.sum(errors ** 2, axis=1))))
        if best is None or rms < BETTER * best[2]:
            best = (kind, errors, rms)
    return best[0], best[1]


def held_out_lines(kind: str, scan_px, frame_px, lines) -> np.ndarray:
    """(n, 2) frame px: each crossing's error under the model ``kind`` (scan px -> frame px) fitted without its
    grid line (:func:`hamta.core.grid.crossings.lines_held_out`; ``lines``: each crossing's grid x and y)."""
    from ..estimation.models import MIN_POINTS, fit_model

    return lines_held_out(scan_px, frame_px, lines, lambda src, dst: fit_model(kind, src, dst).apply,
                          MIN_POINTS[kind])[0]


def _frame_per_scan(model, info) -> float:
    """Frame px per scan px at the scan's centre."""
    from ..estimation.models import local_jacobian

    return float(math.sqrt(abs(np.linalg.det(local_jacobian(model, np.array([[info.width / 2, info.height / 2]]))[0]))))


def _check(fit: SheetFit, frame_px, scale: float, tolerance_px: float, seconds: float) -> Verification:
    """The grid's check as a :class:`Verification` (frame px; ``tolerance_px`` is asked in scan px): each
    crossing a site, its error predicted without its grid line."""
    agree = np.hypot(*fit.held_out.T) <= tolerance_px
    if fit.verified:
        verdict, reasons = "verified", ()
    else:
        verdict = "suspect" if fit.loo_px <= 3 * tolerance_px else "failed"
        reasons = tuple(_reasons(fit, tolerance_px))
    return Verification(verdict, reasons, tolerance_px * scale, 0, len(frame_px), int(agree.sum()),
                        int((~agree).sum()), len(frame_px), 0.0, 0.0, fit.spread, fit.loo_px * scale,
                        fit.loo_px * scale, None, seconds, frame_px, fit.held_out * scale, np.ones(len(frame_px)),
                        agree, ~agree, check="grid-held-out-lines")


def _reasons(fit: SheetFit, tolerance_px: float):
    from .sheet import MIN_FIT, MIN_SPREAD

    if len(fit.gcps) < MIN_FIT:
        yield f"only {len(fit.gcps)} crossings of the printed grid were found ({MIN_FIT} needed)"
    if fit.loo_px > tolerance_px:
        yield (f"each grid line predicted from the others is off by {fit.loo_px:.1f} scan px RMS, beyond the "
               f"{tolerance_px:g} px asked for")
    if fit.spread < MIN_SPREAD:
        yield f"the crossings found cover {fit.spread:.0%} of the sheet ({MIN_SPREAD:.0%} needed)"
    yield from (n for n in fit.notes[1:])
    if fit.apart_px is not None and fit.apart_px > fit.apart_limit_px:
        yield (f"the crossings' model and the lattice of whole lines differ by {fit.apart_px:.1f} px: a line of the "
               "map may have been taken for a grid line")


def _frame(info, fit: SheetFit, frame_crs, grid_crs: str):
    """The frame raster (see the module docstring), written once per run into a private temporary folder."""
    import cv2
    import rasterio
    from pyproj import CRS, Transformer

    outline = np.array([[x, y] for x in np.linspace(0, info.width, 9) for y in np.linspace(0, info.height, 9)])
    xy = fit.to_crs(outline)
    centre = fit.to_crs(np.array([[info.width / 2, info.height / 2], [info.width / 2 + 1, info.height / 2],
                                  [info.width / 2, info.height / 2 + 1]]))
    size = math.sqrt(abs(np.linalg.det(np.array([centre[1] - centre[0], centre[2] - centre[0]]))))
    x0, y0, x1, y1 = xy[:, 0].min(), xy[:, 1].min(), xy[:, 0].max(), xy[:, 1].max()
    size = max(size, (x1 - x0) / FRAME_SIDE_PX, (y1 - y0) / FRAME_SIDE_PX)
    width, height = max(int(math.ceil((x1 - x0) / size)), 1), max(int(math.ceil((y1 - y0) / size)), 1)
    transform = Affine(size, 0, x0, 0, -size, y1)
    image = np.full((height, width), 245, np.uint8)
    to_crs = Transformer.from_crs(CRS.from_user_input(grid_crs), frame_crs, always_xy=True)
    g = fit.gcps[:, 4:6]
    lo, hi = g.min(axis=0) - fit.step, g.max(axis=0) + fit.step
    along = np.linspace(0, 1, 200)
    for axis in (0, 1):
        for value in np.arange(lo[axis], hi[axis] + fit.step / 2, fit.step):
            line = np.empty((len(along), 2))
            line[:, axis], line[:, 1 - axis] = value, lo[1 - axis] + along * (hi[1 - axis] - lo[1 - axis])
            mx, my = to_crs.transform(line[:, 0], line[:, 1])
            px = np.column_stack((~transform) * (np.asarray(mx), np.asarray(my)))
            px = px[np.all(np.isfinite(px), axis=1)]
            if len(px) > 1:
                cv2.polylines(image, [np.round(px * 4).astype(np.int32)], False, 40, 1, cv2.LINE_AA, shift=2)
    path = os.path.join(process_folder("hamta-grid-"), "frame.tif")
    with rasterio.open(path, "w", driver="GTiff", width=width, height=height, count=1, dtype="uint8",
                       crs=rasterio.crs.CRS.from_wkt(frame_crs.to_wkt()), transform=transform,
                       compress="deflate", tiled=True) as dst:
        dst.write(image, 1)
    return open_raster(path, "reference")
