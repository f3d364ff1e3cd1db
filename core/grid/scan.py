"""A scanned sheet's line map, read window by window: a 30 000 px scan is never held whole.

Pixels: the scan's full resolution (x = column, y = row, corner convention). Windows are read through
:class:`hamta.core.io.windows.WindowReader` (grey: the luminance of RGB, of a palette's colours, or band 1),
and the line map (:func:`hamta.core.grid.lines.line_map`) is computed on each window with a margin, so it
is the same as on the whole scan.
"""
from __future__ import annotations

import math
from typing import Optional, Tuple

import numpy as np
from rasterio.windows import Window

from .lines import LINE_WIDTH_PX, line_map


class LineSource:
    """The line map around any point of a scan: :meth:`around`. From a raster (:meth:`from_raster`, used as
    a context manager) or from a grey array in memory (:meth:`from_array`)."""

    def __init__(self, width: int, height: int, read):
        self.width, self.height = width, height
        self._read = read  # (x0, y0, x1, y1) -> grey float32 of that window
        self._reader = None

    @classmethod
    def from_array(cls, grey: np.ndarray) -> "LineSource":
        grey = np.asarray(grey, np.float32)
        return cls(grey.shape[1], grey.shape[0], lambda x0, y0, x1, y1: grey[y0:y1, x0:x1])

    @classmethod
    def from_raster(cls, info, bands) -> "LineSource":
        """``info``: a :class:`hamta.core.io.raster.RasterInfo`; ``bands`` as :func:`resolve_bands` gives."""
        from ..io.windows import WindowReader

        source = cls(info.width, info.height, None)
        source._reader = WindowReader(info, bands)
        source._read = lambda x0, y0, x1, y1: _paper_where_invalid(*source._reader.read(Window(x0, y0, x1 - x0,
                                                                                               y1 - y0)))
        return source

    def __enter__(self) -> "LineSource":
        if self._reader is not None:
            self._reader.__enter__()
        return self

    def __exit__(self, *exc):
        if self._reader is not None:
            self._reader.__exit__(*exc)
        return False

    @property
    def shape(self) -> Tuple[int, int]:
        return self.height, self.width

    def around(self, xy, half: float) -> Optional[Tuple[np.ndarray, float, float]]:
        """(the line map of the window reaching ``half`` px around ``xy``, its left and top edge in scan px), or
        None where that window leaves the scan."""
        x0, y0 = int(math.floor(xy[0] - half)), int(math.floor(xy[1] - half))
        x1, y1 = int(math.ceil(xy[0] + half)) + 1, int(math.ceil(xy[1] + half)) + 1
        if x0 < 0 or y0 < 0 or x1 > self.width or y1 > self.height:
            return None
        return self.lines(x0, y0, x1, y1), float(x0), float(y0)

    def grey(self, x0: int, y0: int, x1: int, y1: int) -> np.ndarray:
        """The scan's grey window [x0, x1) x [y0, y1) (inside the scan)."""
        return self._read(x0, y0, x1, y1)

    def lines(self, x0: int, y0: int, x1: int, y1: int) -> np.ndarray:
        """The line map of the window [x0, x1) x [y0, y1) (inside the scan), as on the whole scan."""
        m = LINE_WIDTH_PX
        r0, c0 = max(y0 - m, 0), max(x0 - m, 0)
        grey = self._read(c0, r0, min(x1 + m, self.width), min(y1 + m, self.height))
        return line_map(grey)[y0 - r0:y1 - r0, x0 - c0:x1 - c0]

    def reduced(self, factor: int, tile: int = 2048) -> np.ndarray:
        """The line map above its median (the grain of the paper and the scan) averaged over ``factor`` x ``factor``
        blocks (a thin line keeps its weight), computed tile by tile: pixel (i, j) covers scan px
        [j * factor, (j + 1) * factor) x [i * factor, (i + 1) * factor)."""
        tile = max(tile // factor, 1) * factor
        out = np.zeros((-(-self.height // factor), -(-self.width // factor)), np.float32)
        for y0 in range(0, self.height, tile):
            for x0 in range(0, self.width, tile):
                x1, y1 = min(x0 + tile, self.width), min(y0 + tile, self.height)
                block = self.lines(x0, y0, x1, y1)
                block = np.maximum(block - np.median(block), 0)  # the paper's grain and the scan's noise: no ink
                h, w = -(-(y1 - y0) // factor) * factor, -(-(x1 - x0) // factor) * factor
                padded = np.zeros((h, w), np.float32)
                padded[:y1 - y0, :x1 - x0] = block
                out[y0 // factor:y0 // factor + h // factor, x0 // factor:x0 // factor + w // factor] = \
                    padded.reshape(h // factor, factor, w // factor, factor).mean(axis=(1, 3))
        return out


def _paper_where_invalid(grey: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """``grey`` with nodata as the paper's tone (the window's brightest common value), so that the edge of a
    missing corner is not taken for a line."""
    if valid.all() or not valid.any():
        return grey
    out = grey.copy()
    out[~valid] = float(np.percentile(grey[valid], 90))
    return out
