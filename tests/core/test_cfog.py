"""The cross-modal product ``cfog``: CFOG descriptors, the structural search, dense matching, end to end."""
import cv2
import numpy as np
import pytest

from hamta.bench.families import CaseSpec, build_case
from hamta.bench.synthetic import make_landscape
from hamta.core import RegisterOptions, register
from hamta.core.descriptors.cfog import ncc_surface
from hamta.core.matching.multimodal import apply, dense_matches, search_similarity, similarity
from hamta.core.similarity.cfog import cfog
from hamta.core.similarity.peak import peak_offset


def _landscape():
    rgb = make_landscape((400, 400), seed=11).astype(np.float32)
    return rgb.mean(axis=0)


def test_cfog_is_unchanged_by_contrast_inversion_and_locates_a_shift():
    img = _landscape()
    d, di = cfog(img), cfog(255.0 - img)
    assert np.abs(d - di).max() < 1e-4
    tmpl = d[:, 100:164, 120:184]
    area = d[:, 97:171, 112:186]  # offset 0 would put the template's corner at (117, 102)
    offset, peak = peak_offset(ncc_surface(area, tmpl), 5)
    assert peak > 0.99 and np.allclose(offset, [3, -2], atol=0.05)


def test_search_and_dense_matching_register_an_inverted_rotated_scaled_image():
    ref = _landscape()
    valid = np.ones(ref.shape, bool)
    truth = similarity(17.0, 1.2, (150, 150), (200, 190))  # target px -> reference px
    inv = np.linalg.inv(np.vstack([truth, [0, 0, 1]]))[:2]
    m = inv.copy()
    m[:, 2] += m[:, :2].sum(axis=1) * 0.5 - 0.5
    tgt = cv2.warpAffine(255.0 - ref, m, (300, 300), flags=cv2.INTER_LINEAR)
    tgt = np.sqrt(tgt ** 2 * np.random.default_rng(0).gamma(4, 0.25, tgt.shape)).astype(np.float32)
    tvalid = cv2.warpAffine(np.ones(ref.shape, np.uint8), m, (300, 300), flags=cv2.INTER_NEAREST) > 0
    candidates, tried = search_similarity(tgt, tvalid, ref, valid)
    grid = np.array([[x, y] for x in (40, 150, 260) for y in (40, 150, 260)], float)
    close = [np.abs(apply(c["affine"], grid) - apply(truth, grid)).max() < 8.0 for c in candidates]
    assert len(tried) == 13 * 11 and any(close[:3])  # the method checks the first three densely
    tx, rx, _ = dense_matches(tgt, tvalid, ref, valid, candidates[close.index(True)]["affine"], search=12)
    err = np.linalg.norm(apply(truth, tx) - rx, axis=1)
    assert len(tx) > 30 and np.median(err) < 0.5


def test_product_registers_the_multimodal_proxy(tmp_path, shared):
    """The folded proxy; the inverted one is registered by cfog in test_auto's escalation test."""
    spec = CaseSpec("multimodal", "landsat_fold", {"source": "landsat", "mapping": "fold"})
    case = build_case(spec, str(tmp_path), 512, str(shared / "data"))
    result = register(case.target, case.reference, "cfog")
    assert np.sqrt(np.mean(case.errors(result.model) ** 2)) < 1.0
    assert result.stats.n_gcps >= 50 and "coarse" in result.diagnostics


def test_product_registers_the_real_sar_optical_pair_within_3_px(tmp_path, shared):
    case = build_case(CaseSpec("pairs", "sar_optical", {"pair": "sar_optical"}), str(tmp_path), 0,
                      str(shared / "data"))
    result = register(case.target, case.reference, "cfog", options=RegisterOptions(pixel_mode=True))
    assert np.sqrt(np.mean(case.errors(result.model) ** 2)) <= 3.0


def test_decimated_multimodal_pair_is_refined_with_cfog(tmp_path, shared):
    spec = CaseSpec("multimodal", "landsat_sqrt-invert", {"source": "landsat", "mapping": "sqrt-invert"})
    case = build_case(spec, str(tmp_path), 700, str(shared / "data"))
    options = RegisterOptions(max_working_pixels=120_000)
    result = register(case.target, case.reference, "cfog", options=options)
    assert result.stats.refined and result.stats.n_refined >= 50
    assert np.sqrt(np.mean(case.errors(result.model) ** 2)) < 1.0


def test_dense_model_is_a_homography_only_where_perspective_needs_it():
    from hamta.core.methods.cfog import _fit

    rng = np.random.default_rng(8)
    ref = rng.uniform(0, 600, (300, 2))
    h = np.array([[1.0, 0.05, 10.0], [0.02, 0.95, -5.0], [4e-4, -3e-4, 1.0]])  # strong perspective
    tgt = apply(np.linalg.inv(h), ref) + rng.normal(0, 0.3, ref.shape)
    model, _ = _fit((tgt, ref), seed=0)
    assert model.shape == (3, 3) and np.abs(apply(model, tgt) - ref).max() < 2.0
    affine = similarity(12.0, 1.1, (300, 300), (310, 290))
    tgt = apply(np.linalg.inv(np.vstack([affine, [0, 0, 1]])), ref) + rng.normal(0, 0.3, ref.shape)
    model, n = _fit((tgt, ref), seed=0)
    assert model.shape == (2, 3) and n >= 290


def test_the_checks_numpy_smoothing_and_sampling_equal_scipys():
    """The check avoids importing scipy.ndimage (a third of a second per run) with the same numbers."""
    from scipy import ndimage

    from hamta.core.similarity.cfog import gaussian_blur, gaussian_kernel
    from hamta.core.verify.sites import bilinear, nearest_valid

    rng = np.random.default_rng(0)
    for shape in ((40, 50), (5, 7), (3, 3)):
        img = rng.normal(size=shape)
        for sigma in (0.8, 1.5, 3.0):
            k = gaussian_kernel(sigma)
            want = ndimage.correlate1d(ndimage.correlate1d(img, k, axis=-1, mode="mirror"), k, axis=-2, mode="mirror")
            assert np.abs(gaussian_blur(img, sigma) - want).max() < 1e-12
    img, valid = rng.normal(size=(20, 30)), rng.random((20, 30)) > 0.3
    for rc in (rng.uniform(-2, 32, (2, 60, 60)) * np.array([[[20 / 30]], [[1.0]]]),
               rng.integers(-2, 64, (2, 60, 60)) / 2.0):
        assert np.abs(bilinear(img, rc) - ndimage.map_coordinates(img, rc, order=1, mode="nearest")).max() < 1e-12
        want = ndimage.map_coordinates(valid.astype(np.uint8), rc, order=0, mode="constant", cval=0) > 0
        assert np.array_equal(nearest_valid(valid, rc), want)


def _cfog_over_the_stack(image, valid, portable, bins=9, sigma=0.8):
    """CFOG as first written: the orientation smoothing and normalisation over the whole stack at once."""
    from hamta.core.similarity.cfog import central_differences, gaussian_blur

    img = image.astype(np.float64 if portable else np.float32)
    img = np.where(valid, img, img.dtype.type(img[valid].mean()))
    blur = gaussian_blur if portable else (lambda a, s: cv2.GaussianBlur(a, (0, 0), s))
    gx, gy = central_differences(img) if portable else (cv2.Sobel(img, cv2.CV_32F, 1, 0, ksize=1),
                                                        cv2.Sobel(img, cv2.CV_32F, 0, 1, ksize=1))
    raw = np.stack([blur(np.abs(img.dtype.type(np.cos(k * np.pi / bins)) * gx
                                + img.dtype.type(np.sin(k * np.pi / bins)) * gy), sigma) for k in range(bins)])
    ch = 0.5 * raw
    ch[1:] += 0.25 * raw[:-1]
    ch[0] += 0.25 * raw[-1]
    ch[:-1] += 0.25 * raw[1:]
    ch[-1] += 0.25 * raw[0]
    norm = np.sqrt(np.einsum("kij,kij->ij", ch, ch))
    norm += img.dtype.type(1e-6 + 1e-3 * float(ch.mean()))
    ch /= norm[None]
    ch *= cv2.erode(valid.astype(np.uint8), np.ones((7, 7), np.uint8), borderType=cv2.BORDER_REPLICATE)[None]
    return ch.astype(np.float32)


@pytest.mark.parametrize("portable", [True, False])
def test_cfog_channel_by_channel_gives_the_numbers_of_the_whole_stack(portable):
    """The check's numbers (and the evidence its thresholds were fitted on) do not move with how CFOG is
    computed: the same operations in the same order give the same bits."""
    rng = np.random.default_rng(3)
    image = _landscape()[:116, :130] + rng.normal(0, 2, (116, 130))
    valid = np.ones(image.shape, bool)
    valid[:9, :20] = False
    assert np.array_equal(cfog(image, valid=valid, portable=portable), _cfog_over_the_stack(image, valid, portable))


def test_the_checks_pruned_fft_surface_is_the_direct_ncc():
    """Only the rows of the inverse transform that the surface needs are computed; the surface (and its
    window sums) are the direct normalised cross-correlation's."""
    from hamta.core.verify.correlation import SearchSpectrum, TemplateSpectrum, fast_length, window_sums

    rng = np.random.default_rng(8)
    side, s = 40, 9
    search = rng.random((9, side + 2 * s, side + 2 * s)).astype(np.float32)
    noise = rng.normal(0, 0.05, (9, side, side)).astype(np.float32)
    template = search[:, s + 2:s + 2 + side, s - 3:s - 3 + side] + noise
    shape = (fast_length(side + 2 * s),) * 2
    surface = SearchSpectrum(search, side, shape).ncc(TemplateSpectrum(template, shape), s)
    assert np.allclose(surface, ncc_surface(search, template), rtol=0, atol=1e-5)
    assert peak_offset(surface, s)[0] == pytest.approx((-3, 2), abs=0.05)
    a = rng.random((12, 15))
    sums = window_sums(a, 5)
    assert sums.shape == (8, 11)
    assert np.allclose(sums, [[a[r:r + 5, c:c + 5].sum() for c in range(11)] for r in range(8)], rtol=0, atol=1e-12)


@pytest.mark.parametrize("tile", [96, 512])
def test_structural_refinement_finds_a_subpixel_shift_whatever_the_tiles(raster_writer, monkeypatch, tile):
    """CFOG descriptors computed once per tile of windows: across an inversion of contrast, the windows find
    the shift to a few hundredths of a pixel (the parabola's sub-pixel bias, at most a fifth), and the tiles'
    size changes no answer."""
    import hamta.core.refine as refine
    from hamta.core.estimation.models import LinearModel
    from hamta.core.io.raster import open_raster

    ref = _landscape()
    shift = np.array([3.3, -2.6])  # reference px = target px + shift
    tgt = cv2.warpAffine(255.0 - ref, np.array([[1, 0, -shift[0]], [0, 1, -shift[1]]]), (400, 400),
                         flags=cv2.INTER_CUBIC, borderMode=cv2.BORDER_REFLECT)
    reference = open_raster(raster_writer("reference.tif", ref.astype(np.float32)))
    target = open_raster(raster_writer("target.tif", tgt.astype(np.float32)))
    params = refine.RefineParams(template_px=64, search_px=6, min_ncc=0.1, points="grid", similarity="cfog",
                                 max_points=120)
    model = LinearModel("affine", np.array([[1, 0, 3.0], [0, 1, -3.0], [0, 0, 1]]))  # half a pixel off
    points = refine.grid_points(model, target, reference, params)

    def refined(tile_px):
        monkeypatch.setattr(refine, "TILE_PX", tile_px)
        return refine.refine_points(model, points, target, (1,), reference, (1,), params)

    found = refined(tile)
    assert len(found.reference_px) >= 0.9 * len(points)
    error = np.abs(found.reference_px - found.target_px - shift)
    assert error.mean() < 0.06 and error.max() < 0.2
    whole = refined(10_000)
    assert np.abs(found.target_px - whole.target_px).max() < 1e-4
