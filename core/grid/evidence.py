"""Whether a lattice placed on the scan is printed there, judged against the sheet's own background.

Each grid line of the lattice (:mod:`hamta.core.grid.lattice`) is compared with copies of itself moved across by
part of a step, which cross the same map content but no printed line: a line stands out where it holds more ink
than every copy and lies :data:`Z_LINE` robust deviations above them. How many lines stand out where no grid is
printed was measured (``tools/calibrate_grid.py``): a family's lines are printed beyond chance by a binomial with
that rate, and both families together by :data:`CHANCE`.

Pixels: the scan's (corner convention).
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import List, Optional, Tuple

import numpy as np

from .lattice import Lattice, mean_ink

OFF_LATTICE = np.array(sorted({k / n for n in (2, 3, 4, 5, 6) for k in range(1, n)}))  # of a step: where each
# line is moved to see what the sheet's content alone puts along it: where the lines of a grid printed at a half,
# third ... sixth of the lattice's step would be (the ratios between usual steps), so that a lattice at a multiple
# of the printed step finds its copies on printed lines


Z_LINE = 4.0  # robust deviations of its copies a line's ink must stand above them, besides above them all
# (tools/calibrate_grid.py: where no grid is printed, a lattice fitted to the content has lines above all their
# copies often, this far above them seldom)


LEAST_COPIES = 6  # copies of a line on the sheet it is judged against (a step wider than the sheet leaves fewer)


P_CHANCE = 0.19  # the mean share of a family's lines that stand out (Z_LINE) where no grid is printed, on lattices
# fitted to imagery, maps and sheets without a grid (tools/calibrate_grid.py; docs/benchmarks.md)


CHANCE = 1e-2  # the probability by chance of as many lines standing out, both families together, below which a
# lattice is taken for printed. A lattice's crossings then decide (hamta.core.grid.check.MIN_SHARE: a lattice where
# none is printed finds at most 13 % of its crossings, tools/calibrate_grid.py)


PRINTED_SHARE = 0.4  # the 95th percentile of a family's share of lines standing out where no grid is printed
# (tools/calibrate_grid.py)


FAMILY_CHANCE = CHANCE ** 0.5  # a family alone: half the evidence both together need (in log10)


COPY_SHARE = 0.5  # a lattice whose lines moved by part of a step keep half its ink above the background is not at
# the printed step (a lattice at twice the step finds as much ink half a step over)


@dataclass(frozen=True)
class Family:
    """One family of a lattice's lines (``axis`` 0: constant grid x, 1: constant grid y) judged on the line map:
    ``lines`` on the sheet, ``printed`` of them holding more ink than every copy of themselves moved across by
    part of a step; ``excess``: the family's ink over its copies' median; ``copy_share``: the strongest copy's
    ink above that median, as a share of the family's; ``chance``: the probability of as many printed lines
    where none is (binomial, :data:`P_CHANCE`)."""

    axis: int
    lines: int
    printed: int
    excess: float
    copy_share: float
    chance: float
    alternate: bool = False  # every other line printed, the others not: the lattice is at half the printed step

    @property
    def stands(self) -> bool:
        """The family alone stands out from the background (:data:`FAMILY_CHANCE`) and is at its printed step."""
        return self.chance <= FAMILY_CHANCE and self.copy_share < COPY_SHARE

    @property
    def at_step(self) -> bool:
        """The family may be at the printed step: its copies moved by part of a step find no printed lines, its
        lines are not printed every other one, and more of them are printed than lattices where no grid is printed
        show but one time in twenty (:data:`PRINTED_SHARE`), or as many as chance seldom gives (a smaller step is
        tried otherwise)."""
        return self.copy_share < COPY_SHARE and not self.alternate and self.printed >= 1 and \
            (self.printed >= PRINTED_SHARE * self.lines or self.chance <= FAMILY_CHANCE)

    def to_dict(self) -> dict:
        return {"axis": "x" if self.axis == 0 else "y", "lines": self.lines, "printed": self.printed,
                "ink_over_background": _num(self.excess), "moved_copy_share": _num(self.copy_share),
                "chance_probability": self.chance}


@dataclass(frozen=True)
class Evidence:
    """Both families of a lattice: printed when together they are beyond chance (:data:`CHANCE`) and neither
    keeps its ink moved by part of a step (:data:`COPY_SHARE`)."""

    families: Tuple[Family, Family]
    threshold: float = CHANCE  # the chance below which it is printed (CHANCE shared by the lattices a search tries)

    @property
    def chance(self) -> float:
        return float(np.prod([f.chance for f in self.families]))

    @property
    def printed(self) -> bool:
        return self.chance <= self.threshold and all(f.at_step for f in self.families)

    @property
    def score(self) -> float:
        """-log10 of the chance: the larger, the surer (to rank lattices)."""
        return -math.log10(max(self.chance, 1e-300))

    @property
    def excess(self) -> float:
        """The smaller family's ink over its background: how well the lattice lies on the printed lines."""
        return float(min(f.excess for f in self.families))

    def text(self) -> str:
        x, y = self.families
        return (f"{x.printed} of {x.lines} lines of constant x and {y.printed} of {y.lines} of constant y stand out "
                f"from the sheet's background (chance {self.chance:.0e})")

    def to_dict(self) -> dict:
        return {"printed": self.printed, "chance_probability": self.chance, "threshold": self.threshold,
                "families": [f.to_dict() for f in self.families]}


def evidence(work: np.ndarray, factor: int, lines, axes, lattice: Lattice, steps: np.ndarray, values=None,
             pieces=(), mask: Optional[np.ndarray] = None) -> Optional[Evidence]:
    """The :class:`Evidence` of ``lattice``'s lines (plane points, ``axes`` 0 or 1 each, ``values`` their grid
    coordinates) on ``work``; ``steps``: scan px of one grid step along each grid axis; ``pieces``: (axis, value,
    plane points) of pieces of grid lines that a grid printed as crosses or ticks inks alone (around each
    crossing; where a line meets the frame, :func:`hamta.core.grid.frame.tick_pieces`): a line is printed where
    it, or one of its pieces, holds more ink than every copy of itself moved across by part of a step. None where
    a family has no line on the sheet."""
    from scipy.stats import binom

    ink = mean_ink(work, factor, outside=math.nan, least=0.05, mask=mask)  # a line across a corner of the sheet counts
    by_line = {}
    for axis, value, xy in pieces:
        by_line.setdefault((axis, round(value, 9)), []).append(xy)
    families: List[Family] = []
    def stands(px, axis):
        """(ink of the line at ``px``, its copies' inks, whether it holds more than all) or None off the sheet; the
        copies moved the way that keeps them on the sheet (a line near its edge)."""
        value = ink(px)
        if not np.isfinite(value):
            return None
        ahead = np.array([ink(px + f * steps[axis]) for f in OFF_LATTICE])
        copies = ahead if np.isfinite(ahead).all() else np.where(
            np.isfinite(ahead), ahead, [ink(px - f * steps[axis]) for f in OFF_LATTICE])
        if np.isfinite(copies).sum() < LEAST_COPIES:
            return None
        middle = float(np.nanmedian(copies))
        spread = 1.4826 * float(np.nanmedian(np.abs(copies - middle))) + 1e-6 * (abs(middle) + 1e-6)
        return value, copies, bool(value > np.nanmax(copies) and (value - middle) / spread >= Z_LINE)

    for axis in (0, 1):
        here, moved, printed, whole, flags = [], [], 0, [], []
        for k, (line, a) in enumerate(zip(lines, axes)):
            if a != axis:
                continue
            found = stands(lattice.model.apply(line), axis)
            if found is None:  # off the sheet
                continue
            value, copies, alone = found
            here.append(value)
            moved.append(copies)
            whole.append(alone)
            for xy in (by_line.get((axis, round(values[k], 9)), []) if values is not None else []):
                tick = stands(lattice.model.apply(xy), axis)
                alone |= tick is not None and tick[2]
            printed += bool(alone)
            flags.append(bool(alone))
        if not here:
            return None
        here, moved, whole, flags = np.array(here), np.array(moved), np.array(whole), np.array(flags, bool)
        background = float(np.nanmedian(moved))
        families.append(Family(axis, len(here), printed, float(here.mean()) / max(background, 1e-12),
                               _copy_share(*((here[whole], moved[whole]) if whole.sum() >= 3 else (here, moved)))
                               if whole.any() else 0.0,
                               float(binom.sf(printed - 1, len(here), P_CHANCE)), _alternate(flags)))
    return Evidence(tuple(families))


def _alternate(flags) -> bool:
    """Whether the lines (in order) are printed every other one: one parity two thirds printed or more, the other a
    third or less, over four lines or more."""
    flags = np.asarray(flags, bool)
    if len(flags) < 4:
        return False
    even, odd = flags[0::2].mean(), flags[1::2].mean()
    return bool(max(even, odd) >= 2 / 3 and min(even, odd) <= 1 / 3)


def _copy_share(here, moved) -> float:
    """The ink a family's strongest copy moved by part of a step keeps above the copies' median, as a share of the
    family's: over its lines that stand out whole where three or more do (lines off the map, on blank paper, tell
    nothing), else over all (a family of ticks alone, no line printed whole, has none: its copies find other
    ticks, and so its lines do not stand out of them)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # a move off the sheet on every line: all NaN
        by_move = np.nanmedian(moved, axis=0)  # each move's copies, over the lines (NaN: off the sheet both ways; the
    background = float(np.nanmedian(by_move))  # median: one copy that meets the neatline does not count)
    above = float(np.median(here)) - background
    copy = float(np.nanmax(by_move)) - background
    return copy / above if above > 0 else math.inf


def _num(v):
    return float(v) if np.isfinite(v) else None
