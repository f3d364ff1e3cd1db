"""The same inputs give the same report on a quiet machine, a slow one and a loaded one: what ``auto`` and the
basemap search try is bounded by counts (methods, zooms, places, requests), not by seconds. A slow machine is
a clock that runs a thousand times fast; a loaded one has every core busy twice over beside the run."""
import os
import subprocess
import sys
import time
import types

import numpy as np
import pytest

from hamta.bench.goals.basemap import rotated_target
from hamta.bench.tileserver import TileServer
from hamta.core import auto, remote, run
from hamta.core.basemap.fetch import Fetcher
from hamta.core.options import RegisterOptions

CENTRE = (300.0, 300.0)  # Landsat source px: the island's middle


@pytest.fixture(scope="module")
def server(landsat):
    tiles = TileServer(landsat, zmax=12).start()
    yield tiles
    tiles.stop()


@pytest.fixture(scope="module")
def case(landsat, tmp_path_factory):
    return rotated_target(landsat, str(tmp_path_factory.mktemp("load") / "target.png"), CENTRE, (320, 420),
                          2.0, 15.0)


def _report(case, server, cache):
    result, _ = run(case.path, server.xyz(), None, options=RegisterOptions(extent=case.search_area(5.0)),
                    fetcher=Fetcher(cache=str(cache), backoff_s=0.01))
    service = result.reference_service
    attempts = [(a.method, a.outcome, a.reason) for a in result.auto.attempts] if result.auto else []
    return {"verdict": result.verification.verdict, "method": result.method, "zoom": service["zoom"],
            "zooms_read": service["zooms_read"], "places": service["places"], "attempts": attempts,
            "notes": list(result.notes),
            "gcps": len(result.gcps) if result.gcps is not None else 0}, result


class _RacingClock:
    """A clock for ``time.monotonic`` and ``time.perf_counter`` that advances 1000 s at every reading."""

    def __init__(self):
        self.now = time.monotonic()

    def __call__(self):
        self.now += 1000.0
        return self.now


def test_a_slow_machine_tries_what_a_fast_one_tries(case, server, tmp_path, monkeypatch):
    quiet, first = _report(case, server, tmp_path / "quiet")
    assert first.verified and quiet["places"], quiet
    clock = _RacingClock()
    racing = types.SimpleNamespace(monotonic=clock, perf_counter=clock, sleep=time.sleep)
    for module in (remote, auto):
        monkeypatch.setattr(module, "time", racing)
    slow, second = _report(case, server, tmp_path / "slow")
    assert slow == quiet
    assert _moved(first, second, case) < 1e-6


def test_every_core_busy_twice_over_gives_the_same_report(case, server, tmp_path):
    quiet, first = _report(case, server, tmp_path / "quiet")
    busy = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(2 * (os.cpu_count() or 1))]
    try:
        loaded, second = _report(case, server, tmp_path / "loaded")
    finally:
        for p in busy:
            p.kill()
            p.wait()
    assert loaded == quiet
    assert _moved(first, second, case) < 1e-6


def _moved(first, second, case) -> float:
    """How far apart (map units) two results put the target's grid."""
    return float(np.abs(second.map_points(case.grid())[1] - first.map_points(case.grid())[1]).max())
