"""Where QGIS's executables load GSL's reference CBLAS first, matching avoids numpy's matrix products."""
import os
import subprocess
import sys

import numpy as np
import pytest

from hamta.core.matching import nearest as nearest_module
from hamta.core.methods import xmodal

GSL = "/lib/x86_64-linux-gnu/libgslcblas.so.0"
PROBE = "from hamta.core.blas import reference_blas; print(reference_blas())"


def _probe(env=None) -> str:
    done = subprocess.run([sys.executable, "-c", PROBE], capture_output=True, text=True, env=env, check=True)
    return done.stdout.strip()


def test_an_ordinary_process_has_an_optimised_blas():
    assert _probe() == "False"


@pytest.mark.skipif(not os.path.exists(GSL), reason="GSL's CBLAS is not installed")
def test_gsl_loaded_first_is_seen_where_numpy_binds_to_it():
    import numpy

    own = str(getattr(numpy.__config__, "CONFIG", {}).get("Build Dependencies", {}).get("blas", {}).get("name", ""))
    expected = "False" if own.startswith(("scipy-openblas", "openblas64")) else "True"  # wheels rename theirs
    assert _probe(dict(os.environ, LD_PRELOAD=GSL)) == expected


def test_the_brute_force_route_finds_the_same_neighbours(monkeypatch):
    rng = np.random.default_rng(9)
    a, b = rng.random((120, 216)).astype(np.float32), rng.random((150, 216)).astype(np.float32)
    fast = xmodal.nearest(a, b), nearest_module._knn(a[:, :128], b[:, :128], "l2"), xmodal.squared_distances(a, b)
    monkeypatch.setattr(xmodal, "reference_blas", lambda: True)
    monkeypatch.setattr(nearest_module, "reference_blas", lambda: True)
    slow = xmodal.nearest(a, b), nearest_module._knn(a[:, :128], b[:, :128], "l2"), xmodal.squared_distances(a, b)
    assert np.array_equal(fast[0], slow[0])
    assert slow[2].dtype == np.float32 and np.allclose(fast[2], slow[2], atol=1e-4)
    assert np.array_equal(fast[1][1], slow[1][1]) and np.allclose(fast[1][0], slow[1][0], rtol=1e-5)
