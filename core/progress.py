"""Progress reporting and cancellation, bridged by each front end (CLI bar, Processing feedback)."""
from __future__ import annotations

import time
from typing import Callable, Optional

from .errors import DeadlineReached, RegistrationCanceled

ProgressFn = Callable[[float, str], None]
CancelFn = Callable[[], bool]


class Monitor:
    """Maps stage-local progress onto an overall 0..1 range and checks for cancellation.

    Parameters
    ----------
    progress : callable(fraction, message), optional
        Receives the overall fraction in [0, 1] and a short stage name.
    is_canceled : callable() -> bool, optional
        Polled at every report; when it returns True, :class:`RegistrationCanceled` is raised.
    deadline : float, optional
        A ``time.perf_counter()`` value; once passed, every report raises :class:`DeadlineReached`.
    """

    def __init__(self, progress: Optional[ProgressFn] = None, is_canceled: Optional[CancelFn] = None,
                 start: float = 0.0, stop: float = 1.0, deadline: Optional[float] = None):
        self._progress = progress
        self._is_canceled = is_canceled
        self._start = start
        self._stop = stop
        self._deadline = deadline

    def report(self, fraction: float, message: str = "") -> None:
        """Report ``fraction`` (0..1) of this monitor's span; raise if cancellation was asked."""
        self.check()
        if self._progress is not None:
            f = min(max(fraction, 0.0), 1.0)
            self._progress(self._start + f * (self._stop - self._start), message)

    def canceled(self) -> bool:
        """Whether the caller asked to stop (without raising)."""
        return self._is_canceled is not None and bool(self._is_canceled())

    def check(self) -> None:
        """Raise :class:`RegistrationCanceled` when the caller asked to stop, :class:`DeadlineReached`
        when the deadline has passed."""
        if self.canceled():
            raise RegistrationCanceled("Registration canceled; no outputs were written.")
        if self._deadline is not None and time.perf_counter() > self._deadline:
            raise DeadlineReached("the time budget is spent")

    def silent(self) -> "Monitor":
        """This monitor without progress reports (for work beside the reporting one); it still cancels."""
        return Monitor(None, self._is_canceled, deadline=self._deadline)

    def until(self, deadline: float) -> "Monitor":
        """This monitor with a ``deadline``."""
        return Monitor(self._progress, self._is_canceled, self._start, self._stop, deadline)

    def span(self, start: float, stop: float) -> "Monitor":
        """A child monitor covering [start, stop] of this monitor's span (with its deadline)."""
        width = self._stop - self._start
        return Monitor(self._progress, self._is_canceled, self._start + start * width, self._start + stop * width,
                       self._deadline)


NULL_MONITOR = Monitor()


class Clock:
    """Wall time of consecutive stages: ``lap(name)`` ends a stage; ``as_dict()`` adds the total."""

    def __init__(self):
        self.start = self.last = time.perf_counter()
        self.laps = {}

    def lap(self, name: str) -> None:
        now = time.perf_counter()
        self.laps[name] = round(now - self.last, 4)
        self.last = now

    def as_dict(self) -> dict:
        return dict(self.laps, total=round(time.perf_counter() - self.start, 4))
