"""Running independent pieces of one registration side by side on this machine's cores.

Reading (GDAL), OpenCV, FFTs and large numpy operations release the GIL, so threads share the cores
without copying the images. Results keep their order whatever finishes first, so a run gives the same
answer on any number of cores.
"""
from __future__ import annotations

import os
from typing import Callable, Optional

from .progress import Monitor

THREADS = max(1, min(os.cpu_count() or 1, 4))


def threaded(fn: Callable, items, monitor: Optional[Monitor] = None, message: str = "") -> list:
    """``[fn(x) for x in items]`` on up to ``THREADS`` threads, in order; exceptions propagate. ``monitor``
    reports the share of items done."""
    from concurrent.futures import ThreadPoolExecutor, as_completed

    items = list(items)
    threads = min(THREADS, len(items))
    if threads < 2:
        out = []
        for i, x in enumerate(items):
            out.append(fn(x))
            if monitor is not None:
                monitor.report((i + 1) / len(items), message)
        return out
    out = [None] * len(items)
    with ThreadPoolExecutor(threads) as pool:
        futures = {pool.submit(fn, x): i for i, x in enumerate(items)}
        for done, future in enumerate(as_completed(futures)):
            out[futures[future]] = future.result()
            if monitor is not None:
                monitor.report((done + 1) / len(items), message)
    return out
