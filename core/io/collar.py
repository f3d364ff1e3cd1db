"""Collars: a constant fill around a raster's footprint that nobody declared as nodata.

Rotated or clipped scenes are often delivered inside a rectangle filled with 0 (or the type's
maximum) without a nodata tag. Read as image content, the collar's straight border becomes the
strongest structure in the image and dominates matching and verification. A constant value that
covers a region connected to the raster's border is therefore treated as nodata when nothing
else (nodata value, mask band, alpha) says which pixels are valid.
"""
from __future__ import annotations

from typing import Optional

import cv2
import numpy as np

# Read at most this many pixels to look for a collar (nearest-neighbour decimation keeps values exact).
SAMPLE_PIXELS = 1_000_000
MIN_BORDER_SHARE = 0.05  # of the raster's border pixels showing the candidate value
MIN_AREA_SHARE = 0.005  # of all pixels in the border-connected constant region


def candidate_values(dtype: str, data: np.ndarray) -> tuple:
    """The fill values worth testing: 0 and the largest value of the type (or of the data for floats)."""
    if np.issubdtype(np.dtype(dtype), np.integer):
        return 0.0, float(np.iinfo(np.dtype(dtype)).max)
    finite = data[np.isfinite(data)]
    return (0.0,) + ((float(finite.max()),) if finite.size else ())


def find_collar(bands: np.ndarray, dtype: str) -> Optional[tuple]:
    """(value, share of pixels) of a collar in a (bands, H, W) sample, or None.

    A pixel is collar when every band holds ``value`` and it is connected (8-neighbourhood) to the
    border through such pixels.
    """
    if bands.ndim != 3 or min(bands.shape[1:]) < 3:
        return None
    for value in candidate_values(dtype, bands):
        equal = np.all(bands == value, axis=0)
        border = np.concatenate([equal[0], equal[-1], equal[:, 0], equal[:, -1]])
        if border.mean() < MIN_BORDER_SHARE:
            continue
        n, labels = cv2.connectedComponents(equal.astype(np.uint8), connectivity=8)
        touching = np.unique(np.concatenate([labels[0], labels[-1], labels[:, 0], labels[:, -1]]))
        touching = touching[touching > 0]
        share = float(np.isin(labels, touching).mean()) if len(touching) else 0.0
        if share >= MIN_AREA_SHARE and share < 0.999:
            return value, share
    return None
