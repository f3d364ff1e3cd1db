"""Printed lines of a scanned sheet and where two of them cross, to a fraction of a pixel.

Pixels: the scan's (x = column, y = row, corner convention: the centre of pixel (0, 0) is (0.5, 0.5)).
A grid line or graticule line is thin and darker than the paper around it; :func:`line_map` keeps what
is thin and dark (a black top-hat) so that map fills, shading and the paper's tone do not count.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

LINE_WIDTH_PX = 9  # the top-hat's side: lines up to about half of this wide are kept whole (printed grids:
# 1-4 px at 150-300 dpi)
PROMINENCE = 2.0  # a line is found in a window when its profile's peak stands this many robust deviations
# (median absolute deviation) above the profile's median


def line_map(grey: np.ndarray, width_px: int = LINE_WIDTH_PX) -> np.ndarray:
    """How much each pixel of ``grey`` (2-D, any dtype) belongs to a thin dark line: float32, 0 on the
    paper and on wide dark areas."""
    import cv2

    image = grey.astype(np.float32)
    kernel = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (width_px, width_px))
    return cv2.morphologyEx(image, cv2.MORPH_BLACKHAT, kernel)


@dataclass(frozen=True)
class Crossing:
    """Where two lines cross: ``xy`` (scan px), how clearly each line stands out (``strength``, the weaker of
    the two profiles' prominences) and how much ink the weaker line holds (``ink``, its peak above the
    profile's median, in the line map's units)."""

    xy: tuple
    strength: float
    ink: float = 0.0


def crossing(source, xy, directions, radius: float, along=None) -> Optional[Crossing]:
    """The crossing nearest ``xy`` of two lines running along ``directions`` (two unit vectors, scan px):
    each line is the sub-pixel peak of the :func:`line_map` of ``source`` (a
    :class:`hamta.core.grid.scan.LineSource`) averaged along it over ``along`` px each way (a long strip: a
    grid line is long and straight, what else is drawn is not; a pair: each line's, a tick's short) at offsets up
    to ``radius`` px across it. None where either line does not stand out (:data:`PROMINENCE`) or the strips
    leave the scan."""
    alongs = [max(a or 3.0 * radius, radius) for a in (along if isinstance(along, (tuple, list)) else (along,) * 2)]
    across = max(radius, PROFILE_PX)  # the profile spans a wide line and the paper beside it; nearer peaks weigh more
    window = source.around(xy, max(alongs) + across + 2)
    if window is None:
        return None
    lines, x0, y0 = window
    found, strength, ink = [], math.inf, math.inf
    for (dx, dy), reach in zip(directions, alongs):
        profile = _strip(lines, (xy[0] - x0, xy[1] - y0), (dx, dy), reach, across)
        if profile is None:
            return None
        offsets = (np.arange(len(profile)) - (len(profile) - 1) / 2) / STEPS_PER_PX
        peak = _profile_peak(profile, np.exp(-0.5 * (offsets / radius) ** 2))  # the nearer of two lines
        if peak is None:
            return None
        found.append((peak[0] - (len(profile) - 1) / 2) / STEPS_PER_PX)
        strength, ink = min(strength, peak[1]), min(ink, peak[2])
    (d1x, d1y), (d2x, d2y) = directions
    normals = np.array([[-d1y, d1x], [-d2y, d2x]], float)
    if abs(np.linalg.det(normals)) < 0.2:  # lines almost parallel: no crossing to find
        return None
    ox, oy = np.linalg.solve(normals, np.array(found))
    return Crossing((xy[0] + ox, xy[1] + oy), strength, ink)


STEPS_PER_PX = 2  # samples across a line per pixel
PROFILE_PX = LINE_WIDTH_PX  # px each side: the least a profile across a line spans (the widest line the line map
# keeps whole, about half of it, and as much paper)


def _strip(lines, xy, direction, along: float, radius: float):
    """The mean of ``lines`` along ``direction`` through ``xy`` (over ``along`` px each way) at each offset
    across it, -radius..radius px in 1/:data:`STEPS_PER_PX` steps; None where the strip leaves the scan."""
    import cv2

    dx, dy = direction
    t = np.arange(-along, along + 0.5)
    n = int(round(radius * STEPS_PER_PX))
    s = np.arange(-n, n + 1) / STEPS_PER_PX
    tt, ss = np.meshgrid(t, s)
    mx = xy[0] + tt * dx - ss * dy - 0.5  # map x; -0.5: corner to centre convention for remap
    my = xy[1] + tt * dy + ss * dx - 0.5
    h, w = lines.shape
    if mx.min() < 0 or my.min() < 0 or mx.max() > w - 1 or my.max() > h - 1:
        return None
    values = cv2.remap(lines, mx.astype(np.float32), my.astype(np.float32), cv2.INTER_LINEAR)
    return np.median(values, axis=1) + values.mean(axis=1)


def _profile_peak(profile: np.ndarray, weights: np.ndarray):
    """(the index of the profile's peak, to a fraction, its prominence and its height above the median) or
    None: the peak of ``profile`` that ``weights`` favour (the nearer of two lines), climbed to the profile's own
    top, whose prominence is the profile's own (weights make a peak of any ink, a line's or none)."""
    median = np.median(profile)
    spread = np.median(np.abs(profile - median)) * 1.4826 + 1e-6
    i = int(np.argmax(profile * weights))
    while 0 < i < len(profile) - 1 and max(profile[i - 1], profile[i + 1]) > profile[i]:
        i += 1 if profile[i + 1] > profile[i - 1] else -1
    prominence = (profile[i] - median) / spread
    if prominence < PROMINENCE or i == 0 or i == len(profile) - 1:
        return None
    left, mid, right = profile[i - 1], profile[i], profile[i + 1]
    denom = left - 2 * mid + right
    shift = 0.0 if denom >= 0 else 0.5 * (left - right) / denom
    return i + shift, float(prominence), float(profile[i] - median)
