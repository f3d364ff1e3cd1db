"""A lattice of the sheet's grid placed on the scan from the hints, in one plane: its crossings (grid coordinates),
the line map it is judged on (reduced so that a step spans at least :data:`MIN_STEP_PX` of it) and the evidence
that it is printed (:mod:`hamta.core.grid.evidence`).

Coordinates: scan pixels (corner convention); grid coordinates in the sheet's CRS; plane coordinates (metres of
the plane, :mod:`hamta.core.grid.planes`).
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..errors import InputError
from ..estimation.models import LinearModel
from .evidence import CHANCE, Evidence, evidence
from .frame import crossing_arms, find_frames, node_pieces, tick_pieces
from .lattice import fit_lattice, mean_ink, on_map, points_per_step
from .planes import Plane
from .steps import describe_pair

MAX_CROSSINGS = 4000


MIN_STEP_PX = 24.0  # a printed grid's crossings are at least this far apart on a scan (its evidence is judged on a
# line map with 24 px a step at least)


def few_lines(source, plane: Plane, hints, step) -> tuple:
    """Per grid axis, whether a lattice of ``step`` puts fewer than two of its lines on the sheet (a step the hints'
    coordinates fit that is wider than the sheet: two hints on one line fit every step dividing it)."""
    hint_xy = plane.forward(hints[:, 2:])
    try:
        nodes = _nodes(first_model(hints[:, :2], hint_xy), source.shape, plane, step)
    except InputError:
        return False, False
    return tuple(len(np.unique(nodes[:, a])) < 4 for a in (0, 1))  # the nodes reach a step beyond the sheet


def too_fine(source, plane: Plane, hints, step) -> bool:
    """Whether a lattice of ``step`` would put crossings closer than :data:`MIN_STEP_PX` (or too many)."""
    return _started(source, plane, hints, step) is None


def _started(source, plane: Plane, hints, step):
    """(the hints' first model, the crossings it puts on the sheet, their spacing in scan px) of the lattice of
    ``step``, or None where the hints leave the plane, or the crossings would be too many or closer than
    :data:`MIN_STEP_PX`."""
    hint_xy = plane.forward(hints[:, 2:])
    if not np.isfinite(hint_xy).all():
        return None
    start = first_model(hints[:, :2], hint_xy)
    try:
        nodes = _nodes(start, source.shape, plane, step)
    except InputError:
        return None
    spacing = _spacing(start, nodes, plane, step)
    return (start, nodes, spacing) if spacing >= MIN_STEP_PX else None


@dataclass(frozen=True)
class Placed:
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
    map_share: float = 1.0  # the share of the scan the map covers (the rest blank paper: lattice.on_map)


def place_lattice(source, works, plane: Plane, hints, step, bend: bool = False, threshold: float = CHANCE
             ) -> Optional[Placed]:
    """The lattice of ``step`` (along grid x, along grid y) in ``plane`` from the hints' first model (``bend``:
    second-order where that finds more ink), or None where its crossings would be too close or too many to be a
    printed grid. ``works``: the reduced line maps computed so far, by reduction."""
    started = _started(source, plane, hints, step)
    if started is None:
        return None
    start, nodes, spacing = started
    factor = _factor(spacing, source.shape)
    work = _work(source, works, factor)
    lines, axes, values = _grid_lines(nodes, step, plane, spacing / factor)
    if not lines:
        return None
    arms = crossing_arms(nodes, step, plane)
    mask = on_map(work, factor, arms, start, spacing)
    lattice = fit_lattice(work, factor, lines, start, spacing, bend, arms, mask)
    steps = _steps(lattice.model, nodes, plane, step)
    frames = find_frames(mean_ink(work, factor, outside=math.nan), lattice.model, plane, nodes, step)
    found = evidence(work, factor, lines, axes, lattice, steps, values,
                     node_pieces(nodes, step, plane) + tick_pieces(frames, nodes, step, plane), mask)
    if found is None:
        return None
    found = dataclasses.replace(found, threshold=threshold)
    return Placed(nodes, lattice, found, float(min(np.hypot(*steps.T))), factor, tuple(step), tuple(frames), steps,
                   1.0 if mask is None else max(float(mask.mean()), 1e-3))


def first_model(px, xy) -> LinearModel:
    """Plane coordinates -> scan px from the hints: a similarity with a reflection (scan rows run down, northings
    up), fitted by least squares; an affine from four hints or more that do not lie along one line (three fix an
    affine exactly: a hint placed a few px off, a step or two from the others, would shear the lattice by as many
    px again a few steps away, where a similarity holds the scan's own shape)."""
    px, xy = np.asarray(px, float), np.asarray(xy, float)
    flip = np.diag([1.0, -1.0, 1.0])
    spread = np.linalg.svd(xy - xy.mean(axis=0), compute_uv=False)
    if len(xy) >= 4 and spread[1] > 0.05 * spread[0]:
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
    """(plane points along every grid line through ``nodes`` and a step and a half beyond, from half a step
    between crossings, :func:`hamta.core.grid.lattice.points_per_step` of them a step, so that each step's points
    are centred on a crossing; each line's axis: 0 where grid x is constant, 1 where grid y is; each line's grid
    coordinate)."""
    n = points_per_step(per_step)
    step = np.asarray(step, float)
    lo, hi = nodes.min(axis=0) - 1.5 * step, nodes.max(axis=0) + 1.5 * step
    out, axes, values = [], [], []
    for axis in (0, 1):
        along = lo[1 - axis] + np.arange(int(round((hi - lo)[1 - axis] / step[1 - axis])) * n + 1) * step[1 - axis] / n
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
