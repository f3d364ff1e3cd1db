"""A sheet's printed coordinates read from the labels in its margins, as hints for
:func:`hamta.core.grid.sheet.fit_sheet`: the sheet georeferenced with no click.

Labels on the top and bottom edges count along x (longitude, easting), those on the left and right along y
(latitude, northing) (a sheet turned by more than a few tens of degrees, whose labels run along turned
lines, is not read: hints are then needed). On each edge, a label's place along the edge follows its value:
linearly (a latitude on a Mercator chart: its Mercator ordinate). The values are fitted to the places robustly
(pairs of labels propose a line; the line most labels agree with is kept, within two glyph heights), which
completes what a label leaves out: minutes printed alone take the degrees of a full label of the same axis,
seconds the degrees and minutes, abbreviated metres the leading digits of a full value; the hemisphere is the
letter printed, else the way the values run (west where they grow leftwards, south where they grow
downwards, the labels being upright). Labels that contradict the others are named. The lines of two values
of each axis, placed from their labels on each edge, cross at the hints. The labels' step (the smallest
difference of their values) gives the steps the lattice is tried at: it, and the usual steps that divide it
(lines may be printed between labelled ones). Whether the labels agree with the lattice found is judged over
the whole sheet by :mod:`hamta.core.grid.check` (:meth:`Reading.agreement`).

Pixels: the scan's (corner convention).
"""
from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

import numpy as np

from .check import LABEL_REACH, LabelAgreement
from .edges import SIDES, axis_family, axis_scale
from .labels import FULL_DIGITS, Label, joined, parse
from .ocr import INSTALL, engine, engines, read_words, reread
from .steps import FIT, TYPED, describe, divisors
from .words import bands, find_words, unique

BAND = 0.12  # of the sheet's shorter side: how deep each edge's band is read first (labels of a sheet scanned
WIDE = 0.25  # with its margins), then how deep where the first band gives no line of an axis (a wide scanner bed)
CHUNK_PX = 4000  # a band is read in pieces this long (memory), overlapping by the band's depth
STEP_SPAN = 10  # the lattice is tried at the labels' step and the usual steps dividing it, down to a tenth
@dataclass
class Reading:
    """What the labels gave: every ``labels`` read with its ``fates`` (kept, or why not); the ``hints`` they make
    (rows of scan x, y, grid x, y; None, with the ``reason``, where they make none), the CRS the values count in
    (``printed_crs``), the ``steps`` to try the lattice at, and per axis the signed value of each kept label."""

    labels: List[Label]
    fates: List[str]
    words: int = 0
    hints: Optional[np.ndarray] = None
    printed_crs: object = None
    steps: Optional[List[List[float]]] = None  # along grid x, along grid y
    reason: str = ""
    kept: Dict[int, Tuple[int, float]] = field(default_factory=dict)  # label index -> (axis, signed value)
    engine_available: bool = True
    failed: Tuple[int, ...] = ()  # the axes whose labels gave no line

    def agreement(self, fit) -> LabelAgreement:
        """How the kept labels agree with the crossings ``fit`` found (a :class:`hamta.core.grid.finding.SheetFit`):
        the grid coordinates at each label's place, from the crossings' model."""
        from .crossings import to_scan

        to_plane = to_scan(fit.crossings[:, [2, 3, 0, 1, 4, 5]], fit.order)  # scan px -> plane
        agreeing, contradicting, edges = ([set(), set()], [[], []], [set(), set()])
        for i, (axis, value) in self.kept.items():
            lab = self.labels[i]
            g = fit.plane.backward(to_plane.apply(np.array([lab.xy], float)))[0]
            off = (g[axis] - value) / fit.step[axis]
            if abs(off) < LABEL_REACH:
                agreeing[axis].add(round(value / fit.step[axis]))
                edges[axis].add(lab.side)
            else:
                contradicting[axis].append(f"'{lab.text}' at ({lab.xy[0]:.0f}, {lab.xy[1]:.0f})")
        return LabelAgreement(tuple(len(a) for a in agreeing), tuple(tuple(c) for c in contradicting),
                              tuple(tuple(sorted(e)) for e in edges))

    def note(self) -> str:
        kept = len(self.kept)
        return (f"no hints: {len(self.labels)} labels read as coordinates ({self.words} words read in the margins), "
                f"{kept} kept" + ("" if self.hints is None else ", giving the crossings "
                                  + ", ".join(f"({gx:.6g}, {gy:.6g})" for gx, gy in self.hints[:, 2:])))

    def to_dict(self) -> dict:
        rows = []
        for i, (lab, fate) in enumerate(zip(self.labels, self.fates)):
            axis, value = self.kept.get(i, (None, None))
            rows.append(dict(lab.to_dict(), fate=fate, value=value,
                             axis=None if axis is None else "xy"[axis]))
        return {"summary": self.note() if not self.reason else f"{self.note()}; {self.reason}", "words": self.words,
                "labels": rows, "reason": self.reason or None, "engine_available": self.engine_available,
                "steps": self.steps}


def read_sheet(source, info, sheet_crs, monitor) -> Reading:
    """The labels in ``source``'s margins (a :class:`hamta.core.grid.scan.LineSource` of the raster ``info``)
    read and interpreted for a sheet whose printed coordinates count in ``sheet_crs`` (a pyproj CRS; a projected
    CRS whose labels are degrees: its datum's). ``monitor``: a :class:`hamta.core.progress.Monitor`."""
    if engine() is None:
        return Reading([], [], reason=INSTALL, engine_available=False)
    pieces = bands(info.width, info.height, BAND, CHUNK_PX)
    names = engines()
    progress = {"done": 0, "total": len(pieces)}

    def tick():
        progress["done"] += 1
        monitor.report(progress["done"] / progress["total"],
                       f"grid: reading the labels {progress['done']}/{progress['total']}")

    def read(job):
        (side, (x0, y0, x1, y1)), turns, name = job
        monitor.check()
        grey = np.clip(source.grey(x0, y0, x1, y1), 0, 255).astype(np.uint8)
        words = read_words(find_words(grey, turns), (x0, y0), name, monitor.check)
        tick()
        return [(side, w) for w in words]

    def pooled(function, jobs):
        with ThreadPoolExecutor(max_workers=2) as pool:  # the engines run two at a time (2 cores)
            return [item for part in pool.map(function, jobs) for item in part]

    monitor.report(0.0, f"grid: reading the labels 0/{len(pieces)}")
    words = pooled(read, [(piece, (0,), names[0]) for piece in pieces])  # upright words, the faster engine
    reading = _interpreted(words, info, sheet_crs)
    if reading.failed and len(names) > 1:  # read again by the better engine
        chunks = [words[k:k + 64] for k in range(0, len(words), 64)]
        progress["total"] += len(chunks)

        def again(chunk):
            out = [(side, w) for (side, _), w in zip(chunk, reread([w for _, w in chunk], names[-1], monitor.check))]
            tick()
            return out

        words = pooled(again, chunks)
        reading = _interpreted(words, info, sheet_crs)
    for more in ("deeper", "turned"):
        if not reading.failed:
            break
        sides = [side for axis in reading.failed for side in SIDES[axis]]
        if more == "deeper":  # the band further in, along the edges of an axis not read yet
            jobs = [(piece, (0,), names[-1]) for piece in bands(info.width, info.height, WIDE, CHUNK_PX, BAND)
                    if piece[0] in sides]
        else:  # words turned a quarter, in the whole depth
            jobs = [(piece, (90, -90), names[-1]) for piece in bands(info.width, info.height, WIDE, CHUNK_PX)
                    if piece[0] in sides]
        progress["total"] += len(jobs)
        words += pooled(read, jobs)
        reading = _interpreted(words, info, sheet_crs)
    return reading


def _interpreted(words, info, sheet_crs) -> Reading:
    """The :class:`Reading` of ``words`` ((side, word) pairs: a word in a corner is read along both its edges)."""
    labels, count = [], 0
    for side in ("top", "bottom", "left", "right"):
        kept = unique([w for s, w in words if s == side and any(c.isdigit() for c in w.text)])
        count += len(kept)
        labels += [lab for lab in (parse(w, side) for w in kept) if lab is not None]
    reading = interpret(joined(labels), info.width, info.height, sheet_crs)
    reading.words = count
    return reading


def interpret(labels: List[Label], width: int, height: int, sheet_crs) -> Reading:
    """The :class:`Reading` of ``labels`` (see the module docstring)."""
    fates = ["not used" for _ in labels]
    angles = sum(lab.degrees is not None for lab in labels)
    linear = sum(lab.number is not None and lab.digits >= FULL_DIGITS for lab in labels)
    geographic = angles >= max(linear, 1) or (sheet_crs.is_geographic and angles > 0)
    if sheet_crs.is_geographic and not geographic and linear:
        return Reading(labels, ["a grid's number, but the sheet's CRS is in degrees" if lab.number is not None
                                else "not used" for lab in labels], reason=(
            f"The labels read look like a projected grid's numbers ({linear} in full), but the sheet's CRS "
            f"'{sheet_crs.name}' is in degrees: give the CRS of the grid printed on the sheet."))
    printed = (sheet_crs if sheet_crs.is_geographic else sheet_crs.geodetic_crs) if geographic else sheet_crs
    families, reasons, usable = {}, [], {}
    for axis in (0, 1):
        mine = [i for i, lab in enumerate(labels) if lab.side in SIDES[axis]]
        for i in mine:
            fates[i] = _unfit_reason(labels[i], axis, geographic) or fates[i]
        usable[axis] = [i for i in mine if _unfit_reason(labels[i], axis, geographic) is None]
    alone = {axis: axis_family(labels, usable[axis], axis, geographic, list(fates)) for axis in (0, 1)}
    first = max((0, 1), key=lambda axis: -1.0 if alone[axis] is None else sum(e.score for e in alone[axis][0]))
    for axis in (first, 1 - first):  # the surer axis first: its scale says what the other's may be
        scale = None if axis == first or families[first] is None else axis_scale(families[first], first, geographic)
        family = axis_family(labels, usable[axis], axis, geographic, fates, scale)
        if family is None:
            what = ("longitude", "latitude")[axis] if geographic else ("eastings", "northings")[axis]
            reasons.append(f"along the {' and '.join(SIDES[axis])} edges, {len(usable[axis])} labels could be "
                           f"{what}, and no two of them agree with a full label")
        families[axis] = family
    if reasons:
        return Reading(labels, fates, printed_crs=printed, reason="Too few printed coordinates agree: "
                       + "; ".join(reasons) + ". Give two or three crossings with their coordinates as hints "
                       "(a QGIS Georeferencer .points file).",
                       failed=tuple(axis for axis in (0, 1) if families[axis] is None))
    kept = {i: (axis, value) for axis, (edges, sign) in families.items()
            for e in edges for i, value in ((i, sign * v) for i, v in e.values.items())}
    for i, (axis, value) in kept.items():
        fates[i] = f"kept: {'xy'[axis]} = {value:.8g} ({labels[i].side} edge)"
    steps = [_steps([v for a, v in kept.values() if a == axis], geographic) for axis in (0, 1)]
    steps = None if None in steps else steps
    hints = _crossings(families, width, height)
    return Reading(labels, fates, hints=hints, printed_crs=printed, steps=steps, kept=kept)


def _unfit_reason(lab: Label, axis: int, geographic: bool) -> Optional[str]:
    """Why ``lab`` cannot be a coordinate of ``axis`` on this sheet, or None."""
    if geographic:
        if not lab.angle:
            return "a number, not an angle"
        if lab.hemisphere and (lab.hemisphere in "EW") != (axis == 0):
            return "its hemisphere letter is of the other axis"
        if lab.degrees is not None and axis == 1 and lab.degrees > 90:
            return "more than 90 degrees: not a latitude"
        return None
    if lab.number is None:
        return "an angle, but the sheet's grid counts in its CRS's units"
    return None


def _steps(values, geographic: bool) -> Optional[List[float]]:
    """The steps to try one axis's lines at: its labels' own step (the median difference between neighbouring
    values: a label misread, or one missing, does not change it) and the usual steps that divide it and most
    values (:data:`STEP_SHARE`)."""
    values = np.unique(np.round(np.abs(values), 9))
    if len(values) < 2:
        return None
    diffs = np.diff(values)
    label_step = float(np.median(diffs[diffs > 1e-9]))

    def divides(step):
        off = np.abs(values - np.round(values / step) * step)
        return np.mean(off <= min(FIT * step, TYPED[geographic])) >= STEP_SHARE

    steps = [s for s in divisors(label_step, geographic, STEP_SPAN) if divides(s)]
    if (not steps or abs(steps[0] - label_step) > 1e-9 * max(label_step, 1)) and divides(label_step):
        steps = [label_step] + steps  # a step no list holds (10 000 yards in a metre CRS...)
    return steps or None


STEP_SHARE = 0.75  # of an axis's label values, those a step must divide (a misread label need not)


def _crossings(families, width: int, height: int) -> np.ndarray:
    """Crossings (rows of scan x, y, grid x, y) of the lines of the two extreme values of each axis, each line
    placed from the labels of the edges that carry it (one edge: the line runs along the scan's axis)."""
    rows = []
    extremes = []
    for axis in (0, 1):
        edges, sign = families[axis]
        values = sorted({v for e in edges for v in e.values.values()})
        extremes.append((edges, sign, (values[0], values[-1])))
    (ex, sx, vx), (ey, sy, vy) = extremes
    for gx in vx:
        for gy in vy:
            px = _intersect(_line(ex, gx, 0), _line(ey, gy, 1))
            if np.isfinite(px).all():
                rows.append([px[0], px[1], sx * gx, sy * gy])
    return np.array(rows).reshape(-1, 4)


def _line(edges, value, axis) -> np.ndarray:
    """Two scan points of the grid line of ``value``: where each edge's labels put it."""
    points = []
    for e in edges:
        p = e.place(value)
        points.append((p, e.across) if axis == 0 else (e.across, p))
    if len(points) == 1:
        p = points[0]
        points.append((p[0], p[1] + 1.0) if axis == 0 else (p[0] + 1.0, p[1]))
    return np.array(points[:2], float)


def _intersect(p, q) -> np.ndarray:
    d1, d2 = p[1] - p[0], q[1] - q[0]
    a = np.column_stack([d1, -d2])
    if abs(np.linalg.det(a)) < 1e-9 * (np.hypot(*d1) * np.hypot(*d2) + 1e-12):
        return np.array([np.nan, np.nan])  # lines parallel: no crossing
    t = np.linalg.solve(a, q[0] - p[0])
    return p[0] + t[0] * d1


def describe_steps(steps, geographic: bool) -> str:
    return ", ".join(describe(s, geographic) for s in steps or [])
