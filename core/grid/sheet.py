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
from .lines import crossing, line_map

HINT_PX = 0.15  # of the grid's spacing: how far from a crossing a hint may be placed
SNAPPED_PX = 1.5  # px: how far the first model from the hints found on the scan is expected to be off nearby
DEGREE_STEPS = (10, 5, 2, 1, 0.5, 1 / 3, 0.25, 1 / 6, 1 / 12, 1 / 24, 1 / 60)  # graticules: 10 degrees to 1'
METRE_STEPS = (100000, 50000, 20000, 10000, 5000, 2000, 1000, 500, 200, 100)  # national grids
MAX_CROSSINGS = 4000
MIN_FIT = 6  # crossings found before the model is refitted on them (and one taken for a wrong line can be told)
MODELS = (("affine", 1, 3, 0.0), ("polynomial-2", 2, 12, 0.5), ("polynomial-3", 3, 30, 0.8))  # name, order, least
# crossings, least share of the sheet they must cover (a polynomial bends wildly beyond its points, and the whole
# sheet is warped through it)


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

    def to_crs(self, px: np.ndarray) -> np.ndarray:
        """Scan px (n, 2) -> ``crs`` coordinates, through the model fitted on every crossing found."""
        return _apply(_fit(self.gcps[:, :2], self.gcps[:, 2:4], self.order), px)


def fit_sheet(grey: np.ndarray, hints: Sequence, crs: str, grid_crs: Optional[str] = None,
              step: Optional[float] = None, tolerance_px: float = 2.0) -> SheetFit:
    """Find the sheet's printed crossings from ``hints`` (rows of scan x, y, grid x, y) and fit the model
    (see the module docstring). ``grey``: the scan (2-D). Raises :class:`InputError` for hints that do not
    fit a grid, :class:`InsufficientMatchesError` when too few crossings are found."""
    from pyproj import CRS, Transformer

    hints = np.asarray(hints, float).reshape(-1, 4)
    if len(hints) < 2:
        raise InputError("Georeferencing by the grid needs at least two crossings placed with their coordinates "
                         f"(got {len(hints)}), until the sheet's labels are read.")
    grid_crs = grid_crs or crs
    to_crs = Transformer.from_crs(CRS.from_user_input(grid_crs), CRS.from_user_input(crs), always_xy=True)
    from_crs = Transformer.from_crs(CRS.from_user_input(crs), CRS.from_user_input(grid_crs), always_xy=True)
    geographic = CRS.from_user_input(grid_crs).is_geographic
    step = step or grid_step(hints[:, 2:], DEGREE_STEPS if geographic else METRE_STEPS)
    lines = line_map(grey)
    hint_xy = np.column_stack(to_crs.transform(hints[:, 2], hints[:, 3]))
    forward, backward = _first_model(hints[:, :2], hint_xy, CRS.from_user_input(crs).is_geographic)
    nodes = _nodes(forward, grey.shape, from_crs, step)
    spacing = _spacing(backward, nodes, to_crs, step)
    ring = _rings(nodes, hints[:, 2:], step)
    found, order, residual = np.zeros((0, 6)), 1, HINT_PX * spacing
    for k in range(int(ring.max()) + 1):
        radius = float(np.clip(2.5 * residual + 2.0, 3.0, 0.3 * spacing)) if k else HINT_PX * spacing
        found = np.vstack([found, _found(lines, nodes[ring == k], backward, to_crs, step, radius, spacing, found)])
        if k == 0:  # the hints, where the lines cross near them: the first model again, on where they were found
            snapped = hints[:, :2].copy()
            for row in found:
                snapped[np.argmin(np.abs(hints[:, 2:] - row[4:6]).sum(axis=1))] = row[:2]
            forward, backward = _first_model(snapped, hint_xy, CRS.from_user_input(crs).is_geographic)
            residual = SNAPPED_PX
        if len(found) < MIN_FIT:  # the first model until enough crossings to tell a wrong one
            continue
        found = _consistent(found, step)
        found = _trimmed(found, min(order, _order_by_count(len(found))))
        order = _order(found)
        forward, backward = _fit(found[:, :2], found[:, 2:4], order), _fit(found[:, 2:4], found[:, :2], order)
        residual = _residual(found, backward)
    if len(found) < 3:
        raise InsufficientMatchesError(f"Only {len(found)} crossings of the printed grid were found near where the "
                                       "hints put them: check the hints' coordinates and the grid's step.",
                                       len(found), 6)
    found = _trimmed(found, order)
    order = _order(found, grey.shape)
    found = _without_stray_lines(found, order)
    order = _order(found, grey.shape)
    loo = _held_out_lines(found, order)[0]
    spread = _spread(found[:, :2], grey.shape)
    notes = [f"{len(found)} crossings of the printed grid found (step {step:g}); each grid line predicted from the "
             f"others: {loo:.2f} px RMS with "
             f"the {MODELS[order - 1][0]} model; they cover {spread:.0%} of the sheet"]
    backward = _fit(found[:, 2:4], found[:, :2], order)
    off = np.hypot(*(_apply(backward, hint_xy) - hints[:, :2]).T)
    far = [i for i in range(len(hints)) if off[i] > HINT_PX * _spacing(backward, nodes, to_crs, step)]
    notes += [f"hint {i + 1} ({hints[i, 2]:g}, {hints[i, 3]:g}) is {off[i]:.0f} px from where the grid found puts "
              "those coordinates: the hints and the printed grid disagree" for i in far]
    verified = len(found) >= 6 and loo <= tolerance_px and spread >= 0.25 and not far
    return SheetFit(found, MODELS[order - 1][0], order, loo, verified, step, notes)


def grid_step(coords: np.ndarray, steps: Sequence[float]) -> float:
    """The largest of ``steps`` that every coordinate of ``coords`` is a multiple of (to 1 % of the step)."""
    for s in steps:
        ratio = np.asarray(coords, float) / s
        if np.all(np.abs(ratio - np.round(ratio)) <= 0.01):
            return float(s)
    raise InputError("The hints' coordinates are not on a grid of a usual step (degrees: 10 to 1'; metres: 100 km "
                     "to 100 m): give the grid's step.")


def _nodes(forward, shape, from_crs, step):
    """Grid coordinates (n, 2) of the crossings the model ``forward`` (scan px -> crs) puts on the sheet."""
    h, w = shape
    edge = np.array([[x, y] for x in np.linspace(0, w, 9) for y in np.linspace(0, h, 9)])
    gx, gy = from_crs.transform(*_apply(forward, edge).T)
    i0, i1 = math.floor(np.nanmin(gx) / step), math.ceil(np.nanmax(gx) / step)
    j0, j1 = math.floor(np.nanmin(gy) / step), math.ceil(np.nanmax(gy) / step)
    if (i1 - i0 + 1) * (j1 - j0 + 1) > MAX_CROSSINGS:
        raise InputError(f"The hints put {(i1 - i0 + 1) * (j1 - j0 + 1)} crossings of a {step:g} step on the sheet, "
                         f"more than {MAX_CROSSINGS}: check the hints' coordinates and the grid's step.")
    ii, jj = np.meshgrid(np.arange(i0, i1 + 1), np.arange(j0, j1 + 1))
    return np.column_stack([ii.ravel() * step, jj.ravel() * step])


def _first_model(px, xy, geographic: bool):
    """(scan px -> crs, crs -> scan px) from the hints: a similarity from two (on longitudes shrunk by the
    cosine of the latitude where the crs is geographic, so that a degree is as long both ways), an affine
    from more."""
    if len(px) > 2:
        return _fit(px, xy, 1), _fit(xy, px, 1)
    shrink = math.cos(math.radians(float(np.mean(xy[:, 1])))) if geographic else 1.0
    squeeze = np.diag([shrink, 1.0])
    forward, backward = _fit(px, xy @ squeeze, 1, True), _fit(xy @ squeeze, px, 1, True)
    forward["m"] = forward["m"] / np.array([shrink, 1.0])
    backward["squeeze"] = shrink
    return forward, backward


def _rings(nodes, hint_grid, step) -> np.ndarray:
    """Each node's ring around the nearest hint: the grid steps to it, the larger of the two axes."""
    d = np.abs(nodes[:, None, :] - hint_grid[None, :, :]) / step
    return np.round(d.max(axis=2).min(axis=1)).astype(int)


def _order_by_count(n: int) -> int:
    """The highest order that ``n`` crossings can fit with some to spare."""
    return max(order for _, order, least, _ in MODELS if n > least or order == 1)


def _residual(found, backward) -> float:
    """The typical distance (scan px, a median: robust to a crossing taken on a wrong line) of the crossings
    found from the model fitted on them."""
    return float(1.4826 * np.median(np.hypot(*(_apply(backward, found[:, 2:4]) - found[:, :2]).T)))


def _spacing(backward, nodes, to_crs, step) -> float:
    """The grid's step in scan px near the middle of ``nodes``."""
    mid = nodes[len(nodes) // 2]
    pts = np.column_stack(to_crs.transform([mid[0], mid[0] + step, mid[0]], [mid[1], mid[1], mid[1] + step]))
    px = _apply(backward, pts)
    return float(min(np.hypot(*(px[1] - px[0])), np.hypot(*(px[2] - px[0]))))


def _found(lines, nodes, backward, to_crs, step, radius, spacing, known=None) -> np.ndarray:
    """Rows (scan x, y, crs x, y, grid x, y) of each crossing found near where it is predicted: from the
    crossings already ``known`` within two steps (a local affine: a curved graticule bends little there), else
    from ``backward`` (crs -> scan px); the two lines' directions there taken from the same model."""
    eps = step * 0.02
    rows = []
    for gx, gy in nodes:
        pts = np.column_stack(to_crs.transform([gx, gx, gx + eps], [gy, gy + eps, gy]))
        if not np.all(np.isfinite(pts)):
            continue
        px = _local(known, gx, gy, step, pts)
        local = px is not None
        if not local:
            px = _apply(backward, pts)
        dirs = [(px[1] - px[0]) / (np.hypot(*(px[1] - px[0])) + 1e-12),  # the line of constant grid x
                (px[2] - px[0]) / (np.hypot(*(px[2] - px[0])) + 1e-12)]  # and of constant grid y
        got = crossing(lines, px[0], dirs, min(radius, LOCAL_RADIUS_PX) if local else radius, along=0.45 * spacing)
        if got is not None:
            rows.append([*got.xy, *pts[0], gx, gy])
    return np.array(rows).reshape(-1, 6)


LOCAL_RADIUS_PX = 4.0  # search radius where neighbours predict a crossing


def _consistent(found, step) -> np.ndarray:
    """``found`` without the crossings that the local affine of their neighbours (within two steps, the
    crossing itself left out) puts more than :data:`LOCAL_AGREE` of a step away: a map line taken for a
    grid line; crossings without enough neighbours are kept."""
    keep = np.ones(len(found), bool)
    spacing = _typical_step_px(found, step)
    for i, row in enumerate(found):
        others = np.delete(found, i, axis=0)
        px = _local(others, row[4], row[5], step, row[None, 2:4])
        if px is not None and np.hypot(*(px[0] - row[:2])) > LOCAL_AGREE * spacing:
            keep[i] = False
    return found[keep]


def _typical_step_px(found, step) -> float:
    """The median distance in scan px between crossings one step apart."""
    d = []
    for row in found:
        near = found[(np.abs(found[:, 4] - row[4]) + np.abs(found[:, 5] - row[5]) - step) ** 2 < (0.01 * step) ** 2]
        d += list(np.hypot(*(near[:, :2] - row[:2]).T))
    return float(np.median(d)) if d else math.inf


LOCAL_AGREE = 0.04  # of a step: how far a crossing may lie from where its neighbours put it (2 px at 50 px)


def _local(known, gx, gy, step, pts):
    """``pts`` (crs) in scan px through an affine fitted on the ``known`` crossings within two steps of
    (gx, gy), where at least four of them span both directions; else None."""
    if known is None or len(known) < 4:
        return None
    near = known[(np.abs(known[:, 4] - gx) <= 2.01 * step) & (np.abs(known[:, 5] - gy) <= 2.01 * step)]
    if len(near) < 4 or np.ptp(near[:, 4]) < step * 0.5 or np.ptp(near[:, 5]) < step * 0.5:
        return None
    return _apply(_fit(near[:, 2:4], near[:, :2], 1), pts)


def _order(found, shape=None) -> int:
    """The model order with the smallest leave-one-out error (a higher order only when 10 % better, on enough
    crossings; for the sheet's model, ``shape`` given, covering enough of it: while the crossings are being
    found, the model need only reach the next ring)."""
    best, best_loo = 1, _loo(found, 1)
    spread = 1.0 if shape is None else _spread(found[:, :2], shape)
    for _, order, least, cover in MODELS[1:]:
        if len(found) < least or spread < cover:
            break
        loo = _loo(found, order)
        if loo < 0.9 * best_loo:
            best, best_loo = order, loo
    return best


def _loo(found, order) -> float:
    """RMS (scan px) of each crossing predicted from its crs coordinates by a model fitted on the others."""
    n = len(found)
    if n <= MODELS[order - 1][2]:
        return math.inf
    errors = []
    for i in range(n):
        keep = np.arange(n) != i
        coef = _fit(found[keep, 2:4], found[keep, :2], order)
        errors.append(np.hypot(*(_apply(coef, found[i:i + 1, 2:4])[0] - found[i, :2])))
    return float(np.sqrt(np.mean(np.square(errors))))


def _held_out_lines(found, order):
    """(RMS in scan px, {line: RMS}) of each crossing predicted by the model fitted without its grid line:
    each line of constant grid x and of constant grid y left out in turn. A line taken on the sheet's frame
    or a border, shifted as a whole, fits with the others crossing by crossing but not as a line."""
    errors, per_line = [], {}
    for axis in (4, 5):
        for value in np.unique(found[:, axis]):
            on = found[:, axis] == value
            if (~on).sum() <= MODELS[order - 1][2]:
                return math.inf, {}
            coef = _fit(found[~on, 2:4], found[~on, :2], order)
            e = np.hypot(*(_apply(coef, found[on, 2:4]) - found[on, :2]).T)
            errors += list(e)
            per_line[(axis, value)] = float(np.sqrt(np.mean(e ** 2)))
    return float(np.sqrt(np.mean(np.square(errors)))), per_line


def _without_stray_lines(found, order) -> np.ndarray:
    """``found`` without the grid lines that the others predict worst, one at a time, while one is beyond
    1.5 px and 3 times the median line."""
    while len(found) > 2 * MODELS[order - 1][2]:
        _, per_line = _held_out_lines(found, order)
        if not per_line:
            break
        (axis, value), worst = max(per_line.items(), key=lambda kv: kv[1])
        if worst <= max(1.5, 3.0 * float(np.median(list(per_line.values())))):
            break
        found = found[found[:, axis] != value]
    return found


def _trimmed(found, order) -> np.ndarray:
    """``found`` without crossings whose residual is beyond 3 times the median (and 1.5 px): a line of the
    map's content taken for a grid line."""
    coef = _fit(found[:, 2:4], found[:, :2], order)
    res = np.hypot(*(_apply(coef, found[:, 2:4]) - found[:, :2]).T)
    keep = res <= max(1.5, 3.0 * float(np.median(res)))
    return found[keep] if keep.sum() >= 3 else found


def _spread(px, shape) -> float:
    """The share of the sheet the crossings' convex hull covers."""
    import cv2

    if len(px) < 3:
        return 0.0
    hull = cv2.convexHull(px.astype(np.float32))
    return float(cv2.contourArea(hull)) / (shape[0] * shape[1])


def _terms(xy: np.ndarray, order: int) -> np.ndarray:
    x, y = xy[:, 0], xy[:, 1]
    return np.column_stack([x ** (i - j) * y ** j for i in range(order + 1) for j in range(i + 1)])


def _fit(src, dst, order, similarity=False) -> dict:
    """Polynomial ``src`` -> ``dst`` of ``order`` (on normalised coordinates); a similarity (two points)."""
    src, dst = np.asarray(src, float), np.asarray(dst, float)
    centre = src.mean(axis=0)
    scale = max(float(np.abs(src - centre).max()), 1e-9)
    u = (src - centre) / scale
    if similarity:  # with a reflection: scan rows run down, map northings up
        a = np.column_stack([u[:, 0], u[:, 1], np.ones(len(u)), np.zeros(len(u))])
        b = np.column_stack([-u[:, 1], u[:, 0], np.zeros(len(u)), np.ones(len(u))])
        p, q, tx, ty = np.linalg.lstsq(np.vstack([a, b]), np.concatenate([dst[:, 0], dst[:, 1]]), rcond=None)[0]
        m = np.array([[tx, ty], [p, q], [q, -p]])
    else:
        m = np.linalg.lstsq(_terms(u, order), dst, rcond=None)[0]
    return {"centre": centre, "scale": scale, "m": m, "order": order}


def _apply(coef: dict, xy) -> np.ndarray:
    xy = np.asarray(xy, float)
    if "squeeze" in coef:  # a model fitted on longitudes shrunk by this factor (see _first_model)
        xy = xy * np.array([coef["squeeze"], 1.0])
    u = (xy - coef["centre"]) / coef["scale"]
    return _terms(u, coef["order"]) @ coef["m"]
