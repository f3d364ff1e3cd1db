"""The crossings found on a sheet, judged as a whole: the model order the crossings support (leave-one-out),
each grid line predicted without it (the check that a line of the map's frame, a border or a road taken for
a grid line fails), and the crossings a robust fit leaves out. Coordinates: rows of scan x, y, plane x, y,
grid x, y (as :func:`hamta.core.grid.sheet.fit_sheet` finds them; the plane: :mod:`hamta.core.grid.planes`)."""
from __future__ import annotations

import math

import numpy as np

from ..estimation.models import PolynomialModel

MODELS = (("affine", 1, 3, 0.0), ("polynomial-2", 2, 12, 0.5), ("polynomial-3", 3, 30, 0.8))  # name, order, least
# crossings, least share of the sheet they must cover (a polynomial bends wildly beyond its points, and the whole
# sheet is warped through it)


def ordered(found, shape=None) -> int:
    """The model order with the smallest leave-one-out error (a higher order only when 10 % better, on enough
    crossings; for the sheet's model, ``shape`` given, covering enough of it: while the crossings are being
    found, the model need only reach the next ring)."""
    best, best_loo = 1, _loo(found, 1)
    spread = 1.0 if shape is None else spread_of(found[:, :2], shape)
    for _, order, least, cover in MODELS[1:]:
        if len(found) < least or spread < cover:
            break
        loo = _loo(found, order)
        if loo < 0.9 * best_loo:
            best, best_loo = order, loo
    return best


def to_scan(found, order: int) -> PolynomialModel:
    """The polynomial of ``order`` from plane coordinates to scan px fitted on ``found``."""
    return PolynomialModel.fit(order, found[:, 2:4], found[:, :2])


def _loo(found, order) -> float:
    """RMS (scan px) of each crossing predicted from its plane coordinates by a model fitted on the others."""
    if len(found) <= MODELS[order - 1][2]:
        return math.inf
    loo = to_scan(found, order).loo_residuals(found[:, 2:4], found[:, :2])
    return float(np.sqrt(np.nanmean(loo ** 2))) if np.isfinite(loo).any() else math.inf


def lines_held_out(src, dst, lines, predictor, least: int):
    """((n, 2) error of each point of ``dst`` predicted from ``src`` by ``predictor(src, dst)`` (a callable
    src -> dst) fitted without its grid line, {(axis, value): RMS of that line}): each line of constant grid x
    (``lines[:, 0]``) left out in turn, and each of constant grid y; a point's error is the larger of its
    two. Infinite errors and no lines where fewer than ``least`` points would be left."""
    errors, per_line = np.zeros((len(src), 2)), {}
    for axis in (0, 1):
        for value in np.unique(lines[:, axis]):
            on = lines[:, axis] == value
            if (~on).sum() < least:
                return np.full((len(src), 2), np.inf), {}
            e = predictor(src[~on], dst[~on])(src[on]) - dst[on]
            per_line[(axis, value)] = float(np.sqrt(np.mean(np.sum(e ** 2, axis=1))))
            worse = np.hypot(*e.T) > np.hypot(*errors[on].T)
            errors[np.flatnonzero(on)[worse]] = e[worse]
    return errors, per_line


def held_out_lines(found, order):
    """(RMS in scan px, (n, 2) error of each crossing, {(axis, value): RMS of that line}) of each crossing
    predicted from its plane coordinates by the polynomial of ``order`` fitted without its grid line (see
    :func:`lines_held_out`). A line taken on the sheet's frame or a border, shifted as a whole, fits with the
    others crossing by crossing but not as a line."""
    def predictor(src, dst):
        return PolynomialModel.fit(order, src, dst).apply

    errors, per_line = lines_held_out(found[:, 2:4], found[:, :2], found[:, 4:6], predictor, MODELS[order - 1][2])
    if not per_line:
        return math.inf, errors, {}
    return float(np.sqrt(np.mean(np.sum(errors ** 2, axis=1)))), errors, per_line


def without_stray_lines(found, order) -> np.ndarray:
    """``found`` without the grid lines that the others predict worst, one at a time, while one is beyond
    1.5 px and 3 times the median line."""
    while len(found) > 2 * MODELS[order - 1][2]:
        per_line = held_out_lines(found, order)[2]
        if not per_line:
            break
        (axis, value), worst = max(per_line.items(), key=lambda kv: kv[1])
        if worst <= max(1.5, 3.0 * float(np.median(list(per_line.values())))):
            break
        found = found[found[:, 4 + axis] != value]  # the keys' axis counts the grid columns (x 0, y 1)
    return found


def trimmed(found, order) -> np.ndarray:
    """``found`` without crossings whose residual is beyond 3 times the median (and 1.5 px), refitted until
    none is: a line of the map's content taken for a grid line."""
    while True:
        res = to_scan(found, order).residuals(found[:, 2:4], found[:, :2])
        keep = res <= max(1.5, 3.0 * float(np.median(res)))
        if keep.all() or keep.sum() < max(3, MODELS[order - 1][2] + 1):
            return found
        found = found[keep]


def spread_of(px, shape) -> float:
    """The share of the sheet the crossings' convex hull covers."""
    import cv2

    if len(px) < 3:
        return 0.0
    hull = cv2.convexHull(px.astype(np.float32))
    return float(cv2.contourArea(hull)) / (shape[0] * shape[1])
