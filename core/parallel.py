"""Running independent pieces of one registration side by side on this machine's cores.

Reading (GDAL), OpenCV, FFTs and large numpy operations release the GIL, so threads share the cores
without copying the images. Results keep their order whatever finishes first, so a run gives the same
answer on any number of cores, and so do errors: the first item's error is raised. Each piece runs in
the caller's context (the run's open files, see :mod:`hamta.core.io.scope`).
"""
from __future__ import annotations

import contextvars
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
    with ThreadPoolExecutor(threads) as pool:
        futures = [pool.submit(contextvars.copy_context().run, fn, x) for x in items]
        try:
            for done, _ in enumerate(as_completed(futures)):
                if monitor is not None:
                    monitor.report((done + 1) / len(items), message)
        except BaseException:  # canceled: what has not started does not start
            for f in futures:
                f.cancel()
            raise
    return [f.result() for f in futures]
