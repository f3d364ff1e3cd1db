"""A scanned sheet's printed crossings, found from a few hints (two or three crossings with their coordinates,
placed roughly by a person or made of the labels printed in the margins).

From the hints: the grid's step (the largest usual step every hint's coordinates are multiples of, or the one
given, :mod:`hamta.core.grid.steps`) and, in each plane the sheet may be drawn in (:mod:`hamta.core.grid.planes`),
a first model (a similarity from two hints, an affine from three). The lattice of every grid line is placed on
the scan from it (:mod:`hamta.core.grid.lattice`) and judged against the sheet's own background; the plane whose
lattice the scan holds surest is kept, at the largest step whose lines are printed. Each crossing is then found
where it is printed (:func:`hamta.core.grid.lines.crossing`, sub-pixel), the model refitted on what was found and
the crossings looked for again, closer. What the crossings are worth (the model, the verdict) is judged once, by
:mod:`hamta.core.grid.check`.

Coordinates: scan pixels (corner convention); grid coordinates in the sheet's CRS (what the printed labels
count in: degrees of a graticule, or a national grid's metres, feet or yards); plane coordinates (metres of
the plane).
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import List, Optional, Sequence

import numpy as np

from ..errors import InputError
from ..estimation.models import LinearModel
from .crossings import ordered, spread_of, to_scan, trimmed, without_stray_lines
from .frame import find_frames, node_pieces, tick_pieces
from .lattice import CHANCE, Evidence, _ink, evidence, fit_lattice
from .lines import crossing
from .planes import Plane, planes_for
from .scan import LineSource
from .steps import describe_pair, hint_steps

HINT_PX = 0.15  # of the grid's spacing: how far from a crossing a hint may be placed
MAX_CROSSINGS = 4000
MIN_STEP_PX = 24.0  # a printed grid's crossings are at least this far apart on a scan (its evidence is judged on a
# line map with 24 px a step at least)
APART = 0.1  # of a step: how far the crossings' model may lie from the lattice of whole lines (placed on a line
# map reduced by up to a tenth of a step, and only affine or quadratic)
STEPS_SPAN = 1e6  # the steps the hints fit that are tried: all, largest first, until their crossings are too close
# (hints on one line leave its step open)
LOCAL_SHARE = 0.04  # of a step: how far from the lattice's place a crossing is looked for
PASSES = 3  # times the crossings are looked for again where those found put them
FAINT = 0.3  # of the median crossing's ink: fainter crossings are noise (off the paper, a gap in the lines)


class NoGridFound(InputError):
    """No lattice of the hints' steps is printed where they put it, in any plane tried; ``tried`` lists what was
    (plane, step, evidence), for the report."""

    def __init__(self, message: str, tried, geographic: bool):
        super().__init__(message)
        self.tried, self.geographic = list(tried), geographic


@dataclass(frozen=True)
class Attempt:
    """One lattice tried: its plane, step (along grid x, along grid y) and what the scan says of it (None: it could
    not be placed), and the share of its line segments printed where its affine lattice puts them."""

    plane: str
    step: tuple
    evidence: Optional[Evidence]
    spacing_px: float = math.nan
    straight: float = math.nan

    def to_dict(self, geographic: bool) -> dict:
        return {"plane": self.plane, "step": list(self.step), "step_text": describe_pair(self.step, geographic),
                "spacing_px": None if not math.isfinite(self.spacing_px) else self.spacing_px,
                "segments_on_lines": None if not math.isfinite(self.straight) else self.straight,
                "evidence": None if self.evidence is None else self.evidence.to_dict()}


@dataclass
class SheetFit:
    """What the sheet's grid gave: ``crossings`` (n, 6): scan x, y, plane x, y and grid x, y of each crossing
    found; the ``plane`` and ``step`` (along grid x, along grid y) of the lattice kept and its ``evidence``;
    ``order`` of the polynomial from the plane to the scan the crossings support; ``spread`` the share of the sheet
    they cover; ``reachable`` the crossings the lattice puts where both their lines can be looked at, near those
    found; ``apart_px`` the RMS distance between the crossings' model and the lattice (``apart_limit_px`` what a
    sound sheet allows); ``tried`` every lattice tried; ``notes``."""

    crossings: np.ndarray
    plane: Plane
    step: np.ndarray
    evidence: Evidence
    order: int
    spread: float
    reachable: int
    apart_px: float
    apart_limit_px: float
    tried: List[Attempt] = field(default_factory=list)
    notes: List[str] = field(default_factory=list)
    lattice_order: int = 1
    plane_fits: dict = field(default_factory=dict)  # plane name -> held-out RMS (scan px) of an affine from it

    @property
    def share(self) -> float:
        """Of the crossings the lattice puts where they can be looked at, the share found on printed lines."""
        return len(self.crossings) / max(self.reachable, 1)


def fit_sheet(scan, hints: Sequence, sheet_crs, steps=None, drawn_in=None, progress=None,
              placed_by_hand: bool = True) -> SheetFit:
    """Find the sheet's printed crossings from ``hints`` (rows of scan x, y, grid x, y in ``sheet_crs``, a pyproj
    CRS); ``steps``: the grid's steps to try along grid x and along grid y (two lists, largest first; None: those
    the hints' coordinates fit); ``drawn_in``: a projected CRS the user says the sheet is drawn in (tried first).
    ``scan``: a :class:`LineSource`, or the scan as a grey 2-D array. Raises :class:`NoGridFound` where no lattice
    of the hints' steps is printed, and :class:`InputError` for hints the printed lattice contradicts (naming the
    hint placed by hand; ``placed_by_hand`` False: hints made of labels, which the check holds to the lattice
    itself). ``progress``: a :class:`hamta.core.progress.Monitor` (reports, and raises where the user cancelled)."""
    from ..progress import Monitor

    monitor = progress or Monitor(None, None)
    hints = np.asarray(hints, float).reshape(-1, 4)
    if len(hints) < 2:
        raise InputError("Georeferencing by the grid needs at least two crossings placed with their coordinates "
                         f"(got {len(hints)}).")
    geographic = sheet_crs.is_geographic
    steps = [list(s) for s in steps] if steps else [hint_steps(hints[:, 2 + a], geographic, STEPS_SPAN)
                                                     for a in (0, 1)]
    source = scan if isinstance(scan, LineSource) else LineSource.from_array(scan)
    planes = ([Plane("the CRS given", drawn_in, sheet_crs)] if drawn_in is not None else []) + \
        planes_for(sheet_crs, _lon_lat_box(hints, source.shape) if geographic else None)
    monitor.report(0.0, "grid: the lattice")
    works, tried, best = {}, [], None
    for k, plane in enumerate(planes):  # the largest steps the hints allow whose lines are printed, each family's
        # smaller where its lines are not; in the other planes, those steps: the plane whose affine lattice lies on
        # most of the printed lines is kept
        monitor.report(0.6 * k / len(planes), f"grid: the lattice in {plane.name}")
        found = _printed(source, works, plane, hints, steps if best is None else [[s] for s in best[1].step],
                         tried, geographic, CHANCE)
        if found is not None and (best is None or found.lattice.straight > best[1].lattice.straight):
            best = (plane, found)
    if best is None:
        raise NoGridFound(_not_found(tried, geographic), tried, geographic)
    best = (best[0], _lattice(source, works, best[0], hints, best[1].step, bend=True,
                              threshold=best[1].evidence.threshold) or best[1])
    plane, lat = best
    monitor.report(0.6, "grid: each crossing")
    fit = _crossings(source, plane, lat, monitor)
    fit.tried = tried
    if placed_by_hand:
        _check_hints(hints, plane.forward(hints[:, 2:]), to_scan(fit.crossings, fit.order)
                     if len(fit.crossings) >= 6 else lat.lattice.model, lat.spacing)
    lines = [len(np.unique(fit.crossings[:, 4 + a])) for a in (0, 1)]
    if len(fit.crossings) < 3 or min(lines) < 2:
        raise NoGridFound(f"Only {len(fit.crossings)} crossings of the printed grid were found ({lines[0]} and "
                          f"{lines[1]} lines each way), on the lattice of {describe_pair(lat.step, geographic)} in "
                          f"{plane.name} ({lat.evidence.text()}): too few to place the sheet.", tried, geographic)
    if len(planes) > 1:
        fit = _drawn_in(fit, planes)
    monitor.report(1.0, "grid: the crossings")
    return fit


def _printed(source, works, plane: Plane, hints, steps, tried, geographic: bool, threshold: float
             ) -> Optional["_Placed"]:
    """The lattice in ``plane`` at the largest steps of ``steps`` (a list for each axis) whose lines are printed
    (beyond ``threshold``: the lattices a search may try share :data:`hamta.core.grid.lattice.CHANCE`): a family
    whose lines are not is tried at its next smaller step; None where no lattice is. Each lattice placed is added
    to ``tried``."""
    ix, iy = 0, 0
    while ix < len(steps[0]) and iy < len(steps[1]):
        step = (steps[0][ix], steps[1][iy])
        found = _lattice(source, works, plane, hints, step, threshold=threshold)
        tried.append(Attempt(plane.name, step, None if found is None else found.evidence,
                             math.nan if found is None else found.spacing,
                             math.nan if found is None else found.lattice.straight))
        if found is None:  # a step wider than the sheet can judge, or one whose crossings are closer than printed:
            if _too_fine(source, plane, hints, step):  # none smaller is printed
                return None
            ix, iy = ix + 1, iy + 1
            continue
        if found.evidence.printed:
            return _equal_steps(source, works, plane, hints, steps, found, tried, threshold)
        fx, fy = (family.at_step for family in found.evidence.families)
        if fx and fy:
            return None  # each family at its step, but not both together beyond chance: no grid of these steps
        if not fx and not fy:  # the coarser family first: a lattice wrong one way misplaces the other's lines too
            coarser = int(np.argmax(np.hypot(*found.steps_px.T)))
            fx, fy = coarser == 1, coarser == 0
        ix, iy = ix + (not fx), iy + (not fy)
    return None


def _equal_steps(source, works, plane, hints, steps, found, tried, threshold):
    """``found``, or the lattice with both steps the larger of its two where that is printed too (a family at
    half its printed step still finds every printed line: the larger step is the grid's)."""
    sx, sy = found.step
    if sx == sy:
        return found
    both = max(sx, sy)
    if both not in steps[0] or both not in steps[1]:
        return found
    again = _lattice(source, works, plane, hints, (both, both), threshold=threshold)
    tried.append(Attempt(plane.name, (both, both), None if again is None else again.evidence,
                         math.nan if again is None else again.spacing,
                         math.nan if again is None else again.lattice.straight))
    return again if again is not None and again.evidence.printed else found


def _too_fine(source, plane: Plane, hints, step) -> bool:
    """Whether a lattice of ``step`` would put crossings closer than :data:`MIN_STEP_PX` (or too many)."""
    hint_xy = plane.forward(hints[:, 2:])
    if not np.isfinite(hint_xy).all():
        return True
    start = _first_model(hints[:, :2], hint_xy)
    try:
        nodes = _nodes(start, source.shape, plane, step)
    except InputError:
        return True
    return not _spacing(start, nodes, plane, step) >= MIN_STEP_PX


@dataclass(frozen=True)
class _Placed:
    """A lattice placed in a plane: the crossings it puts on the sheet (grid coordinates), the lattice, its
    evidence, the step in scan px, the line map's reduction, its lines (plane points) and their axes."""

    nodes: np.ndarray
    lattice: object
    evidence: Evidence
    spacing: float
    factor: int
    step: tuple
    frames: tuple = ()
    steps_px: np.ndarray = None  # scan px of one step along grid x and along grid y


def _lattice(source, works, plane: Plane, hints, step, bend: bool = False, threshold: float = CHANCE
             ) -> Optional[_Placed]:
    """The lattice of ``step`` (along grid x, along grid y) in ``plane`` from the hints' first model (``bend``:
    second-order where that finds more ink), or None where its crossings would be too close or too many to be a
    printed grid. ``works``: the reduced line maps computed so far, by reduction."""
    hint_xy = plane.forward(hints[:, 2:])
    if not np.isfinite(hint_xy).all():
        return None
    start = _first_model(hints[:, :2], hint_xy)
    try:
        nodes = _nodes(start, source.shape, plane, step)
    except InputError:
        return None
    spacing = _spacing(start, nodes, plane, step)
    if not spacing >= MIN_STEP_PX:
        return None
    factor = _factor(spacing, source.shape)
    work = _work(source, works, factor)
    lines, axes, values = _grid_lines(nodes, step, plane, spacing / factor)
    if not lines:
        return None
    lattice = fit_lattice(work, factor, lines, start, spacing, bend)
    steps = _steps(lattice.model, nodes, plane, step)
    frames = find_frames(_ink(work, factor, outside=math.nan), lattice.model, plane, nodes, step)
    found = evidence(work, factor, lines, axes, lattice, steps, values,
                     node_pieces(nodes, step, plane) + tick_pieces(frames, nodes, step, plane))
    if found is None:
        return None
    found = dataclasses.replace(found, threshold=threshold)
    return _Placed(nodes, lattice, found, float(min(np.hypot(*steps.T))), factor, tuple(step), tuple(frames), steps)


def _crossings(source, plane: Plane, placed: _Placed, monitor) -> SheetFit:
    """Every crossing of the lattice ``placed`` and every tick on its frame, found where it is printed and judged
    as a whole. Rows: scan x, y, plane x, y, grid x, y; then ``kind`` (-1 a crossing of two grid lines; else a
    tick on the frame line of that index, whose coordinate across the frame is the frame's, estimated) and the
    frame's direction on the scan (unit x, y; 0 for crossings)."""
    shape = source.shape
    spacing, factor, nodes = placed.spacing, placed.factor, placed.nodes
    step = np.asarray(placed.step, float)
    frames = list(placed.frames)
    model = placed.lattice.model
    radius = max(3.0, 0.6 * factor, LOCAL_SHARE * spacing)

    def look(model, radius):
        inner = _found(source, nodes, model, plane, step, radius, spacing, monitor.check)
        inner = np.column_stack([inner, np.full((len(inner), 3), [-1.0, 0.0, 0.0])])
        return np.vstack([inner, _ticks(source, frames, nodes, model, plane, step, radius, spacing, monitor.check)])

    found = look(model, radius)
    for _ in range(PASSES):  # again, where the crossings found put the others (the lattice is placed on a
        # reduced line map: off by a few px where the paper or the projection bends)
        if len(found) < 3:
            break
        frames = _frames_refined(frames, found, shape, plane)
        again = trimmed(found, ordered(found, shape))
        more = look(to_scan(again, ordered(again, shape)), max(radius, 2 * LOCAL_SHARE * spacing))
        if len(more) <= len(found):
            break
        found = more
    if len(found) < 3:
        return SheetFit(found, plane, step, placed.evidence, 1, 0.0, len(nodes), math.inf, 0.0)
    for _ in range(2):  # the frames' values where their ticks put them, and the ticks' coordinates with them
        frames = _frames_refined(frames, found, shape, plane)
        found = _on_frames(found, frames, plane)
    found = trimmed(found, ordered(found, shape))
    found = without_stray_lines(found, ordered(found, shape))
    order = ordered(found, shape)
    apart = float(np.sqrt(np.mean(np.sum((to_scan(found, order).apply(found[:, 2:4]) - model.apply(found[:, 2:4])) ** 2,
                                         axis=1))))
    node_px = model.apply(plane.forward(nodes))
    reachable = _inside(node_px, shape, 0.45 * spacing + radius + 2) & _within(node_px, found[:, :2], 0.25 * spacing)
    ticks_on = sum(len(_tick_points(f, nodes, plane)) for f in frames)
    return SheetFit(found, plane, step, placed.evidence, order, spread_of(found[:, :2], shape),
                    int(reachable.sum()) + ticks_on, apart, max(2.0, factor, APART * spacing),
                    lattice_order=placed.lattice.order)


def _tick_points(frame, nodes, plane) -> np.ndarray:
    """Grid coordinates of each grid line's tick on ``frame`` (a :class:`hamta.core.grid.frame.FrameLine`)."""
    axis = 1 - frame.axis
    g = np.empty((len(np.unique(nodes[:, axis])), 2))
    g[:, axis], g[:, frame.axis] = np.unique(nodes[:, axis]), frame.value
    return g[np.isfinite(plane.forward(g)).all(axis=1)]


def _ticks(source, frames, nodes, model, plane: Plane, step, radius, spacing, check) -> np.ndarray:
    """Rows (see :func:`_crossings`) of each tick found where a grid line meets a frame line: a short strip along
    the grid line (:data:`hamta.core.grid.frame.TICK` of a step each side of the frame) crossing a long one along
    the frame."""
    from .frame import TICK

    rows = []
    for k, frame in enumerate(frames):
        axis = 1 - frame.axis
        eps = 0.02 * step
        for g in _tick_points(frame, nodes, plane):
            check()
            along_line, along_frame = g.copy(), g.copy()
            along_line[frame.axis] += eps[frame.axis]
            along_frame[axis] += eps[axis]
            pts = plane.forward(np.array([g, along_line, along_frame]))
            if not np.isfinite(pts).all():
                continue
            px = model.apply(pts)
            tick, edge = px[1] - px[0], px[2] - px[0]
            tick, edge = tick / (np.hypot(*tick) + 1e-12), edge / (np.hypot(*edge) + 1e-12)
            one = model.apply(plane.forward(np.array([g, g + np.eye(2)[frame.axis] * step[frame.axis]])))
            length = TICK * float(np.hypot(*(one[1] - one[0])))
            got = crossing(source, px[0], [tick, edge], radius, along=(max(length, radius + 2), 0.45 * spacing))
            if got is not None:
                rows.append([*got.xy, *pts[0], *g, k, *edge, got.ink])
    rows = np.array(rows).reshape(-1, 10)
    inked = rows[:, 9] >= FAINT * np.median(rows[:, 9]) if len(rows) else np.zeros(0, bool)
    return rows[inked, :9]


def _on_frames(found, frames, plane: Plane) -> np.ndarray:
    """``found`` with each tick's coordinate across its frame (and its plane coordinates) the frame's value."""
    found = found.copy()
    for k, frame in enumerate(frames):
        on = found[:, 6] == k
        found[on, 4 + frame.axis] = frame.value
        found[on, 2:4] = plane.forward(found[on, 4:6])
    return found


def _frames_refined(frames, found, shape, plane: Plane):
    """Each frame line's value where the crossings found put its ticks: the median, over its ticks, of the value
    across the frame at the tick's scan px, through the model of all crossings."""
    from .frame import FrameLine

    ticks = found[:, 6] >= 0
    if not ticks.any() or len(found) < 4:
        return frames
    back = to_scan(found[:, [2, 3, 0, 1, 4, 5]], ordered(found, shape))  # scan px -> plane
    out = []
    for k, frame in enumerate(frames):
        on = found[:, 6] == k
        if on.sum() < 2:
            out.append(frame)
            continue
        g = plane.backward(back.apply(found[on, :2]))
        out.append(FrameLine(frame.axis, float(np.median(g[:, frame.axis])), frame.strength))
    return out


def _drawn_in(fit: SheetFit, planes) -> SheetFit:
    """``fit`` in the plane where an affine predicts the crossings' grid lines, each held out in turn, best (the
    projection the sheet is drawn in: its lines straight and evenly spaced); the lattice's where none is 10 %
    better. ``fit.plane_fits``: each plane's held-out RMS (scan px)."""
    from .crossings import lines_held_out

    def held_out(plane):
        xy = plane.forward(fit.crossings[:, 4:6])
        if not np.isfinite(xy).all() or len(xy) < 4:
            return math.inf, xy
        errors = lines_held_out(xy, fit.crossings[:, :2], fit.crossings[:, 4:6],
                                lambda s, d: LinearModel.fit("affine", s, d).apply, 3)[0]
        return float(np.sqrt(np.mean(np.sum(errors ** 2, axis=1)))), xy

    scored = {p.name: (p,) + held_out(p) for p in planes}
    fit.plane_fits = {name: rms for name, (_, rms, _) in scored.items()}
    best = min(scored.values(), key=lambda t: t[1])
    if best[1] < 0.9 * scored[fit.plane.name][1]:
        crossings = fit.crossings.copy()
        crossings[:, 2:4] = best[2]
        fit.crossings, fit.plane = crossings, best[0]
        fit.order = ordered(crossings)
    return fit


def _not_found(tried: List[Attempt], geographic: bool) -> str:
    seen = [a for a in tried if a.evidence is not None]
    if not seen:
        return ("No lattice of the hints' step can be placed on the sheet (its crossings would be closer than "
                f"{MIN_STEP_PX:g} px or more than {MAX_CROSSINGS}): check the hints' coordinates and the grid's step.")
    best = max(seen, key=lambda a: a.evidence.score)
    return (f"No printed grid was found where the hints put it: tried {len(tried)} lattices "
            f"(steps {', '.join(sorted({describe_pair(a.step, geographic) for a in tried}))}); the best, "
            f"{describe_pair(best.step, geographic)} in {best.plane}: {best.evidence.text()}. Check the hints' "
            "coordinates and the grid's step, or register the sheet onto a reference layer.")


def _lon_lat_box(hints, shape):
    """(west, south, east, north) degrees the sheet covers, from the hints by a similarity on longitudes shrunk by
    the cosine of their latitude (a first look: the planes need only their centre and span)."""
    lat0 = float(np.mean(hints[:, 3]))
    shrink = max(math.cos(math.radians(lat0)), 0.05)
    xy = hints[:, 2:] * [shrink, 1.0]
    model = _first_model(hints[:, :2], xy).inverse()  # scan px -> shrunk degrees
    h, w = shape
    edge = model.apply(np.array([[x, y] for x in np.linspace(0, w, 5) for y in np.linspace(0, h, 5)]))
    lon, lat = edge[:, 0] / shrink, np.clip(edge[:, 1], -89.9, 89.9)
    return float(lon.min()), float(lat.min()), float(lon.max()), float(lat.max())


def _first_model(px, xy) -> LinearModel:
    """Plane coordinates -> scan px from the hints: a similarity with a reflection (scan rows run down, northings
    up) from two hints or three along one line, an affine from three or more."""
    px, xy = np.asarray(px, float), np.asarray(xy, float)
    flip = np.diag([1.0, -1.0, 1.0])
    spread = np.linalg.svd(xy - xy.mean(axis=0), compute_uv=False)
    if len(xy) >= 3 and spread[1] > 0.05 * spread[0]:
        return LinearModel.fit("affine", xy, px)
    similarity = LinearModel.fit("similarity", xy * [1.0, -1.0], px)
    return LinearModel("affine", similarity.matrix @ flip)


def _factor(spacing: float, shape) -> int:
    """The line map's reduction: a step of at least 24 reduced px, at most 4000 px on the long side and at least
    256; the finest reduction the scan allows times a power of two (each made of the finest, :func:`_work`)."""
    finest = _finest(shape)
    coarsest = max(max(shape) / 256 / finest, 1.0)
    return finest * 2 ** int(math.floor(math.log2(min(max(spacing / (24 * finest), 1.0), coarsest))))


def _finest(shape) -> int:
    return max(1, int(np.ceil(max(shape) / 4000)))


def _work(source, works, factor: int) -> np.ndarray:
    """The line map reduced by ``factor`` (:meth:`LineSource.reduced`), the finest read once and the others
    averaged from it by 2 x 2 blocks."""
    if factor not in works:
        finest = _finest(source.shape)
        if factor == finest:
            works[factor] = source.reduced(factor)
        else:
            half = _work(source, works, factor // 2)
            h, w = half.shape[0] // 2 * 2, half.shape[1] // 2 * 2
            works[factor] = half[:h, :w].reshape(h // 2, 2, w // 2, 2).mean(axis=(1, 3))
    return works[factor]


def _nodes(model, shape, plane: Plane, step) -> np.ndarray:
    """Grid coordinates (n, 2) of the crossings ``model`` (plane -> scan px) puts on the sheet."""
    h, w = shape
    edge = np.array([[x, y] for x in np.linspace(0, w, 9) for y in np.linspace(0, h, 9)])
    g = plane.backward(model.inverse().apply(edge))
    g = g[np.isfinite(g).all(axis=1)]
    if not len(g):
        raise InputError("The hints put the sheet outside the plane's coordinates.")
    step = np.asarray(step, float)
    i0, i1 = math.floor(g[:, 0].min() / step[0]), math.ceil(g[:, 0].max() / step[0])
    j0, j1 = math.floor(g[:, 1].min() / step[1]), math.ceil(g[:, 1].max() / step[1])
    if (i1 - i0 + 1) * (j1 - j0 + 1) > MAX_CROSSINGS:
        raise InputError(f"The hints put {(i1 - i0 + 1) * (j1 - j0 + 1)} crossings of a {step[0]:g} x {step[1]:g} "
                         f"step on the sheet, more than {MAX_CROSSINGS}: check the hints' coordinates and the grid's "
                         "step.")
    ii, jj = np.meshgrid(np.arange(i0, i1 + 1), np.arange(j0, j1 + 1))
    nodes = np.column_stack([ii.ravel() * step[0], jj.ravel() * step[1]])
    return nodes[np.isfinite(plane.forward(nodes)).all(axis=1)]


def _grid_lines(nodes, step, plane: Plane, per_step: float):
    """(plane points along every grid line through ``nodes`` and one step beyond, ``per_step`` a step; each
    line's axis: 0 where grid x is constant, 1 where grid y is; each line's grid coordinate)."""
    n = max(int(np.ceil(per_step)), 4)
    step = np.asarray(step, float)
    lo, hi = nodes.min(axis=0) - step, nodes.max(axis=0) + step
    out, axes, values = [], [], []
    for axis in (0, 1):
        along = np.arange(lo[1 - axis], hi[1 - axis] + step[1 - axis] / n / 2, step[1 - axis] / n)
        for value in np.unique(nodes[:, axis]):
            g = np.empty((len(along), 2))
            g[:, axis], g[:, 1 - axis] = value, along
            xy = plane.forward(g)
            xy = xy[np.isfinite(xy).all(axis=1)]
            if len(xy) >= 2:
                out.append(xy)
                axes.append(axis)
                values.append(float(value))
    return out, axes, values


def _steps(model, nodes, plane: Plane, step) -> np.ndarray:
    """Scan px of one grid step along grid x and along grid y at the middle of ``nodes``."""
    mid = nodes[len(nodes) // 2]
    px = model.apply(plane.forward(np.array([mid, mid + [step[0], 0], mid + [0, step[1]]])))
    return np.array([px[1] - px[0], px[2] - px[0]])


def _spacing(model, nodes, plane: Plane, step) -> float:
    """The grid's step in scan px near the middle of ``nodes``."""
    s = _steps(model, nodes, plane, step)
    return float(min(np.hypot(*s[0]), np.hypot(*s[1])))


def _check_hints(hints, hint_xy, model, spacing) -> None:
    """Each hint within :data:`HINT_PX` of a step from where the lattice puts its coordinates, else the hint
    is named as the one that disagrees."""
    off = np.hypot(*(model.apply(hint_xy) - hints[:, :2]).T)
    for i in np.flatnonzero(off > HINT_PX * spacing):
        raise InputError(f"The printed grid found from the hints does not pass through hint {i + 1} ({hints[i, 2]:g}, "
                         f"{hints[i, 3]:g}): it puts those coordinates {off[i]:.0f} px away. Check that hint's "
                         "coordinates and place; if they are right, the grid is too faint here to be followed: "
                         "register the sheet onto a reference layer.")


def _found(source, nodes, model, plane: Plane, step, radius, spacing, check=lambda: None) -> np.ndarray:
    """Rows (scan x, y, plane x, y, grid x, y) of each crossing found within ``radius`` px of where ``model``
    (plane -> scan px) puts it, the two lines' directions there taken from the same model, whose lines hold at
    least :data:`FAINT` of the median crossing's ink (off the paper, noise peaks). ``check`` raises where the
    user cancelled."""
    eps = np.asarray(step, float) * 0.02
    rows = []
    for k, (gx, gy) in enumerate(nodes):
        if k % 64 == 0:
            check()
        pts = plane.forward(np.array([[gx, gy], [gx, gy + eps[1]], [gx + eps[0], gy]]))
        if not np.all(np.isfinite(pts)):
            continue
        px = model.apply(pts)
        dirs = [(px[1] - px[0]) / (np.hypot(*(px[1] - px[0])) + 1e-12),  # the line of constant grid x
                (px[2] - px[0]) / (np.hypot(*(px[2] - px[0])) + 1e-12)]  # and of constant grid y
        got = crossing(source, px[0], dirs, radius, along=0.45 * spacing)
        if got is not None:
            rows.append([*got.xy, *pts[0], gx, gy, got.ink])
    rows = np.array(rows).reshape(-1, 7)
    inked = rows[:, 6] >= FAINT * np.median(rows[:, 6]) if len(rows) else np.zeros(0, bool)
    return rows[inked, :6]


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
