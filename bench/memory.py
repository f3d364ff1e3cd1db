"""Peak resident memory of the process during a block of work (what ``hamta bench`` reports)."""
from __future__ import annotations

import ctypes
import gc
import os
import resource
import threading
from typing import Optional


class PeakRss:
    """Peak resident memory of this process during a block. Freed heap is first returned to the
    system and the kernel's high-water mark reset (Linux), so a case is not charged with what an
    earlier case in the same worker left behind; elsewhere the resident size is sampled every 5 ms."""

    def __enter__(self):
        gc.collect()
        self.exact = _reset_peak()
        self.peak = _rss_mb()
        self._stop = threading.Event()
        self._thread = None
        if not self.exact:
            self._thread = threading.Thread(target=self._sample, daemon=True)
            self._thread.start()
        return self

    def _sample(self):
        while not self._stop.wait(0.005):
            self.peak = max(self.peak, _rss_mb())

    def __exit__(self, *exc):
        self._stop.set()
        if self._thread is not None:
            self._thread.join()
        self.peak = _hwm_mb() if self.exact else max(self.peak, _rss_mb())
        return False


def _reset_peak() -> bool:
    """Trim the C heap and reset VmHWM; False where that is not possible."""
    try:
        ctypes.CDLL("libc.so.6").malloc_trim(0)
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
        return _hwm_mb() > 0
    except (OSError, AttributeError):
        return False


def _hwm_mb() -> float:
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024.0
    return 0.0


def _rss_mb() -> float:
    try:
        with open("/proc/self/statm") as f:
            return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2 ** 20
    except OSError:
        return _maxrss_mb()


def _maxrss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


SPAWN = ("import os, sys; pid = os.posix_spawnp(sys.argv[1], sys.argv[1:], os.environ); "
         "_, status, usage = os.wait4(pid, 0); print(usage.ru_maxrss / 1024.0, os.waitstatus_to_exitcode(status))")


def measured(cmd, env=None, printed: Optional[list] = None) -> tuple:
    """(seconds, peak MB, exit code) of a program run in a fresh process (with ``env``, else this one's
    environment); the lines it printed are added to ``printed`` when given. It is started from a small
    Python process: Linux carries a process's peak RSS across exec, so a child forked from the (large)
    bench process would report the bench's memory as its own."""
    import subprocess
    import sys
    import time

    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, "-c", SPAWN, *cmd], capture_output=True, text=True, check=True, env=env)
    *lines, last = out.stdout.splitlines()  # what the program printed itself, then SPAWN's line
    peak, code = last.split()
    if printed is not None:
        printed.extend(lines)
    return time.perf_counter() - t0, float(peak), int(code)
