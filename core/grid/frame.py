"""The sheet's frame (its neatline) and the ticks printed on it.

Many sheets print few grid lines, or none, across their face: their coordinates are ticks on the neatline, a
short stroke where each grid line meets the frame. A neatline of a chart or a map series is a line of constant
coordinate (a parallel, a meridian, a grid line at the sheet's corner), so it is looked for as one: the ink along
the lines of constant grid y (constant x) placed by the lattice's model, at every small fraction of a step over
the sheet, has a peak where a long line is printed; the peaks that are not the lattice's own lines and stand
out of that profile (robustly: its median and spread) are the frame's candidates. A grid line's tick is the
piece of it within :data:`TICK` of a step of a frame line; it is evidence of the line (see
:func:`hamta.core.grid.lattice.evidence`) and, where it meets the frame, a crossing
(:func:`hamta.core.grid.sheet.fit_sheet`): its coordinate along the frame is the grid line's, across it the
frame's (estimated from its ticks).

Coordinates: grid coordinates of the sheet's CRS; plane coordinates; scan px (corner convention).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import List

import numpy as np

FINE = 40  # profile samples per step
TICK = 0.06  # of a step: the half-length of the piece of a grid line that is its tick (ticks: 1-6 % of a step)
STANDS = 6.0  # robust deviations above the profile's median a frame line stands (a long line, printed whole)
SIDE_SHARE = 0.3  # of the sheet's span of a coordinate: how near its end a frame line lies


@dataclass(frozen=True)
class FrameLine:
    """A frame line: ``axis`` the coordinate it keeps constant (0: grid x, a left or right frame; 1: grid y, top
    or bottom), its ``value`` (grid units) and how far it stands out of the profile (``strength``)."""

    axis: int
    value: float
    strength: float


def find_frames(ink, model, plane, nodes, step) -> List[FrameLine]:
    """The frame lines the line map shows (see the module docstring): ``ink`` (plane-to-scan px -> mean line map,
    :func:`hamta.core.grid.lattice._ink` with NaN outside), ``model`` the lattice (plane -> scan px), ``nodes`` the
    lattice's crossings (grid coordinates), ``step`` along grid x and y."""
    step = np.asarray(step, float)
    lo, hi = nodes.min(axis=0) - step, nodes.max(axis=0) + step
    out = []
    for axis in (0, 1):
        values = np.arange(lo[axis], hi[axis] + step[axis] / FINE / 2, step[axis] / FINE)
        along = np.linspace(lo[1 - axis], hi[1 - axis], 64)
        profile = np.array([_line_ink(ink, model, plane, axis, v, along) for v in values])
        ok = np.isfinite(profile)
        if ok.sum() < FINE:
            continue
        base = float(np.median(profile[ok]))
        spread = float(np.median(np.abs(profile[ok] - base))) * 1.4826 + 1e-9
        z = np.where(ok, (profile - base) / spread, -np.inf)
        on_lattice = np.abs(values / step[axis] - np.round(values / step[axis])) < 0.05
        span = values[ok][-1] - values[ok][0]
        for end, near in ((0, values <= values[ok][0] + SIDE_SHARE * span),
                          (1, values >= values[ok][-1] - SIDE_SHARE * span)):
            peaks = [i for i in np.flatnonzero(near & ~on_lattice & (z >= STANDS))
                     if z[i] >= z[max(i - 1, 0)] and z[i] >= z[min(i + 1, len(z) - 1)]]
            if peaks:
                best = max(peaks, key=lambda i: z[i])
                out.append(FrameLine(axis, float(_peak(values, profile, best)), float(z[best])))
    return out


def _line_ink(ink, model, plane, axis: int, value: float, along: np.ndarray) -> float:
    g = np.empty((len(along), 2))
    g[:, axis], g[:, 1 - axis] = value, along
    xy = plane.forward(g)
    xy = xy[np.isfinite(xy).all(axis=1)]
    return ink(model.apply(xy)) if len(xy) >= 2 else np.nan


def _peak(values, profile, i) -> float:
    """The value at the profile's peak ``i``, to a fraction of a sample."""
    if 0 < i < len(profile) - 1 and np.isfinite(profile[i - 1:i + 2]).all():
        left, mid, right = profile[i - 1], profile[i], profile[i + 1]
        denom = left - 2 * mid + right
        if denom < 0:
            return values[i] + 0.5 * (left - right) / denom * (values[1] - values[0])
    return values[i]


def tick_pieces(frames: List[FrameLine], nodes, step, plane):
    """[(axis of the grid line, its value, plane points along its tick)] of every grid line through ``nodes`` on
    each frame line of the other family."""
    step = np.asarray(step, float)
    out = []
    for frame in frames:
        axis = 1 - frame.axis  # the grid lines that meet this frame keep the other coordinate constant
        half = TICK * step[frame.axis]
        along = np.linspace(frame.value - half, frame.value + half, 9)
        for v in np.unique(nodes[:, axis]):
            g = np.empty((len(along), 2))
            g[:, axis], g[:, frame.axis] = v, along
            xy = plane.forward(g)
            if np.isfinite(xy).all():
                out.append((axis, float(v), xy))
    return out


NODE_SHARE = 0.15  # of a step: the piece of a grid line each side of a crossing that a cross inks (arms 3-25 %)


def crossing_arms(nodes, step, plane) -> np.ndarray:
    """Plane points (n, 14, 2) of both lines' pieces around each of ``nodes`` (grid coordinates; those the plane
    does not map are left out): what a grid printed as crosses inks, and full lines too."""
    step = np.asarray(step, float)
    offsets = np.linspace(-NODE_SHARE, NODE_SHARE, 7)
    arms = np.concatenate([np.column_stack([offsets * step[0], np.zeros(7)]),
                           np.column_stack([np.zeros(7), offsets * step[1]])])
    xy = plane.forward((nodes[:, None, :] + arms[None]).reshape(-1, 2)).reshape(len(nodes), len(arms), 2)
    return xy[np.isfinite(xy).all(axis=(1, 2))]


def node_pieces(nodes, step, plane):
    """[(axis, value, plane points)] of each grid line through ``nodes``: its pieces around every crossing on it, as
    one set (a grid printed as crosses, or dashed lines, inks those)."""
    step = np.asarray(step, float)
    out = []
    for axis in (0, 1):
        other = np.unique(nodes[:, 1 - axis])
        offsets = np.linspace(-NODE_SHARE, NODE_SHARE, 7) * step[1 - axis]
        for v in np.unique(nodes[:, axis]):
            g = np.empty((len(other) * len(offsets), 2))
            g[:, axis] = v
            g[:, 1 - axis] = (other[:, None] + offsets[None, :]).ravel()
            xy = plane.forward(g)
            xy = xy[np.isfinite(xy).all(axis=1)]
            if len(xy) >= 2:
                out.append((axis, float(v), xy))
    return out
