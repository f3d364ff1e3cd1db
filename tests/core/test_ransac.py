import numpy as np
import pytest

from hamta.core.coords import apply_matrix
from hamta.core.estimation.models import MIN_POINTS
from hamta.core.estimation.ransac import _squared_errors, minimal_fits, ransac

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


def test_only_no_consensus_is_no_model(monkeypatch, data):
    """'No model' is said by its own error (a ValueError too, as before); a bug inside RANSAC is not
    turned into 'no model' by ``ransac_or_none``."""
    import importlib

    from hamta.core.errors import NoConsensusError

    module = importlib.import_module("hamta.core.estimation.ransac")  # the package's 'ransac' is the function

    rng = np.random.default_rng(0)
    with pytest.raises(NoConsensusError, match="needs at least 4") as info:
        ransac(rng.random((3, 2)), rng.random((3, 2)), "projective", threshold_px=1.0)
    assert (info.value.found, info.value.needed) == (3, 4)
    with pytest.raises(NoConsensusError, match="no affine hypothesis gathered 3 inliers"):  # one place: degenerate
        ransac(np.ones((6, 2)), rng.random((6, 2)) * 100, "affine", threshold_px=1.0)
    assert module.ransac_or_none(rng.random((3, 2)), rng.random((3, 2)), "projective", threshold_px=1.0)[0] is None

    def broken(*args, **kwargs):
        raise ValueError("operands could not be broadcast")

    monkeypatch.setattr(module, "polish", broken)
    src = data[0]
    with pytest.raises(ValueError, match="broadcast"):
        module.ransac_or_none(src, src + 1.0, "affine", threshold_px=1.0)


def test_the_gcps_hold_no_place_twice():
    from hamta.core.estimation.models import fit_model
    from hamta.core.estimation.robust import Estimate, final_fit
    from hamta.core.types import Correspondences

    rng = np.random.default_rng(3)
    tgt = rng.uniform(0, 500, (40, 2))
    tgt = np.vstack([tgt, tgt[:5], tgt[5:8] + [[0.0, 0.0]]])  # 8 exact repeats
    ref = tgt * 1.1 + [20.0, -7.0]
    ref[-3:] += 0.2  # one target pixel matched to two reference pixels: keep the better scored
    score = np.r_[np.ones(40), np.full(5, 0.5), np.full(3, 2.0)]
    points = Correspondences(tgt, ref, score, np.ones(len(tgt), bool))
    fit = final_fit("affine", Estimate(fit_model("affine", tgt, ref), points, 1.0), 500, None)
    used_t, used_r = tgt[fit.used], ref[fit.used]
    assert len(fit.used) == 40
    assert len(np.unique(used_t, axis=0)) == len(np.unique(used_r, axis=0)) == 40
    assert set(fit.used[np.isin(fit.used, [5, 6, 7])]) == set() and {45, 46, 47} <= set(fit.used)
    from hamta.core.result import make_gcps

    points.inlier[[10, 11, 40]] = False  # rejected points are listed, but not at a GCP's place (40 is at 0's)
    fit = final_fit("affine", Estimate(fit_model("affine", tgt, ref), points, 1.0), 500, None)
    gcps = make_gcps(fit, lambda xy: xy)
    assert len({g.target_px for g in gcps}) == len({g.reference_px for g in gcps}) == len(gcps)
    assert sum(not g.enabled for g in gcps) == 2


def _squared_errors_by_matrix(m, src, dst):
    """Each hypothesis applied as a 3 x 3 matrix product: transfer errors, inf behind its horizon."""
    h = np.einsum("kij,nj->kni", m, np.column_stack([src, np.ones(len(src))]))
    with np.errstate(divide="ignore", invalid="ignore"):
        e = ((h[..., :2] / h[..., 2:] - dst) ** 2).sum(axis=2)
    e[~np.isfinite(e) | (h[..., 2] <= 0)] = np.inf
    return e


@pytest.mark.parametrize("kind", list(TRUE))
def test_hypotheses_are_scored_by_their_transfer_errors(kind):
    rng = np.random.default_rng(3)
    src, dst = rng.random((200, 2)) * 4 - 2, rng.random((200, 2)) * 4 - 2
    hypotheses, ok = minimal_fits(kind, *(p[rng.integers(0, 200, (64, MIN_POINTS[kind]))] for p in (src, dst)))
    hypotheses = hypotheses[ok]
    expected = _squared_errors_by_matrix(hypotheses, src, dst)
    got = _squared_errors(hypotheses, src, dst)
    assert np.array_equal(np.isinf(got), np.isinf(expected))
    if kind == "projective":
        assert np.isinf(got).any()  # some points lie behind some hypotheses' horizons
    w = np.einsum("kj,nj->kn", hypotheses[:, 2, :2], src) + hypotheses[:, 2, 2:]
    finite = np.isfinite(expected) & (np.abs(w) > 1e-6)  # at the horizon itself, rounding decides
    assert np.allclose(got[finite], expected[finite], rtol=1e-9, atol=1e-12)
