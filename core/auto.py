"""``auto``: methods from fast to robust, until one's result verifies.

For two georeferenced rasters, the offset their georeferencing leaves is measured first, by
correlation in well-spread windows (:mod:`hamta.core.methods.shift`, AROSICS's ground). Then the
fast path: OpenCV SIFT registers most same-sensor pairs in about a second, and
when its result verifies nothing else runs. Otherwise rotation- and scale-invariant multimodal
matching (``xmodal``), then, where the optional 'learned' extra is installed, XFeat's learned
features (images of other years, :mod:`hamta.core.methods.xfeat`), then the structural (CFOG) search
for north-up modality gaps, then
SAR-specific matching, and last the slow all-rotation structural search, each checked by the
same independent verification (:mod:`hamta.core.verify`), until one verifies or the chain ends (a count
of methods: the same work, and the same verdict, on any machine and under any load; a time cap is the
user's choice, off by default). The result says which methods ran, in what order, how long each took and why each was
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
from enum import Enum
from typing import Callable, List, Mapping, Optional, Tuple

from .errors import DeadlineReached, InsufficientMatchesError, method_crashes
from .learned import available as learned_available
from .outcome import Attempt, AutoRun
from .progress import Monitor
from .verify import corroborate, corroborating, error_bound, result_rank

AUTO = "auto"


# The shift's verified result whose check bounds its error above this share of the tolerance (0.5 px of the
# default 3) lets the precise steps try to do better; the one with the smaller bound is kept. On NAIP pairs
# two to seven years apart (``hamta bench --families years-apart``), the shift verified with bounds of
# 0.69-1.33 px (errors 0.44-0.86 px) where xmodal's bounds were 0.31-0.88 px (errors 0.16-0.56 px).
# Relative, because a user who asks for 15 px does not want the time spent on a tenth of a pixel. Only
# after the shift: after SIFT (refined at full resolution, the fast path of pairs without georeferencing)
# xmodal and XFeat took a small optical pair's bound from 3.63 to 3.21 px in 9 s more.
PRECISE_SHARE = 1 / 6


class When(Enum):
    """A condition under which a step of :data:`CHAIN` is in a plan's chain (:func:`chain_for`)."""

    PRIOR = "the target's georeferencing placed it on the reference"
    NO_PRIOR = "nothing placed the target on the reference"
    FULL = "the whole chain, not the short one of a basemap search's places"
    LEARNED = "the 'learned' extra is installed and not turned off"


@dataclass(frozen=True)
class Step:
    """One method ``auto`` may try, with its parameters, what it is for, and its refinement when the
    user leaves it on 'auto' ('on': SIFT keypoints are located to a few hundredths of a pixel; full-
    resolution correlation around them makes the result three to five times more accurate for a
    few tenths of a second, measured on the rotation family). ``rough``: a fast step whose verified result,
    when the check bounds its error above :data:`PRECISE_SHARE` of the tolerance, the ``precise`` steps after
    it try to beat (fast, and as accurate as any). ``when``: the conditions that must all hold for the step
    to be in a chain (none: always)."""

    method: str
    params: Mapping[str, object]
    why: str
    refine: str = "auto"
    precise: bool = False
    rough: bool = False
    when: Tuple[When, ...] = ()


LEARNED_WHY = "optical images years apart: learned features (the 'learned' extra)"
# Refinement 'on' for the shift: its windows are few, the full-resolution grid gives the fit its spread and
# precision. XFeat runs upright where the georeferencing placed the target on the reference, turned every 45
# degrees otherwise; after xmodal (before it, XFeat's answers were kept on 6 of 54 real multimodal pairs that
# xmodal registers more accurately, and it cost time on every pair).
CHAIN = (
    Step("shift", {}, "both rasters georeferenced: the offset left, by correlation in windows", refine="on",
         rough=True, when=(When.PRIOR,)),
    Step("sift", {}, "fast; the same sensor or similar images, any rotation and scale", refine="on", precise=True),
    Step("xmodal", {}, "across modalities (SAR, infrared, depth, maps, night lights), any rotation, scale 1/2-2",
         precise=True),
    Step("xfeat", {}, LEARNED_WHY, refine="on", precise=True, when=(When.LEARNED, When.PRIOR)),
    Step("xfeat", {"max_rotation_deg": 180.0}, LEARNED_WHY, refine="on", precise=True,
         when=(When.LEARNED, When.NO_PRIOR)),
    Step("cfog", {}, "across modalities, target roughly north-up: dense structural search"),
    Step("regions", {}, "a scanned map onto a layer of its areas (lakes, blocks): regions as control points, any "
         "rotation and scale", when=(When.FULL,)),
    Step("ndsift-pc", {}, "SAR onto SAR: speckle-robust features, any rotation", when=(When.FULL,)),
    Step("cfog", {"max_rotation_deg": 180.0}, "across modalities at any rotation, dense (slow)", when=(When.FULL,)),
)


def chain_for(plan_mode: str, short: bool = False):
    """The steps of :data:`CHAIN` whose conditions hold for a plan: the shift first when the target's
    georeferencing placed it; the learned matcher when its extra is available (:func:`hamta.core.learned.available`).
    ``short``: up to the north-up structural search only, and the first verified result taken (a
    basemap search's places, where a wrong place must cost little, and the same work on any machine: the
    SAR matcher and the all-rotation dense search after it are for gaps a basemap seldom has; trying to
    beat a verified place's bound would cost every place the precise matchers' time again)."""
    prior = plan_mode == "georeferenced"
    holds = {When.PRIOR: prior, When.NO_PRIOR: not prior, When.FULL: not short, When.LEARNED: learned_available()}
    chain = tuple(step for step in CHAIN if all(holds[w] for w in step.when))
    return tuple(dataclasses.replace(step, precise=False) for step in chain) if short else chain


class Polishing(Enum):
    """Whether the precise steps may try to beat the verified result: undecided until a result verifies,
    then on when that first verified result is a rough step's (the shift), off otherwise."""

    UNDECIDED = "undecided"
    ON = "on"
    OFF = "off"


def register_auto(attempt: Callable, options, monitor: Monitor, chain) -> object:
    """Try ``chain``'s steps (:func:`chain_for`) in order; return the first verified result, else the best
    unverified one. When the first verified result is a rough step's (the shift) and the check bounds its
    error above :data:`PRECISE_SHARE` of ``options.tolerance_px``, the precise steps after it run until one is
    bounded within that, and the verified result with the smallest bound is returned.

    The chain bounds the work. ``options.auto_budget_s``, where the user sets it, is a time cap: once spent,
    the running step is stopped (at its next progress report) and no further step starts. The first step is
    exempt, so that a cap shorter than the fast path still gives a result. Raises
    :class:`InsufficientMatchesError` (listing every attempt) when no step produced a model. Only that error
    means "no model": a step raising anything else but a Hamta error is a bug, and ends the run as
    :class:`MethodCrashed` naming it.
    """
    start = time.perf_counter()
    cap = options.auto_budget_s
    spent = f"time cap of {cap:g} s spent" if cap is not None else ""
    attempts: List[Attempt] = []
    found = []
    best, chosen = None, None
    polishing = Polishing.UNDECIDED
    for i, step in enumerate(chain):
        if cap is not None and time.perf_counter() - start > cap:
            attempts.append(tried(step, "skipped", spent))
            continue
        if best is not None and best.verified and not step.precise:
            break
        t0 = time.perf_counter()
        step_monitor = monitor.span(i / len(chain), (i + 1) / len(chain))
        if i and cap is not None:
            step_monitor = step_monitor.until(start + cap)
        result, record = run_step(attempt, step, step_monitor, spent, t0)
        attempts.append(record)
        if result is None:
            continue
        result, attempts[-1] = corroborated(result, attempts[-1], found, options.tolerance_px)
        found.append(result)
        if best is not None and best.verified and result.verified:
            attempts[-1] = dataclasses.replace(attempts[-1], reason=compared(result, best))
        if better(result, best):
            best, chosen = result, len(attempts) - 1
        if result.verified and polishing is Polishing.UNDECIDED:
            polishing = Polishing.ON if step.rough else Polishing.OFF
        if best.verified and not (polishing is Polishing.ON and bound(best) > PRECISE_SHARE * options.tolerance_px):
            break
    monitor.report(1.0, "registered")
    if best is None:
        raise InsufficientMatchesError(
            "No method found a registration ('auto' tried " + "; ".join(
                f"{a.method}: {a.reason}" for a in attempts) + ").", 0, 1)
    timings = dataclasses.replace(best.timings, auto_total=round(time.perf_counter() - start, 4))
    return dataclasses.replace(best, auto=AutoRun.of(attempts, chosen), timings=timings)


def run_step(attempt: Callable, step: Step, monitor: Monitor, spent: str, t0: float):
    """``step`` run through ``attempt`` (started at ``t0``): its result, None when it found no model or the
    budget (``spent``) stopped it, and its :class:`Attempt`. Any other Hamta error (bad input, canceled) and a
    bug (:class:`MethodCrashed`) end the run."""
    try:
        with method_crashes(step.method):
            result = attempt(step.method, dict(step.params), monitor, step.refine)
    except DeadlineReached:
        return None, tried(step, "stopped", spent, t0)
    except InsufficientMatchesError as exc:  # the one signal of "this method found no model"
        return None, tried(step, "no model", _first_line(exc), t0)
    v = result.verification
    return result, tried(step, v.verdict, "; ".join(v.reasons) or "verified", t0)


def corroborated(result, record: Attempt, found: list, tolerance_px: float):
    """``result`` and its ``record``, or, where it did not verify on its own but it and a result ``found``
    before it each have partial support and agree within ``tolerance_px``, the two corroborated (verified)."""
    partner = None if result.verification.verified else corroborating(result, found, tolerance_px)
    if partner is None:
        return result, record
    result = corroborate(result, partner[0], partner[1])
    return result, dataclasses.replace(record, outcome="verified",
                                       reason=_first_line(result.verification.corroboration["summary"]))


def bound(result) -> float:
    """The check's bound on the result's error, reference px (infinite where it gave none)."""
    return error_bound(result.verification)


def better(result, best) -> bool:
    """Whether ``result`` is to be returned rather than ``best``: of two verified results the one the check
    bounds more tightly (never the fit's own residuals), else the better verdict and support."""
    if best is None:
        return True
    if result.verified and best.verified:
        return bound(result) < bound(best)
    return result_rank(result) > result_rank(best)


def compared(result, best) -> str:
    """Why a verified result after ``best`` (verified) is kept or not, in the attempts list."""
    verb = "kept" if better(result, best) else "not kept"
    return f"verified, error bound {bound(result):.2f} px against {best.method}'s {bound(best):.2f} px: {verb}"


def tried(step: Step, outcome: str, reason: str, t0: Optional[float] = None) -> Attempt:
    """The attempt of ``step``: its outcome, why, and the time since ``t0`` (0 when it did not start)."""
    return Attempt(step.method, dict(step.params), step.why, outcome, reason,
                   0.0 if t0 is None else round(time.perf_counter() - t0, 3))


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return text[0] if text else type(exc).__name__
