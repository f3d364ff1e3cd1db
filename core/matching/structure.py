"""Where in a search area a target lies, by the structure that lasts between dates: channels of
oriented gradients, correlated over the whole area at every turn and scale of the target.

Dalal, N. & Triggs, B. (2005). Histograms of oriented gradients for human detection. CVPR, 886-893
(gradient energy binned by orientation, pooled in cells, normalised across orientations).
:DOI:`10.1109/CVPR.2005.177`
Ye, Y., Bruzzone, L., Shan, J., Bovolo, F. & Zhu, Q. (2019). Fast and robust matching for multimodal
remote sensing image registration. IEEE TGRS 57(11):9059-9070 (such channels compared by normalised
cross-correlation over all channels at once, computed with FFTs). :DOI:`10.1109/TGRS.2019.2924684`

Keypoint descriptors fail where the ground changed between dates (crops turned over, water up): few
of the target's keypoints find their match. The shapes that last (field boundaries, roads, shores)
still line up as a whole. Here the target is drawn at each turn (``TURN_DEG``) and scale
(``SCALE_STEP``) in turn, and its channels are correlated with the area's at every position at
once (FFT); orientations are unsigned, so a contrast inverted between dates changes nothing. Each
position keeps its best score over the poses, a score scaled by the square root of the template's
cells so that scales compare (a small template correlates highly by chance more often). The
highest, apart from each other, are the candidates: where to look, never a result; only the
independent check of a later registration decides.

Pixels: target working pixels and area working pixels, corner convention.
"""
from __future__ import annotations

import math
from typing import List

import cv2
import numpy as np

from ..parallel import THREADS
from .locate import Candidate

BINS = 6  # unsigned orientations, 30 degrees apart, each gradient shared between its two nearest
TEMPLATE_CELLS = 24  # a template's longer side is 24 to 48 cells: the cell is a power of two of area pixels
TURN_DEG = 15.0  # a pose's turn is within 7.5 degrees of one tried ...
SCALE_STEP = 2.0 ** (1.0 / 3.0)  # ... and its scale within 12 % (the channels' smoothing absorbs the rest)
SMOOTH_CELLS = 1.0  # Gaussian smoothing of the channels, in cells: a template off by a cell still correlates
ROUGH = 6  # places of the coarse pass correlated again finely
ON_AREA = 0.9  # share of a template's cells that must fall on the area's data (the rest may be outside it)


def structure_places(target, target_valid, area, area_valid, sides, limit: int = 2) -> List[Candidate]:
    """Up to ``limit`` places of the grey ``target`` in the grey ``area`` (each with its validity
    mask), best first, for target longer sides (in area pixels) between ``sides`` = (low, high):
    each a :class:`Candidate` whose ``score`` is the correlation scaled by the square root of the
    template's cells, ``inliers`` 0. None within half the target's size of a better one.

    Coarse to fine: every pose with templates of TEMPLATE_CELLS to twice that, then each of the
    ``ROUGH`` best places again with cells half as large, at turns and scales around its own."""
    low, high = sides
    if high < low:
        return []
    h, w = target.shape
    grids = {}
    n_scales = int(math.floor(math.log(high / low) / math.log(SCALE_STEP))) + 1
    for k in range(n_scales):
        side = low * SCALE_STEP ** k
        cell = 2 ** max(1, int(math.floor(math.log2(side / TEMPLATE_CELLS))))
        if cell not in grids:
            grids[cell] = _Area(area, area_valid, cell)
        for turn in np.arange(0.0, 360.0, TURN_DEG):
            grids[cell].add(target, target_valid, side / max(h, w), float(turn))
    diagonal = math.hypot(h, w)
    rough = sorted((p + (grid.cell,) for grid in grids.values() for p in grid.peaks(ROUGH, diagonal)),
                   key=lambda p: -p[0])[:ROUGH]
    del grids
    found = sorted((_refined(target, target_valid, area, area_valid, p, diagonal) for p in rough),
                   key=lambda p: -p[0])
    out: List[Candidate] = []
    centre = np.array([w / 2.0, h / 2.0])
    for score, xy, scale, turn in found:
        if any(np.hypot(*(xy - c.apply(centre[None])[0])) < 0.5 * scale * diagonal for c in out):
            continue
        lin = scale * _turn(turn)
        out.append(Candidate(np.column_stack([lin, xy - lin @ centre]), 0, 0, score))
    return out[:limit]


def _refined(target, target_valid, area, area_valid, rough, diagonal: float):
    """The place ``rough`` (score, centre in area px, scale, turn, cell) correlated again with cells half
    as large, at turns and scales within a step of its own, over the area around it."""
    _, (x, y), scale, turn, cell = rough
    radius = 0.5 * scale * diagonal + 3 * cell
    r0, c0 = max(0, int(y - radius)), max(0, int(x - radius))
    r1, c1 = min(area.shape[0], int(math.ceil(y + radius))), min(area.shape[1], int(math.ceil(x + radius)))
    fine = _Area(area[r0:r1, c0:c1], area_valid[r0:r1, c0:c1], max(2, cell // 2))
    for ds in np.linspace(-0.5, 0.5, 5):
        for dt in np.linspace(-0.5, 0.5, 5):
            fine.add(target, target_valid, scale * SCALE_STEP ** ds, turn + dt * TURN_DEG)
    peaks = fine.peaks(1, diagonal)
    if not peaks:
        return rough[:4]
    score, xy, scale, turn = peaks[0]
    return score, xy + (c0, r0), scale, turn


def channels(grey: np.ndarray, valid: np.ndarray) -> tuple:
    """(BINS, H/2, W/2) float32 channels of a grey image drawn at half a cell per pixel, and the cells
    wholly on valid pixels: gradient energy by unsigned orientation, pooled 2 x 2, square-rooted (strong
    edges do not drown the rest), normalised across orientations per cell, smoothed by SMOOTH_CELLS."""
    g = cv2.GaussianBlur(grey.astype(np.float32), (0, 0), 0.7)
    gx = cv2.Sobel(g, cv2.CV_32F, 1, 0, ksize=3)
    gy = cv2.Sobel(g, cv2.CV_32F, 0, 1, ksize=3)
    magnitude = cv2.magnitude(gx, gy)
    position = np.mod(np.arctan2(gy, gx), np.float32(np.pi)) * np.float32(BINS / np.pi)
    del gx, gy
    lower = np.floor(position)
    upper_share = position - lower
    lower = lower.astype(np.int8) % BINS
    upper = (lower + 1) % BINS
    inside = cv2.erode(valid.astype(np.uint8), np.ones((5, 5), np.uint8)) > 0
    magnitude *= inside
    to_lower, to_upper = magnitude * (1.0 - upper_share), magnitude * upper_share
    h, w = grey.shape[0] // 2, grey.shape[1] // 2
    out = np.empty((BINS, h, w), np.float32)
    for k in range(BINS):
        energy = np.where(lower == k, to_lower, 0.0) + np.where(upper == k, to_upper, 0.0)
        out[k] = cv2.resize(energy[:2 * h, :2 * w], (w, h), interpolation=cv2.INTER_AREA)
    np.sqrt(out, out=out)
    out /= np.sqrt((out ** 2).sum(axis=0)) + np.float32(1e-3 * (float(out.max()) + 1e-6))
    for k in range(BINS):
        out[k] = cv2.GaussianBlur(out[k], (0, 0), SMOOTH_CELLS)
    cells = cv2.resize(inside[:2 * h, :2 * w].astype(np.float32), (w, h), interpolation=cv2.INTER_AREA) > 0.99
    return out * cells, cells


def _turn(turn_deg: float) -> np.ndarray:
    """The linear map of a turn counter-clockwise as displayed (y down)."""
    a = math.radians(turn_deg)
    return np.array([[math.cos(a), math.sin(a)], [-math.sin(a), math.cos(a)]])


class _Area:
    """The area's channels at one cell size, their transforms, and the best score at each cell over the
    poses added (as the target centre's cell)."""

    def __init__(self, area, valid, cell: int):
        half = cell // 2
        h, w = area.shape[0] // half, area.shape[1] // half
        grey = cv2.resize(area[:h * half, :w * half], (w, h), interpolation=cv2.INTER_AREA) if half > 1 else area
        mask = cv2.resize(valid[:h * half, :w * half].astype(np.uint8), (w, h), interpolation=cv2.INTER_NEAREST) > 0 \
            if half > 1 else valid
        self.cell = cell
        self.features, self.valid = channels(grey, mask)
        self.shape = self.valid.shape
        self.best = np.full(self.shape, -np.inf, np.float32)
        self.pose = np.zeros(self.shape + (4,), np.float32)  # scale, turn, the centre's offset from its cell
        self._spectra = {}

    def add(self, target, valid, scale: float, turn: float) -> None:
        """Correlate the target at ``scale`` (area px per target px) and ``turn`` (degrees) everywhere."""
        canvas, inside, centre = _drawn(target, valid, scale * 2.0 / self.cell, turn)
        template, cells = channels(canvas, inside)
        th, tw = cells.shape
        if th < 4 or tw < 4 or th > self.shape[0] or tw > self.shape[1]:
            return
        score = self._correlate(template, cells)
        cx, cy = (int(round(v / 2.0)) for v in centre)
        dx, dy = (v / 2.0 - round(v / 2.0) for v in centre)
        rows, cols = score.shape
        view = (slice(cy, cy + rows), slice(cx, cx + cols))
        better = score[:self.shape[0] - cy, :self.shape[1] - cx] > self.best[view]
        self.best[view][better] = score[:self.shape[0] - cy, :self.shape[1] - cx][better]
        self.pose[view][better] = (scale, turn, dx, dy)

    def _correlate(self, template, cells) -> np.ndarray:
        """Normalised cross-correlation of ``template`` (zero outside ``cells``) over every channel at once,
        at each placement of its top-left cell wholly inside the area; scaled by sqrt(cells); -inf where
        less than ON_AREA of it falls on the area's data."""
        import scipy.fft as fft

        th, tw = cells.shape
        size = (fft.next_fast_len(self.shape[0] + th, True), fft.next_fast_len(self.shape[1] + tw, True))
        area, sums, squares, valid = self._spectrum(size)
        m = cells.astype(np.float32)
        n = float(m.sum()) * BINS
        t = (template - np.float32(template.sum() / n)) * m
        norm = math.sqrt(float((t ** 2).sum()))
        if norm == 0.0:
            return np.full((self.shape[0] - th + 1, self.shape[1] - tw + 1), -np.inf, np.float32)
        flip = (slice(None, None, -1), slice(None, None, -1))
        spectrum = fft.rfft2(t[(slice(None),) + flip], s=size, workers=THREADS)
        window = fft.rfft2(m[flip], s=size, workers=THREADS)
        crop = (slice(th - 1, self.shape[0]), slice(tw - 1, self.shape[1]))
        product = fft.irfft2(np.einsum("kij,kij->ij", area, spectrum), s=size, workers=THREADS)[crop]
        local = fft.irfft2(sums * window, s=size, workers=THREADS)[crop]
        energy = fft.irfft2(squares * window, s=size, workers=THREADS)[crop]
        covered = fft.irfft2(valid * window, s=size, workers=THREADS)[crop]
        spread = np.sqrt(np.maximum(energy - local ** 2 / n, 1e-6))
        score = product / (norm * spread) * np.float32(math.sqrt(m.sum()))
        score[covered < ON_AREA * m.sum()] = -np.inf
        return score.astype(np.float32)

    def _spectrum(self, size):
        if size not in self._spectra:
            import scipy.fft as fft

            self._spectra = {size: (fft.rfft2(self.features, s=size, workers=THREADS),
                                    fft.rfft2(self.features.sum(axis=0), s=size, workers=THREADS),
                                    fft.rfft2((self.features ** 2).sum(axis=0), s=size, workers=THREADS),
                                    fft.rfft2(self.valid.astype(np.float32), s=size, workers=THREADS))}
        return self._spectra[size]

    def peaks(self, limit: int, diagonal: float) -> list:
        """The ``limit`` best cells, each half a target's ``diagonal`` (target px) from a better one:
        (score, the target centre in area px, scale, turn)."""
        best = self.best.copy()
        out = []
        while len(out) < limit:
            r, c = divmod(int(np.argmax(best)), best.shape[1])
            if not np.isfinite(best[r, c]):
                break
            scale, turn, dx, dy = (float(v) for v in self.pose[r, c])
            out.append((float(best[r, c]), np.array([c + dx, r + dy]) * self.cell, scale, turn))
            radius = max(1, int(0.5 * scale * diagonal / self.cell))
            best[max(0, r - radius):r + radius + 1, max(0, c - radius):c + radius + 1] = -np.inf
        return out


def _drawn(target, valid, scale: float, turn: float):
    """``target`` drawn at ``scale`` and ``turn`` on a canvas just holding it: (canvas, valid pixels,
    the target's centre on the canvas), pixels shrunk by area averaging first so that nothing aliases."""
    h, w = target.shape
    image, mask, factor = target, valid, 1.0
    if scale < 0.7:
        sw, sh = max(1, round(w * scale / 0.7)), max(1, round(h * scale / 0.7))
        image = cv2.resize(target.astype(np.float32), (sw, sh), interpolation=cv2.INTER_AREA)
        mask = cv2.resize(valid.astype(np.uint8), (sw, sh), interpolation=cv2.INTER_NEAREST) > 0
        factor = sw / w
    lin = _turn(turn) * (scale / factor)
    corners = np.array([[0, 0], [w, 0], [0, h], [w, h]], float) * factor @ lin.T
    lo, hi = corners.min(axis=0), corners.max(axis=0)
    size = (int(math.ceil(hi[0] - lo[0])), int(math.ceil(hi[1] - lo[1])))
    matrix = np.column_stack([lin, -lo + lin @ [0.5, 0.5] - 0.5])  # OpenCV's pixel-centre convention
    canvas = cv2.warpAffine(image.astype(np.float32), matrix, size, flags=cv2.INTER_LINEAR)
    inside = cv2.warpAffine(mask.astype(np.uint8), matrix, size, flags=cv2.INTER_NEAREST) > 0
    centre = lin @ (np.array([w, h], float) * factor / 2.0) - lo
    return canvas, inside, centre
