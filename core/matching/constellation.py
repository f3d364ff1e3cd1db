"""Regions matched as a constellation: the similarity under which most regions of one image fall on regions
of the other (Goshtasby, Stockman and Page 1986, regions' centroids as control points).

No region is matched by its looks alone (a lake drawn on a map and the same lake on a photo of another year
share little but place and rough shape). Each pair of a large target region and a large reference region
proposes a turn (their outlines' radial profiles aligned), a scale (their areas) and a shift (their
centroids); a proposal is scored by the regions it brings onto a region of the other image, of a like area
and the same darker-or-brighter relation, with a tolerance that grows away from the pair (the turn and scale
of one pair are rough). The best proposals are then made exact by a second region each, and the best result
is fitted by least squares on the regions it brings together.

Coordinates: working pixels of each image (corner convention); the similarity maps target to reference.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..detectors.regions import BINS, Regions
from ..estimation.models import LinearModel


@dataclass(frozen=True)
class Constellation:
    """``target``/``reference``: indexes of the regions brought together; ``matrix`` (2 x 3) the similarity,
    target -> reference working px; ``score`` the sum over them of log(area)."""

    target: np.ndarray
    reference: np.ndarray
    matrix: np.ndarray
    score: float


def match_constellation(t: Regions, r: Regions, *, anchors_target: int = 60, anchors_reference: int = 150,
                        kept: int = 30, area_tolerance: float = 0.7, slack: float = 0.1) -> Optional[Constellation]:
    """The best constellation of ``t`` on ``r``, or None where no proposal brings three regions together.
    ``area_tolerance``: natural log of the area ratio a region may differ by from the scale's; ``slack``: the
    first proposals' tolerance per px of distance from their pair."""
    if len(t) < 3 or len(r) < 3:
        return None
    from scipy.spatial import cKDTree

    tree = cKDTree(r.xy)
    scorer = _Scorer(t, r, tree, area_tolerance)
    proposals = []
    for i, j, matrix in _pairs(t, r, anchors_target, anchors_reference):
        score, ok, nearest = scorer(matrix, slack, anchor=r.xy[j])
        proposals.append((score, i, j, ok, nearest))
    proposals.sort(key=lambda p: -p[0])
    best = None
    for _, i, j, ok, nearest in proposals[:kept]:
        for k in np.flatnonzero(ok):
            if np.hypot(*(t.xy[k] - t.xy[i])) < 1e-6:
                continue
            matrix = _similarity(t.xy[[i, k]], r.xy[[j, nearest[k]]])
            result = scorer(matrix)
            if best is None or result[0] > best[0]:
                best = result + (matrix,)
    if best is None or best[1].sum() < 3:
        return None
    for _ in range(2):
        score, ok, nearest, _ = best
        matrix = _similarity(t.xy[ok], r.xy[nearest[ok]])
        again = scorer(matrix)
        if again[0] < score:
            break
        best = again + (matrix,)
    score, ok, nearest, matrix = best
    return Constellation(np.flatnonzero(ok), nearest[ok], matrix, float(score))


def _pairs(t: Regions, r: Regions, n_target: int, n_reference: int):
    """(i, j, similarity) for the largest natural-shaped target regions and the largest reference ones."""
    natural = np.flatnonzero(~t.blocky)
    ti = natural[np.argsort(-t.area[natural], kind="stable")][:n_target]
    rj = np.argsort(-r.area, kind="stable")[:n_reference]
    spectrum_r = np.fft.rfft(r.profile[rj], axis=1)
    for i in ti:
        shifts = np.argmax(np.fft.irfft(spectrum_r * np.conj(np.fft.rfft(t.profile[i])), BINS, axis=1), axis=1)
        for j, shift in zip(rj, shifts):
            turn = 2 * np.pi * shift / BINS
            a = np.sqrt(r.area[j] / t.area[i]) * np.array([[np.cos(turn), -np.sin(turn)],
                                                          [np.sin(turn), np.cos(turn)]])
            yield i, j, np.column_stack([a, r.xy[j] - a @ t.xy[i]])


class _Scorer:
    """Scores a similarity: the regions of the target it brings within tolerance of a reference region."""

    def __init__(self, t: Regions, r: Regions, tree, area_tolerance: float):
        self.t, self.r, self.tree, self.area_tolerance = t, r, tree, area_tolerance
        self.weight = np.log(np.maximum(t.area, 2.0))

    def __call__(self, matrix, slack: float = 0.0, anchor=None):
        t, r = self.t, self.r
        moved = t.xy @ matrix[:, :2].T + matrix[:, 2]
        distance, nearest = self.tree.query(moved)
        tolerance = np.maximum(1.5, 0.15 * np.sqrt(r.area[nearest]))
        if slack:
            tolerance = tolerance + slack * np.hypot(*(moved - anchor).T)
        scale2 = max(abs(np.linalg.det(matrix[:, :2])), 1e-12)
        ok = (distance < tolerance) & (np.abs(np.log(r.area[nearest] / (t.area * scale2))) < self.area_tolerance)
        same = t.dark == r.dark[nearest]
        ok &= same if (same & ok).sum() >= (~same & ok).sum() else ~same
        best = np.zeros(len(r))
        np.maximum.at(best, nearest[ok], self.weight[ok])
        return float(best.sum()), ok, nearest


def _similarity(src, dst) -> np.ndarray:
    """The least-squares similarity src -> dst (exact through two points), 2 x 3."""
    return LinearModel.fit("similarity", src, dst).matrix[:2]
