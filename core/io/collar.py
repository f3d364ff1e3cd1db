"""Collars: a constant fill around a raster's footprint that nobody declared as nodata.

Rotated or clipped scenes are often delivered inside a rectangle filled with 0 (or the type's
maximum) without a nodata tag. Read as image content, the collar's straight border becomes the
strongest structure in the image and dominates matching and verification. A constant value that
covers a region connected to the raster's border is therefore treated as nodata when nothing
else (nodata value, mask band, alpha) says which pixels are valid, and when what it leaves is a
footprint: a convex region (a scene's outline), not the white background of a map or the dark
of a night image that happens to reach the border.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional

import cv2
import numpy as np

# Read at most this many pixels to look for a collar (nearest-neighbour decimation keeps values exact).
SAMPLE_PIXELS = 1_000_000
MIN_BORDER_SHARE = 0.05  # of the raster's border pixels showing the candidate value
MIN_AREA_SHARE = 0.005  # of all pixels in the border-connected constant region
MIN_SOLIDITY = 0.97  # the rest's area over its convex hull's: a footprint is convex
RINGING = 12  # 8-bit JPEG lifts a fill's edge this far from its value
EDGE_PX = 2  # pixels beside the collar are neither fill nor scene (ringing, averaged cells)


def candidate_values(dtype: str, data: np.ndarray) -> tuple:
    """The fill values worth testing: 0 and the largest value of the type (or of the data for floats)."""
    if np.issubdtype(np.dtype(dtype), np.integer):
        return 0.0, float(np.iinfo(np.dtype(dtype)).max)
    finite = data[np.isfinite(data)]
    return (0.0,) + ((float(finite.max()),) if finite.size else ())


@dataclass(frozen=True, eq=False)
class Collar:
    """A raster's collar: its ``value``, the ``share`` of pixels it covers, and where it is: ``mask``
    (True = collar) on the detection sample, which spans the whole raster (``scale`` raster px per
    sample px)."""

    value: float
    share: float
    mask: np.ndarray = field(repr=False)
    scale: float = 1.0

    def window_mask(self, col_off: float, row_off: float, width: float, height: float, shape) -> np.ndarray:
        """Collar pixels (True) of a read of the raster window (col_off, row_off, width, height) at
        ``shape`` (rows, cols), widened by ``EDGE_PX`` output px and the sample's coarseness."""
        rows, cols = shape
        sy, sx = self.mask.shape
        xs = (col_off + (np.arange(cols) + 0.5) * width / cols) / self.scale
        ys = (row_off + (np.arange(rows) + 0.5) * height / rows) / self.scale
        ix = np.clip(np.floor(xs).astype(int), 0, sx - 1)
        iy = np.clip(np.floor(ys).astype(int), 0, sy - 1)
        inside = ((xs >= 0) & (xs < sx))[None, :] & ((ys >= 0) & (ys < sy))[:, None]
        out = self.mask[np.ix_(iy, ix)] & inside
        r = EDGE_PX + max(int(np.ceil(self.scale * cols / max(width, 1e-9))) - 1, 0)
        return cv2.dilate(out.astype(np.uint8), np.ones((2 * r + 1, 2 * r + 1), np.uint8)) > 0


def find_collar(bands: np.ndarray, dtype: str, scale: float = 1.0) -> Optional[Collar]:
    """The collar of a (bands, H, W) sample of a raster (``scale`` raster px per sample px), or None.

    Detection asks for pixels where every band holds exactly ``value``, connected (8-neighbourhood)
    to the border through such pixels, and for the rest to be a footprint (see :func:`_solidity`).
    The collar then also takes the compression ringing next to it (8-bit data): every band within
    ``RINGING`` of the value, connected (4-neighbourhood) to the border.
    """
    if bands.ndim != 3 or min(bands.shape[1:]) < 3:
        return None
    for value in candidate_values(dtype, bands):
        equal = np.all(bands == value, axis=0)
        if _border(equal).mean() < MIN_BORDER_SHARE:
            continue
        collar = _touching_border(equal, 8)
        share = float(collar.mean())
        if MIN_AREA_SHARE <= share < 0.999 and _solidity(~collar) >= MIN_SOLIDITY:
            if np.dtype(dtype) == np.uint8:
                collar = _touching_border(np.all(np.abs(bands - value) <= RINGING, axis=0), 4)
            return Collar(value, float(collar.mean()), collar, scale)
    return None


def _border(a: np.ndarray) -> np.ndarray:
    return np.concatenate([a[0], a[-1], a[:, 0], a[:, -1]])


def _touching_border(a: np.ndarray, connectivity: int) -> np.ndarray:
    n, labels = cv2.connectedComponents(a.astype(np.uint8), connectivity=connectivity)
    touching = np.unique(_border(labels))
    return np.isin(labels, touching[touching > 0])


def _solidity(region: np.ndarray) -> float:
    """Area of ``region``'s largest part over the area of its convex hull (1 for a convex region),
    after an opening that drops the specks compression leaves in a fill; 0 when that part is not
    nearly all of the region."""
    opened = cv2.morphologyEx(region.astype(np.uint8), cv2.MORPH_OPEN, np.ones((5, 5), np.uint8))
    n, labels, sizes, _ = cv2.connectedComponentsWithStats(opened, connectivity=8)
    if n < 2:
        return 0.0
    largest = 1 + int(np.argmax(sizes[1:, cv2.CC_STAT_AREA]))
    if sizes[largest, cv2.CC_STAT_AREA] < 0.95 * opened.sum():  # the fill cuts the image: not a footprint
        return 0.0
    region = labels == largest
    pts = cv2.findNonZero(region.astype(np.uint8))
    if pts is None:
        return 0.0
    hull = cv2.convexHull(pts)
    return float(region.sum()) / max(cv2.contourArea(hull) + 0.5 * cv2.arcLength(hull, True), 1.0)
