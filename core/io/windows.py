"""Many small full-resolution windows of one raster, as :func:`hamta.core.io.raster.read_image` reads
them: what the refinement and the check read at hundreds of sites. A small raster without tiles is read
whole once (once per run, within :func:`hamta.core.io.scope.run_scope`) and its windows cut from memory (a
JPEG, or a file in strips, is decoded from its start or a strip's for every window GDAL reads). Others are
read window by window: within a run through the run's dataset, whose blocks GDAL decoded when the run
described the file, else through one open dataset per thread.
Coordinates: windows in whole full-resolution pixels of the raster (corner convention).
"""
from __future__ import annotations

import dataclasses
import threading

import numpy as np
import rasterio
from rasterio.windows import Window

from .raster import RasterInfo, numpy_dtype, read_image
from .scope import current, dataset_for, file_key

HOLD_PIXELS = 4_000_000  # largest raster without tiles held whole: 20 MB of grey image and mask, read once
SHARED_BYTES = 512 * 2 ** 20  # largest raster read through the run's dataset (what GDAL's block cache may keep)


class WindowReader:
    """Grey windows and their validity (as :func:`read_image` returns them) of ``info``'s ``bands``; use as
    a context manager. One reader may be shared by threads."""

    def __init__(self, info: RasterInfo, bands, hold_pixels: int = HOLD_PIXELS):
        self.info, self.bands = info, tuple(bands)
        self._hold = info.width * info.height <= hold_pixels
        self._held = None
        size = info.width * info.height * info.count * numpy_dtype(info.dtype).itemsize
        files = current() if size <= SHARED_BYTES and file_key(info.path) is not None else None
        self._shared = None if files is None else files.dataset(info.path)  # (dataset, its lock)
        self._local = threading.local()
        self._opened = []
        self._lock = threading.Lock()

    def __enter__(self) -> "WindowReader":
        if self._hold:
            with dataset_for(self.info.path) as ds:  # the run's, when there is a run
                if ds.block_shapes[0][1] >= self.info.width:  # no tiles: a window decodes from a row's start
                    self._held = _whole_without_collar(self.info, self.bands, ds)  # the collar is masked per window
        return self

    def __exit__(self, *exc):
        for ds in self._opened:
            ds.close()
        self._opened.clear()
        self._held = None
        return False

    def read(self, window: Window):
        """(image, valid) of ``window``, parts outside the raster invalid and 0."""
        if self._held is None and self._shared is not None:
            ds, lock = self._shared
            with lock:
                return read_image(self.info, self.bands, window, dataset=ds)
        if self._held is None:
            return read_image(self.info, self.bands, window, dataset=self._dataset())
        image, valid = self._held
        c0, r0, w, h = int(window.col_off), int(window.row_off), int(window.width), int(window.height)
        out, ok = np.zeros((h, w), np.float32), np.zeros((h, w), bool)
        x0, y0 = max(c0, 0), max(r0, 0)
        x1, y1 = min(c0 + w, self.info.width), min(r0 + h, self.info.height)
        if x1 > x0 and y1 > y0:
            out[y0 - r0:y1 - r0, x0 - c0:x1 - c0] = image[y0:y1, x0:x1]
            ok[y0 - r0:y1 - r0, x0 - c0:x1 - c0] = valid[y0:y1, x0:x1]
        if self.info.collar_fill is not None:
            ok &= ~self.info.collar_fill.window_mask(c0, r0, w, h, (h, w))
            out[~ok] = 0
        return out, ok

    def _dataset(self):
        ds = getattr(self._local, "ds", None)
        if ds is None:  # a GDAL dataset is not shared by threads
            ds = self._local.ds = rasterio.open(self.info.path)
            with self._lock:
                self._opened.append(ds)
        return ds


def _whole_without_collar(info: RasterInfo, bands, dataset=None) -> tuple:
    """(image, valid) of the whole raster, its collar not masked; within a run, read once (read only) for every
    caller (see :meth:`RunFiles.whole`)."""
    plain = dataclasses.replace(info, collar_fill=None)
    read = lambda: read_image(plain, bands, dataset=dataset)  # noqa: E731
    files, key = current(), file_key(info.path)
    return read() if files is None or key is None else files.whole((key, plain, tuple(bands)), read)


def read_whole(info: RasterInfo, bands) -> tuple:
    """(image, valid) of the whole raster as :func:`read_image` gives them. Within a run, a raster small enough
    to hold is read once for this and for its window readers (read only)."""
    if info.width * info.height > HOLD_PIXELS:
        return read_image(info, bands)
    image, valid = _whole_without_collar(info, bands)
    if info.collar_fill is None:
        return image, valid
    valid = valid & ~info.collar_fill.window_mask(0, 0, info.width, info.height, valid.shape)
    return np.where(valid, image, 0).astype(np.float32, copy=False), valid
