"""The printed lattice as a whole: every grid line of the sheet placed at once on the scan's line map.

A crossing alone is easily confused with a road or a border near it; a lattice of long lines is not. The
lines of constant grid coordinate (sampled densely in the output CRS) are mapped to the scan by a model
(affine, then a second-order polynomial where the projection bends them) whose parameters maximise the
mean line map along all of them, from the hints' first model, on a line map blurred less and less. How
much more ink each family of lines finds than the same lines moved by part of a step (:func:`contrast`)
says whether a grid of that step is printed there at all.

Pixels: the scan's (corner convention); the reduced line map's pixel (i, j) covers ``factor`` scan px from
(j * factor, i * factor).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .polynomial import apply_poly, poly_terms

BLURS = (0.15, 0.05, 0.0)  # of the grid's step: the line map's blur at each stage (a wide basin first); each
# stage's lattice is then refined on the sharp map, and the one that finds most ink there is kept
REACH = 0.3  # of a step: how far the lattice may move from the hints' model (a whole step finds as much ink)
BENT_GAIN = 1.02  # a second-order lattice is kept when it finds this much more ink than the affine


@dataclass(frozen=True)
class Lattice:
    """``coef``: the model output-CRS coordinates -> scan px (see :func:`hamta.core.grid.polynomial.apply_poly`);
    ``ink``: the mean line map along its lines; ``order`` 1 or 2."""

    coef: dict
    ink: float
    order: int


def fit_lattice(work: np.ndarray, factor: int, lines, start: dict, spacing_px: float) -> Lattice:
    """The lattice model from ``start`` (a model output CRS -> scan px): ``lines`` is a list of (n, 2) arrays of
    output-CRS points along each grid line; ``spacing_px`` the grid's step on the scan."""
    import cv2
    from scipy.optimize import minimize


    pts = np.vstack(lines)
    centre = pts.mean(axis=0)
    scale = max(float(np.abs(pts - centre).max()), 1e-9)
    u = (pts - centre) / scale
    target = apply_poly(start, pts)
    design = {1: poly_terms(u, 1), 2: poly_terms(u, 2)}
    m = np.linalg.lstsq(design[1], target, rcond=None)[0]
    step_work = spacing_px / factor
    reach = REACH * spacing_px  # each parameter moves the lattice's edge by as many px: never a whole step
    bounds = [(v - reach, v + reach) for v in m.ravel()]

    def climb(m, image, move):
        ink = _ink(image, factor)
        start = np.clip(m.ravel(), [lo for lo, _ in bounds], [hi for _, hi in bounds])
        res = minimize(lambda v: -ink(design[1] @ v.reshape(-1, 2)), start, method="Powell", bounds=bounds,
                       options={"xtol": 0.02 * factor, "ftol": 1e-5, "direc": np.eye(m.size) * move})
        return res.x.reshape(-1, 2)

    def similar(m, v):  # m moved by a shift, a scale and a turn about the lattice's centre (scan px)
        tx, ty, grow, turn = v
        out = m.copy()
        out[0] += (tx, ty)
        for k in (1, 2):
            out[k] = m[k] * (1 + grow) + turn * np.array([-m[k][1], m[k][0]])
        return out

    def climb_similar(m, image, move):  # four parameters where the line map is blurred: a steadier basin
        ink = _ink(image, factor)
        size = max(float(np.hypot(*m[1])), float(np.hypot(*m[2])), 1e-9)
        res = minimize(lambda v: -ink(design[1] @ similar(m, v)), np.zeros(4), method="Powell",
                       bounds=[(-reach, reach)] * 2 + [(-reach / size, reach / size)] * 2,
                       options={"xtol": 1e-4, "ftol": 1e-5, "direc": np.diag([move, move, move / size, move / size])})
        return similar(m, res.x)

    fine = cv2.GaussianBlur(work, (0, 0), 0.7)
    ink = _ink(fine, factor)
    tries, current = [climb(m, fine, factor * 0.5)], m  # from the hints' model as it is, and from a wide basin
    for blur in BLURS[:-1]:
        sigma = blur * step_work
        current = climb_similar(current, cv2.GaussianBlur(work, (0, 0), sigma), sigma * factor)
        tries.append(climb(current, fine, factor * 0.5))
    m = max(tries, key=lambda t: ink(design[1] @ t))
    best = Lattice(_coef(centre, scale, m, 1), ink(design[1] @ m), 1)
    m2 = np.vstack([m, np.zeros((3, 2))])
    bounds = [(v - reach, v + reach) for v in m2.ravel()]
    res = minimize(lambda v: -ink(design[2] @ v.reshape(-1, 2)), m2.ravel(), method="Powell", bounds=bounds,
                   options={"xtol": 0.02 * factor, "ftol": 1e-5, "direc": np.eye(m2.size) * factor})
    if -res.fun > BENT_GAIN * best.ink:
        best = Lattice(_coef(centre, scale, res.x.reshape(-1, 2), 2), -float(res.fun), 2)
    return best


def contrast(work: np.ndarray, factor: int, lines, axes, lattice: Lattice, steps: np.ndarray) -> float:
    """How many times more ink ``lattice``'s lines find on ``work`` than the same lines moved across
    themselves by a quarter, a half and three quarters of a step, for each family of lines (``axes``: 0 for
    a line of constant grid x, 1 for constant grid y; ``steps``: scan px of one grid step along each grid
    axis) apart: the smaller of the two families' worst ratio. A lattice at twice the printed step (a hint's
    coordinates one step off) finds as much ink half a step over, and fails here."""

    ink = _ink(work, factor)
    ratios = []
    for axis in (0, 1):
        family = [line for line, a in zip(lines, axes) if a == axis]
        if not family:
            return 0.0
        px = apply_poly(lattice.coef, np.vstack(family))
        here = ink(px)
        moved = max(ink(px + f * steps[axis]) for f in MOVES)
        ratios.append(here / max(moved, 1e-9))
    return float(min(ratios))


MOVES = (0.25, 0.5, 0.75)  # of a step: where a family of lines is moved to see the ink it finds off the printed lines


def _ink(image: np.ndarray, factor: int):
    """px (n, 2, scan px) -> the mean of ``image`` (a reduced line map) there, over the points inside it."""
    import cv2

    h, w = image.shape

    def ink(px) -> float:
        x, y = px[:, 0] / factor - 0.5, px[:, 1] / factor - 0.5
        inside = (x >= 0) & (y >= 0) & (x <= w - 1) & (y <= h - 1)
        if inside.sum() < 0.2 * len(px):
            return 0.0
        n = int(inside.sum())
        rows = -(-n // ROW)  # remap takes fewer than 32767 columns a row
        mx, my = np.zeros(rows * ROW, np.float32), np.zeros(rows * ROW, np.float32)
        mx[:n], my[:n] = x[inside], y[inside]
        values = cv2.remap(image, mx.reshape(rows, ROW), my.reshape(rows, ROW), cv2.INTER_LINEAR)
        return float(values.ravel()[:n].mean())

    return ink


ROW = 4096


def _coef(centre, scale, m, order) -> dict:
    return {"centre": centre, "scale": scale, "m": m, "order": order}
