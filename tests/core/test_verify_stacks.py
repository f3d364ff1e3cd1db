"""The independent check gives the same verdict on every library stack: fixed inputs (the real development
pairs, their hand-picked model and the same model 6 px off), compared with values stored from the PyPI
wheels stack. Sites, agreeing sites and the verdict must match exactly; the error estimate and bound
within 0.01 px (OpenCV's resampling and filters differ in the last digits between versions: on Debian's
OpenCV 4.6 they differ from OpenCV 5 by at most 0.005 px here)."""
import json
import os

import numpy as np
import pytest

from hamta.core.estimation.models import fit_model
from hamta.core.io.raster import open_raster, resolve_bands
from hamta.core.verify import VerifyParams, verify

EXPECTED = {  # (pair, shift px): verdict, sites, agreeing sites, estimated error px, error bound px
    ("multitemporal", 0.0): ("verified", 25, 18, 0.2355, 0.4487),
    ("multitemporal", 6.0): ("failed", 25, 1, 1.8942, 2.1770),
    ("sar_optical", 0.0): ("verified", 18, 18, 0.9876, 1.5761),
    ("sar_optical", 6.0): ("failed", 16, 0, None, None),
}
TOLERANCE_PX = 0.01


@pytest.mark.parametrize("pair, shift", sorted(EXPECTED))
def test_the_check_gives_the_stored_numbers(shared, pair, shift):
    pairs = os.path.join(shared, "data", "pairs")
    spec = next(p for p in json.load(open(os.path.join(pairs, "ground_truth.json")))["pairs"] if p["id"] == pair)
    target, reference = open_raster(os.path.join(pairs, spec["a"])), open_raster(os.path.join(pairs, spec["b"]))
    points = np.array(spec["points"], float)
    model = fit_model("affine", points[:, :2], points[:, 2:] + shift)
    v = verify(model, target, resolve_bands(target, None), reference, resolve_bands(reference, None), VerifyParams())
    verdict, sites, agree, error, bound = EXPECTED[(pair, shift)]
    assert (v.verdict, v.n_sites, v.n_agree) == (verdict, sites, agree)
    for got, stored in ((v.error_px, error), (v.error_bound_px, bound)):
        assert (got is None) == (stored is None), (got, stored)
        assert stored is None or abs(got - stored) <= TOLERANCE_PX, (got, stored)
