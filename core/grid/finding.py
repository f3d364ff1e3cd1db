"""Every crossing of a placed lattice (:mod:`hamta.core.grid.placing`) and every tick on its frame, found where
it is printed (:func:`hamta.core.grid.lines.crossing`, sub-pixel), the model refitted on what was found and the
crossings looked for again, closer.

Coordinates: scan pixels (corner convention); grid coordinates in the sheet's CRS; plane coordinates.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List

import numpy as np

from .crossings import ordered, spread_of, to_scan, trimmed, without_stray_lines
from .evidence import Evidence
from .lines import crossing
from .placing import Attempt, Placed
from .planes import Plane

APART = 0.1  # of a step: how far the crossings' model may lie from the lattice of whole lines (placed on a line
# map reduced by up to a tenth of a step, and only affine or quadratic)


LOCAL_SHARE = 0.04  # of a step: how far from the lattice's place a crossing is looked for


PASSES = 3  # times the crossings are looked for again where those found put them


FAINT = 0.3  # of the median crossing's ink: fainter crossings are noise (off the paper, a gap in the lines)


@dataclass
class SheetFit:
    """What the sheet's grid gave: ``crossings`` (n, 6): scan x, y, plane x, y and grid x, y of each crossing
    found; the ``plane`` and ``step`` (along grid x, along grid y) of the lattice kept and its ``evidence``;
    ``order`` of the polynomial from the plane to the scan the crossings support; ``spread`` the share of the map
    they cover (of the scan where it is all map; blank margins and the scanner's bed left out); ``reachable`` the
    crossings the lattice puts where both their lines can be looked at, near those found; ``apart_px`` the RMS
    distance between the crossings' model and the lattice (``apart_limit_px`` what a sound sheet allows);
    ``tried`` every lattice tried; ``notes``."""

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


def find_crossings(source, plane: Plane, placed: Placed, monitor) -> SheetFit:
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
    return SheetFit(found, plane, step, placed.evidence, order, min(spread_of(found[:, :2], shape) / placed.map_share,
                                                                     1.0),
                    int(reachable.sum()) + ticks_on, apart, max(2.0, factor, APART * spacing),
                    lattice_order=placed.lattice.order)


def _tick_points(frame, nodes, plane) -> np.ndarray:
    """Grid coordinates of each grid line's tick on ``frame`` (a :class:`hamta.core.grid.frame.FrameLine`)."""
    axis = 1 - frame.axis
    g = np.empty((len(np.unique(nodes[:, axis])), 2))
    g[:, axis], g[:, frame.axis] = np.unique(nodes[:, axis]), frame.value
    return g[np.isfinite(plane.forward(g)).all(axis=1)]


def _ticks(source, frames, nodes, model, plane: Plane, step, radius, spacing, check) -> np.ndarray:
    """Rows (see :func:`find_crossings`) of each tick found where a grid line meets a frame line: a short strip along
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
