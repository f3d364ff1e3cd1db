import numpy as np
import pytest

from hamta.core.coords import apply_matrix
from hamta.core.estimation.models import ThinPlateSplineModel, fit_model, model_from_dict
from hamta.core.options import MODEL_CHOICES, canonical_model

H = np.array([[0.92, -0.21, 31.0], [0.24, 0.97, -12.0], [2e-5, -1e-5, 1.0]])


@pytest.fixture
def points():
    rng = np.random.default_rng(3)
    src = rng.random((80, 2)) * 900
    return src, rng


@pytest.mark.parametrize("kind", ["similarity", "affine", "projective"])
def test_linear_models_recover_exact_transforms(kind, points):
    src, _ = points
    m = H.copy()
    if kind != "projective":
        m[2] = [0, 0, 1]
    if kind == "similarity":
        m[:2, :2] = [[0.9, -0.2], [0.2, 0.9]]
    fitted = fit_model(kind, src, apply_matrix(m, src))
    assert np.allclose(fitted.matrix, m, atol=1e-9)


@pytest.mark.parametrize("kind", ["polynomial-2", "polynomial-3"])
def test_polynomials_recover_polynomial_maps(kind, points):
    src, _ = points
    dst = np.column_stack([3 + 1.1 * src[:, 0] + 2e-4 * src[:, 0] * src[:, 1],
                           -7 + 0.95 * src[:, 1] - 1e-4 * src[:, 0] ** 2])
    fitted = fit_model(kind, src, dst)
    assert np.abs(fitted.apply(src) - dst).max() < 1e-6


def test_tps_without_smoothing_interpolates_its_control_points(points):
    src, rng = points
    dst = apply_matrix(H, src) + rng.normal(0, 0.5, src.shape)
    tps = ThinPlateSplineModel.fit(src, dst, smoothing=0)
    assert np.abs(tps.apply(src) - dst).max() < 1e-6


def test_tps_evaluates_its_formula_in_chunks(points):
    """f(p) = affine + sum_i w_i U(|q - q_i|^2), U(r2) = r2 log r2, however the points are chunked."""
    src, rng = points
    tps = ThinPlateSplineModel.fit(src, apply_matrix(H, src) + rng.normal(0, 0.5, src.shape), smoothing=0)
    p = rng.random((500, 2)) * 1000
    q, c = (p - tps.center) / tps.scale, (tps.control - tps.center) / tps.scale
    r2 = ((q[:, None, :] - c[None, :, :]) ** 2).sum(axis=2)
    u = np.where(r2 > 0, r2 * np.log(np.where(r2 > 0, r2, 1.0)), 0.0)
    expected = np.column_stack([np.ones(len(q)), q]) @ tps.affine + u @ tps.weights
    assert np.allclose(tps.apply(p, max_cells=len(c) * 7), expected, rtol=0, atol=1e-9)


def test_tps_auto_smoothing_keeps_match_noise_out_of_the_surface(points):
    src, rng = points
    dst = apply_matrix(H, src)
    noisy = dst + rng.normal(0, 0.5, src.shape)
    probe = rng.random((200, 2)) * 800 + 50
    exact = ThinPlateSplineModel.fit(src, noisy, smoothing=0)
    smooth = ThinPlateSplineModel.fit(src, noisy)
    err = lambda m: np.sqrt(np.mean(np.sum((m.apply(probe) - apply_matrix(H, probe)) ** 2, axis=1)))  # noqa: E731
    assert smooth.smoothing > 0 and err(smooth) < 0.5 * err(exact)


def _brute_loo(fit, src, dst):
    out = []
    for i in range(len(src)):
        keep = np.arange(len(src)) != i
        out.append(np.linalg.norm(fit(src[keep], dst[keep]).apply(src[i:i + 1])[0] - dst[i]))
    return np.array(out)


@pytest.mark.parametrize("kind", [k for k in MODEL_CHOICES if k != "tps"])
def test_leave_one_out_matches_brute_force(kind, points):
    src, rng = points
    src = src[:40]
    dst = apply_matrix(H, src) + rng.normal(0, 0.4, src.shape)
    loo = fit_model(kind, src, dst).loo_residuals(src, dst)
    brute = _brute_loo(lambda s, d: fit_model(kind, s, d), src, dst)
    tol = 1e-3 if kind == "projective" else 1e-8  # projective LOO is linearised at the fit
    assert np.allclose(loo, brute, atol=tol)


@pytest.mark.parametrize("smoothing", [0.0, 1e-3, 0.1])
def test_tps_leave_one_out_matches_brute_force(smoothing, points):
    src, rng = points
    src = src[:40]
    dst = apply_matrix(H, src) + rng.normal(0, 0.4, src.shape)
    full = ThinPlateSplineModel.fit(src, dst, smoothing=smoothing)
    kept = full.loo_residuals(src, dst)  # the fit's own
    again = model_from_dict(full.to_dict()).loo_residuals(src, dst)  # solved again from the model alone
    brute = _brute_loo(lambda s, d: ThinPlateSplineModel.fit(s, d, smoothing, full.center, full.scale), src, dst)
    assert np.allclose(kept, brute, atol=1e-6) and np.allclose(again, brute, atol=1e-6)


def test_tps_jacobian_is_the_derivative_of_the_spline(points):
    """The spline's exact derivative, in chunks, equals central differences of a small step, away
    from and at its control points (where the kernel's term vanishes)."""
    from hamta.core.estimation.models import local_jacobian

    src, rng = points
    tps = ThinPlateSplineModel.fit(src, apply_matrix(H, src) + rng.normal(0, 0.5, src.shape), smoothing=0)
    probe = np.vstack([rng.random((50, 2)) * 900, src[:5]])
    h = 1e-4
    numeric = np.stack([(tps.apply(probe + d) - tps.apply(probe - d)) / (2 * h) for d in ([h, 0], [0, h])], axis=2)
    exact = tps.jacobian(probe, max_cells=len(src) * 7)
    assert np.allclose(exact, numeric, rtol=0, atol=1e-6)
    # The same sums in other chunks: BLAS kernels may order them differently (AVX-512 against AVX2), so
    # agreement to the last few bits, not equality.
    assert np.allclose(local_jacobian(tps, probe), tps.jacobian(probe), rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("kind", MODEL_CHOICES)
def test_report_round_trip_reproduces_the_model(kind, points):
    src, rng = points
    dst = apply_matrix(H, src) + rng.normal(0, 0.3, src.shape)
    model = fit_model(kind, src, dst)
    again = model_from_dict(model.to_dict())
    probe = rng.random((30, 2)) * 900
    assert np.allclose(again.apply(probe), model.apply(probe))
    assert again.kind == kind


def test_model_names_accept_qgis_aliases_and_reject_unknown():
    assert canonical_model("Helmert") == "similarity"
    assert canonical_model("poly1") == "affine"
    with pytest.raises(ValueError, match="unknown model"):
        canonical_model("spline-of-doom")


def test_too_few_points_is_an_error():
    with pytest.raises(ValueError, match="at least 6"):
        fit_model("polynomial-2", np.zeros((5, 2)), np.zeros((5, 2)))
