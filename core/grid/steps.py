"""The steps a printed grid may have, in the units of its coordinates.

Graticules count in degrees, minutes and seconds: a step is a whole number of one of them that divides the
next unit up evenly, or a half or quarter of one (7.5', 2.5', 0.5'), as publishers choose them. Grids count in
the linear unit of their CRS (metres, feet, yards): 1, 2, 2.5 or 5 times a power of ten. Nothing else is
assumed of a sheet: the step of its lattice is the largest of these that its hints or labels fit and whose
lines are printed (:func:`hamta.core.grid.sheet.fit_sheet`).
"""
from __future__ import annotations

from typing import List, Sequence

import numpy as np

from ..errors import InputError

SEXAGESIMAL = (1, 2, 2.5, 3, 4, 5, 6, 7.5, 10, 12, 15, 20, 30)  # whole steps of a degree, minute or second
DEGREES = (90, 45, 30, 20, 15, 10, 5, 4, 3, 2.5, 2, 1)
DECIMAL = (1, 2, 2.5, 5)
FIT = 0.005  # of a step: how far from a multiple of it a printed coordinate may be (44°29' typed 44.48333), and at
TYPED = {True: 1e-4, False: 0.5}  # most this (degrees: 0.36"; linear units): a coordinate typed with its decimals


def degree_steps() -> List[float]:
    """Every graticule step from 90 degrees down to a second, in degrees, largest first."""
    steps = set(DEGREES)
    steps |= {m / 60 for m in SEXAGESIMAL} | {s / 3600 for s in SEXAGESIMAL}
    steps |= {0.5 / 60, 0.25 / 60, 0.2 / 60, 0.1 / 60}  # decimal minutes
    return sorted(steps, reverse=True)


def linear_steps(largest: float = 1e6, smallest: float = 1.0) -> List[float]:
    """1, 2, 2.5 and 5 times each power of ten from ``largest`` down to ``smallest`` (CRS units), largest first."""
    out = []
    power = 10.0 ** np.floor(np.log10(largest))
    while power >= smallest:
        out += [float(d * power) for d in DECIMAL if d * power <= largest]
        power /= 10
    return sorted(set(out), reverse=True)


def usual_steps(geographic: bool) -> List[float]:
    return degree_steps() if geographic else linear_steps()


def fitting(coords, steps: Sequence[float], geographic: bool = True) -> List[float]:
    """Those of ``steps`` that every coordinate of ``coords`` is a multiple of (within :data:`FIT` of the step and
    :data:`TYPED`), largest first."""
    coords = np.asarray(coords, float).ravel()
    out = []
    for s in sorted(steps, reverse=True):
        off = np.abs(coords - np.round(coords / s) * s)
        if np.all(off <= min(FIT * s, TYPED[geographic])):
            out.append(float(s))
    return out


def hint_steps(coords, geographic: bool, span: float) -> List[float]:
    """The usual steps the hints' coordinates fit, largest first, down to ``span`` times smaller than the
    largest (hints a few steps apart fit twice the printed step as well as the step). Raises
    :class:`InputError` where none does."""
    fits = fitting(coords, usual_steps(geographic), geographic)
    if not fits:
        raise InputError("The hints' coordinates are not all on one grid of a usual step (degrees, minutes or "
                         "seconds: 1, 2, 2.5, 3, 5, 7.5, 10, 15, 20 or 30 of them; metres, feet or yards: 1, 2, 2.5 "
                         "or 5 times a power of ten): give the grid's step (--param step=...).")
    return [s for s in fits if s >= fits[0] / span]


def divisors(step: float, geographic: bool, span: float) -> List[float]:
    """The usual steps that divide ``step`` (a step between labelled lines: lines may be printed between
    them), largest first, down to ``span`` times smaller."""
    return [s for s in fitting([step], usual_steps(geographic), geographic) if s >= step / span]


def describe_pair(step, geographic: bool) -> str:
    """Steps along grid x and grid y as a person writes them: 1° where they are the same, else 30' x 1°."""
    sx, sy = (float(v) for v in step)
    if abs(sx - sy) <= 1e-12 * max(abs(sx), 1.0):
        return describe(sx, geographic)
    return f"{describe(sx, geographic)} x {describe(sy, geographic)}"


def describe(step: float, geographic: bool) -> str:
    """A step as a person writes it: 2', 15", 0.5', 5°, 1000 (CRS units)."""
    if not geographic:
        return f"{step:g}"
    for unit, sign in ((1.0, "°"), (1 / 60, "'"), (1 / 3600, '"')):
        if step >= unit - 1e-12:
            value = step / unit
            return f"{round(value, 3):g}{sign}"
    return f'{step * 3600:.2g}"'
