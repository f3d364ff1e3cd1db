"""``make test`` on a machine without the development data: CI fails at once, a user is told in one line; and
how its two halves share the cases of `split` tests."""
import os
import pathlib
import subprocess
import sys

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
NEEDS_DATA = "tests/core/test_working.py::test_pixel_mode_without_reference_georeferencing"


def _pytest(tmp_path, require: str):
    env = dict(os.environ, HAMTA_SHARED=str(tmp_path / "nowhere"), HAMTA_REQUIRE_DATA=require)
    return subprocess.run([sys.executable, "-P", "-m", "pytest", NEEDS_DATA, "-q", "-rs", "-p", "no:cacheprovider"],
                          cwd=REPO, env=env, capture_output=True, text=True, timeout=120)


def test_ci_fails_when_the_data_is_missing(tmp_path):
    run = _pytest(tmp_path, "1")
    assert run.returncode == 4, run.stdout + run.stderr
    assert f"development data not found at {tmp_path / 'nowhere'}/data" in run.stderr + run.stdout


def test_a_user_is_told_in_one_line_what_was_skipped(tmp_path):
    run = _pytest(tmp_path, "0")
    assert run.returncode == 0, run.stdout + run.stderr
    assert "SKIPPED" in run.stdout  # -rs lists each skip with its reason
    assert f"hamta: development data not found at {tmp_path / 'nowhere'}/data (set HAMTA_SHARED); 1 tests skipped" \
        in run.stdout


class _Case:
    """A collected test case as the split hook sees it."""

    def __init__(self, name, params, split=None):
        self.nodeid = f"tests/core/test_x.py::{name}[{'-'.join(map(str, params.values()))}]"
        self.callspec = type("CallSpec", (), {"params": params})()
        self._split = split

    def get_closest_marker(self, name):
        return None if self._split is None or name != "split" else type("Mark", (), {"args": self._split})()


def _conftest():
    """The tests' own conftest module, as pytest loaded it."""
    return next(m for m in list(sys.modules.values()) if getattr(m, "__file__", None) == str(REPO / "tests" /
                                                                                              "conftest.py"))


def _halves(items, monkeypatch):
    out = []
    for half in ("0", "1"):
        monkeypatch.setenv("HAMTA_TEST_HALF", half)
        kept, config = list(items), type("Config", (), {"hook": type("Hook", (), {})()})()
        config.hook.pytest_deselected = lambda items: None
        _conftest().pytest_collection_modifyitems(config, kept)
        out.append({i.nodeid for i in kept})
    return out


def test_split_tests_run_each_case_once_and_every_value_on_both_halves(monkeypatch):
    cases = [_Case("t", {"angle": a, "method": m}, split=("angle",)) for a in (45, 137) for m in ("rilbp", "cslbp")]
    cases += [_Case("w", {"wrong": w}, split=()) for w in ("shift4", "rot2", "scale1.05")]
    cases += [_Case("plain", {"model": m}) for m in ("affine", "tps")]
    cases += [_Case("alone", {"angle": 45, "method": "sift"}, split=("angle",))]  # a group of one, as -k leaves
    a, b = _halves(cases, monkeypatch)
    everywhere = {c.nodeid for c in cases if "::plain[" in c.nodeid or "::alone[" in c.nodeid}
    assert a | b == {c.nodeid for c in cases} and a & b == everywhere
    for half in (a, b):
        for value in ("rilbp", "cslbp", "[45-", "[137-"):  # every method and every angle on both stacks
            assert {n for n in half if "::t[" in n and value in n}, (value, half)
        assert {n for n in half if "::w[" in n}
    monkeypatch.setenv("HAMTA_TEST_HALF", "0")
    with pytest.raises(pytest.UsageError, match="names parameters"):
        _conftest().pytest_collection_modifyitems(None, [_Case("typo", {"angle": 1, "m": 2}, split=("angle, m",))])
    monkeypatch.delenv("HAMTA_TEST_HALF")
    kept = list(cases)
    _conftest().pytest_collection_modifyitems(None, kept)
    assert kept == cases  # a plain pytest runs every case
