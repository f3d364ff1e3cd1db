"""Short pieces of text printed along a scan's edges, found: what :mod:`hamta.core.grid.ocr` reads and
:mod:`hamta.core.grid.labels` parses as coordinates.

Each edge band is read at full resolution; printed ink is what stands darker than its surroundings (and, for
labels printed light on a dark band, lighter); long lines (the neatline, grid lines, rules) are taken out so that
a label touching its line stays a label; what remains is cut into connected pieces, and the glyph-sized ones are
strung into words: pieces of similar height side by side, no further apart than a glyph. Labels printed along a
side edge (turned a quarter) are found in the band turned both ways.

Pixels: the scan's (corner convention).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import List, Optional, Sequence, Tuple

import numpy as np

MIN_GLYPH_PX, MAX_GLYPH_PX = 6, 120  # glyphs smaller are unreadable; larger ones are titles, not labels
MAX_GLYPHS = 14  # a word longer than this is a sentence, not a label (156°59'30"W has 11)


@dataclass(frozen=True)
class Word:
    """A word read: its ``text``; ``box`` (x0, y0, x1, y1, scan px, axis-aligned); ``turn`` how the text runs (0:
    left to right; 90: upwards, read with the scan turned a quarter clockwise; -90: downwards); ``glyph_px`` its
    glyphs' height on the scan; ``confidence`` the engine's (0-100); ``light``: light glyphs on a dark ground."""

    text: str
    box: Tuple[float, float, float, float]
    turn: int
    glyph_px: float
    confidence: float
    light: bool = False
    crop: Optional[np.ndarray] = field(default=None, repr=False, compare=False)  # as the engine read it

    @property
    def xy(self) -> Tuple[float, float]:
        return (self.box[0] + self.box[2]) / 2, (self.box[1] + self.box[3]) / 2


@dataclass(frozen=True)
class Found:
    """A word found but not read yet: its crop (grey, upright, dark glyphs on light), box and how it runs."""

    crop: np.ndarray
    box: Tuple[float, float, float, float]
    turn: int
    glyph_px: float
    light: bool


def find_words(grey: np.ndarray, turns: Sequence[int] = (0,)) -> List[Found]:
    """The words printed in ``grey`` (a band of the scan, uint8), dark on light and light on a dark ground, running
    in each of ``turns`` (0, 90, -90); boxes in ``grey``'s px."""
    import cv2

    out = []
    for turn in turns:
        image = grey if turn == 0 else cv2.rotate(grey, cv2.ROTATE_90_CLOCKWISE if turn == 90 else
                                                  cv2.ROTATE_90_COUNTERCLOCKWISE)
        for light in (False, True):
            if light and np.mean(image < DARK_GROUND) < 0.01:
                continue  # no dark ground to print light labels on
            page = 255 - image if light else image
            ink, lines, paper = _ink(page)
            clean = page.copy()
            clean[lines > 0] = paper[lines > 0]  # lines painted as paper
            seen = []
            for box, glyph in _words(ink):
                if any(_overlap(box, b) > 0.6 for b in seen):
                    continue
                seen.append(box)
                x0, y0, x1, y1 = box
                pad = int(round(0.35 * glyph))
                crop = clean[max(y0 - pad, 0):y1 + pad, max(x0 - pad, 0):x1 + pad]
                if light and np.median(image[max(y0 - pad, 0):y1 + pad, max(x0 - pad, 0):x1 + pad]) > DARK_GROUND:
                    continue  # light marks on a light ground: gaps between dark strokes, not words
                out.append(Found(crop, _unturn(box, turn, grey.shape), turn, glyph, light))
    return out


DARK_GROUND = 110  # grey level below which a word's surroundings are a dark ground for light glyphs


def _unturn(box, turn, shape) -> Tuple[float, float, float, float]:
    """A box of the band turned by ``turn`` as a box of the band itself."""
    x0, y0, x1, y1 = box
    h, w = shape
    if turn == 90:  # turned clockwise: (x, y) of the turned image is (h - y, x) of... the band's (y, h - x)
        return float(y0), float(h - x1), float(y1), float(h - x0)
    if turn == -90:
        return float(w - y1), float(x0), float(w - y0), float(x1)
    return float(x0), float(y0), float(x1), float(y1)


def _words(ink: np.ndarray):
    """(box x0, y0, x1, y1; glyph height) of each word on the ``ink`` mask: as it is, and opened by 3 and 5 px
    (which parts a label from thin linework that touches it: a coast, a contour)."""
    import cv2

    for size in (0, 3, 5):
        mask = ink if not size else cv2.morphologyEx(ink, cv2.MORPH_OPEN,
                                                      cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (size, size)))
        yield from _strung(mask, min_glyph=MIN_GLYPH_PX if not size else 3 * size)


def _strung(ink: np.ndarray, min_glyph: int):
    """Words of the connected pieces of ``ink``: glyph-sized pieces strung together (see the module docstring)."""
    import cv2

    n, _, stats, _ = cv2.connectedComponentsWithStats(ink, connectivity=8)
    x, y, w, h, area = (stats[1:, i] for i in range(5))
    glyph = (h >= min_glyph) & (h <= MAX_GLYPH_PX) & (w <= 8 * h) & (area >= 0.08 * w * h)  # touching glyphs: a run
    small = (h >= 2) & (h < MIN_GLYPH_PX * 2) & (w <= MAX_GLYPH_PX) & ~glyph  # degree signs, primes, dots
    index = np.flatnonzero(glyph)
    if not len(index):
        return
    order = index[np.argsort(x[index])]
    parent = {int(i): int(i) for i in order}

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, i in enumerate(order):  # each glyph joined to those just right of it, of like height and row
        for j in order[a + 1:]:
            gap = x[j] - (x[i] + w[i])
            size = max(h[i], h[j])
            if gap > 0.9 * size:
                break
            overlap = min(y[i] + h[i], y[j] + h[j]) - max(y[i], y[j])
            if overlap >= 0.5 * min(h[i], h[j]) and max(h[i], h[j]) <= 1.8 * min(h[i], h[j]):
                parent[find(int(j))] = find(int(i))
    groups = {}
    for i in order:
        groups.setdefault(find(int(i)), []).append(int(i))
    smalls = np.flatnonzero(small | (glyph & (h < 0.6 * MAX_GLYPH_PX)))
    for members in groups.values():
        if len(members) > MAX_GLYPHS:
            continue
        m = np.array(members)
        x0, y0 = int(x[m].min()), int(y[m].min())
        x1, y1 = int((x[m] + w[m]).max()), int((y[m] + h[m]).max())
        size = float(np.median(h[m]))
        if x1 - x0 > MAX_GLYPHS * 0.8 * size:
            continue  # longer than a label's glyphs set side by side: a name, a sentence
        near = smalls[(x[smalls] >= x0 - 0.9 * size) & (x[smalls] + w[smalls] <= x1 + 1.2 * size)
                      & (y[smalls] >= y0 - 0.4 * size) & (y[smalls] + h[smalls] <= y0 + 0.6 * size)
                      & (h[smalls] < 0.6 * size)]
        if len(near):  # a degree sign or a prime just beyond the digits belongs to the word
            x0, y0 = min(x0, int(x[near].min())), min(y0, int(y[near].min()))
            x1 = max(x1, int((x[near] + w[near]).max()))
        if len(m) == 1 and not len(near):
            continue  # a lone glyph is no coordinate (a label has two characters at least)
        yield (x0, y0, x1, y1), size


def _ink(page: np.ndarray):
    """(dark glyphs on ``page`` without long straight lines, the lines taken out: uint8 masks, 255 = ink; the
    paper around them)."""
    import cv2

    block = 2 * (MAX_GLYPH_PX // 2) + 1
    background = cv2.dilate(page, cv2.getStructuringElement(cv2.MORPH_RECT, (block // 3 | 1, block // 3 | 1)))
    background = cv2.blur(background, (block, block))
    contrast = np.maximum(background.astype(np.int16) - page.astype(np.int16), 0).astype(np.uint8)
    noise = 1.4826 * float(np.median(np.abs(contrast.astype(np.float32) - np.median(contrast))))
    near = cv2.dilate(contrast, cv2.getStructuringElement(cv2.MORPH_RECT, (block // 2 | 1, block // 2 | 1)))
    level = np.maximum(0.45 * near.astype(np.float32), max(4.0 * noise, 12.0))  # each glyph against the darkest
    ink = (contrast >= level).astype(np.uint8) * 255  # ink near it (a faint label beside a bold title), and above
    # the paper's grain (four robust deviations of the band's contrast)
    lines = np.zeros_like(ink)
    for kernel in _line_kernels():
        lines |= cv2.morphologyEx(ink, cv2.MORPH_OPEN, kernel)
    lines = cv2.dilate(lines, np.ones((3, 3), np.uint8))
    return cv2.subtract(ink, lines), lines, background


def _line_kernels():
    """Straight runs :data:`LINE_PX` long, along x and y and turned a little each way (a scan is rarely square to
    its sheet): what an opening by them keeps is a line, not a glyph."""
    import cv2

    if not _KERNELS:
        n = LINE_PX
        for turn in (-3.0, -1.5, 0.0, 1.5, 3.0):
            kernel = np.zeros((n, n), np.uint8)
            t = np.tan(np.radians(turn))
            c = n // 2
            for x in range(n):
                kernel[int(round(c + (x - c) * t)), x] = 1
            _KERNELS.extend([kernel, cv2.rotate(kernel, cv2.ROTATE_90_CLOCKWISE)])
    return _KERNELS


_KERNELS: list = []


LINE_PX = 49  # longer than any glyph a label is read at (MAX_GLYPH_PX is a title's), shorter than a neatline's side


def bands(width: int, height: int, inner: float, longest: int, outer: float = 0.0
          ) -> List[Tuple[str, Tuple[int, int, int, int]]]:
    """(side, window x0, y0, x1, y1) of pieces of each edge's band from ``outer`` to ``inner`` of the shorter side
    in from the edge, at most ``longest`` px long (overlapping by the band's depth, and the bands by a tenth of
    theirs, so that a label cut at one piece's end is whole in the next)."""
    short = min(width, height)
    d0 = max(int(outer * short) - int(0.1 * (inner - outer) * short), 0) if outer else 0
    d1 = max(int(inner * short), d0 + 1)
    out = []
    for side in ("top", "bottom", "left", "right"):
        along = width if side in ("top", "bottom") else height
        step = max(longest - (d1 - d0), 1)
        for a0 in range(0, along, step):
            a1 = min(a0 + longest, along)
            if side == "top":
                out.append((side, (a0, d0, a1, d1)))
            elif side == "bottom":
                out.append((side, (a0, height - d1, a1, height - d0)))
            elif side == "left":
                out.append((side, (d0, a0, d1, a1)))
            else:
                out.append((side, (width - d1, a0, width - d0, a1)))
            if a1 == along:
                break
    return out


def unique(words: List[Word]) -> List[Word]:
    """Words found twice (overlapping pieces, two polarities, two turns) kept once: the more confident."""
    kept: List[Word] = []
    for w in sorted(words, key=lambda w: -w.confidence):
        if not any(_overlap(w.box, k.box) > 0.5 for k in kept):
            kept.append(w)
    return kept


def _overlap(a, b) -> float:
    ix = max(0.0, min(a[2], b[2]) - max(a[0], b[0]))
    iy = max(0.0, min(a[3], b[3]) - max(a[1], b[1]))
    inter = ix * iy
    smaller = min((a[2] - a[0]) * (a[3] - a[1]), (b[2] - b[0]) * (b[3] - b[1]))
    return inter / smaller if smaller > 0 else 0.0
