"""SIFT baseline through the public ``register`` entry point on known-transform Landsat pairs."""
import numpy as np
import pytest

from hamta.bench.cases import reprojected_case, similarity_case
from hamta.core import RegisterOptions, register

SIMILARITY_CASES = [  # (angle deg, scale target px per reference px, shift reference px)
    (0.0, 1.0, (17.0, -9.0)),
    (10.0, 0.8, (0.0, 0.0)),
    (-20.0, 1.25, (-25.0, 14.0)),
    (30.0, 0.9, (11.0, 31.0)),
    (25.0, 1.1, (-8.0, -20.0)),
]


@pytest.mark.split
@pytest.mark.parametrize("angle,scale,shift", SIMILARITY_CASES)
def test_sift_recovers_rotation_scale_shift_to_half_a_pixel(tmp_path, landsat, angle, scale, shift):
    case = similarity_case(str(tmp_path), landsat, angle_deg=angle, scale=scale, shift_px=shift)
    result = register(case.target, case.reference, "sift", options=RegisterOptions(model="affine"))
    err = case.errors(result.model)
    assert len(case.check_points) > 200
    assert np.sqrt(np.mean(err ** 2)) < 0.5, f"check-point RMSE {np.sqrt(np.mean(err ** 2)):.3f} px"
    assert result.stats.n_gcps >= 50


@pytest.mark.parametrize("model", ["similarity", "projective", "polynomial-2", "tps"])
def test_every_model_is_accurate_on_a_similarity_case(tmp_path, landsat, model):
    case = similarity_case(str(tmp_path), landsat, angle_deg=15.0, scale=0.9, shift_px=(5.0, -5.0))
    result = register(case.target, case.reference, "sift", options=RegisterOptions(model=model))
    assert result.model.kind == model
    assert np.sqrt(np.mean(case.errors(result.model) ** 2)) < 0.5


@pytest.mark.parametrize("crs,shift", [("EPSG:32617", (35.0, -22.0)), ("EPSG:4326", (-28.0, 40.0))])
def test_target_reprojected_to_another_crs_with_wrong_georeferencing(tmp_path, landsat, crs, shift):
    case = reprojected_case(str(tmp_path), landsat, dst_crs=crs, shift_px=shift)
    result = register(case.target, case.reference, "sift", options=RegisterOptions(model="affine"))
    assert result.plan.mode == "georeferenced"
    err = case.errors(result.model)
    assert np.sqrt(np.mean(err ** 2)) < 0.5, f"check-point RMSE {np.sqrt(np.mean(err ** 2)):.3f} px"


def test_decimated_working_images_are_refined_to_full_resolution(tmp_path, landsat):
    case = similarity_case(str(tmp_path), landsat, angle_deg=12.0, scale=1.0, shift_px=(6.0, 3.0))
    coarse = register(case.target, case.reference, "sift",
                      options=RegisterOptions(model="affine", max_working_pixels=90_000, refine="off"))
    fine = register(case.target, case.reference, "sift",
                    options=RegisterOptions(model="affine", max_working_pixels=90_000, refine="on"))
    e_coarse = np.sqrt(np.mean(case.errors(coarse.model) ** 2))
    e_fine = np.sqrt(np.mean(case.errors(fine.model) ** 2))
    assert fine.stats.refined and not coarse.stats.refined
    assert e_fine < 0.25 and e_fine < e_coarse


def test_results_are_deterministic(tmp_path, landsat):
    case = similarity_case(str(tmp_path), landsat, angle_deg=7.0, scale=0.95)
    a = register(case.target, case.reference, "sift")
    b = register(case.target, case.reference, "sift")
    assert np.array_equal(a.model.matrix, b.model.matrix)
    assert [g.target_px for g in a.gcps] == [g.target_px for g in b.gcps]
