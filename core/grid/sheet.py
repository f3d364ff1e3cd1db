"""Georeferencing a scanned sheet by its own printed grid or graticule, from a few hints.

The user places one to three crossings of the printed lines roughly and types their coordinates (a QGIS
Georeferencer ``.points`` file). From them: the grid's step (the largest usual step that every hint's
coordinates are multiples of, or the one given), a first model (a similarity from two hints, an affine
from three), and from it where every other crossing of the sheet should be. Each is then found where it
is printed (:func:`hamta.core.grid.lines.crossing`, sub-pixel), the model refitted on what was found and
the crossings looked for again, closer. The model is chosen by leave-one-out: each crossing predicted by
a model fitted on the others (the check never reuses the point it judges); affine, or a polynomial where
the projection bends the lines (Mercator, conic sheets) or the paper is warped.

Coordinates: scan pixels (corner convention); ``grid_crs`` is what the printed labels count in (degrees
of EPSG:4326 for a graticule, or the national grid's CRS); ``crs`` is the output's (the sheet's
projection, where known, makes the affine model exact).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Optional, Sequence

import numpy as np

from ..errors import InputError, InsufficientMatchesError
from .crossings import MODELS, held_out_lines, ordered, spread_of, trimmed, without_stray_lines
from .lattice import contrast, fit_lattice
from .lines import crossing
from .polynomial import apply_poly, fit_poly
from .scan import LineSource

HINT_PX = 0.15  # of the grid's spacing: how far from a crossing a hint may be placed
DEGREE_STEPS = (10, 5, 2, 1, 0.5, 1 / 3, 0.25, 1 / 6, 1 / 12, 1 / 24, 1 / 60)  # graticules: 10 degrees to 1'
METRE_STEPS = (100000, 50000, 20000, 10000, 5000, 2000, 1000, 500, 200, 100)  # national grids
MAX_CROSSINGS = 4000
MIN_FIT = 6  # crossings a verified result needs (and one taken for a wrong line can be told)

@dataclass
class SheetFit:
    """What the sheet's grid gave: ``gcps`` (n, 6): scan x, y, ``crs`` x, y and grid x, y of each crossing
    found; ``model`` and its ``order``; ``loo_px``, the RMS in scan px of each crossing predicted by the
    model fitted on the others; ``verified`` when that is within the tolerance over enough well-spread
    crossings; ``step`` the grid's step (``grid_crs`` units); ``notes``."""

    gcps: np.ndarray
    model: str
    order: int
    loo_px: float
    verified: bool
    step: float
    notes: List[str] = field(default_factory=list)
    held_out: Optional[np.ndarray] = None  # (n, 2) scan px: each crossing's error predicted without its grid line
    spread: float = 0.0  # share of the sheet the crossings cover
    nodes: int = 0  # crossings the lattice puts on the sheet where both their lines can be looked at
    apart_px: Optional[float] = None  # the largest distance between the crossings' model and the lattice's
    apart_limit_px: float = math.inf  # and how far they may be apart for a verified result
    contrast: float = 0.0  # the lattice's ink over its lines moved by part of a step (see lattice.contrast)
    sound: bool = False  # enough crossings, spread over the sheet, on the lattice of whole lines: all the
    # verdict asks but the lines held out (``verified`` adds them, with this model)

    def to_crs(self, px: np.ndarray) -> np.ndarray:
        """Scan px (n, 2) -> ``crs`` coordinates, through the model fitted on every crossing found."""
        return apply_poly(fit_poly(self.gcps[:, :2], self.gcps[:, 2:4], self.order), px)

    def to_scan(self, xy: np.ndarray) -> np.ndarray:
        """``crs`` coordinates (n, 2) -> scan px, through the model fitted on every crossing found."""
        return apply_poly(fit_poly(self.gcps[:, 2:4], self.gcps[:, :2], self.order), xy)


def fit_sheet(scan, hints: Sequence, crs: str, grid_crs: Optional[str] = None,
              step: Optional[float] = None, tolerance_px: float = 2.0, progress=None) -> SheetFit:
    """Find the sheet's printed crossings from ``hints`` (rows of scan x, y, grid x, y) and fit the model
    (see the module docstring). ``scan``: a :class:`LineSource`, or the scan as a grey 2-D array. Raises
    :class:`InputError` for hints that do not fit a grid or a grid the hints do not find, and
    :class:`InsufficientMatchesError` when too few crossings are found. ``progress``: a
    :class:`hamta.core.progress.Monitor` (reports, and raises where the user cancelled)."""
    from pyproj import CRS, Transformer

    from ..progress import Monitor

    monitor = progress or Monitor(None, None)

    hints = np.asarray(hints, float).reshape(-1, 4)
    if len(hints) < 2:
        raise InputError("Georeferencing by the grid needs at least two crossings placed with their coordinates "
                         f"(got {len(hints)}), until the sheet's labels are read.")
    grid_crs = grid_crs or crs
    to_crs = Transformer.from_crs(CRS.from_user_input(grid_crs), CRS.from_user_input(crs), always_xy=True)
    from_crs = Transformer.from_crs(CRS.from_user_input(crs), CRS.from_user_input(grid_crs), always_xy=True)
    geographic = CRS.from_user_input(grid_crs).is_geographic
    steps = [step] if step else grid_steps(hints[:, 2:], DEGREE_STEPS if geographic else METRE_STEPS)
    steps = [s for s in steps if s >= steps[0] / STEPS_SPAN]
    source = scan if isinstance(scan, LineSource) else LineSource.from_array(scan)
    shape = source.shape
    hint_xy = np.column_stack(to_crs.transform(hints[:, 2], hints[:, 3]))
    forward, backward = _first_model(hints[:, :2], hint_xy, CRS.from_user_input(crs).is_geographic)
    monitor.report(0.0, "grid: the scan's lines")
    works, tried = {}, []
    for k, step in enumerate(steps):  # the largest step the hints allow whose lines are printed
        monitor.report(0.1 + 0.5 * k / len(steps), f"grid: a lattice of step {step:g}")
        found_lattice = _lattice(source, works, forward, backward, from_crs, to_crs, step)
        if found_lattice is None:
            break
        nodes, lattice, ink, spacing, factor = found_lattice
        tried.append(f"{step:g} ({ink:.2f})")
        if ink >= MIN_CONTRAST:
            break
    else:
        found_lattice = None
    if found_lattice is None or ink < MIN_CONTRAST:
        raise InsufficientMatchesError(
            "No printed grid was found where the hints put it: the lines of a lattice of step "
            f"{', '.join(tried) or '-'} hold that many times the ink of the same lines moved by part of a step "
            f"({MIN_CONTRAST:g} needed). "
            "Check the hints' coordinates and the grid's step, or register the sheet onto a reference layer.", 0, 6)
    _check_hints(hints, hint_xy, lattice.coef, spacing)
    radius = max(3.0, 0.6 * factor, LOCAL_SHARE * spacing)
    monitor.report(0.6, "grid: each crossing")
    found = _found(source, nodes, lattice.coef, to_crs, step, radius, spacing, monitor.check)
    for _ in range(PASSES):  # again, where the crossings found put the others (the lattice is placed on a
        # reduced line map: off by a few px where the paper or the projection bends)
        if len(found) < 3 or len(found) == len(nodes):
            break
        again = trimmed(found, ordered(found, shape))
        coef = fit_poly(again[:, 2:4], again[:, :2], ordered(again, shape))
        more = _found(source, nodes, coef, to_crs, step, max(radius, 2 * LOCAL_SHARE * spacing), spacing,
                      monitor.check)
        if len(more) <= len(found):
            break
        found = more
    if len(found) < 3:
        raise InsufficientMatchesError(f"Only {len(found)} crossings of the printed grid were found on the lattice "
                                       "the hints give: check the hints' coordinates and the grid's step.",
                                       len(found), 6)
    order = ordered(found, shape)
    found = trimmed(found, order)
    order = ordered(found, shape)
    found = without_stray_lines(found, order)
    order = ordered(found, shape)
    loo, held_out, _ = held_out_lines(found, order)
    spread = spread_of(found[:, :2], shape)
    backward = fit_poly(found[:, 2:4], found[:, :2], order)
    apart = float(np.max(np.hypot(*(apply_poly(backward, found[:, 2:4]) - apply_poly(lattice.coef, found[:, 2:4])).T)))
    notes = [f"{len(found)} crossings of the printed grid found (step {step:g}); each grid line predicted from the "
             f"others: {loo:.2f} px RMS with the {MODELS[order - 1][0]} model; they cover {spread:.0%} of the sheet; "
             f"the lattice of whole lines holds {ink:.2f} times the ink of its lines moved by part of a step, and is "
             f"within {apart:.1f} px of the crossings' model"]
    limit = max(2 * tolerance_px, factor, APART * spacing)
    node_px = apply_poly(lattice.coef, np.column_stack(to_crs.transform(*nodes.T)))
    reachable = _inside(node_px, shape, 0.45 * spacing + radius + 2) & _within(node_px, found[:, :2], 0.25 * spacing)
    share = len(found) / max(int(reachable.sum()), 1)  # of the crossings where both strips lie on the scan, among
    # those found (a sheet's margin has no grid)
    sound = len(found) >= MIN_FIT and spread >= MIN_SPREAD and apart <= limit and share >= MIN_SHARE
    notes += [f"only {len(found)} of the {int(reachable.sum())} crossings the lattice puts among them were found "
              f"on printed lines ({MIN_SHARE:.0%} needed): the lattice may not be the printed grid"] \
        if share < MIN_SHARE else []
    verified = sound and loo <= tolerance_px
    monitor.report(1.0, "grid: the model")
    return SheetFit(found, MODELS[order - 1][0], order, loo, verified, step, notes, held_out, spread,
                    int(reachable.sum()), apart, limit, ink, sound)


def _within(px, around, reach: float) -> np.ndarray:
    """Which of ``px`` lie within ``reach`` px of the convex hull of ``around`` (all where it has no area)."""
    import cv2

    if len(around) < 3:
        return np.ones(len(px), bool)
    hull = cv2.convexHull(around.astype(np.float32))
    return np.array([cv2.pointPolygonTest(hull, (float(x), float(y)), True) >= -reach for x, y in px])


def _inside(px, shape, margin: float = 0.0) -> np.ndarray:
    h, w = shape
    return (px[:, 0] >= margin) & (px[:, 1] >= margin) & (px[:, 0] <= w - margin) & (px[:, 1] <= h - margin)


MIN_CONTRAST = 1.3  # the lattice's ink over its lines moved by part of a step: below, no grid of that step is there
MIN_SPREAD = 0.25  # share of the sheet the crossings must cover for a verified result
MIN_SHARE = 0.5  # of the crossings the lattice puts on the sheet, those found on printed lines for a verified result
LOCAL_SHARE = 0.04  # of a step: how far from the lattice's place a crossing is looked for
PASSES = 3  # times the crossings are looked for again where those found put them
FAINT = 0.3  # of the median crossing's ink: fainter crossings are noise (off the paper, a gap in the lines)


def _factor(spacing: float, shape) -> int:
    """The line map's reduction: a step of at least 24 reduced px, and at most 4000 px on the long side."""
    return max(1, int(spacing // 24), int(np.ceil(max(shape) / 4000)))


def _grid_lines(nodes, step, to_crs, per_step: float):
    """(output-CRS points along every grid line through ``nodes`` and one step beyond, ``per_step`` a step; each
    line's axis: 0 where grid x is constant, 1 where grid y is)."""
    n = max(int(np.ceil(per_step)), 4)
    lo, hi = nodes.min(axis=0) - step, nodes.max(axis=0) + step
    out, axes = [], []
    for axis in (0, 1):
        along = np.arange(lo[1 - axis], hi[1 - axis] + step / n / 2, step / n)
        for value in np.unique(nodes[:, axis]):
            g = np.empty((len(along), 2))
            g[:, axis], g[:, 1 - axis] = value, along
            xy = np.column_stack(to_crs.transform(g[:, 0], g[:, 1]))
            out.append(xy[np.all(np.isfinite(xy), axis=1)])
            axes.append(axis)
    return out, axes


def _steps(coef, nodes, to_crs, step) -> np.ndarray:
    """Scan px of one grid step along grid x and along grid y at the middle of ``nodes``."""
    mid = nodes[len(nodes) // 2]
    pts = np.column_stack(to_crs.transform([mid[0], mid[0] + step, mid[0]], [mid[1], mid[1], mid[1] + step]))
    px = apply_poly(coef, pts)
    return np.array([px[1] - px[0], px[2] - px[0]])


def _check_hints(hints, hint_xy, coef, spacing) -> None:
    """Each hint within :data:`HINT_PX` of a step from where the lattice puts its coordinates, else the hint
    is named as the one that disagrees."""
    off = np.hypot(*(apply_poly(coef, hint_xy) - hints[:, :2]).T)
    for i in np.flatnonzero(off > HINT_PX * spacing):
        raise InputError(f"The printed grid found from the hints does not pass through hint {i + 1} ({hints[i, 2]:g}, "
                         f"{hints[i, 3]:g}): it puts those coordinates {off[i]:.0f} px away. Check that hint's "
                         "coordinates and place; if they are right, the grid is too faint here to be followed: "
                         "register the sheet onto a reference layer.")


STEP_FIT = 0.005  # of a step: how far from a multiple of it a printed coordinate may be (rounding of
# seconds: 44°29' is 44.48333)


def grid_steps(coords: np.ndarray, steps: Sequence[float]) -> List[float]:
    """Those of ``steps`` that every coordinate of ``coords`` is a multiple of (to :data:`STEP_FIT` of the step),
    largest first: hints a few steps apart fit twice the printed step as well as the step itself."""
    fits = []
    for s in steps:
        ratio = np.asarray(coords, float) / s
        if np.all(np.abs(ratio - np.round(ratio)) <= STEP_FIT):
            fits.append(float(s))
    if not fits:
        raise InputError("The hints' coordinates are not on a grid of a usual step (degrees: 10 to 1'; metres: 100 "
                         "km to 100 m): give the grid's step.")
    return fits


def _lattice(source, works, forward, backward, from_crs, to_crs, step):
    """(nodes, lattice, its contrast, the step in scan px, the line map's reduction) of a grid of ``step`` from
    the hints' first model, or None where its crossings would be too close or too many to be a printed grid.
    ``works``: the reduced line maps computed so far, by reduction."""
    try:
        nodes = _nodes(forward, source.shape, from_crs, step)
    except InputError:
        return None
    spacing = _spacing(backward, nodes, to_crs, step)
    if spacing < MIN_STEP_PX:
        return None
    factor = _factor(spacing, source.shape)
    if factor not in works:
        works[factor] = source.reduced(factor)
    work = works[factor]
    lines, axes = _grid_lines(nodes, step, to_crs, spacing / factor)
    lattice = fit_lattice(work, factor, lines, backward, spacing)
    steps = _steps(lattice.coef, nodes, to_crs, step)
    ink = contrast(work, factor, lines, axes, lattice, steps)
    return nodes, lattice, ink, float(min(np.hypot(*steps.T))), factor


MIN_STEP_PX = 12.0  # a printed grid's crossings are at least this far apart on a scan
APART = 0.1  # of a step: how far the crossings' model may lie from the lattice of whole lines (placed on a line
# map reduced by up to a tenth of a step, and only affine or quadratic)
STEPS_SPAN = 10  # the steps the hints fit that are tried: down to a tenth of the largest (hints on crossings ten
# steps apart at most)


def _nodes(forward, shape, from_crs, step):
    """Grid coordinates (n, 2) of the crossings the model ``forward`` (scan px -> crs) puts on the sheet."""
    h, w = shape
    edge = np.array([[x, y] for x in np.linspace(0, w, 9) for y in np.linspace(0, h, 9)])
    gx, gy = from_crs.transform(*apply_poly(forward, edge).T)
    i0, i1 = math.floor(np.nanmin(gx) / step), math.ceil(np.nanmax(gx) / step)
    j0, j1 = math.floor(np.nanmin(gy) / step), math.ceil(np.nanmax(gy) / step)
    if (i1 - i0 + 1) * (j1 - j0 + 1) > MAX_CROSSINGS:
        raise InputError(f"The hints put {(i1 - i0 + 1) * (j1 - j0 + 1)} crossings of a {step:g} step on the sheet, "
                         f"more than {MAX_CROSSINGS}: check the hints' coordinates and the grid's step.")
    ii, jj = np.meshgrid(np.arange(i0, i1 + 1), np.arange(j0, j1 + 1))
    return np.column_stack([ii.ravel() * step, jj.ravel() * step])


def _first_model(px, xy, geographic: bool):
    """(scan px -> crs, crs -> scan px) from the hints: a similarity with a reflection (scan rows run down,
    northings up), on longitudes shrunk by the cosine of the latitude where the crs is geographic, so that a
    degree is as long both ways. Hints along one line fix a similarity but not an affine; the lattice frees
    it (:func:`hamta.core.grid.lattice.fit_lattice`)."""
    shrink = math.cos(math.radians(float(np.mean(xy[:, 1])))) if geographic else 1.0
    squeeze = np.diag([shrink, 1.0])
    forward, backward = fit_poly(px, xy @ squeeze, 1, True), fit_poly(xy @ squeeze, px, 1, True)
    forward["m"] = forward["m"] / np.array([shrink, 1.0])
    backward["squeeze"] = shrink
    return forward, backward


def _spacing(backward, nodes, to_crs, step) -> float:
    """The grid's step in scan px near the middle of ``nodes``."""
    mid = nodes[len(nodes) // 2]
    pts = np.column_stack(to_crs.transform([mid[0], mid[0] + step, mid[0]], [mid[1], mid[1], mid[1] + step]))
    px = apply_poly(backward, pts)
    return float(min(np.hypot(*(px[1] - px[0])), np.hypot(*(px[2] - px[0]))))


def _found(source, nodes, coef, to_crs, step, radius, spacing, check=lambda: None) -> np.ndarray:
    """Rows (scan x, y, crs x, y, grid x, y) of each crossing found within ``radius`` px of where the lattice
    ``coef`` (crs -> scan px) puts it, the two lines' directions there taken from the same model, whose lines
    hold at least :data:`FAINT` of the median crossing's ink (off the paper, noise peaks). ``check`` raises
    where the user cancelled."""
    eps = step * 0.02
    rows = []
    for k, (gx, gy) in enumerate(nodes):
        if k % 64 == 0:
            check()
        pts = np.column_stack(to_crs.transform([gx, gx, gx + eps], [gy, gy + eps, gy]))
        if not np.all(np.isfinite(pts)):
            continue
        px = apply_poly(coef, pts)
        dirs = [(px[1] - px[0]) / (np.hypot(*(px[1] - px[0])) + 1e-12),  # the line of constant grid x
                (px[2] - px[0]) / (np.hypot(*(px[2] - px[0])) + 1e-12)]  # and of constant grid y
        got = crossing(source, px[0], dirs, radius, along=0.45 * spacing)
        if got is not None:
            rows.append([*got.xy, *pts[0], gx, gy, got.ink])
    rows = np.array(rows).reshape(-1, 7)
    inked = rows[:, 6] >= FAINT * np.median(rows[:, 6]) if len(rows) else np.zeros(0, bool)
    return rows[inked, :6]
