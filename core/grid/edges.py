"""The labels of one grid axis fitted edge by edge (:mod:`hamta.core.grid.reading` reads and keeps them).

Along an edge, a label's place is a line of its value (of its Mercator ordinate for a chart's latitudes): the
line most of the edge's labels agree with, through a label printed in full, gives each label its value (a label
printed short, minutes alone or a grid number's last digits, completed by its neighbours); the opposite edge's
labels must put the same lines near them. The other axis's scale is held to the first's (square grid cells, a
graticule's conformal or plate carree degrees).

Pixels: the scan's (corner convention).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, List, Optional, Tuple

import numpy as np

from .labels import FULL_DIGITS, Label, normalised

REACH_GLYPHS = 2.0  # glyph heights: how far from the line its edge's labels fit a label may lie (labels are set
# beside their line or tick, as far on each)


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


def axis_scale(family, axis: int, geographic: bool):
    """value, mercator -> the px per unit of value (per unit of a latitude's Mercator ordinate) the other axis's
    labels may have, given the labels of ``axis`` (a tuple: each is allowed): a grid's cells are square (a
    scanner's axes differ by a fraction of a per cent); a graticule's degree of longitude is the cosine of the
    latitude of a degree of latitude where the sheet is drawn conformal or equal-area near it (every projection
    charts and topographic sheets are drawn in), or one degree of latitude on a plate carree (old maps, weather
    charts)."""
    b = float(np.median([abs(e.b) for e in family[0]]))
    if not geographic:
        return lambda value, mercator: (b,)
    if axis == 0:  # degrees of longitude known: latitude's px per degree, or per radian of its Mercator ordinate
        return lambda value, mercator: ((b * 180 / math.pi,) if mercator else
                                        (b / max(math.cos(math.radians(value)), 0.05), b))
    e = family[0][0]  # degrees of latitude known: longitude's px per degree
    lat = math.radians(float(np.mean(list(e.values.values()))))
    per_degree = (abs(e.b) * math.pi / 180,) if e.mercator else (abs(e.b) * math.cos(lat), abs(e.b))
    return lambda value, mercator: per_degree


SCALE_SPREAD = 1.33  # how far the axes' scales may differ from a square or conformal grid (paper, projection)


def axis_family(labels, usable, axis, geographic, fates, scale=None):
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
    :func:`axis_family` takes it."""
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
                    if scale is not None and not any(1 / SCALE_SPREAD <= abs(b) / s <= SCALE_SPREAD
                                                     for s in scale(vi, mercator)):
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
