"""Progress reporting and cancellation, bridged by each front end (CLI bar, Processing feedback).

What a front end is told moves forward only: the fraction of a run never goes back, and a stage's
counter ('fetching tiles 17/26') counts on over the run instead of restarting at each read (see
:class:`Forward`); :func:`stage_name` strips the counter, so a log has one line per stage.
"""
from __future__ import annotations

import re
import threading
import time
from typing import Callable, Dict, Optional, Tuple

from .errors import DeadlineReached, RegistrationCanceled

ProgressFn = Callable[[float, str], None]
CancelFn = Callable[[], bool]


COUNTER = re.compile(r"^(.*?)\s*(\d+)/(\d+)$")  # 'fetching tiles 3/16': the stage, then done/total


def stage_name(message: str) -> str:
    """The stage a progress message is about, without its trailing counter: 'fetching tiles 3/16' ->
    'fetching tiles' (a log shows one line per stage, not one per tile)."""
    found = COUNTER.match(message or "")
    return found.group(1) if found else (message or "")


class Forward:
    """What a run reports, made to move forward only, then passed to ``progress(fraction, message)``.

    The fraction never goes back (stages run in threads, and a later stage's span may begin below
    where an earlier report stood); a report that says nothing new (same fraction and message) is
    dropped. A stage's counter continues over the run: when 'fetching tiles 1/16' follows
    'fetching tiles 10/10', it reads 'fetching tiles 11/26'. Applying it twice changes nothing, so a
    monitor nested in another's span (:func:`hamta.core.pipeline.register` inside a run) is harmless.
    Thread-safe: ``progress`` is called under a lock, in the order of the fractions it gets.
    """

    def __init__(self, progress: "ProgressFn"):
        self._progress = progress
        self._lock = threading.RLock()
        self._last: Optional[Tuple[float, str]] = None
        self._counted: Dict[str, Tuple[int, int, int]] = {}  # stage -> (before this count, done, total)

    def __call__(self, fraction: float, message: str = "") -> None:
        with self._lock:
            fraction = max(fraction, self._last[0]) if self._last is not None else fraction
            message = self._counter(message)
            if (fraction, message) == self._last:
                return
            self._last = fraction, message
            self._progress(fraction, message)

    def _counter(self, message: str) -> str:
        found = COUNTER.match(message or "")
        if found is None:
            return message
        stage, done, total = found.group(1), int(found.group(2)), int(found.group(3))
        before, last, last_total = self._counted.get(stage, (0, 0, 0))
        if done < last and (done == 1 or total != last_total):  # a new count: it goes on from the last one
            before, last = before + last, 0
        done = max(done, last)  # a late report of the same count (threads) does not go back
        self._counted[stage] = before, done, total
        return f"{stage} {before + done}/{before + total}"


class Monitor:
    """Maps stage-local progress onto an overall 0..1 range and checks for cancellation.

    Parameters
    ----------
    progress : callable(fraction, message), optional
        Receives the overall fraction in [0, 1] and a short stage name, through :class:`Forward`: the
        fraction never goes back and a stage's counter continues over the run.
    is_canceled : callable() -> bool, optional
        Polled at every report; when it returns True, :class:`RegistrationCanceled` is raised.
    deadline : float, optional
        A ``time.perf_counter()`` value; once passed, every report raises :class:`DeadlineReached`.
    """

    def __init__(self, progress: Optional[ProgressFn] = None, is_canceled: Optional[CancelFn] = None,
                 start: float = 0.0, stop: float = 1.0, deadline: Optional[float] = None, label: str = ""):
        self._progress = progress if progress is None or isinstance(progress, Forward) else Forward(progress)
        self._is_canceled = is_canceled
        self._start = start
        self._stop = stop
        self._deadline = deadline
        self._label = label

    def report(self, fraction: float, message: str = "") -> None:
        """Report ``fraction`` (0..1) of this monitor's span; raise if cancellation was asked."""
        self.check()
        if self._progress is not None:
            f = min(max(fraction, 0.0), 1.0)
            text = f"{self._label}: {message}" if self._label and message else message
            self._progress(self._start + f * (self._stop - self._start), text)

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
        return Monitor(self._progress, self._is_canceled, self._start, self._stop, deadline, self._label)

    def labelled(self, label: str) -> "Monitor":
        """This monitor with its messages prefixed by ``label`` (which part of a run they are from)."""
        return Monitor(self._progress, self._is_canceled, self._start, self._stop, self._deadline, label)

    def span(self, start: float, stop: float) -> "Monitor":
        """A child monitor covering [start, stop] of this monitor's span (with its deadline and label)."""
        width = self._stop - self._start
        return Monitor(self._progress, self._is_canceled, self._start + start * width, self._start + stop * width,
                       self._deadline, self._label)


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
