"""CenSurE keypoints with octagonal bi-level filters.

Agrawal, M., Konolige, K., & Blas, M. R. (2008). CenSurE: Center surround extremas for realtime
feature detection and matching. ECCV 2008, LNCS 5305, 102-115. :DOI:`10.1007/978-3-540-88693-8_8`

Seven center-surround filters (inner and outer octagons of Table 1 of Sedaghat & Mohammadi 2019,
the CenSurE table) are applied to the image itself, without a pyramid. Each filter response is
``mean(inner octagon) - mean(outer octagon minus inner)``, which has no DC response and is
comparable across scales. Octagon sums cost a constant dozen array lookups per pixel: the
axis-aligned middle band comes from the upright integral image, and the two 45-degree trapezoids
from cumulative sums of row prefix sums along the two diagonals (the slanted integral images).
Extrema over 3x3x3 (x, y, scale) neighbourhoods above a response threshold are kept, lines are
rejected with CenSurE's scale-adapted Harris test on the response (trace^2 / det > 10), and the
strongest ``n_features`` survive.

OpenCV's ``StarDetector`` (not in opencv-python-headless) uses star-shaped filters instead of
octagons; this module implements the octagons the paper uses.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Tuple

import cv2
import numpy as np

from ..types import Keypoints
from .extrema import scale_space_extrema
from .patches import patch_gradients

# (m, n) of the inner and outer octagons for scales 1..7 (Agrawal et al. 2008; paper's Table 1).
OCTAGONS = (((3, 0), (5, 2)), ((3, 1), (5, 3)), ((3, 2), (7, 3)), ((5, 2), (9, 4)),
            ((5, 3), (9, 7)), ((5, 4), (13, 7)), ((5, 5), (15, 10)))


def octagon_extent(m: int, n: int) -> int:
    """Side of the square an (m, n) octagon fills: m + 2n pixels."""
    return m + 2 * n


def octagon_area(m: int, n: int) -> int:
    """Pixels of an (m, n) octagon: the square minus four corner triangles of n(n+1)/2 pixels."""
    return octagon_extent(m, n) ** 2 - 2 * n * (n + 1)


def octagon_mask(m: int, n: int) -> np.ndarray:
    """Boolean (m + 2n) x (m + 2n) footprint of the octagon (for tests and documentation)."""
    s = octagon_extent(m, n)
    mask = np.ones((s, s), bool)
    for k in range(n):
        cut = n - k
        for row in (k, s - 1 - k):
            mask[row, :cut] = False
            mask[row, s - cut:] = False
    return mask


class OctagonSums:
    """Constant-time octagon sums at every pixel of an image (integral images on a padded copy)."""

    def __init__(self, image: np.ndarray, pad: int):
        img = np.pad(image.astype(np.float64), pad + 1, mode="reflect")
        self.pad = pad + 1
        self.shape = image.shape
        h, w = img.shape
        row = np.zeros((h, w + 1))
        np.cumsum(img, axis=1, out=row[:, 1:])  # row[y, x] = sum of img[y, :x]
        self.integral = np.zeros((h + 1, w + 1))
        np.cumsum(row, axis=0, out=self.integral[1:])  # integral[y, x] = sum of img[:y, :x]
        # down-right and down-left diagonal cumulative sums of the row prefixes (slanted integrals)
        self.dr = row.copy()
        self.dl = row.copy()
        for y in range(1, h):
            self.dr[y, 1:] += self.dr[y - 1, :-1]
            self.dl[y, :-1] += self.dl[y - 1, 1:]

    def _at(self, table: np.ndarray, dy: int, dx: int) -> np.ndarray:
        """``table[cy + dy, cx + dx]`` for every original pixel (cx, cy), as an (H, W) view."""
        h, w = self.shape
        y0, x0 = self.pad + dy, self.pad + dx
        return table[y0:y0 + h, x0:x0 + w]

    def octagon(self, m: int, n: int) -> np.ndarray:
        """Sum over the (m, n) octagon centred on each pixel."""
        h = (m + 2 * n - 1) // 2
        at = self._at
        # middle band: rows -h+n .. h-n, columns -h .. h (integral image has a one-pixel offset)
        total = (at(self.integral, h - n + 1, h + 1) - at(self.integral, -h + n, h + 1)
                 - at(self.integral, h - n + 1, -h) + at(self.integral, -h + n, -h))
        if n == 0:
            return total
        # top trapezoid: rows -h .. -h+n-1; row k spans columns -h+n-k .. h-n+k
        total = total + (at(self.dr, -h + n - 1, h) - at(self.dr, -h - 1, h - n))
        total = total - (at(self.dl, -h + n - 1, -h + 1) - at(self.dl, -h - 1, -h + n + 1))
        # bottom trapezoid: rows h-n+1 .. h; row k spans columns -h+k+1 .. h-k-1
        total = total + (at(self.dl, h, h - n + 1) - at(self.dl, h - n, h + 1))
        total = total - (at(self.dr, h, -h + n) - at(self.dr, h - n, -h))
        return total


@dataclass(frozen=True)
class CensureDetector:
    """CenSurE settings.

    Attributes
    ----------
    n_features : int
        Strongest extrema kept (2500 in Sedaghat & Mohammadi 2019).
    response_threshold : float
        Smallest |response| (grey levels of the 0..255 input) for an extremum; the paper takes
        CenSurE's defaults without giving them, and keeping the strongest ``n_features`` makes
        this a floor against flat-area noise only.
    line_threshold : float
        CenSurE's limit on trace^2 / det of the response's second-moment matrix (10).
    support_factor : float
        Support radius = factor x half the outer octagon; the paper leaves the region size
        unspecified (spec 000, section 3); 2.5 was chosen on synthetic pairs.
    subpixel : bool
        Not in CenSurE or the paper: refine each extremum by a quadratic fit of the response,
        so positions are not limited to whole pixels. Off in the faithful mode.
    """

    n_features: int = 2500
    response_threshold: float = 2.0
    line_threshold: float = 10.0
    support_factor: float = 2.5
    subpixel: bool = True

    def support_radius(self, scale_index) -> np.ndarray:
        outer = np.array([octagon_extent(*o) for _, o in OCTAGONS], float)
        return self.support_factor * outer[np.asarray(scale_index)] / 2.0


def censure_responses(image: np.ndarray) -> np.ndarray:
    """(7, H, W) float32 filter responses of an image (float, any range)."""
    pad = max(octagon_extent(*o) for _, o in OCTAGONS) // 2 + 1
    sums = OctagonSums(image, pad)
    out = np.empty((len(OCTAGONS),) + image.shape, np.float32)
    for s, (inner, outer) in enumerate(OCTAGONS):
        s_in, s_out = sums.octagon(*inner), sums.octagon(*outer)
        a_in, a_out = octagon_area(*inner), octagon_area(*outer)
        out[s] = s_in / a_in - (s_out - s_in) / (a_out - a_in)
    return out


def censure_keypoints(image: np.ndarray, mask: np.ndarray, detector: CensureDetector = CensureDetector()
                      ) -> Tuple[Keypoints, np.ndarray]:
    """Detect CenSurE keypoints.

    Parameters
    ----------
    image : (H, W) array, working pixels (the 0..255 range the thresholds assume).
    mask : (H, W) bool, where keypoints may lie (their whole filter support must be valid).

    Returns
    -------
    keypoints : Keypoints
        ``xy`` in corner-convention pixels (pixel centres at +0.5), ``size`` = support diameter,
        ``response`` = filter response (signed), ``angle`` NaN (CenSurE assigns none).
    scale_index : (N,) int
        Filter scale (0..6) of each keypoint.
    """
    resp = censure_responses(image)
    margin = max(octagon_extent(*o) for _, o in OCTAGONS) // 2 + 1
    usable = cv2.erode(mask.astype(np.uint8), np.ones((2 * margin + 1, 2 * margin + 1), np.uint8),
                       borderType=cv2.BORDER_CONSTANT, borderValue=0) > 0
    s_idx, ys, xs = scale_space_extrema(resp, detector.response_threshold, end_layers=True, valid=usable)
    order = np.argsort(-np.abs(resp[s_idx, ys, xs]), kind="stable")
    # The line test is run on the strongest candidates only, enough to leave n_features.
    order = order[: 4 * detector.n_features]
    s_idx, ys, xs = s_idx[order], ys[order], xs[order]
    keep = _not_lines(resp, s_idx, ys, xs, detector.line_threshold)
    s_idx, ys, xs = s_idx[keep][: detector.n_features], ys[keep][: detector.n_features], xs[keep][: detector.n_features]
    xy = np.column_stack([xs + 0.5, ys + 0.5]).astype(np.float64)
    if detector.subpixel and len(xy):
        xy += _subpixel_offsets(resp, s_idx, ys, xs)
    size = 2.0 * detector.support_radius(s_idx)
    kp = Keypoints(xy, size, np.full(len(xy), np.nan), resp[s_idx, ys, xs].astype(np.float64))
    return kp, s_idx


def _not_lines(resp, s_idx, ys, xs, ratio):
    """CenSurE's line test: scale-adapted Harris matrix of the response over the filter's extent,
    evaluated in a window around each candidate only."""
    keep = np.zeros(len(s_idx), bool)
    h, w = resp.shape[1:]
    for s in np.unique(s_idx):
        sel = np.flatnonzero(s_idx == s)
        k = octagon_extent(*OCTAGONS[s][1])
        off = np.arange(-(k // 2) - 1, k // 2 + 2)
        rows = np.clip(ys[sel, None, None] + off[None, :, None], 0, h - 1)
        cols = np.clip(xs[sel, None, None] + off[None, None, :], 0, w - 1)
        win = resp[s][rows, cols].astype(np.float64)
        gx, gy = patch_gradients(win)  # unscaled: the trace^2 / det test is scale-free
        sxx, syy, sxy = (gx * gx).sum(axis=(1, 2)), (gy * gy).sum(axis=(1, 2)), (gx * gy).sum(axis=(1, 2))
        det = sxx * syy - sxy * sxy
        keep[sel] = (det > 0) & ((sxx + syy) ** 2 < ratio * det)
    return keep


def _subpixel_offsets(resp, s_idx, ys, xs):
    """Offsets (dx, dy) of the quadratic fit's extremum in the keypoint's response layer, |.| <= 0.5."""
    r = resp
    c = r[s_idx, ys, xs].astype(np.float64)
    h, w = r.shape[1:]
    xm, xp = np.clip(xs - 1, 0, w - 1), np.clip(xs + 1, 0, w - 1)
    ym, yp = np.clip(ys - 1, 0, h - 1), np.clip(ys + 1, 0, h - 1)
    dx = (r[s_idx, ys, xp] - r[s_idx, ys, xm]) / 2.0
    dy = (r[s_idx, yp, xs] - r[s_idx, ym, xs]) / 2.0
    dxx = r[s_idx, ys, xp] + r[s_idx, ys, xm] - 2 * c
    dyy = r[s_idx, yp, xs] + r[s_idx, ym, xs] - 2 * c
    dxy = (r[s_idx, yp, xp] - r[s_idx, yp, xm] - r[s_idx, ym, xp] + r[s_idx, ym, xm]) / 4.0
    det = dxx * dyy - dxy * dxy
    with np.errstate(divide="ignore", invalid="ignore"):
        ox = np.where(np.abs(det) > 1e-12, -(dyy * dx - dxy * dy) / det, 0.0)
        oy = np.where(np.abs(det) > 1e-12, -(dxx * dy - dxy * dx) / det, 0.0)
    return np.clip(np.column_stack([ox, oy]), -0.5, 0.5)
