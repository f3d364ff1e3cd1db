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
from typing import Optional

import numpy as np

from ..estimation.models import PolynomialModel, poly_design

BLURS = (0.15, 0.05)  # of the grid's step: the line map's blur where the first model is climbed (a wide basin
# first, then a narrower one)
REACH = 0.3  # of a step: how far the lattice may move from the hints' model (a whole step finds as much ink)
SNAPS = (0.3, 0.12, 0.05)  # of a step: how far across each line its ink is looked at, at each snap
FLOOR_PX = 3.0  # line-map px: the least reach of a snap (a narrower profile is all line, and has no peak)
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


def fit_lattice(work: np.ndarray, factor: int, lines, start, spacing_px: float, bend: bool = True,
                arms: Optional[np.ndarray] = None, mask: Optional[np.ndarray] = None) -> Lattice:
    """The lattice model from ``start`` (any model plane -> scan px with ``apply``): ``lines`` is a list of (n, 2)
    arrays of plane points along each grid line; ``spacing_px`` the grid's step on the scan; ``bend``: a
    second-order lattice may be kept (:data:`BENT_GAIN`); ``arms``: plane points (n, k, 2) of the lines' pieces
    around each crossing (:func:`hamta.core.grid.frame.crossing_arms`). The lattice's ink is the median crossing's
    (what most crossings hold, not what a frame, the lettering in it or a road gives a few; a grid printed as
    crosses inks only there), or, with fewer than :data:`LEAST_CROSSINGS`, the mean along its lines; ``mask``: where
    the map is (:func:`on_map`; None: everywhere), the crossings elsewhere left out."""
    import cv2
    from scipy.optimize import minimize

    pts = np.vstack(lines)
    centre = pts.mean(axis=0)
    scale = max(float(np.abs(pts - centre).max()), 1e-9)
    design = poly_design((pts - centre) / scale, 1)
    m = np.linalg.lstsq(design, start.apply(pts), rcond=None)[0]
    if arms is not None and mask is not None:
        kept = values_at(mask.astype(np.float32), factor)(start.apply(arms.mean(axis=1))) > 0.5
        arms = arms[kept] if kept.sum() >= LEAST_CROSSINGS else arms
    crossings = arms is not None and len(arms) >= LEAST_CROSSINGS
    measured = arms.reshape(-1, 2) if crossings else pts
    at = poly_design((measured - centre) / scale, 1)  # where the lattice's ink is measured

    def lattice_ink(image):
        if not crossings:
            return mean_ink(image, factor)
        values = values_at(image, factor)
        k = arms.shape[1]

        def median_crossing(px) -> float:
            v = values(px).reshape(-1, k)
            seen = np.isfinite(v).sum(axis=1) > k // 2
            if seen.sum() < LEAST_CROSSINGS:
                return 0.0
            return float(np.median(np.nanmean(v[seen], axis=1)))
        return median_crossing
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
        ink = lattice_ink(image)
        size = max(float(np.hypot(*m[1])), float(np.hypot(*m[2])), 1e-9)
        res = minimize(lambda v: -ink(at @ similar(m, v)), np.zeros(4), method="Powell",
                       bounds=[(-reach, reach)] * 2 + [(-reach / size, reach / size)] * 2,
                       options={"xtol": 1e-4, "ftol": 1e-5, "direc": np.diag([move, move, move / size, move / size])})
        return similar(m, res.x)

    fine = cv2.GaussianBlur(work, (0, 0), 0.7)
    ink = lattice_ink(fine)
    snap = _Snapper(fine, factor, lines, centre, scale, spacing_px, design @ m,
                    judge=lambda c, order: ink(poly_design((measured - centre) / scale, order) @ c))
    tries, current = [snap(m, 1)], m
    for blur in BLURS:
        sigma = blur * step_work
        current = climb_similar(current, cv2.GaussianBlur(work, (0, 0), sigma), sigma * factor)
        tries.append(snap(current, 1))
    m = max(tries, key=lambda t: ink(at @ t))
    best = Lattice(PolynomialModel(1, centre, scale, m), ink(at @ m), snap.share(m, 1))
    if bend and snap.bendable:
        m2 = snap(np.vstack([m, np.zeros((3, 2))]), 2)
        bent = ink(poly_design((measured - centre) / scale, 2) @ m2)
        if bent > BENT_GAIN * best.ink:
            best = Lattice(PolynomialModel(2, centre, scale, m2), bent, snap.share(m2, 2))
    return best


def on_map(work, factor: int, arms: np.ndarray, start, spacing_px: float) -> Optional[np.ndarray]:
    """Where the line map shows the map rather than blank paper (a bool map like ``work``), or None where all of
    it may: the most ink within half a step of each crossing of ``arms`` (plane points, n x k x 2, placed by
    ``start``), split over the crossings into two classes (:func:`_two_classes`, on its logarithm); where the upper
    holds :data:`BLANK_RATIO` times the lower's or more, the lower is blank paper (a scan's margins, the scanner's
    bed: their ink is the scan's noise, the map's is its lines). The lattice is fitted to the crossings on the map,
    and its lines judged there, so that a sheet turned on a wider bed is judged by its map."""
    import cv2

    side = max(int(spacing_px / factor) | 1, 3)
    most = cv2.dilate(work, cv2.getStructuringElement(cv2.MORPH_RECT, (side, side)))
    at = values_at(most, factor)(start.apply(arms.mean(axis=1)))
    seen = np.log(np.maximum(np.sort(at[np.isfinite(at)]), 1e-6))
    if len(seen) < 2 * LEAST_CROSSINGS:
        return None
    split = _two_classes(seen)
    low, high = seen[:split], seen[split:]
    if len(high) < LEAST_CROSSINGS or high.mean() - low.mean() < math.log(BLANK_RATIO):
        return None
    return most >= math.exp((low[-1] + high[0]) / 2)


def _two_classes(sorted_values: np.ndarray) -> int:
    """Where ``sorted_values`` split into two classes of the largest variance between them (Otsu's split): the
    index of the upper class's first value."""
    n = len(sorted_values)
    k = np.arange(1, n)
    total = np.cumsum(sorted_values)
    low = total[:-1] / k
    high = (total[-1] - total[:-1]) / (n - k)
    return int(np.argmax(k * (n - k) * (high - low) ** 2)) + 1


BLANK_RATIO = 5.0  # how much more ink (geometric means) the map's crossings hold than blank paper's at least (random
# synthetic sheets, tune seeds: the map's 7 times blank paper's or more, a map without margins splits at 1.5-3)
LEAST_CROSSINGS = 8  # crossings the median crossing is taken over (fewer: the mean along the lines)


def points_per_step(per_step: float) -> int:
    """How many points a step a lattice's lines are sampled at (``per_step``: the step in line-map px): one a
    line-map pixel, four at least. Lines start half a step before a crossing, so that the snapper's segments,
    a step of points each, are centred on the crossings (a grid printed as crosses inks only there)."""
    return max(int(math.ceil(per_step)), 4)


class _Snapper:
    """Snaps a lattice's lines where they are printed (see the module docstring): ``snapper(m, order)`` -> the
    coefficients (normalised plane coordinates -> scan px) fitted to where each line segment's ink peaks."""

    def __init__(self, image, factor, lines, centre, scale, spacing_px, start_px, judge=None):
        self.image, self.factor, self.spacing, self.judge = image, factor, spacing_px, judge
        self.centre, self.scale = centre, scale
        self.start = (np.vstack(lines), start_px)  # where the hints put the lines: a snap may not move them a step
        points, seg, family = [], [], []
        n = points_per_step(spacing_px / factor)
        for line in lines:  # segments of a step, each centred on a crossing (see points_per_step), at most 16
            t = line[-1] - line[0]  # points each
            for part in (line[i:i + n] for i in range(0, len(line) - 1, n)):
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
            got = self._measure(m, order, max(share * self.spacing, FLOOR_PX * self.factor))
            if got is None or np.abs(poly_design(u, order) @ got - start_px).max() > REACH * self.spacing:
                continue  # too few lines seen each way, or a lattice moved a step from the hints: not this one
            if self.judge is None or self.judge(got, order) >= self.judge(m, order):
                m = got  # kept where the lattice's ink (its median crossing's) grows: peaks that content put
        return m  # near the lines (a frame's lettering, a road beside a cross) move it off them

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


def values_at(image: np.ndarray, factor: int):
    """px (n, 2, scan px) -> ``image`` (a reduced line map) at each point, NaN off it."""
    import cv2

    h, w = image.shape

    def values(px) -> np.ndarray:
        x, y = px[:, 0] / factor - 0.5, px[:, 1] / factor - 0.5
        inside = (x >= 0) & (y >= 0) & (x <= w - 1) & (y <= h - 1)
        out = np.full(len(px), np.nan)
        n = int(inside.sum())
        if n:
            rows = -(-n // ROW)  # remap takes fewer than 32767 columns a row
            mx, my = np.zeros(rows * ROW, np.float32), np.zeros(rows * ROW, np.float32)
            mx[:n], my[:n] = x[inside], y[inside]
            out[inside] = cv2.remap(image, mx.reshape(rows, ROW), my.reshape(rows, ROW), cv2.INTER_LINEAR).ravel()[:n]
        return out

    return values


def mean_ink(image: np.ndarray, factor: int, outside: float = 0.0, least: float = 0.2,
             mask: Optional[np.ndarray] = None):
    """px (n, 2, scan px) -> the mean of ``image`` (a reduced line map) there, over the points inside it and, with
    a ``mask`` (:func:`on_map`), on the map (``outside`` where fewer than ``least`` of them, or than 8, are)."""
    import cv2

    h, w = image.shape
    on = None if mask is None else values_at(mask.astype(np.float32), factor)

    def ink(px) -> float:
        x, y = px[:, 0] / factor - 0.5, px[:, 1] / factor - 0.5
        inside = (x >= 0) & (y >= 0) & (x <= w - 1) & (y <= h - 1)
        if on is not None:
            inside &= np.nan_to_num(on(px)) > 0.5
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
