"""Freed arrays go back to the system, so a long-lived process does not grow run after run (glibc).

A run allocates large arrays (tiles, an area's features, FFT planes) in several threads. By default glibc
gives threads up to eight heaps (arenas) per core, and what a thread frees stays in its heap, in fragments
the next thread's arrays do not fit. In one process (QGIS, a batch worker, the bench), a 30x basemap
search peaked at 722 MB as its first run and 903 MB as its third; with two heaps, 484 and 553 MB, in
the same time. (Mapping every array of 1 MiB or more on its own cut the peaks as much but cost up to 70 %
more time: each new array's pages are zeroed again.)

The setting is made once per process, at its first run, and only where the user set no ``MALLOC_*``
variable of their own; elsewhere (another C library) nothing is done. A process that has already made
more heaps (QGIS's threads) keeps them.
"""
from __future__ import annotations

import ctypes
import os
import sys
import threading

M_ARENA_MAX = -8
ARENAS = 2

_done = threading.Event()


def return_freed_memory() -> None:
    if _done.is_set():
        return
    _done.set()
    if not sys.platform.startswith("linux") or any(k.startswith("MALLOC_") for k in os.environ):
        return
    try:
        libc = ctypes.CDLL("libc.so.6")
        libc.mallopt(M_ARENA_MAX, ARENAS)
    except (OSError, AttributeError):
        pass
