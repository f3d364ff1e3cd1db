"""The printed lattice as a whole: every grid line of the sheet placed at once on the scan's line map.

A crossing alone is easily confused with a road or a border near it; a lattice of long lines is not. The
lines of constant grid coordinate (sampled densely in the sheet's plane, :mod:`hamta.core.grid.planes`) are
mapped to the scan by a model from the plane (affine; a second-order polynomial where the paper bends them).
From the hints' first model, a shift, scale and turn is climbed on the line map blurred by a sixth, then a
twentieth of a step (a wide basin first); then each line is snapped where it is printed: its ink across
itself, segment by segment, gives where the line lies, and the model is fitted to those places by least
squares (each across its line only), a few times, closer each time. Whether that lattice is printed is
judged against the sheet's own background (:func:`evidence`): each line against copies of itself moved
across by part of a step, which cross the same map content but no printed line.

Pixels: the scan's (corner convention); the reduced line map's pixel (i, j) covers ``factor`` scan px from
(j * factor, i * factor).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import List, Optional, Tuple

import numpy as np

from ..estimation.models import PolynomialModel, poly_design

BLURS = (0.15, 0.05)  # of the grid's step: the line map's blur where the first model is climbed (a wide basin
# first, then a narrower one)
REACH = 0.3  # of a step: how far the lattice may move from the hints' model (a whole step finds as much ink)
SNAPS = (0.3, 0.12, 0.05)  # of a step: how far across each line its ink is looked at, at each snap
BENT_GAIN = 1.02  # a second-order lattice is kept when it finds this much more ink than the affine


@dataclass(frozen=True)
class Lattice:
    """``model``: plane coordinates -> scan px (a :class:`PolynomialModel` of ``order`` 1 or 2); ``ink``: the
    mean line map along its lines."""

    model: PolynomialModel
    ink: float
    straight: float = 0.0  # the share of line segments on the sheet printed where the lattice puts them (_Snapper)

    @property
    def order(self) -> int:
        return self.model.order


def fit_lattice(work: np.ndarray, factor: int, lines, start, spacing_px: float, bend: bool = True) -> Lattice:
    """The lattice model from ``start`` (any model plane -> scan px with ``apply``): ``lines`` is a list of (n, 2)
    arrays of plane points along each grid line; ``spacing_px`` the grid's step on the scan; ``bend``: a
    second-order lattice may be kept (:data:`BENT_GAIN`)."""
    import cv2
    from scipy.optimize import minimize

    pts = np.vstack(lines)
    centre = pts.mean(axis=0)
    scale = max(float(np.abs(pts - centre).max()), 1e-9)
    design = poly_design((pts - centre) / scale, 1)
    m = np.linalg.lstsq(design, start.apply(pts), rcond=None)[0]
    reach = REACH * spacing_px
    step_work = spacing_px / factor

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
        res = minimize(lambda v: -ink(design @ similar(m, v)), np.zeros(4), method="Powell",
                       bounds=[(-reach, reach)] * 2 + [(-reach / size, reach / size)] * 2,
                       options={"xtol": 1e-4, "ftol": 1e-5, "direc": np.diag([move, move, move / size, move / size])})
        return similar(m, res.x)

    fine = cv2.GaussianBlur(work, (0, 0), 0.7)
    ink = _ink(fine, factor)
    snap = _Snapper(fine, factor, lines, centre, scale, spacing_px, design @ m)
    tries, current = [snap(m, 1)], m
    for blur in BLURS:
        sigma = blur * step_work
        current = climb_similar(current, cv2.GaussianBlur(work, (0, 0), sigma), sigma * factor)
        tries.append(snap(current, 1))
    m = max(tries, key=lambda t: ink(design @ t))
    best = Lattice(PolynomialModel(1, centre, scale, m), ink(design @ m), snap.share(m, 1))
    if bend and snap.bendable:
        m2 = snap(np.vstack([m, np.zeros((3, 2))]), 2)
        bent = ink(poly_design((pts - centre) / scale, 2) @ m2)
        if bent > BENT_GAIN * best.ink:
            best = Lattice(PolynomialModel(2, centre, scale, m2), bent, snap.share(m2, 2))
    return best


class _Snapper:
    """Snaps a lattice's lines where they are printed (see the module docstring): ``snapper(m, order)`` -> the
    coefficients (normalised plane coordinates -> scan px) fitted to where each line segment's ink peaks."""

    def __init__(self, image, factor, lines, centre, scale, spacing_px, start_px):
        self.image, self.factor, self.spacing = image, factor, spacing_px
        self.centre, self.scale = centre, scale
        self.start = (np.vstack(lines), start_px)  # where the hints put the lines: a snap may not move them a step
        points, seg, family = [], [], []
        for line in lines:  # segments of about a step (a line is sampled spacing/factor points a step), at most
            n = max(int(round(len(line) / max(spacing_px / factor, 4))), 1)  # 16 points each
            t = line[-1] - line[0]
            for part in np.array_split(line, n):
                if len(part) >= 2:
                    part = part[np.linspace(0, len(part) - 1, min(len(part), 16)).round().astype(int)]
                    points.append(part)
                    seg.append(np.full(len(part), len(points) - 1))
                    family.append(abs(t[0]) > abs(t[1]))  # which way the line runs in the plane
        self.u = (np.vstack(points) - centre) / scale if points else np.zeros((0, 2))
        self.seg = np.concatenate(seg) if seg else np.zeros(0, int)
        self.starts = np.flatnonzero(np.r_[True, np.diff(self.seg) != 0]) if len(self.seg) else np.zeros(0, int)
        self.family = np.array(family, bool)
        self.bendable = len(lines) >= 6

    def __call__(self, m, order: int) -> np.ndarray:
        m = np.asarray(m, float)
        pts, start_px = self.start
        u = (pts - self.centre) / self.scale
        for share in SNAPS:
            got = self._measure(m, order, share * self.spacing)
            if got is None or np.abs(poly_design(u, order) @ got - start_px).max() > REACH * self.spacing:
                break  # too few lines seen each way, or a lattice moved a step from the hints: not this one
            m = got
        return m

    def share(self, m, order: int) -> float:
        """Of the line segments on the sheet, the share whose ink peaks within the last snap's reach (or 1.5 px of
        the line map) of where ``m`` puts them: how straight and evenly spaced the printed lines are in the plane
        (lines drawn in another projection leave the lattice where the hints are far)."""
        found = self._peaks(np.asarray(m, float), order, SNAPS[1] * self.spacing)
        if found is None:
            return 0.0
        ok, on, at = found[0], found[1], found[5]
        near = ok & (np.abs(at) <= max(SNAPS[-1] * self.spacing, 1.5 * self.factor))
        return float(near.sum()) / max(int(on.sum()), 1)

    def _peaks(self, m, order, reach):
        """(each segment's peak found, on the sheet, the design's mean, the mean px, the normal, the offset of
        the peak across, its height above the profile's median), or None without segments."""
        import cv2

        if not len(self.seg):
            return None
        d = poly_design(self.u, order)
        px = d @ m
        first, last = self.starts, np.r_[self.starts[1:], len(self.seg)] - 1
        t = px[last] - px[first]
        length = np.hypot(*t.T) + 1e-12
        normal = np.column_stack([-t[:, 1], t[:, 0]]) / length[:, None]
        k = 2 * max(int(math.ceil(reach / max(self.factor * 0.5, 0.5))), 4) + 1
        offsets = np.linspace(-reach, reach, k)
        probe = px[None] + offsets[:, None, None] * normal[self.seg][None]
        x, y = probe[..., 0] / self.factor - 0.5, probe[..., 1] / self.factor - 0.5
        values = np.full(x.shape, np.nan, np.float32)
        for r0 in range(0, x.shape[1], ROW):  # remap takes fewer than 32767 columns a row
            values[:, r0:r0 + ROW] = cv2.remap(self.image, x[:, r0:r0 + ROW].astype(np.float32),
                                               y[:, r0:r0 + ROW].astype(np.float32), cv2.INTER_LINEAR,
                                               borderMode=cv2.BORDER_CONSTANT, borderValue=np.nan)
        counts = np.diff(np.r_[self.starts, len(self.seg)])
        profile = np.add.reduceat(values, self.starts, axis=1) / counts  # (k offsets, segments)
        on = np.isfinite(profile).all(axis=0)
        profile = np.where(on[None, :], profile, 0.0)  # a segment leaving the sheet is not looked at
        i = np.argmax(profile, axis=0)
        base = np.median(profile, axis=0)
        spread = np.median(np.abs(profile - base), axis=0) * 1.4826 + 1e-9
        cols = np.arange(profile.shape[1])
        peak = profile[i, cols]
        ok = on & (i > 0) & (i < k - 1) & ((peak - base) / spread >= PEAK)
        left, right = profile[(i - 1).clip(0), cols], profile[(i + 1).clip(max=k - 1), cols]
        denom = left - 2 * peak + right
        frac = np.where(denom < 0, 0.5 * (left - right) / np.where(denom < 0, denom, -1.0), 0.0)
        at = offsets[i] + np.nan_to_num(frac) * (offsets[1] - offsets[0])
        mean_d = np.add.reduceat(d, self.starts, axis=0) / counts[:, None]
        mean_px = np.add.reduceat(px, self.starts, axis=0) / counts[:, None]
        return ok, on, mean_d, mean_px, normal, at, np.nan_to_num(peak - base)

    def _measure(self, m, order, reach) -> Optional[np.ndarray]:
        """One snap: each segment's ink peak within ``reach`` scan px across it, and the model fitted to them."""
        found = self._peaks(m, order, reach)
        if found is None:
            return None
        ok, _, mean_d, mean_px, normal, at, height = found
        a = np.column_stack([normal[:, :1] * mean_d, normal[:, 1:] * mean_d])[ok]
        b = np.sum(normal * (mean_px + at[:, None] * normal), axis=1)[ok]
        wts = np.sqrt(np.maximum(height, 0))[ok]
        n_coef = m.shape[0]
        if len(b) < 2 * n_coef or min(np.sum(ok & self.family), np.sum(ok & ~self.family)) < n_coef:
            return None
        keep = np.ones(len(b), bool)
        for _ in range(3):  # least squares, leaving out segments that snapped to something else
            coef = np.linalg.lstsq(a[keep] * wts[keep, None], b[keep] * wts[keep], rcond=None)[0]
            res = np.abs(a @ coef - b)
            new = res <= max(3.0 * float(np.median(res[keep])), 0.5 * self.factor)
            if new.sum() < 2 * n_coef or np.array_equal(new, keep):
                break
            keep = new
        return coef.reshape(2, n_coef).T


PEAK = 3.0  # robust deviations above its median a segment's profile must peak to place its line (a line shows)


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
             pieces=()) -> Optional[Evidence]:
    """The :class:`Evidence` of ``lattice``'s lines (plane points, ``axes`` 0 or 1 each, ``values`` their grid
    coordinates) on ``work``; ``steps``: scan px of one grid step along each grid axis; ``pieces``: (axis, value,
    plane points) of pieces of grid lines that a grid printed as crosses or ticks inks alone (around each
    crossing; where a line meets the frame, :func:`hamta.core.grid.frame.tick_pieces`): a line is printed where
    it, or one of its pieces, holds more ink than every copy of itself moved across by part of a step. None where
    a family has no line on the sheet."""
    from scipy.stats import binom

    ink = _ink(work, factor, outside=math.nan, least=0.05)  # a line crossing a corner of the sheet counts
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
        here, moved, whole = np.array(here), np.array(moved), np.array(whole)
        background = float(np.nanmedian(moved))
        families.append(Family(axis, len(here), printed, float(here.mean()) / max(background, 1e-12),
                               _copy_share(here, moved) if whole.any() else 0.0,
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
    family's (a family of ticks alone, no line printed whole, has none: its copies find other ticks, and so its
    lines do not stand out of them)."""
    with np.errstate(all="ignore"):
        by_move = np.nanmedian(moved, axis=0)  # each move's copies, over the lines (NaN: off the sheet both ways; the
    background = float(np.nanmedian(by_move))  # median: one copy that meets the neatline does not count)
    above = float(np.median(here)) - background
    copy = float(np.nanmax(by_move)) - background
    return copy / above if above > 0 else math.inf


def _num(v):
    return float(v) if np.isfinite(v) else None


def _ink(image: np.ndarray, factor: int, outside: float = 0.0, least: float = 0.2):
    """px (n, 2, scan px) -> the mean of ``image`` (a reduced line map) there, over the points inside it
    (``outside`` where fewer than ``least`` of them, or than 8, are)."""
    import cv2

    h, w = image.shape

    def ink(px) -> float:
        x, y = px[:, 0] / factor - 0.5, px[:, 1] / factor - 0.5
        inside = (x >= 0) & (y >= 0) & (x <= w - 1) & (y <= h - 1)
        if inside.sum() < max(least * len(px), 8):
            return outside
        n = int(inside.sum())
        rows = -(-n // ROW)  # remap takes fewer than 32767 columns a row
        mx, my = np.zeros(rows * ROW, np.float32), np.zeros(rows * ROW, np.float32)
        mx[:n], my[:n] = x[inside], y[inside]
        values = cv2.remap(image, mx.reshape(rows, ROW), my.reshape(rows, ROW), cv2.INTER_LINEAR)
        return float(values.ravel()[:n].mean())

    return ink


ROW = 4096
