"""``auto``: methods from fast to robust, until one's result verifies.

For two georeferenced rasters, the offset their georeferencing leaves is measured first, by
correlation in well-spread windows (:mod:`hamta.core.methods.shift`, AROSICS's ground). Then the
fast path: OpenCV SIFT registers most same-sensor pairs in about a second, and
when its result verifies nothing else runs. Otherwise rotation- and scale-invariant multimodal
matching (``xmodal``), then, where the optional 'learned' extra is installed, XFeat's learned
features (images of other years, :mod:`hamta.core.methods.xfeat`), then the structural (CFOG) search
for north-up modality gaps, then
SAR-specific matching, and last the slow all-rotation structural search, each checked by the
same independent verification (:mod:`hamta.core.verify`), until one verifies or the time budget
is spent. The result says which methods ran, in what order, how long each took and why each was
accepted or rejected; when none verified, the best unverified result is returned, marked as such.
Two results of different methods that each have partial support from the check and agree with
each other within the tolerance verify each other (agreement between independent estimates).

This module does not register by itself: :func:`register_auto` receives ``attempt(method, params,
monitor, refine) -> RegistrationResult``, which the pipeline binds to images it has read once.
"""
from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass
from typing import Callable, List, Mapping, Optional

from .errors import DeadlineReached, InsufficientMatchesError, method_crashes
from .outcome import Attempt, AutoRun
from .progress import Monitor
from .verify import corroborate, corroborating, result_rank

AUTO = "auto"


@dataclass(frozen=True)
class Step:
    """One method ``auto`` may try, with its parameters, what it is for, and its refinement when the
    user leaves it on 'auto' ('on': SIFT keypoints are located to a few hundredths of a pixel; full-
    resolution correlation around them makes the result three to five times more accurate for a
    few tenths of a second, measured on the rotation family)."""

    method: str
    params: Mapping[str, object]
    why: str
    refine: str = "auto"


CHAIN = (
    Step("sift", {}, "fast; the same sensor or similar images, any rotation and scale", refine="on"),
    Step("xmodal", {}, "across modalities (SAR, infrared, depth, maps, night lights), any rotation, scale 1/2-2"),
    Step("cfog", {}, "across modalities, target roughly north-up: dense structural search"),
    Step("ndsift-pc", {}, "SAR onto SAR: speckle-robust features, any rotation"),
    Step("cfog", {"max_rotation_deg": 180.0}, "across modalities at any rotation, dense (slow)"),
)
# Refinement 'on': the windows are few, the full-resolution grid gives the fit its spread and precision.
SHIFT_STEP = Step("shift", {}, "both rasters georeferenced: the offset left, by correlation in windows", refine="on")


def chain_for(plan_mode: str, short: bool = False):
    """The steps for a plan: the shift first when the target's georeferencing placed it; the learned
    matcher after ``xmodal`` when its extra is installed (before it, XFeat's answers were kept on 6 of 54
    real multimodal pairs that ``xmodal`` registers more accurately, and it cost time on every pair).
    ``short``: up to the north-up structural search only (a
    basemap search's places, where a wrong place must cost little, and the same work on any machine: the
    SAR matcher and the all-rotation dense search after it are for gaps a basemap seldom has)."""
    prior = plan_mode == "georeferenced"
    return ((SHIFT_STEP,) if prior else ()) + CHAIN[:2] + learned_steps(prior) + CHAIN[2:3 if short else None]


def learned_steps(prior: bool) -> tuple:
    """XFeat when the 'learned' extra is installed: upright where the georeferencing placed the target
    on the reference, every 45 degrees otherwise."""
    from .descriptors.xfeat import available

    if not available():
        return ()
    return (Step("xfeat", {} if prior else {"max_rotation_deg": 180.0},
                 "optical images years apart: learned features (the 'learned' extra)", refine="on"),)


def register_auto(attempt: Callable, options, monitor: Monitor, chain=None):
    """Try ``chain``'s steps in order; return the first verified result, else the best one.

    ``options.auto_budget_s`` is a deadline: once spent, the running step is stopped (at its next
    progress report) and no further step starts. The first step is exempt, so that a budget shorter
    than the fast path still gives a result. Raises :class:`InsufficientMatchesError` (listing
    every attempt) when no step produced a model. Only that error means "no model": a step raising
    anything else but a Hamta error is a bug, and ends the run as :class:`MethodCrashed` naming it.
    """
    chain = CHAIN if chain is None else chain
    start = time.perf_counter()
    attempts: List[Attempt] = []
    found = []
    best, chosen = None, None
    for i, step in enumerate(chain):
        elapsed = time.perf_counter() - start

        spent = f"time budget of {options.auto_budget_s:g} s spent"
        if elapsed > options.auto_budget_s:
            attempts.append(tried(step, "skipped", spent))
            continue
        t0 = time.perf_counter()
        step_monitor = monitor.span(i / len(chain), (i + 1) / len(chain))
        if i:
            step_monitor = step_monitor.until(start + options.auto_budget_s)
        try:  # any other Hamta error (bad input, canceled) and a bug (MethodCrashed) end the run
            with method_crashes(step.method):
                result = attempt(step.method, dict(step.params), step_monitor, step.refine)
        except DeadlineReached:
            attempts.append(tried(step, "stopped", spent, t0))
            continue
        except InsufficientMatchesError as exc:  # the one signal of "this method found no model"
            attempts.append(tried(step, "no model", _first_line(exc), t0))
            continue
        v = result.verification
        attempts.append(tried(step, v.verdict, "; ".join(v.reasons) or "verified", t0))
        partner = None if v.verified else corroborating(result, found, options.tolerance_px)
        if partner is not None:
            result = corroborate(result, partner[0], partner[1])
            attempts[-1] = dataclasses.replace(attempts[-1], outcome="verified",
                                               reason=_first_line(result.verification.corroboration["summary"]))
        found.append(result)
        if best is None or result_rank(result) > result_rank(best):
            best, chosen = result, len(attempts) - 1
        if result.verified:
            break
    monitor.report(1.0, "registered")
    if best is None:
        raise InsufficientMatchesError(
            "No method found a registration ('auto' tried " + "; ".join(
                f"{a.method}: {a.reason}" for a in attempts) + ").", 0, 1)
    timings = dataclasses.replace(best.timings, auto_total=round(time.perf_counter() - start, 4))
    return dataclasses.replace(best, auto=AutoRun.of(attempts, chosen), timings=timings)


def tried(step: Step, outcome: str, reason: str, t0: Optional[float] = None) -> Attempt:
    """The attempt of ``step``: its outcome, why, and the time since ``t0`` (0 when it did not start)."""
    return Attempt(step.method, dict(step.params), step.why, outcome, reason,
                   0.0 if t0 is None else round(time.perf_counter() - t0, 3))


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return text[0] if text else type(exc).__name__
