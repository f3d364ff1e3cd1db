"""A scanned sheet georeferenced by its own grid, as a :class:`hamta.core.result.RegistrationResult`: the same
outputs (report, GCP layer, ``.points``, the georeferenced raster), ``hamta map-points`` and batch as any
registration.

The sheet's CRS is what its printed coordinates count in (degrees of a graticule's datum, or a national
grid's CRS); a projected CRS given for a sheet whose coordinates are degrees is taken for the projection it is
drawn in. The output is in the output CRS when one is asked for, else in the sheet's CRS where it is projected,
else in the projection the graticule was found to be drawn in (:mod:`hamta.core.grid.planes`). The reference of
such a result is a frame: a north-up raster in the output CRS over the sheet's footprint, at the scan's pixel
size (or coarser, at most :data:`FRAME_SIDE_PX` a side), on which the grid lines are drawn (what the report
shows beside the scan). Its pixels are the result's reference px; GCPs are the crossings found (scan px ->
frame px, and their coordinates). The check is the grid's own (:mod:`hamta.core.grid.check`).
"""
from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np
from affine import Affine
from rasterio.windows import Window

from ..errors import HamtaError, InputError, OutputError, Refused, RegistrationCanceled, UsageError
from ..io.raster import open_raster, resolve_bands
from ..io.scope import run_scope
from ..io.working import Plan
from ..options import RegisterOptions
from ..outcome import Stats, Timings
from ..progress import Monitor
from ..result import Gcp, RegistrationResult, peak_rss_mb
from ..scratch import process_folder
from .check import judge
from .finding import SheetFit
from .scan import LineSource
from .sheet import fit_sheet

FRAME_SIDE_PX = 2048
METHOD = "grid"
PARAMS = ("hints", "sheet_crs", "step")


@dataclass(frozen=True)
class GridParams:
    """What a run by the grid is given beside the scan: ``hints`` (a QGIS ``.points`` file, or rows of scan x,
    y, grid x, y; None: read from the labels printed in the margins), ``sheet_crs`` (what the printed coordinates
    count in) and the grid's ``step`` (where the hints do not tell it)."""

    hints: object
    sheet_crs: str
    step: Optional[float] = None

    @classmethod
    def make(cls, params, output) -> "GridParams":
        """From a run's ``params`` (a mapping: hints, sheet_crs, step) and output options (whose ``crs`` stands
        for the sheet's where ``sheet_crs`` is not given)."""
        if isinstance(params, cls):
            return params
        params = dict(params or {})
        unknown = sorted(set(params) - set(PARAMS))
        if unknown:
            raise UsageError(f"georeferencing by the grid takes no parameter {', '.join(unknown)}; it takes "
                             f"{', '.join(PARAMS)}")
        sheet_crs = params.get("sheet_crs") or getattr(output, "crs", None)
        if not sheet_crs:
            raise InputError("Georeferencing a sheet by its printed grid needs the sheet's CRS (--sheet-crs): what "
                             "the coordinates printed on it count in, e.g. EPSG:4326 for degrees of WGS 84, or the "
                             "national grid's CRS.")
        _crs(sheet_crs, "sheet's CRS")
        step, hints = params.get("step"), params.get("hints")
        if hints is None or (isinstance(hints, str) and not hints):
            hints = None
        elif isinstance(hints, os.PathLike):
            hints = os.fspath(hints)
        elif not isinstance(hints, str):  # rows: kept as plain numbers (a run's request is JSON)
            hints = np.asarray(hints, float).reshape(-1, 4).tolist()
        if step not in (None, "") and not float(step) > 0:
            raise UsageError(f"step must be a positive number of the sheet CRS's units, got {step!r}")
        return cls(hints, str(sheet_crs), None if step in (None, "") else float(step))


@run_scope()
def register_grid(target, sheet_crs: str, hints: Optional[Sequence] = None, *, step: Optional[float] = None,
                  output_crs: Optional[str] = None, options: RegisterOptions = RegisterOptions(), progress=None,
                  is_canceled=None) -> RegistrationResult:
    """Georeference the scan ``target`` by its printed grid, from ``hints``: rows of (scan x, y, grid x, y) or a
    QGIS ``.points`` file (mapX, mapY = the printed coordinates; sourceX, -sourceY = the scan's px); None: from
    the labels printed in its margins (:mod:`hamta.core.grid.reading`). ``sheet_crs``: what the printed
    coordinates count in (see the module docstring); ``output_crs``: the result's CRS. Nothing is written (see
    :func:`hamta.core.runner.run`). Raises :class:`Refused` (what was read and tried in ``findings``) where no
    printed grid is found."""
    monitor = Monitor(progress, is_canceled)
    t0 = time.perf_counter()
    info = open_raster(target, "target")
    given = _crs(sheet_crs, "sheet's CRS")
    reading, rows = None, None
    try:
        with LineSource.from_raster(info, resolve_bands(info, options.target_band)) as source:
            if hints is None:
                from .reading import read_sheet

                reading = read_sheet(source, info, given, monitor.span(0.0, 0.5))
                if reading.hints is None:
                    raise Refused(reading.reason, {})
                rows, printed = reading.hints, reading.printed_crs
            else:
                rows, file_crs = read_hints(hints, info.path)
                printed = _crs(file_crs, "hints' CRS") if file_crs else printed_crs(rows[:, 2:], given)
            drawn_in = given if given.is_projected and printed.is_geographic else None
            monitor.report(0.5 if hints is None else 0.05, "grid: reading the scan")
            opened = time.perf_counter()
            steps = [[step], [step]] if step else (reading.steps if reading else None)
            fit = fit_sheet(source, rows, printed, steps, drawn_in, placed_by_hand=hints is not None,
                            progress=monitor.span(0.5 if hints is None else 0.05, 0.9))
    except (RegistrationCanceled, OutputError):
        raise
    except HamtaError as exc:  # the grid or its labels not found, hints it contradicts: a refusal with a report
        raise _refusal(exc, info, reading, rows) from None
    fitted = time.perf_counter()
    frame_crs = _crs(output_crs, "output CRS") if output_crs else (drawn_in or (printed if printed.is_projected
                                                                               else fit.plane.crs))
    result = _result(info, fit, frame_crs, reading, rows, options, {"open": opened - t0, "match": fitted - opened})
    monitor.report(1.0, "grid: done")
    return result


def _refusal(exc: HamtaError, info, reading, rows) -> Refused:
    """``exc`` as a :class:`Refused` whose findings say what was read and tried."""
    findings = {"reason": str(exc), "target": info.path, "labels": None if reading is None else reading.to_dict(),
                "hints": None if rows is None else np.asarray(rows, float).tolist(),
                "lattices": [a.to_dict(getattr(exc, "geographic", False)) for a in getattr(exc, "tried", [])]}
    if isinstance(exc, Refused):
        findings = dict(exc.findings, **{k: v for k, v in findings.items() if k not in exc.findings or v})
    return Refused(str(exc), findings)


def printed_crs(coords: np.ndarray, crs):
    """What printed coordinates count in where no file says: the geographic CRS of ``crs``'s datum when they
    look like degrees and ``crs`` is projected, else ``crs`` itself. Coordinates that cannot be degrees in a
    geographic ``crs`` are refused, saying so."""
    degrees = bool(np.all(np.abs(coords[:, 0]) <= 360) and np.all(np.abs(coords[:, 1]) <= 90))
    if crs.is_geographic and not degrees:
        raise InputError("The hints' coordinates look like metres of a projected grid, but the sheet's CRS "
                         f"'{crs.name}' is in degrees: give the CRS of the grid printed on the sheet.")
    return crs.geodetic_crs if crs.is_projected and degrees else crs


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


def _crs(text, what: str):
    from pyproj import CRS

    try:
        return CRS.from_user_input(text)
    except Exception as exc:
        raise InputError(f"The {what} '{text}' is not one PROJ knows: {exc}") from None


def _result(info, fit: SheetFit, frame_crs, reading, hints, options: RegisterOptions, laps) -> RegistrationResult:
    from pyproj import Transformer

    from ..estimation.models import fit_model, local_jacobian

    t0 = time.perf_counter()
    to_frame = Transformer.from_crs(fit.plane.sheet_crs, frame_crs, always_xy=True)
    scan_px, grid_xy = fit.crossings[:, :2], fit.crossings[:, 4:6]
    map_xy = np.column_stack(to_frame.transform(grid_xy[:, 0], grid_xy[:, 1]))
    frame = _frame(info, fit, frame_crs, to_frame)
    frame_px = np.column_stack((~frame.transform) * (map_xy[:, 0], map_xy[:, 1]))
    centre = np.array([[info.width / 2, info.height / 2]])
    scale = float(math.sqrt(abs(np.linalg.det(local_jacobian(fit_model("affine", scan_px, frame_px), centre)[0]))))
    labels = None if reading is None else reading.agreement(fit)
    kind, check = judge(fit, frame_px, scale, options.model, options.tolerance_px, labels, time.perf_counter() - t0)
    model = fit_model(kind, scan_px, frame_px)
    residual = model.apply(scan_px) - frame_px
    gcps = [Gcp(tuple(map(float, s)), tuple(map(float, f)), tuple(map(float, m)), tuple(map(float, r)), 1.0, True)
            for s, f, m, r in zip(scan_px, frame_px, map_xy, residual)]
    res = np.hypot(*residual.T)
    loo = model.loo_residuals(scan_px, frame_px)
    stats = Stats(n_keypoints_target=len(fit.crossings), n_keypoints_reference=0, n_matches=len(gcps),
                  n_inliers=len(gcps), n_gcps=len(gcps), n_refined=0, rmse_px=float(np.sqrt(np.mean(res ** 2))),
                  rms_loo_px=float(np.sqrt(np.nanmean(loo ** 2))) if np.isfinite(loo).any() else None,
                  max_residual_px=float(res.max()), refined=False, peak_rss_mb=peak_rss_mb())
    timings = Timings.from_laps(dict(laps, fit=time.perf_counter() - t0))
    plan = Plan("grid", Window(0, 0, frame.width, frame.height), Window(0, 0, info.width, info.height),
                ("the sheet's own printed grid",))
    geographic = fit.plane.sheet_crs.is_geographic
    params = {"sheet_crs": fit.plane.sheet_crs.to_string(), "step": [float(v) for v in fit.step],
              "hints": None if hints is None else np.asarray(hints, float).tolist()}
    notes = [f"{len(gcps)} crossings of the printed grid found (step {check.step_text}), covering {fit.spread:.0%} "
             f"of the sheet; the lattice: {fit.evidence.text()}; drawn in: {fit.plane.name}"
             + ("" if check.plane_affine_scan_px is None else
                f" (an affine there predicts each line held out within {check.plane_affine_scan_px:.2f} scan px)")
             + f"; the {kind} model{'' if options.model else ', chosen by the check'}: each grid line predicted "
             f"from the others is off by {check.held_out_scan_px:.2f} scan px RMS"]
    if reading is not None:
        notes.append(reading.note())
    diagnostics = {"grid": {"plane": fit.plane.name, "plane_crs": fit.plane.crs.to_wkt(),
                            "step": [float(v) for v in fit.step],
                            "geographic": geographic, "model": kind, "held_out_rms_px": check.held_out_scan_px,
                            "coverage": fit.spread, "crossings": len(gcps), "lattice": fit.evidence.to_dict(),
                            "lattices_tried": [a.to_dict(geographic) for a in fit.tried],
                            "planes_held_out_scan_px": fit.plane_fits,
                            "frame_px_per_scan_px": scale,
                            "labels": None if reading is None else reading.to_dict()}}
    return RegistrationResult(METHOD, params, {"model": options.model, "tolerance_px": options.tolerance_px,
                                               "target_band": options.target_band}, model, info, frame, plan, gcps,
                              stats, timings, notes=notes, verification=check, diagnostics=diagnostics)


def _frame(info, fit: SheetFit, frame_crs, to_frame):
    """The frame raster (see the module docstring), written once per run into a private temporary folder."""
    import cv2
    import rasterio

    from .crossings import to_scan

    to_plane = to_scan(fit.crossings[:, [2, 3, 0, 1, 4, 5]], fit.order)  # scan px -> plane
    outline = np.array([[x, y] for x in np.linspace(0, info.width, 9) for y in np.linspace(0, info.height, 9)])
    centre = np.array([[info.width / 2, info.height / 2], [info.width / 2 + 1, info.height / 2],
                       [info.width / 2, info.height / 2 + 1]])

    def frame_xy(px):
        g = fit.plane.backward(to_plane.apply(px))
        return np.column_stack(to_frame.transform(g[:, 0], g[:, 1]))

    xy, c = frame_xy(outline), frame_xy(centre)
    size = math.sqrt(abs(np.linalg.det(np.array([c[1] - c[0], c[2] - c[0]]))))
    x0, y0, x1, y1 = xy[:, 0].min(), xy[:, 1].min(), xy[:, 0].max(), xy[:, 1].max()
    size = max(size, (x1 - x0) / FRAME_SIDE_PX, (y1 - y0) / FRAME_SIDE_PX)
    width, height = max(int(math.ceil((x1 - x0) / size)), 1), max(int(math.ceil((y1 - y0) / size)), 1)
    transform = Affine(size, 0, x0, 0, -size, y1)
    image = np.full((height, width), 245, np.uint8)
    g = fit.crossings[:, 4:6]
    step = np.asarray(fit.step, float)
    lo, hi = g.min(axis=0) - step, g.max(axis=0) + step
    along = np.linspace(0, 1, 200)
    for axis in (0, 1):
        for value in np.arange(lo[axis], hi[axis] + step[axis] / 2, step[axis]):
            line = np.empty((len(along), 2))
            line[:, axis], line[:, 1 - axis] = value, lo[1 - axis] + along * (hi[1 - axis] - lo[1 - axis])
            mx, my = to_frame.transform(line[:, 0], line[:, 1])
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
