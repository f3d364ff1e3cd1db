import numpy as np
import pytest

from hamta.core.coords import apply_matrix
from hamta.core.estimation.ransac import ransac

TRUE = {
    "similarity": np.array([[0.9, -0.3, 40.0], [0.3, 0.9, -25.0], [0, 0, 1.0]]),
    "affine": np.array([[0.95, -0.2, 40.0], [0.25, 1.05, -25.0], [0, 0, 1.0]]),
    "projective": np.array([[0.95, -0.2, 40.0], [0.25, 1.05, -25.0], [3e-5, -2e-5, 1.0]]),
}


@pytest.fixture
def data():
    rng = np.random.default_rng(7)
    src = rng.random((300, 2)) * 2000
    noise = rng.normal(0, 0.3, src.shape)
    outliers = rng.choice(300, 120, replace=False)
    return src, noise, outliers, rng


@pytest.mark.parametrize("kind", list(TRUE))
def test_ransac_finds_the_exact_inlier_set_and_model(kind, data):
    src, noise, outliers, rng = data
    dst = apply_matrix(TRUE[kind], src) + noise
    dst[outliers] += rng.uniform(20, 200, (len(outliers), 2)) * rng.choice([-1, 1], (len(outliers), 2))
    model, inliers = ransac(src, dst, kind, threshold_px=2.0, rng=0)
    expected = np.ones(len(src), bool)
    expected[outliers] = False
    assert np.array_equal(inliers, expected)
    probe = np.array([[100.0, 100.0], [1900.0, 1500.0]])
    assert np.abs(model.apply(probe) - apply_matrix(TRUE[kind], probe)).max() < 0.2


def test_ransac_is_deterministic_for_a_seed(data):
    src, noise, outliers, rng = data
    dst = apply_matrix(TRUE["affine"], src) + noise
    dst[outliers] = rng.random((len(outliers), 2)) * 2000
    a = ransac(src, dst, "affine", threshold_px=1.5, rng=42)
    b = ransac(src, dst, "affine", threshold_px=1.5, rng=42)
    assert np.array_equal(a[1], b[1]) and np.array_equal(a[0].matrix, b[0].matrix)


def test_ransac_fails_clearly_without_consensus():
    rng = np.random.default_rng(0)
    with pytest.raises(ValueError, match="needs at least 4"):
        ransac(rng.random((3, 2)), rng.random((3, 2)), "projective", threshold_px=1.0)
