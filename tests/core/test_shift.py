"""The shift in windows (``auto``'s first step for georeferenced pairs): right offsets fast, escalation otherwise."""
import numpy as np
import pytest

from hamta.bench.cases import reprojected_case
from hamta.bench.goals.speed import georeferenced_pair
from hamta.core import RegisterOptions, register


def test_a_georeferencing_offset_is_measured_to_a_fiftieth_of_a_pixel_and_auto_stops_there(tmp_path, shared):
    target, reference, truth = georeferenced_pair(str(tmp_path), str(shared / "data"))
    result = register(target, reference)
    assert result.method == "shift" and result.verified
    assert [a.method for a in result.auto.attempts] == ["shift"]
    pts = np.array([[x, y] for x in (100, 1000, 1900) for y in (100, 800, 1500)], float)
    err = np.linalg.norm(result.model.apply(pts) - (pts + truth[:2, 2]), axis=1)
    assert err.max() < 0.05, err


@pytest.mark.parametrize("crs,shift", [("EPSG:4326", (-28.0, 40.0)), ("EPSG:32617", (60.0, 15.0))])
def test_a_target_in_another_crs_is_registered_by_the_shift_alone(tmp_path, landsat, crs, shift):
    case = reprojected_case(str(tmp_path), landsat, dst_crs=crs, shift_px=shift)
    result = register(case.target, case.reference, "shift", options=RegisterOptions(refine="on"))
    assert np.sqrt(np.mean(case.errors(result.model) ** 2)) < 0.3


def test_a_turned_target_is_not_taken_from_the_shift_and_auto_escalates(tmp_path, landsat):
    """Georeferencing that leaves a 20 degree turn: the windows cannot agree on a shift that verifies."""
    from hamta.bench.cases import similarity_case

    case = similarity_case(str(tmp_path), landsat, angle_deg=20.0, scale=1.0, shift_px=(12.0, -7.0))
    import rasterio

    with rasterio.open(case.reference) as ref, rasterio.open(case.target, "r+") as tgt:
        tgt.crs, tgt.transform = ref.crs, ref.transform  # placed on the reference's grid, turn left in
    result = register(case.target, case.reference)
    attempts = [a.method for a in result.auto.attempts]
    assert attempts[0] == "shift" and result.auto.attempts[0].outcome != "verified"
    assert result.verified and result.method != "shift"
    assert np.sqrt(np.mean(case.errors(result.model) ** 2)) < 1.0


def test_pairs_without_georeferencing_do_not_try_the_shift(demo_pair):
    result = register(demo_pair["target"], demo_pair["reference"])
    assert "shift" not in [a.method for a in result.auto.attempts]
