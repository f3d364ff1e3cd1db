"""``auto``: the fast path decides first, escalation when it does not verify, every attempt reported."""
import dataclasses

import numpy as np
import pytest

from hamta.bench.families import CaseSpec, build_case
from hamta.core import InsufficientMatchesError, register
from hamta.core import auto as auto_module
from hamta.core.auto import Step


def test_easy_pair_stops_at_sift(demo_pair):
    result = register(demo_pair["target"], demo_pair["reference"])
    assert result.method == "sift" and result.verified
    attempts = result.auto.attempts
    assert [a.method for a in attempts] == ["sift"] and attempts[0].accepted
    assert result.to_report()["auto"]["chosen"] == 0


def test_escalates_to_a_method_whose_result_verifies(tmp_path, shared, monkeypatch):
    spec = CaseSpec("multimodal", "landsat_invert", {"source": "landsat", "mapping": "invert"})
    case = build_case(spec, str(tmp_path), 512, str(shared / "data"))
    chain = (Step("phasecorr", {}, "test"), Step("sift", {}, "test"), Step("cfog", {}, "test"))
    monkeypatch.setattr(auto_module, "CHAIN", chain)
    result = register(case.target, case.reference)
    attempts = result.auto.attempts
    assert result.method == "cfog" and result.verified and attempts[-1].accepted
    # cfog's own registration of the inverted proxy (test_cfog registers the folded one)
    assert np.sqrt(np.mean(case.errors(result.model) ** 2)) < 1.0
    assert result.stats.n_gcps >= 50 and "coarse" in result.diagnostics
    assert [a.method for a in attempts] == ["phasecorr", "sift", "cfog"]
    assert all(a.outcome != "verified" for a in attempts[:2]) and all(a.time_s >= 0 for a in attempts)


def test_nothing_found_names_every_attempt(raster_writer, demo_pair, monkeypatch):
    import numpy as np

    noise = raster_writer("noise.tif", np.random.default_rng(0).integers(0, 255, (300, 300), dtype=np.uint8))
    monkeypatch.setattr(auto_module, "CHAIN", (Step("sift", {}, "test"), Step("orb", {}, "test")))
    with pytest.raises(InsufficientMatchesError, match="'auto' tried sift: .*; orb: "):
        register(noise, demo_pair["reference"])


def test_auto_takes_no_method_parameters(demo_pair):
    with pytest.raises(ValueError, match="takes no method parameters"):
        register(demo_pair["target"], demo_pair["reference"], "auto", params={"ratio": 0.7})


def test_a_time_cap_the_user_sets_stops_a_running_method(monkeypatch):
    """A time cap is a deadline: a step still running when it is spent stops at its next progress
    report (the first step, the fast path, is exempt), and the steps after it do not start."""
    import time

    from hamta.core import RegisterOptions
    from hamta.core.progress import Monitor

    ran = []

    def attempt(method, params, monitor, refine):
        ran.append(method)
        t0 = time.perf_counter()
        while time.perf_counter() - t0 < (0.4 if method == "first" else 30):
            time.sleep(0.01)
            monitor.report(0.5, "working")
        raise InsufficientMatchesError("nothing", 0, 8)

    chain = (Step("first", {}, "t"), Step("slow", {}, "t"), Step("never", {}, "t"))
    t0 = time.perf_counter()
    with pytest.raises(InsufficientMatchesError, match="first: nothing; slow: time cap of 1 s spent; never: time "
                                                        "cap"):
        auto_module.register_auto(attempt, RegisterOptions(auto_budget_s=1.0), Monitor(), chain)
    assert ran == ["first", "slow"] and time.perf_counter() - t0 < 2.0


@pytest.mark.parametrize("error", [ValueError("operands could not be broadcast"), ZeroDivisionError("division by zero"),
                                   IndexError("index 3 is out of bounds")])
def test_a_bug_in_a_method_ends_auto_naming_the_method(demo_pair, raising_method, monkeypatch, error):
    """Errors are not outcomes: anything but a Hamta error raised inside a method is a bug; 'auto'
    does not record it as "no model" and go on, it stops and names the method (the cause kept)."""
    from hamta.core.errors import HamtaError, MethodCrashed

    name = raising_method(error)
    monkeypatch.setattr(auto_module, "CHAIN", (Step(name, {}, "test"), Step("sift", {}, "test")))
    with pytest.raises(MethodCrashed, match=rf"internal error in method '{name}' \({type(error).__name__}: ") as info:
        register(demo_pair["target"], demo_pair["reference"])
    assert info.value.method == name and info.value.__cause__ is error and not isinstance(info.value, HamtaError)
    with pytest.raises(MethodCrashed, match=f"method '{name}'"):  # chosen directly too
        register(demo_pair["target"], demo_pair["reference"], name)


def test_no_model_from_a_method_lets_auto_go_on(demo_pair, raising_method, monkeypatch):
    name = raising_method(InsufficientMatchesError("only 2 matches", 2, 8))
    monkeypatch.setattr(auto_module, "CHAIN", (Step(name, {}, "test"), Step("sift", {}, "test")))
    result = register(demo_pair["target"], demo_pair["reference"])
    first, second = result.auto.attempts
    assert (first.method, first.outcome, first.reason) == (name, "no model", "only 2 matches")
    assert result.method == "sift" and second.accepted and result.verified


def test_a_wrong_method_name_or_parameter_is_the_callers_error_not_a_crash(demo_pair):
    with pytest.raises(ValueError, match="unknown method 'nope'"):
        register(demo_pair["target"], demo_pair["reference"], "nope")
    with pytest.raises(ValueError, match="has no parameter"):
        register(demo_pair["target"], demo_pair["reference"], "sift", params={"wobble": 1})


@dataclasses.dataclass(frozen=True)
class _Check:
    verdict: str
    error_bound_px: float
    n_agree: int = 12
    reasons: tuple = ()
    tolerance_px: float = 3.0
    chance: float = 1e-3
    z_chance: float = 1.0
    z_mw: float = 1.0
    look: str = "grid"

    @property
    def verified(self):
        return self.verdict == "verified"


@dataclasses.dataclass(frozen=True)
class _Timings:
    auto_total: float = 0.0


@dataclasses.dataclass(frozen=True)
class _Result:
    method: str
    verification: _Check
    timings: _Timings = _Timings()
    auto: object = None

    @property
    def verified(self):
        return self.verification.verified


def _auto(outcomes, chain):
    """``register_auto`` over ``chain`` where each method's result is ``outcomes[method]`` (verdict, bound)."""
    from hamta.core import RegisterOptions
    from hamta.core.progress import Monitor

    def attempt(method, params, monitor, refine):
        return _Result(method, _Check(*outcomes[method]))

    return auto_module.register_auto(attempt, RegisterOptions(), Monitor(), chain)


CHAIN_37 = (Step("shift", {}, "t", rough=True), Step("sift", {}, "t", precise=True),
            Step("xmodal", {}, "t", precise=True), Step("cfog", {}, "t"))


def test_a_verified_but_loose_result_lets_the_precise_steps_beat_it():
    result = _auto({"shift": ("verified", 1.4), "sift": ("verified", 0.9), "xmodal": ("verified", 0.35)}, CHAIN_37)
    assert result.method == "xmodal"
    attempts = result.auto.attempts
    assert [a.method for a in attempts] == ["shift", "sift", "xmodal"] and attempts[2].accepted
    assert "0.35 px against sift's 0.90 px: kept" in attempts[2].reason


def test_the_tighter_bound_is_kept_whatever_comes_later():
    result = _auto({"shift": ("verified", 0.8), "sift": ("verified", 1.2), "xmodal": ("suspect", 0.2)}, CHAIN_37)
    attempts = result.auto.attempts
    assert result.method == "shift" and attempts[0].accepted
    assert "not kept" in attempts[1].reason and attempts[2].outcome == "suspect" and len(attempts) == 3


def test_a_precise_first_answer_ends_auto():
    result = _auto({"shift": ("verified", 0.3)}, CHAIN_37)
    assert result.method == "shift" and [a.method for a in result.auto.attempts] == ["shift"]


def test_after_a_verified_fast_path_that_is_not_rough_nothing_more_runs():
    result = _auto({"sift": ("verified", 2.0)}, CHAIN_37[1:])
    assert result.method == "sift" and [a.method for a in result.auto.attempts] == ["sift"]


def test_the_precision_asked_for_is_a_share_of_the_tolerance():
    from hamta.core import RegisterOptions
    from hamta.core.progress import Monitor

    def attempt(method, params, monitor, refine):
        return _Result(method, _Check(*{"shift": ("verified", 1.9), "sift": ("verified", 0.9)}[method]))

    loose = auto_module.register_auto(attempt, RegisterOptions(tolerance_px=15.0), Monitor(), CHAIN_37)
    assert loose.method == "shift" and len(loose.auto.attempts) == 1


ANY_TURN = {"max_rotation_deg": 180.0}
# (learned extra installed, target placed by its georeferencing, short): the chain as (method, params), as
# chain_for built it from slices of the chain before its steps were declared by name (with regions added after cfog).
CHAINS = {
    (False, False, False): [("sift", {}), ("xmodal", {}), ("cfog", {}), ("regions", {}), ("ndsift-pc", {}),
                            ("cfog", ANY_TURN)],
    (False, False, True): [("sift", {}), ("xmodal", {}), ("cfog", {})],
    (False, True, False): [("shift", {}), ("sift", {}), ("xmodal", {}), ("cfog", {}), ("regions", {}),
                           ("ndsift-pc", {}), ("cfog", ANY_TURN)],
    (False, True, True): [("shift", {}), ("sift", {}), ("xmodal", {}), ("cfog", {})],
    (True, False, False): [("sift", {}), ("xmodal", {}), ("xfeat", ANY_TURN), ("cfog", {}), ("regions", {}),
                           ("ndsift-pc", {}), ("cfog", ANY_TURN)],
    (True, False, True): [("sift", {}), ("xmodal", {}), ("xfeat", ANY_TURN), ("cfog", {})],
    (True, True, False): [("shift", {}), ("sift", {}), ("xmodal", {}), ("xfeat", {}), ("cfog", {}), ("regions", {}),
                          ("ndsift-pc", {}), ("cfog", ANY_TURN)],
    (True, True, True): [("shift", {}), ("sift", {}), ("xmodal", {}), ("xfeat", {}), ("cfog", {})],
}

# Each step's (refine, precise, rough); a short chain has no precise step.
FLAGS = {"shift": ("on", False, True), "sift": ("on", True, False), "xmodal": ("auto", True, False),
         "xfeat": ("on", True, False), "cfog": ("auto", False, False), "regions": ("auto", False, False),
         "ndsift-pc": ("auto", False, False)}


@pytest.mark.parametrize("learned, prior, short", sorted(CHAINS))
def test_the_chain_of_every_plan(monkeypatch, learned, prior, short):
    from hamta.core import learned as learned_module

    monkeypatch.delenv("HAMTA_LEARNED", raising=False)
    monkeypatch.setattr(learned_module, "installed", lambda: learned)
    chain = auto_module.chain_for("georeferenced" if prior else "search", short)
    assert [(s.method, dict(s.params)) for s in chain] == CHAINS[learned, prior, short]
    assert [(s.refine, s.precise, s.rough) for s in chain] == [
        (refine, precise and not short, rough) for refine, precise, rough in (FLAGS[s.method] for s in chain)]


def test_without_a_cap_every_step_runs_however_slow(monkeypatch):
    """No time cap by default: the chain is the budget, so a slow machine tries what a fast one tries."""
    import time

    from hamta.core import RegisterOptions
    from hamta.core.progress import Monitor

    ran = []

    def attempt(method, params, monitor, refine):
        ran.append(method)
        time.sleep(0.3)
        monitor.report(0.5, "working")
        raise InsufficientMatchesError("nothing", 0, 8)

    chain = tuple(Step(name, {}, "t") for name in ("a", "b", "c", "d"))
    assert RegisterOptions().auto_budget_s is None
    with pytest.raises(InsufficientMatchesError, match="a: nothing; b: nothing; c: nothing; d: nothing"):
        auto_module.register_auto(attempt, RegisterOptions(), Monitor(), chain)
    assert ran == ["a", "b", "c", "d"]
