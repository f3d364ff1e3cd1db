"""The command line's progress display."""
from __future__ import annotations

import sys


class ProgressBar:
    """A one-line progress bar on stderr (plain percentage lines when stderr is not a terminal)."""

    def __init__(self, enabled: bool = True, stream=None):
        self.enabled = enabled
        self.stream = stream or sys.stderr
        self.tty = self.stream.isatty()
        self.last = -1

    def __call__(self, fraction: float, message: str = "") -> None:
        if not self.enabled:
            return
        pct = int(round(100 * fraction))
        if self.tty:
            bar = "#" * (pct // 4) + "-" * (25 - pct // 4)
            self.stream.write(f"\r[{bar}] {pct:3d}% {message:<24}")
            if pct >= 100:
                self.stream.write("\n")
            self.stream.flush()
        elif pct // 10 > self.last // 10 or pct == 100 and self.last != 100:
            self.stream.write(f"{pct:3d}% {message}\n")
        self.last = pct
