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

import math
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

import numpy as np

from .check import LABEL_REACH, LabelAgreement
from .labels import FULL_DIGITS, Label, joined, normalised, parse
from .ocr import INSTALL, bands, engine, engines, find_words, read_words, reread, unique
from .steps import FIT, TYPED, describe, divisors

BAND = 0.12  # of the sheet's shorter side: how deep each edge's band is read first (labels of a sheet scanned
WIDE = 0.25  # with its margins), then how deep where the first band gives no line of an axis (a wide scanner bed)
CHUNK_PX = 4000  # a band is read in pieces this long (memory), overlapping by the band's depth
REACH_GLYPHS = 2.0  # glyph heights: how far from the line its edge's labels fit a label may lie (labels are set
# beside their line or tick, as far on each)
STEP_SPAN = 10  # the lattice is tried at the labels' step and the usual steps dividing it, down to a tenth
SIDES = {0: ("top", "bottom"), 1: ("left", "right")}
TURN = 10.0  # degrees: how far a sheet whose labels are read upright may be turned (and its lines converge)


@dataclass
class Edge:
    """The labels of one edge fitted: place along the edge = ``a`` + ``b`` * ``warp``(value), ``across`` the
    median place of its labels across the edge; ``values``: label index -> its (unsigned) value."""

    side: str
    a: float
    b: float
    mercator: bool
    across: float
    values: Dict[int, float]
    score: float = 0.0  # the agreeing labels, each counted by the engine's confidence in it

    def place(self, value: float) -> float:
        return self.a + self.b * _warp(abs(value), self.mercator)

    def value_at(self, place: float) -> float:
        """The (unsigned) value this edge's labels put at ``place`` along the edge."""
        w = (place - self.a) / self.b
        return math.degrees(2 * math.atan(math.exp(w)) - math.pi / 2) if self.mercator else w

    def confirms(self, place: float, value: float, span: float = 0.0) -> bool:
        """Whether this edge puts ``value`` near ``place``, on the opposite edge ``span`` px away: within half its
        labels' smallest difference, and as far as lines turned by :data:`TURN` degrees drift over ``span``."""
        values = np.unique(list(self.values.values()))
        gap = float(np.diff(values).min()) if len(values) > 1 else math.inf
        drift = abs(self.value_at(place + span * math.tan(math.radians(TURN))) - self.value_at(place))
        return abs(self.value_at(place) - value) < 0.5 * gap + drift


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
        """How the kept labels agree with the crossings ``fit`` found (a :class:`hamta.core.grid.sheet.SheetFit`):
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
    alone = {axis: _family(labels, usable[axis], axis, geographic, list(fates)) for axis in (0, 1)}
    first = max((0, 1), key=lambda axis: -1.0 if alone[axis] is None else sum(e.score for e in alone[axis][0]))
    for axis in (first, 1 - first):  # the surer axis first: its scale says what the other's may be
        scale = None if axis == first or families[first] is None else _scale(families[first], first, geographic)
        family = _family(labels, usable[axis], axis, geographic, fates, scale)
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


def _candidates(labels: List[Label], usable: List[int], geographic: bool) -> Dict[int, List[Tuple[float, bool]]]:
    """label index -> [(unsigned value, whole: printed in full)] for each label of one axis: parts a label leaves
    out taken from the full labels of the axis (their degrees, minutes or leading digits, and the next ones)."""
    out: Dict[int, List[Tuple[float, bool]]] = {}
    if geographic:
        degrees = sorted({labels[i].degrees for i in usable if labels[i].degrees is not None})
        minutes = sorted({(labels[i].degrees, labels[i].minutes or 0.0) for i in usable
                          if labels[i].degrees is not None})
        around = sorted({d + k for d in degrees for k in (-1, 0, 1) if d + k >= 0})
        for i in usable:
            lab = labels[i]
            values = []
            if lab.degrees is not None:
                values.append((lab.degrees + (lab.minutes or 0) / 60 + (lab.seconds or 0) / 3600, True))
            elif lab.minutes is not None:
                values += [(d + lab.minutes / 60 + (lab.seconds or 0) / 3600, False) for d in around]
            elif lab.seconds is not None:  # seconds; or minutes whose prime the engine doubled
                values += [(d + (m + k) / 60 + lab.seconds / 3600, False) for d, m in minutes for k in (-1, 0, 1)
                           if 0 <= m + k < 60]
                values += [(d + lab.seconds / 60, False) for d in around]
            if values:
                out[i] = values
        return out
    full = [labels[i].number for i in usable if labels[i].digits >= FULL_DIGITS]
    for i in usable:
        lab = labels[i]
        if lab.digits >= FULL_DIGITS:
            out[i] = [(lab.number, True)]
        elif full and lab.digits <= 2 and len(normalised(lab.text)) == 2:  # abbreviated: the kilometres' last
            values = set()  # two digits, as topographic sheets print them between full values (85 for 6 785 000)
            for f in full:
                base = math.floor(f / 1000 / 100) * 100
                values |= {(base + k * 100 + lab.number) * 1000 for k in (-1, 0, 1)}
            out[i] = [(v, False) for v in sorted(values) if v > 0]
    return out


def _scale(family, axis: int, geographic: bool):
    """value -> the px per unit of value (per unit of a latitude's Mercator ordinate) the other axis's labels
    should have, given the labels of ``axis``: a grid's cells are square (a scanner's axes differ by a fraction of
    a per cent); a graticule's degree of longitude is the cosine of the latitude of a degree of latitude (every
    projection charts are drawn in keeps this near the sheet)."""
    b = float(np.median([abs(e.b) for e in family[0]]))
    if not geographic:
        return lambda value, mercator: b
    if axis == 0:  # degrees of longitude known: latitude's px per degree, or per radian of its Mercator ordinate
        return lambda value, mercator: b * (180 / math.pi if mercator else 1 / max(math.cos(math.radians(value)),
                                                                                  0.05))
    e = family[0][0]  # degrees of latitude known: longitude's px per degree
    lat = math.radians(float(np.mean(list(e.values.values()))))
    per_degree = abs(e.b) * math.pi / 180 if e.mercator else abs(e.b) * math.cos(lat)
    return lambda value, mercator: per_degree


SCALE_SPREAD = 1.33  # how far the axes' scales may differ from a square or conformal grid (paper, projection)


def _family(labels, usable, axis, geographic, fates, scale=None):
    """([:class:`Edge`] of each edge whose labels agree, the sign of the values: -1 west or south), or None where
    no edge has two labels of distinct values that agree, one of them whole (printed in full, or completed as the
    opposite edge's labels put the same line). ``scale``: value, mercator -> the px per unit the other axis
    expects (within :data:`SCALE_SPREAD`), or None."""
    cands = _candidates(labels, usable, geographic)
    for i in usable:
        if i not in cands:
            fates[i] = ("no full label (with its degrees, or the leading digits) on this axis to complete it"
                        if fates[i] == "not used" else fates[i])
    own = {}
    for side in SIDES[axis]:  # each edge alone; the one most labels agree on then completes and checks the other
        mine = [i for i in cands if labels[i].side == side]
        own[side] = (mine, _fit_edge(labels, mine, cands, {i: {v for v, w in cands[i] if w} for i in mine}, axis,
                                     geographic and axis == 1, scale))
    ranked = sorted((side for side in own if own[side][1] is not None), key=lambda side: -own[side][1].score)
    if not ranked:
        return None
    first = own[ranked[0]][1]
    edges = []
    for side in SIDES[axis]:  # the other edge: its labels' values where the first edge puts the same lines
        mine = own[side][0]
        if side == first.side:
            fitted = first
        else:
            span = abs(np.mean([labels[i].xy[1 - axis] for i in first.values]) -
                       np.mean([labels[i].xy[1 - axis] for i in mine])) if mine else 0.0
            near = {i: [(v, True) for v, _ in cands[i] if first.confirms(labels[i].xy[axis], v, span)] for i in mine}
            near = {i: c for i, c in near.items() if c}
            fitted = _fit_edge(labels, list(near), near, {i: {v for v, _ in c} for i, c in near.items()}, axis,
                               geographic and axis == 1, scale)
            if fitted is None:
                for i in mine:
                    fates[i] = (f"agrees with no line the {first.side} edge's labels put near it"
                                if fates[i] == "not used" else fates[i])
                continue
        edges.append(fitted)
        for i in mine:
            if i not in fitted.values:
                fates[i] = f"contradicts the other labels of the {side} edge"
    if not edges:
        return None
    grows = np.sign(np.mean([np.sign(e.b) for e in edges]))
    natural = 1.0 if axis == 0 else -1.0  # x grows rightwards, y (northing, latitude) upwards: scan y downwards
    letters = [labels[i].hemisphere for e in edges for i in e.values if labels[i].hemisphere]
    if letters:
        sign = -1.0 if max(set(letters), key=letters.count) in "WS" else 1.0
    else:
        sign = 1.0 if grows == natural else -1.0
    if not geographic and sign < 0:
        for e in edges:
            for i in e.values:
                fates[i] = "the grid's values run the wrong way (the sheet upside down or mirrored?)"
        return None
    return edges, sign


def _fit_edge(labels, mine, cands, wholes, axis, latitude, scale=None) -> Optional[Edge]:
    """The :class:`Edge` most of ``mine`` (label indexes of one edge) agree with, or None without two agreeing
    labels of distinct values, one of them whole (``wholes``: the values of each label that are); ``scale`` as
    :func:`_family` takes it."""
    if len(mine) < 2:
        return None
    place = {i: labels[i].xy[axis] for i in mine}
    reach = {i: REACH_GLYPHS * labels[i].glyph_px for i in mine}
    best, best_key = None, None
    anchors = [(i, v) for i in mine for v in wholes[i]]
    for mercator in ((False, True) if latitude else (False,)):
        for i, vi in anchors:  # a line through a whole label and any other label's value
            wi = _warp(vi, mercator)
            for j in mine:
                for vj, _ in cands[j]:
                    if j == i or abs(vi - vj) < 1e-9:
                        continue
                    b = (place[j] - place[i]) / (_warp(vj, mercator) - wi)
                    a = place[i] - b * wi
                    if scale is not None and not 1 / SCALE_SPREAD <= abs(b) / scale(vi, mercator) <= SCALE_SPREAD:
                        continue
                    fit, misfit = {}, 0.0
                    for k in mine:
                        off, v = min((abs(place[k] - a - b * _warp(v, mercator)), v) for v, _ in cands[k])
                        if off <= reach[k]:
                            fit[k] = v
                            misfit += (off / labels[k].glyph_px) ** 2
                    whole = sum(fit[k] in wholes[k] for k in fit)
                    key = (round(sum(_weight(labels[k]) for k in fit), 6), whole, -misfit)
                    if best_key is None or key > best_key:
                        best, best_key = (a, b, mercator, fit), key
    if best is None or len(best[3]) < 2:
        return None
    a, b, mercator, fit = best
    if len(fit) >= 3:  # the line refitted on all that agree
        x = np.array([_warp(v, mercator) for v in fit.values()])
        b, a = np.polyfit(x, np.array([place[k] for k in fit]), 1)
    across = float(np.median([labels[k].xy[1 - axis] for k in fit]))
    return Edge(labels[next(iter(fit))].side, float(a), float(b), mercator, across, fit, best_key[0])


def _weight(lab: Label) -> float:
    """How much a label counts in a fit: the engine's confidence in it (0-100), from a tenth up (a misread
    label still tells its place); a number without marks a third of that (a sounding, a height, or minutes whose
    mark was lost)."""
    return max(lab.confidence, 10.0) / 100.0 * (1.0 if lab.marked or lab.whole else BARE)


BARE = 1 / 3


def _warp(value: float, mercator: bool) -> float:
    """A latitude's Mercator ordinate (radians), or the value itself."""
    if not mercator:
        return value
    phi = math.radians(min(abs(value), 89.9))
    return math.log(math.tan(math.pi / 4 + phi / 2))


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
