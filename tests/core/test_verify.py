"""The independent check: right models verify, wrong ones do not, and the evidence says why."""
import json
import math

import numpy as np
import pytest

from hamta.core.estimation.models import LinearModel, PolynomialModel
from hamta.core.io.raster import open_raster, resolve_bands
from hamta.core.verify import VerifyParams, error_field, fit_field, judge, verify


@pytest.fixture(scope="module")
def demo(demo_pair):
    truth = np.array(json.load(open(demo_pair["truth"]))["target_px_to_reference_px"])
    t, r = open_raster(demo_pair["target"]), open_raster(demo_pair["reference"])
    return t, resolve_bands(t, None), r, resolve_bands(r, None), truth


def _shifted(m, dx, dy=0.0):
    return np.array([[1, 0, dx], [0, 1, dy], [0, 0, 1.0]]) @ m


def _rotated(m, angle_deg, centre):
    a = math.radians(angle_deg)
    r = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    e = np.eye(3)
    e[:2, :2], e[:2, 2] = r, np.asarray(centre) - r @ np.asarray(centre)
    return e @ m


def test_the_true_model_verifies_with_a_small_error_bound(demo):
    t, tb, r, rb, truth = demo
    v = verify(LinearModel("affine", truth), t, tb, r, rb)
    assert v.verdict == "verified" and not v.reasons
    assert v.n_agree >= 10 and v.chance < 1e-10 and v.error_bound_px < 0.5
    assert json.loads(json.dumps(v.to_dict()))["verdict"] == "verified"


@pytest.mark.parametrize("wrong", ["shift4", "shift12", "shift80", "rot2", "rot90", "scale1.05"])
def test_wrong_models_do_not_verify(demo, wrong):
    t, tb, r, rb, truth = demo
    centre = [500.0, 500.0]
    m = {"shift4": _shifted(truth, 4.0), "shift12": _shifted(truth, 0, 12.0), "shift80": _shifted(truth, 80, -40),
         "rot2": _rotated(truth, 2.0, centre), "rot90": _rotated(truth, 90.0, centre),
         "scale1.05": np.diag([1.05, 1.05, 1.0]) @ _shifted(truth, -25, -25)}[wrong]
    v = verify(LinearModel("projective", m), t, tb, r, rb)
    assert v.verdict != "verified", v.to_dict()
    assert v.reasons


def test_a_larger_tolerance_accepts_what_it_covers_and_no_more(demo):
    t, tb, r, rb, truth = demo
    off = LinearModel("affine", _shifted(truth, 2.5))
    assert not verify(off, t, tb, r, rb, VerifyParams(tolerance_px=1.5)).verified
    assert verify(off, t, tb, r, rb, VerifyParams(tolerance_px=5.0)).verified


def test_non_linear_models_are_checked_through_their_local_inverse(demo):
    t, tb, r, rb, truth = demo
    gx, gy = np.meshgrid(np.linspace(0, t.width, 8), np.linspace(0, t.height, 8))
    src = np.column_stack([gx.ravel(), gy.ravel()])
    dst = LinearModel("affine", truth).apply(src)
    bent = dst + 6.0 * np.sin(src[:, :1] / 120.0)  # up to 6 px off, varying across the image
    assert verify(PolynomialModel.fit(2, src, dst), t, tb, r, rb).verified
    assert not verify(PolynomialModel.fit(3, src, bent), t, tb, r, rb).verified


def test_a_model_that_misses_the_reference_has_nothing_to_check(demo):
    t, tb, r, rb, truth = demo
    v = verify(LinearModel("affine", _shifted(truth, 5000.0)), t, tb, r, rb)
    assert v.verdict == "failed" and v.n_sites == 0


@pytest.mark.parametrize("side, canvas", [(40, 64), (57, 81), (90, 120)])
def test_turned_template_spectra_are_those_of_the_turned_templates(side, canvas):
    """The half turn and the two mirrors (orientation channels following) of a CFOG template, derived from
    its spectrum, equal the spectra computed from the turned templates themselves."""
    from hamta.core.verify.correlation import TemplateSpectrum, fast_length, turned

    template = np.random.default_rng(side).random((9, side, side))
    spectrum = TemplateSpectrum(template, (canvas, canvas))
    for derived, stack in zip(spectrum.turned(), turned(template)):
        direct = TemplateSpectrum(stack, (canvas, canvas))
        assert np.allclose(derived.spectrum, direct.spectrum, rtol=0, atol=1e-9 * np.abs(direct.spectrum).max())
        assert derived.norm == pytest.approx(direct.norm) and derived.size == direct.size
    assert [fast_length(n) for n in (64, 65, 97, 114, 121)] == [64, 72, 100, 120, 125]


def test_judge_separates_agreement_from_chance():
    rng = np.random.default_rng(3)
    n, k = 20, 8
    sites = np.column_stack([rng.uniform(0, 500, n), rng.uniform(0, 500, n)])
    extent = np.column_stack([rng.uniform(0, 500, 200), rng.uniform(0, 500, 200)])
    peaks = np.column_stack([np.full(n, 0.8), rng.uniform(0.05, 0.3, (n, k - 1))])
    offsets = rng.uniform(-7.5, 7.5, (n, k, 2))
    offsets[:, 0] = rng.normal(0, 0.2, (n, 2))
    z = np.column_stack([np.full(n, 4.0), rng.normal(0, 1, (n, k - 1))])
    margins = np.full(peaks.shape, -0.1)
    v = judge(sites, offsets, peaks, z, margins, None, extent, VerifyParams())
    assert v.verified and v.n_agree == n
    offsets[:, 0] = rng.uniform(-7.5, 7.5, (n, 2))
    peaks[:, 0] = rng.uniform(0.05, 0.3, n)
    z[:, 0] = rng.normal(0, 1, n)
    assert judge(sites, offsets, peaks, z, margins, None, extent, VerifyParams()).verdict == "failed"


def test_error_field_recovers_a_rotation_error_the_mean_would_hide():
    gx, gy = np.meshgrid(np.linspace(50, 450, 5), np.linspace(50, 450, 5))
    sites = np.column_stack([gx.ravel(), gy.ravel()])
    a = math.radians(1.0)
    r = np.array([[math.cos(a) - 1, -math.sin(a)], [math.sin(a), math.cos(a) - 1]])
    offsets = (sites - 250.0) @ r.T  # zero mean, 1 degree about the centre
    error, bound, scatter = error_field(sites, offsets, sites)
    expected = float(np.sqrt(np.mean(np.sum(offsets ** 2, axis=1))))
    assert error == pytest.approx(expected, rel=1e-6) and scatter < 1e-6 and bound >= error


def test_a_curved_error_is_bounded_where_no_site_measured_it():
    """Offsets that curve (a projective model's error) over sites in the middle of the overlap:
    the bound must cover the larger error toward the edge, which an affine field would miss."""
    gx, gy = np.meshgrid(np.linspace(100, 900, 6), np.linspace(300, 900, 5))
    sites = np.column_stack([gx.ravel(), gy.ravel()])
    truth = lambda xy: np.column_stack([0.002 * (xy[:, 0] - 500), 8e-6 * (xy[:, 1] - 600) ** 2 - 1.0])  # noqa: E731
    offsets = truth(sites) + np.random.default_rng(0).normal(0, 0.1, sites.shape)
    ex, ey = np.meshgrid(np.linspace(25, 975, 20), np.linspace(25, 975, 20))
    extent = np.column_stack([ex.ravel(), ey.ravel()])
    true_rms = float(np.sqrt(np.mean(np.sum(truth(extent) ** 2, axis=1))))
    error, bound, _ = error_field(sites, offsets, extent)
    assert abs(error - true_rms) < 0.25 * true_rms and bound >= true_rms


def test_chance_tails_match_scipy():
    """The binomial tail and the Mann-Whitney test are computed here (scipy.stats costs half a second to
    import); they must agree with scipy's."""
    from scipy import stats

    from hamta.core.verify import binomial_tail, mann_whitney_greater

    rng = np.random.default_rng(1)
    for _ in range(200):
        n = int(rng.integers(1, 40))
        k, p = int(rng.integers(1, n + 1)), float(rng.uniform(0.001, 0.6))
        assert binomial_tail(k, n, p) == pytest.approx(stats.binom.sf(k - 1, n, p), rel=1e-9, abs=1e-300)
        x = np.round(rng.normal(0.5, 1, int(rng.integers(3, 40))), 1)
        y = np.round(rng.normal(0, 1, int(rng.integers(8, 300))), 1)
        expected = stats.mannwhitneyu(x, y, alternative="greater", method="asymptotic").pvalue
        assert mann_whitney_greater(x, y) == pytest.approx(expected, rel=1e-9)


def _grid_sites(n=5, lo=50.0, hi=450.0):
    gx, gy = np.meshgrid(np.linspace(lo, hi, n), np.linspace(lo, hi, n))
    return np.column_stack([gx.ravel(), gy.ravel()])


def _evidence(offsets0, peaks0, margins0, rng, k=7):
    """Per-site arrays for judge: column 0 as given, k - 1 chance columns of weak scattered peaks, and the
    turned model's comparisons as weak scattered peaks."""
    n = len(offsets0)
    offsets = rng.uniform(-7.5, 7.5, (n, k, 2))
    offsets[:, 0] = offsets0
    peaks = np.column_stack([peaks0, rng.uniform(0.05, 0.3, (n, k - 1))])
    z = np.column_stack([np.full(n, 4.0), rng.normal(0, 1, (n, k - 1))])
    margins = np.column_stack([margins0, rng.uniform(-0.05, 0.1, (n, k - 1))])
    turned = (rng.uniform(-7.5, 7.5, (n, 2)), rng.uniform(0.05, 0.3, n))
    return offsets, peaks, z, margins, turned


def test_a_peak_elsewhere_contradicts_only_when_it_beats_the_zero_offset_decisively():
    """Twelve of 25 sites peak clearly elsewhere, each in its own direction: by a hair over their correlation near
    zero (ambiguous sites: repeated structure, speckle) the model verifies; by a wide margin they contradict it."""
    rng = np.random.default_rng(5)
    sites = _grid_sites()
    extent = _grid_sites(20, 25.0, 475.0)
    offsets0 = rng.normal(0, 0.2, (25, 2))
    angles = rng.uniform(0, 2 * math.pi, 12)
    offsets0[:12] = 7.0 * np.column_stack([np.cos(angles), np.sin(angles)])
    peaks0 = np.full(25, 0.8)
    for margin, verdict in ((0.01, "verified"), (0.4, "suspect")):
        margins0 = np.where(np.arange(25) < 12, margin, -0.3)
        v = judge(sites, *_evidence(offsets0, peaks0, margins0, np.random.default_rng(6)), extent, VerifyParams())
        assert v.verdict == verdict and v.n_contradict == (12 if margin > 0.1 else 0), v.reasons


def test_a_missed_turn_is_caught_though_only_the_central_sites_agree():
    """A model 1.5 degrees off about the overlap's centre: the sites near the centre agree (within 3 px) and
    alone would bound the error at a pixel; the outer sites follow the turn, which the shared field finds."""
    sites = _grid_sites()
    extent = _grid_sites(20, 25.0, 475.0)
    a = math.radians(1.5)
    turn = np.array([[math.cos(a) - 1, -math.sin(a)], [math.sin(a), math.cos(a) - 1]])
    offsets0 = (sites - 250.0) @ turn.T + np.random.default_rng(1).normal(0, 0.2, (25, 2))
    v = judge(sites, *_evidence(offsets0, np.full(25, 0.8), np.full(25, 0.1), np.random.default_rng(2)), extent,
              VerifyParams())
    true_rms = float(np.sqrt(np.mean(np.sum(((extent - 250.0) @ turn.T) ** 2, axis=1))))
    assert true_rms > 3 and v.verdict != "verified"
    assert any("agree on an error" in r for r in v.reasons), v.reasons


def test_the_bound_covers_the_true_error_in_95_percent_of_fits_and_is_tighter_than_before():
    """Affine error fields from none to 3 px RMS, measured with 1 px noise at 6 to 25 sites: the debiased bound
    covers the field's true RMS in at least 95 % of 2000 fits, and is below the plain RMS plus two standard
    errors (the bound before) wherever the field is within the noise."""
    rng = np.random.default_rng(11)
    extent = _grid_sites(20, 25.0, 475.0)
    covered, tighter = [], []
    for _ in range(2000):
        k = int(rng.integers(6, 26))
        sites = rng.uniform(40, 460, (k, 2))
        coef = rng.normal(0, 1, (3, 2)) * rng.uniform(0, 1.5)
        field = lambda xy: np.column_stack([np.ones(len(xy)), (xy - 250.0) / 225.0]) @ coef  # noqa: E731
        true = float(np.sqrt(np.mean(np.sum(field(extent) ** 2, axis=1))))
        fit = fit_field(sites, field(sites) + rng.normal(0, 1.0, (k, 2)), extent)
        covered.append(fit.bound >= true)
        if fit.error <= 2 * fit.se:
            tighter.append(fit.bound < fit.error + 2 * fit.se)
    assert np.mean(covered) >= 0.95 and len(tighter) > 200 and all(tighter)


def test_a_model_whose_half_turned_twin_fits_too_is_not_verified():
    """A scene of repeated parcels can fit a model and the same model turned by 180 degrees: when the twin
    agrees at more sites than chance explains, the check cannot tell them apart and says so."""
    rng = np.random.default_rng(8)
    sites = _grid_sites()
    extent = _grid_sites(20, 25.0, 475.0)
    evidence = list(_evidence(rng.normal(0, 0.3, (25, 2)), np.full(25, 0.8), np.full(25, -0.3), rng))
    assert judge(sites, *evidence, extent, VerifyParams()).verified
    evidence[4] = (rng.normal(0, 0.5, (25, 2)), np.full(25, 0.7))
    v = judge(sites, *evidence, extent, VerifyParams())
    assert v.verdict == "suspect" and v.turned_agree == 25
    assert any("turned by 180 degrees" in r for r in v.reasons), v.reasons


@pytest.mark.parametrize("wrong", [None, "shift5", "turn2"])
def test_the_second_look_verifies_a_weak_right_pair_and_not_the_same_model_a_little_off(shared, wrong):
    """An optical image onto a speckled SAR scene (Optical-SAR pair 17 of the multimodal set, both grey): the
    grid cannot decide, the second look, at sites where both images show structure, verifies the right
    model; the same model 5 px off or turned by 2 degrees (about 3 px at the edges) is not verified."""
    folder = shared / "data" / "multimodal" / "Optical-SAR"
    t, r = open_raster(str(folder / "pair17_1.jpg")), open_raster(str(folder / "pair17_2.jpg"))
    m = np.array([[0.987343, 0.818094, -51.45221], [-0.803034, 0.976061, 110.015971], [0, 0, 1.0]])
    m = {None: m, "shift5": _shifted(m, 5.0), "turn2": _rotated(m, 2.0, [128.0, 128.0])}[wrong]
    v = verify(LinearModel("affine", m), t, resolve_bands(t, None), r, resolve_bands(r, None), VerifyParams())
    if wrong is None:
        assert v.verified and v.look == "structure", v.reasons
    else:
        assert not v.verified and v.reasons


def test_of_two_unverified_results_the_stronger_evidence_ranks_first_not_the_more_sites():
    """A wrong model that lies over more sites agrees at more of them by chance; the result whose agreement
    is less likely from wrong alignments is the better one to return (the numbers of a held-out Landsat
    search: a wrong model 4 of 12 sites with probability 8.3e-3, the right one 3 of 7 with 1.9e-4)."""
    import types

    from hamta.core.verify import result_rank
    from hamta.core.verify.params import Verification

    def result(n_agree, n_sites, chance, z_chance):
        empty = np.zeros((0, 2))
        v = Verification("suspect", (), 3.0, 40, n_sites, n_agree, 0, n_agree, 0.1, chance, 0.8, 1.0, 2.0, 0.5,
                         0.0, empty, empty, np.zeros(0), np.zeros(0, bool), np.zeros(0, bool), z_chance=z_chance,
                         z_mw=1e-4)
        return types.SimpleNamespace(verification=v)

    wrong, right = result(4, 12, 8.3e-3, 8.3e-3), result(3, 7, 1e-2, 1.9e-4)
    assert result_rank(right) > result_rank(wrong)
    params = VerifyParams()
    assert params.shortfall(right.verification) == pytest.approx(190.0)
    assert not params.significant(right.verification)
    verified = result(5, 7, 1e-6, 1.0)
    assert params.significant(verified.verification) and params.shortfall(verified.verification) <= 1.0
