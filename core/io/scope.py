"""What one run keeps of its input files while it lasts: their descriptions, one open dataset per
file, and small rasters read whole for their windows. A run reads each input several times (its description
samples the pixels for a collar, then the working image, the refinement's and the check's windows, the
previews); GDAL keeps the blocks a dataset decoded, so on one dataset a large file's second decimated read
costs a tenth of its first. Outside :func:`run_scope` nothing is kept.
"""
from __future__ import annotations

import contextlib
import os
import stat
import threading
from contextvars import ContextVar
from typing import Optional

import rasterio

from ..memory import return_freed_memory


class RunFiles:
    """Descriptions, open datasets and small rasters read whole, by file (see :func:`file_key`), each dataset
    with its lock (a GDAL dataset is read by one thread at a time)."""

    def __init__(self):
        self.described = {}
        self._open = {}
        self._whole = {}
        self._lock = threading.Lock()

    def whole(self, key, read):
        """``read()`` (a raster read whole, as a tuple of arrays, kept read only) once per run for ``key``:
        the refinement and the check of every attempt read the same small raster."""
        with self._lock:
            found = self._whole.get(key)
        if found is None:
            found = read()
            for array in found:
                array.setflags(write=False)
            with self._lock:
                found = self._whole.setdefault(key, found)
        return found

    def dataset(self, path: str):
        key = file_key(path)
        with self._lock:
            if key not in self._open:
                self._open[key] = (rasterio.open(path), threading.Lock())
            return self._open[key]

    def close(self) -> None:
        with self._lock:
            for ds, _ in self._open.values():
                ds.close()
            self._open.clear()
            self._whole.clear()


_CURRENT: ContextVar[Optional[RunFiles]] = ContextVar("hamta_run_files", default=None)


@contextlib.contextmanager
def run_scope():
    """Within this block (one job, and threads started with its context), input files are described once
    and read through one dataset each; inside another such block, that block's files."""
    if current() is not None:
        yield current()
        return
    return_freed_memory()
    files = RunFiles()
    token = _CURRENT.set(files)
    try:
        yield files
    finally:
        _CURRENT.reset(token)
        files.close()


def current() -> Optional[RunFiles]:
    return _CURRENT.get()


def release_datasets() -> None:
    """Close the run's datasets (and free the blocks GDAL keeps for them); a later read opens them again."""
    files = current()
    if files is not None:
        files.close()


def file_key(path: str):
    """A local file's path and what changes with its content; None for other paths (a ``/vsi`` path, a
    subdataset or a URL is described and opened afresh every time)."""
    try:
        st = os.stat(path)
    except (OSError, ValueError):
        return None
    if not stat.S_ISREG(st.st_mode):
        return None
    return path, os.path.abspath(path), st.st_ino, st.st_size, st.st_mtime_ns


@contextlib.contextmanager
def dataset_for(path: str, dataset=None):
    """An open dataset of ``path``: ``dataset`` when given, the run's own (locked while used) inside
    :func:`run_scope`, else one opened for this block."""
    files = current()
    if dataset is not None:
        yield dataset
    elif files is not None and file_key(path) is not None:
        ds, lock = files.dataset(path)
        with lock:
            yield ds
    else:
        ds = rasterio.open(path)
        with ds:
            yield ds
