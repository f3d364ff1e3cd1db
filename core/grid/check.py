"""The check of a sheet georeferenced by its own printed grid, and the model it chooses: the one place where
what the crossings are worth is decided.

A sheet has no second image to compare with. Its check holds grid lines out: each line of constant grid x,
and each of constant grid y, is left out in turn, the model is fitted on the other crossings and predicts the
left-out line's crossings (a line of the map's frame, a border or a road taken for a grid line fits crossing by
crossing but not as a line). The model is the simplest whose lines held out are predicted best (similarity,
affine, polynomial 2 or 3, thin plate spline; a polynomial or a spline only over crossings that cover enough of
the sheet to be followed between them). Where the coordinates came from the labels printed in the margins, the
labels must agree with the lattice: each within half a step of its own line, on at least two lines of each
axis, so that a label misread by a whole step cannot move the sheet. A result is verified when its crossings
are sound (enough of them, spread over the sheet, on a lattice the scan holds, near the lattice of whole
lines), the lines held out are within the accuracy asked for, and the labels agree.

Pixels: ``scan`` px of the sheet; ``frame`` px of the result's reference (a north-up raster in the output CRS,
:mod:`hamta.core.grid.register`). The accuracy is asked, and judged, in scan px.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Dict, Optional, Tuple

import numpy as np

from .crossings import lines_held_out
from .finding import SheetFit
from .steps import describe_pair

KINDS = (("affine", 6, 3, 0.0), ("polynomial-2", 12, 4, 0.5), ("polynomial-3", 30, 5, 0.8), ("tps", 12, 4, 0.5))
# the sheet's models, simplest first: the crossings each needs, the lines each way (one held out, the others
# must fix the model's terms along that way), and the share of the sheet they must cover (a polynomial or a spline
# bends wildly beyond them); a similarity where there are too few for an affine (a scanner's two axes differ in
# scale by a few tenths of a per cent: a similarity leaves pixels of it at a large sheet's corners)
BETTER = 0.9  # a model after the simplest is taken when its lines held out are this much closer, and by at least
GAIN_PX = 0.25  # this many scan px (less is within the crossings' own scatter: 0.1-0.3 px on the synthetic sheets)
MIN_CROSSINGS = 4  # a verified sheet needs this many crossings: two lines each way, each held out in turn
MIN_SPREAD = 0.25  # share of the sheet the crossings must cover for a verified result
MIN_SHARE = 0.3  # of the crossings the lattice puts on the sheet, those found on printed lines for a verified result (a
# lattice off the printed grid finds crossings at a tenth of its nodes: tools/calibrate_grid.py)
LABEL_REACH = 0.5  # of a step: a label further from its own line lies nearer another one
MIN_LABEL_LINES = 2  # lines of each axis whose labels must agree with the lattice


@dataclass(frozen=True)
class LabelAgreement:
    """How the labels read agree with the lattice found: for each axis (x, y), the lines whose labels agree and
    the labels that contradict it (text and place)."""

    agreeing: Tuple[int, int]
    contradicting: Tuple[Tuple[str, ...], Tuple[str, ...]]
    edges: Tuple[Tuple[str, ...], Tuple[str, ...]]

    @property
    def agree(self) -> bool:
        return all(n >= MIN_LABEL_LINES and n > 2 * len(bad) for n, bad in zip(self.agreeing, self.contradicting))

    def reasons(self):
        for axis, (n, bad) in enumerate(zip(self.agreeing, self.contradicting)):
            name = "x (longitude, easting)" if axis == 0 else "y (latitude, northing)"
            if n < MIN_LABEL_LINES:
                yield (f"the labels of only {n} line(s) of {name} agree with the printed grid found "
                       f"({MIN_LABEL_LINES} needed, so that one misread label cannot move the sheet)")
            elif n <= 2 * len(bad):
                yield f"labels of {name} contradict the printed grid found: {', '.join(bad[:4])}"

    def to_dict(self) -> dict:
        return {axis: {"lines_agreeing": n, "contradicting": list(bad), "edges": list(edges)}
                for axis, n, bad, edges in zip("xy", self.agreeing, self.contradicting, self.edges)}


@dataclass(frozen=True)
class GridCheck:
    """The grid's check (:mod:`hamta.core.grid.check`), in the shape every front end reads a check in:
    ``verdict``, ``reasons``; ``tolerance_px``, ``error_px`` and ``error_bound_px`` in frame px (the result's
    reference px: the held-out RMS stands for both); the rest in the grid's own words (scan px)."""

    verdict: str
    reasons: Tuple[str, ...]
    tolerance_px: float
    error_px: float
    tolerance_scan_px: float
    held_out_scan_px: float
    lines: Tuple[int, int]
    worst_line_scan_px: float
    crossings: int
    coverage: float
    share_found: float
    apart_px: float
    models: Dict[str, float]
    model: str
    plane: str
    plane_affine_scan_px: Optional[float]
    step: tuple
    step_text: str
    evidence: dict
    labels: Optional[LabelAgreement]
    time_s: float
    sites_xy: np.ndarray = field(repr=False)
    offset_xy: np.ndarray = field(repr=False)
    check: str = "grid-held-out-lines"
    corroboration = None

    @property
    def verified(self) -> bool:
        return self.verdict == "verified"

    @property
    def error_bound_px(self) -> float:
        return self.error_px

    @property
    def agree(self) -> np.ndarray:
        return np.hypot(*self.offset_xy.T) <= self.tolerance_px

    def summary(self) -> str:
        text = (f"each of {sum(self.lines)} grid lines predicted from the others: {self.held_out_scan_px:.2f} scan px "
                f"RMS ({self.crossings} crossings, {self.model})")
        if self.labels is not None:
            text += f"; labels of {self.labels.agreeing[0]} + {self.labels.agreeing[1]} lines agree"
        return text

    def to_dict(self) -> dict:
        def num(v):
            return None if v is None or not np.isfinite(v) else float(v)

        return {"verdict": self.verdict, "reasons": list(self.reasons), "check": self.check,
                "tolerance_px": self.tolerance_px, "tolerance_scan_px": self.tolerance_scan_px,
                "estimated_error_px": num(self.error_px), "error_bound_px": num(self.error_px),
                "held_out_rms_scan_px": num(self.held_out_scan_px),
                "lines_held_out": {"x": self.lines[0], "y": self.lines[1]},
                "worst_line_rms_scan_px": num(self.worst_line_scan_px), "crossings": self.crossings,
                "coverage": self.coverage, "share_found": self.share_found, "lattice_apart_px": num(self.apart_px),
                "model": self.model, "models_held_out_scan_px": {k: num(v) for k, v in self.models.items()},
                "plane": self.plane, "plane_affine_held_out_scan_px": num(self.plane_affine_scan_px),
                "step": list(self.step), "step_text": self.step_text, "lattice": self.evidence,
                "labels": None if self.labels is None else self.labels.to_dict(), "time_s": self.time_s,
                "sites": [{"reference_px": [float(x), float(y)], "offset_px": [float(dx), float(dy)]}
                          for (x, y), (dx, dy) in zip(self.sites_xy, self.offset_xy)]}


def choose_model(asked: Optional[str], fit: SheetFit, scan_px, frame_px, scale: float = 1.0):
    """(kind, (n, 2) frame px error of each crossing predicted without its grid line, {kind: held-out RMS frame
    px}) of the model ``asked``, else of the simplest the check finds best (:data:`KINDS`, :data:`BETTER`,
    :data:`GAIN_PX`; ``scale``: frame px per scan px)."""
    lines = min(len(np.unique(fit.crossings[:, 4 + a])) for a in (0, 1))
    kinds = [asked] if asked else [k for k, least, each, cover in KINDS
                                   if len(scan_px) >= least and lines >= each and fit.spread >= cover]
    best, table = None, {}
    for kind in kinds or ["similarity"]:  # a similarity: from two crossings on each of two lines
        errors = along_frames(held_out_errors(kind, scan_px, frame_px, fit.crossings[:, 4:6]), fit.crossings,
                              frame_px)
        rms = float(np.sqrt(np.mean(np.sum(errors ** 2, axis=1))))
        table[kind] = rms
        if best is None or rms < min(BETTER * best[2], best[2] - GAIN_PX * scale):
            best = (kind, errors, rms)
    return best[0], best[1], table


def along_frames(errors, crossings, frame_px) -> np.ndarray:
    """``errors`` (n, 2, frame px) with a tick's kept along its frame only (its coordinate across the frame is the
    frame's, fitted on the frame's ticks: only its place along the frame tests the model). ``crossings``: rows as
    :class:`hamta.core.grid.finding.SheetFit` holds them (the frames' directions in scan px)."""
    from ..estimation.models import fit_model

    if crossings.shape[1] < 9 or not (crossings[:, 6] >= 0).any():
        return errors
    ticks = crossings[:, 6] >= 0
    linear = fit_model("affine", crossings[:, :2], frame_px).matrix[:2, :2]  # scan directions -> frame px
    d = crossings[ticks, 7:9] @ linear.T
    d /= np.hypot(*d.T)[:, None] + 1e-12
    out = errors.copy()
    out[ticks] = d * np.sum(errors[ticks] * d, axis=1, keepdims=True)
    return out


def held_out_errors(kind: str, src, dst, lines) -> np.ndarray:
    """(n, 2) error of each point of ``dst`` under the model ``kind`` from ``src`` fitted without its grid line
    (``lines``: each point's grid x and y)."""
    from ..estimation.models import MIN_POINTS, fit_model

    return lines_held_out(src, dst, lines, lambda s, d: fit_model(kind, s, d).apply, MIN_POINTS[kind])[0]


def plane_affine(fit: SheetFit) -> Optional[float]:
    """Held-out RMS (scan px) of an affine from the plane to the scan: how straight and even the printed lines
    are in the plane kept (a projection the sheet is drawn in fits within the scan's own accuracy)."""
    if len(fit.crossings) < 6:
        return None
    errors = held_out_errors("affine", fit.crossings[:, 2:4], fit.crossings[:, :2], fit.crossings[:, 4:6])
    return float(np.sqrt(np.mean(np.sum(errors ** 2, axis=1))))


def judge(fit: SheetFit, frame_px, scale: float, asked_model: Optional[str], tolerance_px: float,
          labels: Optional[LabelAgreement], seconds: float) -> Tuple[str, GridCheck]:
    """(the model kind, the :class:`GridCheck`) of the crossings ``fit`` found, mapped to ``frame_px``; ``scale``:
    frame px per scan px at the sheet's centre; ``tolerance_px`` asked in scan px."""
    scan_px = fit.crossings[:, :2]
    kind, errors, table = choose_model(asked_model, fit, scan_px, frame_px, scale)
    held_out = errors / scale
    rms = float(np.sqrt(np.mean(np.sum(held_out ** 2, axis=1))))
    per_line = lines_held_out(scan_px, frame_px, fit.crossings[:, 4:6],
                              lambda s, d: _fitted(kind, s, d), _least(kind))[1]
    reasons = list(_unsound(fit))
    if rms > tolerance_px:
        reasons.append(f"each grid line predicted from the others is off by {rms:.1f} scan px RMS, beyond the "
                       f"{tolerance_px:g} px asked for")
    if labels is not None:
        reasons += list(labels.reasons())
    verdict = "verified" if not reasons else ("suspect" if rms <= 3 * tolerance_px else "failed")
    lines = tuple(len(np.unique(fit.crossings[:, 4 + a])) for a in (0, 1))
    check = GridCheck(verdict, tuple(reasons), tolerance_px * scale, rms * scale, tolerance_px, rms, lines,
                      max(per_line.values()) / scale if per_line else math.inf, len(scan_px), fit.spread,
                      fit.share, fit.apart_px, {k: v / scale for k, v in table.items()}, kind, fit.plane.name,
                      plane_affine(fit), tuple(map(float, fit.step)),
                      describe_pair(fit.step, fit.plane.sheet_crs.is_geographic),
                      fit.evidence.to_dict(), labels, seconds, np.asarray(frame_px, float), errors)
    return kind, check


def _fitted(kind, src, dst):
    from ..estimation.models import fit_model

    return fit_model(kind, src, dst).apply


def _least(kind) -> int:
    from ..estimation.models import MIN_POINTS

    return MIN_POINTS[kind]


def _unsound(fit: SheetFit):
    """Why the crossings cannot verify the sheet, whatever the model."""
    if len(fit.crossings) < MIN_CROSSINGS or min(len(np.unique(fit.crossings[:, 4 + a])) for a in (0, 1)) < 2:
        yield (f"only {len(fit.crossings)} crossings of the printed grid were found ({MIN_CROSSINGS} needed, on two "
               "lines each way)")
    if fit.spread < MIN_SPREAD:
        yield f"the crossings found cover {fit.spread:.0%} of the map ({MIN_SPREAD:.0%} needed)"
    if fit.share < MIN_SHARE:
        yield (f"only {len(fit.crossings)} of the {fit.reachable} crossings the lattice puts among them were found on "
               f"printed lines ({MIN_SHARE:.0%} needed): the lattice may not be the printed grid")
    if fit.apart_px > fit.apart_limit_px:
        yield (f"the crossings' model and the lattice of whole lines differ by {fit.apart_px:.1f} px: a line of the "
               "map may have been taken for a grid line")
    yield from fit.notes
