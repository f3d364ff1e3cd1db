"""A sheet's printed coordinates read from the labels in its margins, as hints (two or three crossings with
their coordinates) for :func:`hamta.core.grid.sheet.fit_sheet`: the sheet georeferenced with no click.

Text is read by Tesseract (the ``tesseract`` program, Debian's ``tesseract-ocr``: its English model ships
in the package; nothing is downloaded), band by band along the four edges of the scan, read window by
window. A label is degrees (``146°``, ``44°27'``, ``72°N``), minutes alone (``30'``: the degree from its
neighbours) or metres of a grid (``503000``; ``85`` for 6 785 000 when a full value of the same edge gives
the leading digits). Labels on the top and bottom edges count along x, those on the left and right along
y; each family's values are fitted robustly against their place (a label that contradicts the others is
named), and lines of the same value on opposite edges give each grid line, so that a sheet turned a little
is followed. Where values of x fall to the right, the degrees are west; where values of y grow downwards,
south. Assumed: the labels read upright (a sheet turned by more than about 30 degrees is not read; hints
are then needed).

Pixels: the scan's (corner convention).
"""
from __future__ import annotations

import math
import os
import re
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from typing import List, Optional

import numpy as np

from ..errors import InputError, InsufficientMatchesError

TESSERACT = "tesseract"
BAND = 0.2  # of the sheet's shorter side: how deep each edge's band is read (margins of small sheets are wide)
CHUNK_PX = 4000  # a band is read in pieces this long (Tesseract's time and memory), overlapping by a label
MIN_CONFIDENCE = 60.0  # Tesseract's word confidence (0-100) a number alone needs to be taken for metres (a
# degree sign, or minutes, make a label whatever the confidence: the fit of each family leaves out what disagrees)
MIN_LABELS = 3  # per family of lines, agreeing
PLACED = 0.05  # of a step: how far from where the sheet's CRS puts its line a label of one edge may be
DEGREE = r"(\d{1,3})\s*[°ºo]\s*(?:(\d{1,2}(?:\.\d+)?)\s*['’′`!]?)?\s*([NSEW])?"
MINUTES = r"(\d{1,2})\s*['’′`]"
METRES = r"(\d{2,7})(?:\s*m)?"


@dataclass(frozen=True)
class Label:
    """One label read: its ``text``; ``value`` (degrees, or metres; minutes alone: 0-59 until resolved);
    ``kind`` 'degrees', 'minutes' or 'metres'; ``hemisphere`` a letter printed with it or ''; ``xy`` its
    centre (scan px); ``side`` 'top', 'bottom', 'left' or 'right'."""

    text: str
    value: float
    kind: str
    hemisphere: str
    xy: tuple
    side: str


def tesseract_available() -> bool:
    return shutil.which(TESSERACT) is not None


def read_labels(read_window, width: int, height: int, check=lambda: None) -> List[Label]:
    """Every label read in the four edge bands of a ``width`` x ``height`` scan; ``read_window(x0, y0, x1, y1)``
    returns the grey window (uint8-like values). Raises :class:`InputError` without Tesseract."""
    if not tesseract_available():
        raise InputError("Reading the sheet's printed labels needs Tesseract (Debian, Ubuntu: 'sudo apt install "
                         "tesseract-ocr'); without it, give two or three crossings with their coordinates as "
                         "hints (a QGIS Georeferencer .points file).")
    depth = int(BAND * min(width, height))
    jobs = []
    for side in ("top", "bottom", "left", "right"):
        horizontal = side in ("top", "bottom")
        length = width if horizontal else height
        for start in range(0, length, CHUNK_PX - depth):
            stop = min(start + CHUNK_PX, length)
            if horizontal:
                box = (start, 0 if side == "top" else height - depth, stop, depth if side == "top" else height)
            else:
                box = (0 if side == "left" else width - depth, start, depth if side == "left" else width, stop)
            jobs.append((side, box))
            if stop == length:
                break

    def read(job):
        check()
        side, (x0, y0, x1, y1) = job
        grey = np.clip(read_window(x0, y0, x1, y1), 0, 255).astype(np.uint8)
        found = []
        for text, (cx, cy), conf in _words(grey, side in ("left", "right")):
            parsed = parse(text)
            if parsed is not None and conf >= (MIN_CONFIDENCE if parsed[1] == "metres" else 0.0):
                found.append(Label(text, *parsed, (x0 + cx, y0 + cy), side))
        return found

    from concurrent.futures import ThreadPoolExecutor

    with ThreadPoolExecutor(max_workers=max(os.cpu_count() or 1, 1)) as pool:  # Tesseract runs in processes
        labels = [lab for found in pool.map(read, jobs) for lab in found]
    return _unique(labels)


def parse(text: str):
    """(value, kind, hemisphere) of a label's text, or None where it is not a coordinate."""
    text = text.strip().strip(",;:()[]")
    m = re.fullmatch(DEGREE, text)
    if m:
        value = float(m.group(1)) + (float(m.group(2)) / 60 if m.group(2) else 0.0)
        return (value, "degrees", m.group(3) or "") if value <= 360 and (m.group(2) is None or
                                                                        float(m.group(2)) < 60) else None
    m = re.fullmatch(MINUTES, text)
    if m:
        return (float(m.group(1)), "minutes", "") if float(m.group(1)) < 60 else None
    m = re.fullmatch(METRES, text)
    if m:
        return float(m.group(1)), "metres", ""
    return None


def hints_from_labels(labels: List[Label], width: int, height: int, geographic: bool, to_crs=None):
    """(hints: rows of scan x, y, grid x, y of three crossings far apart; the labels that contradict the
    others, as text, but those of the other family read in a corner). ``to_crs``: a pyproj Transformer from
    the printed coordinates to the sheet's CRS, in which places along an edge are fitted (a Mercator chart's
    parallels are not evenly spaced in degrees).
    Raises :class:`InsufficientMatchesError` where too few labels agree."""
    kind = "degrees" if geographic else "metres"
    families, contradicting = {}, []
    for axis, sides in ((0, ("top", "bottom")), (1, ("left", "right"))):
        mine = [lab for lab in labels if lab.side in sides and lab.kind in ((kind, "minutes") if geographic else
                                                                             (kind,))]
        fitted, bad = _family(mine, axis, geographic)
        contradicting.append(bad)
        if fitted is None:
            raise InsufficientMatchesError(
                f"Too few printed coordinates were read along the sheet's {' and '.join(sides)} edges "
                f"({len(mine)} labels in {kind}, {MIN_LABELS} agreeing needed): give two or three crossings with "
                "their coordinates as hints (a QGIS Georeferencer .points file).", len(mine), MIN_LABELS)
        families[axis] = fitted
    for axis in (0, 1):
        other = float(np.median(families[1 - axis]["lines"]))
        families[axis]["project"] = _projection(to_crs, axis, other)
        families[axis]["sides"] = {}
        for side, (places, values) in families[axis]["points"].items():
            fit = _robust_line([(p, families[axis]["project"](v)) for p, v in zip(places, values)], PLACED, 2)
            if fit is not None:  # the labels of one edge where the sheet's CRS puts them: a label a tenth of a
                families[axis]["sides"][side] = fit[:2]  # step off its line is not one of them
        if not families[axis]["sides"]:
            raise InsufficientMatchesError("The printed coordinates read do not fall where the sheet's CRS puts "
                                           "them: check the CRS, or give two or three crossings as hints.", 0, 2)
    named = [f"'{lab.text}' at ({lab.xy[0]:.0f}, {lab.xy[1]:.0f})" for axis, bad in enumerate(contradicting)
             for lab in bad if not families[1 - axis]["agrees"](lab)]  # not a label of the other edges' lines
    return _crossings(families, width, height), named


def _projection(to_crs, axis: int, other: float):
    """value of the family -> its coordinate in the sheet's CRS (the other coordinate held at ``other``)."""
    if to_crs is None:
        return lambda v: v
    if axis == 0:
        return lambda v: float(to_crs.transform(v, other)[0])
    return lambda v: float(to_crs.transform(other, v)[1])


def _family(labels: List[Label], axis: int, geographic: bool):
    """({"points": {side: (places, signed values) of the labels that agree}, "lines": the signed values of the
    grid lines labelled in full}, the labels that contradict), or (None, ...) with fewer than
    :data:`MIN_LABELS` agreeing. Minutes alone take their degree from the fit of the full labels; metres
    abbreviated (``85``) their leading digits from a full value."""
    labels = _expanded(labels)
    full = [lab for lab in labels if lab.kind != "minutes"]
    fit = _robust_line([(lab.xy[axis], lab.value) for lab in full])
    if fit is None:
        return None, []
    a, b, tol = fit
    values = []
    for lab in labels:
        value = lab.value
        if lab.kind == "minutes":
            guess = a + b * lab.xy[axis]
            degrees = np.floor(abs(guess)) + np.array([-1, 0, 1])
            value = float(min(degrees + lab.value / 60, key=lambda v: abs(v - abs(guess))))
        values.append(value)
    places = np.array([lab.xy[axis] for lab in labels])
    values = np.array(values)
    agree = np.abs(a + b * places - values) <= tol
    printed_in_full = np.array([lab.kind != "metres" or len(re.sub(r"\D", "", lab.text)) >= 6 for lab in labels])
    if agree.sum() < MIN_LABELS or (agree & printed_in_full).sum() < 2:  # abbreviated metres rest on two full
        return None, []  # values that agree: one misread (a digit lost) would move the whole family
    sign = -1.0 if geographic and (b < 0 if axis == 0 else b > 0) else 1.0  # west, south
    points = {}
    for side in {lab.side for lab in labels}:
        on = agree & np.array([lab.side == side for lab in labels])
        if on.sum() >= 2:
            points[side] = (places[on], sign * values[on])
    bad = [lab for lab, ok in zip(labels, agree) if not ok]
    lines = sorted({round(sign * v, 9) for v, ok, lab in zip(values, agree, labels) if ok and lab.kind != "minutes"})
    fitted = {"points": points, "lines": lines, "agrees": lambda lab: _agrees(lab, axis, a, b, tol)}
    return (fitted if points and len(lines) >= 2 else None), bad


def _agrees(lab: Label, axis: int, a: float, b: float, tol: float) -> bool:
    """Whether ``lab`` fits a family's values (a + b * place, unsigned) within ``tol`` (minutes alone: any)."""
    if lab.kind == "minutes":
        return True
    return abs(a + b * lab.xy[axis] - lab.value) <= tol


def _expanded(labels: List[Label]) -> List[Label]:
    """Metres printed in full (six digits or more) kept; abbreviated ones (the kilometres' last digits, ``85``
    for 6 785 000) completed from the nearest full value's leading digits, or left out without one."""
    metres = [lab for lab in labels if lab.kind == "metres"]
    if not metres:
        return labels
    full = [lab for lab in metres if lab.value >= 1e5]
    out = [lab for lab in labels if lab.kind != "metres"] + full
    for lab in metres:
        if lab.value >= 1e5 or not full:
            continue
        modulus = 10 ** len(str(int(lab.value)))
        km = min(full, key=lambda f: math.hypot(f.xy[0] - lab.xy[0], f.xy[1] - lab.xy[1])).value / 1000
        base = math.floor(km / modulus) * modulus
        value = min((base + d * modulus + lab.value for d in (-1, 0, 1)), key=lambda v: abs(v - km))
        out.append(Label(lab.text, value * 1000, "metres", "", lab.xy, lab.side))
    return out


def _robust_line(points, share: float = 0.2, least: int = MIN_LABELS):
    """(a, b, tolerance) of value = a + b * place agreeing with most ``points`` (pairs tried in turn; the
    tolerance ``share`` of the median step between neighbouring values), or None with fewer than ``least``."""
    if len(points) < least:
        return None
    p = np.array(points, float)
    steps = np.diff(np.unique(p[:, 1]))
    if not len(steps):
        return None
    tol = share * float(np.median(steps))
    best, best_n = None, 0
    for i in range(len(p)):
        for j in range(i + 1, len(p)):
            if abs(p[j, 0] - p[i, 0]) < 1e-6 or p[j, 1] == p[i, 1]:
                continue
            b = (p[j, 1] - p[i, 1]) / (p[j, 0] - p[i, 0])
            a = p[i, 1] - b * p[i, 0]
            n = int((np.abs(a + b * p[:, 0] - p[:, 1]) <= tol).sum())
            if n > best_n:
                best, best_n = (a, b), n
    if best is None or best_n < least:
        return None
    on = np.abs(best[0] + best[1] * p[:, 0] - p[:, 1]) <= tol
    b, a = np.polyfit(p[on, 0], p[on, 1], 1)
    return float(a), float(b), tol


def _crossings(families, width: int, height: int) -> np.ndarray:
    """Three crossings far apart (rows of scan x, y, grid x, y) of the grid lines labelled in full, each line
    placed from the labels of opposite edges (one edge: the line runs along the scan's axis)."""
    xs, ys = families[0]["lines"], families[1]["lines"]
    rows = []
    for vx, vy in ((xs[0], ys[0]), (xs[-1], ys[-1]), (xs[0], ys[-1])):
        px = _intersect(_line(families[0], vx, 0, width, height), _line(families[1], vy, 1, width, height))
        rows.append([px[0], px[1], vx, vy])
    return np.array(rows)


def _line(family, value, axis, width, height):
    """Two scan points of the grid line of ``value``: where each edge's labels put it."""
    points = []
    for side, (a, b) in family["sides"].items():
        place = (family["project"](value) - a) / b
        edge = {"top": 0.0, "bottom": float(height), "left": 0.0, "right": float(width)}[side]
        points.append((place, edge) if axis == 0 else (edge, place))
    if len(points) == 1:
        p = points[0]
        points.append((p[0], p[1] + 1.0) if axis == 0 else (p[0] + 1.0, p[1]))
    return np.array(points[:2], float)


def _intersect(p, q) -> np.ndarray:
    d1, d2 = p[1] - p[0], q[1] - q[0]
    t = np.linalg.solve(np.column_stack([d1, -d2]), q[0] - p[0])
    return p[0] + t[0] * d1


def _words(grey: np.ndarray, along: bool):
    """(text, centre in the window, confidence) of each word Tesseract reads, in ``grey`` as it is
    and, ``along`` a side edge, turned a quarter both ways (labels there are often printed along it)."""
    import cv2

    h, w = grey.shape
    for turn in (None,) + ((cv2.ROTATE_90_CLOCKWISE, cv2.ROTATE_90_COUNTERCLOCKWISE) if along else ()):
        image = grey if turn is None else cv2.rotate(grey, turn)
        for text, (cx, cy), conf in _tesseract(image):
            if turn == cv2.ROTATE_90_CLOCKWISE:  # (x, y) of the turned image -> the window's
                cx, cy = cy, h - cx
            elif turn == cv2.ROTATE_90_COUNTERCLOCKWISE:
                cx, cy = w - cy, cx
            yield text, (cx, cy), conf


def _tesseract(image: np.ndarray):
    import cv2

    with tempfile.TemporaryDirectory(prefix="hamta-ocr-") as folder:
        path = os.path.join(folder, "band.png")
        cv2.imwrite(path, image)
        try:
            out = subprocess.run([TESSERACT, path, "stdout", "--psm", "11", "tsv"], capture_output=True, text=True,
                                 timeout=120, check=False, env=dict(os.environ, OMP_THREAD_LIMIT="1")).stdout
        except (OSError, subprocess.TimeoutExpired):
            return []
    words = []
    for line in out.splitlines()[1:]:
        cells = line.split("\t")
        if len(cells) < 12 or not cells[11].strip():
            continue
        try:
            left, top, w, h, conf = (float(c) for c in cells[6:11])
        except ValueError:
            continue
        words.append((cells[11], (left + w / 2, top + h / 2), conf))
    return words


def _unique(labels: List[Label]) -> List[Label]:
    """Labels read twice (overlapping pieces, two turns) kept once."""
    kept: List[Label] = []
    for lab in labels:
        if not any(k.value == lab.value and math.hypot(k.xy[0] - lab.xy[0], k.xy[1] - lab.xy[1]) < 20 for k in kept):
            kept.append(lab)
    return kept


def label_note(labels: List[Label], contradicting: List[str]) -> Optional[str]:
    if not contradicting:
        return None
    return (f"{len(contradicting)} of the {len(labels)} labels read contradict the others and were left out: "
            + ", ".join(contradicting[:8]))
