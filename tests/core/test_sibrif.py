"""SIBRIF (spec 001) and the PCA-SIFT baseline."""
import cv2
import numpy as np
import pytest

from hamta.bench.cases import similarity_case
from hamta.core import RegisterOptions, register
from hamta.core.descriptors.pca_sift import gradient_vectors, load_basis
from hamta.core.descriptors.rbrief import intensity_centroid_angle, rbrief_descriptors
from hamta.core.matching.nearest import self_similar
from hamta.core.methods.sibrif import SibrifFaithfulParams, SibrifParams, edge_image, selective_vote
from hamta.core.preprocess.edges import sobel_edge_image
from hamta.core.types import Features, Keypoints


@pytest.fixture(scope="module")
def texture():
    rng = np.random.default_rng(4)
    img = cv2.GaussianBlur((rng.random((400, 400)) * 255).astype(np.float32), (0, 0), 2.0)
    return cv2.normalize(img, None, 0, 255, cv2.NORM_MINMAX).astype(np.uint8)


def test_edge_image_is_thresholded_to_zero_not_binarised(texture):
    full = sobel_edge_image(texture, 0)
    edges = sobel_edge_image(texture, 30)
    assert np.array_equal(edges[full > 30], full[full > 30]) and (edges[full <= 30] == 0).all()
    soft = edge_image(texture, SibrifParams(edge_threshold=30, magnitude="l1"))
    gx = cv2.Sobel(texture, cv2.CV_32F, 1, 0, ksize=3)
    gy = cv2.Sobel(texture, cv2.CV_32F, 0, 1, ksize=3)
    expected = np.clip(np.round(0.5 * np.abs(gx) + 0.5 * np.abs(gy) - 30), 0, 255)
    assert np.abs(soft.astype(float) - expected).max() <= 1  # soft: magnitude minus T, no jump at T
    assert np.array_equal(edge_image(texture, SibrifFaithfulParams(edge_threshold=30)), edges)


def test_intensity_centroid_angle_uses_image_axes():
    ramp_x = np.tile(np.arange(64, dtype=np.uint8) * 4, (64, 1))  # brighter to the right
    ramp_y = ramp_x.T.copy()  # brighter downwards
    c = np.array([[32.5, 32.5]])
    assert intensity_centroid_angle(ramp_x, c)[0] == pytest.approx(0.0, abs=1e-6)
    assert intensity_centroid_angle(ramp_y, c)[0] == pytest.approx(90.0, abs=1e-6)


def test_rbrief_is_steered_by_the_intensity_centroid(texture):
    pts = np.random.default_rng(5).random((80, 2)) * 200 + 100
    h, w = texture.shape
    m = cv2.getRotationMatrix2D((w / 2 - 0.5, h / 2 - 0.5), 50, 1.0)
    rot = cv2.warpAffine(texture, m, (w, h), flags=cv2.INTER_CUBIC, borderMode=cv2.BORDER_REFLECT)
    pts_rot = (m[:, :2] @ (pts - 0.5).T).T + m[:, 2] + 0.5
    ia, a = rbrief_descriptors(texture, pts, intensity_centroid_angle(texture, pts))
    ib, b = rbrief_descriptors(rot, pts_rot, intensity_centroid_angle(rot, pts_rot))
    assert len(ia) == 80 and len(ib) == 80 and a.shape == (80, 32)
    same = np.unpackbits(a ^ b, axis=1).sum(axis=1)
    other = np.unpackbits(a ^ np.roll(b, 1, axis=0), axis=1).sum(axis=1)
    assert np.median(same) < 0.4 * np.median(other)
    kept, _ = rbrief_descriptors(texture, np.array([[5.0, 5.0], [200.0, 200.0]]), np.zeros(2))
    assert list(kept) == [1]  # within OpenCV's 31-px border a keypoint gets no descriptor


def test_self_similar_keypoints_are_removed():
    rng = np.random.default_rng(6)
    desc = rng.integers(0, 256, (50, 32), dtype=np.uint8)
    desc[10] = desc[3]
    desc[11] = desc[4]
    desc[11, 0] ^= 1  # one bit apart
    f = Features(Keypoints(np.zeros((50, 2)), np.ones(50), np.zeros(50), np.ones(50)), desc, "hamming")
    assert sorted(np.flatnonzero(self_similar(f, 10))) == [3, 4, 10, 11]
    assert not self_similar(f, 0).any()


def test_selective_vote_keeps_the_dominant_angle_and_scale():
    n = 40
    kp_t = Keypoints(np.zeros((n, 2)), np.full(n, 4.0), np.zeros(n), np.ones(n))
    angles = np.r_[np.full(30, 47.0), np.linspace(100, 300, 10)]
    sizes = np.r_[np.full(30, 8.0), np.full(10, 40.0)]
    kp_r = Keypoints(np.zeros((n, 2)), sizes, angles, np.ones(n))
    ft = Features(kp_t, np.zeros((n, 32), np.uint8), "hamming")
    fr = Features(kp_r, np.zeros((n, 32), np.uint8), "hamming")
    keep = selective_vote(ft, fr, np.arange(n), np.arange(n))
    assert keep[:30].all() and not keep[30:].any()


@pytest.mark.split("angle", "scale")
@pytest.mark.parametrize("method", ["sibrif", "sibrif-faithful"])
@pytest.mark.parametrize("angle,scale", [(45, 1.0), (170, 1.1)])
def test_sibrif_registers_rotated_landsat_pairs(tmp_path, landsat, method, angle, scale):
    case = similarity_case(str(tmp_path), landsat, angle_deg=angle, scale=scale, shift_px=(7.0, 3.0))
    result = register(case.target, case.reference, method, options=RegisterOptions(model="affine"))
    assert np.sqrt(np.mean(case.errors(result.model) ** 2)) < 1.0


def test_product_sibrif_survives_scale_changes_the_paper_does_not(tmp_path, landsat):
    case = similarity_case(str(tmp_path), landsat, angle_deg=20, scale=0.6, shift_px=(3.0, 2.0))
    result = register(case.target, case.reference, "sibrif")
    assert np.sqrt(np.mean(case.errors(result.model) ** 2)) < 1.0


def test_pca_sift_basis_is_orthonormal_and_fits_real_imagery(landsat):
    from hamta.core.descriptors.sift import OPENCV_SIFT_BIAS_PX, SiftDetector, keypoints_from_opencv
    from hamta.core.io.raster import open_raster, read_image, resolve_bands
    from hamta.core.preprocess.normalize import stretch_to_uint8

    mean, comp = load_basis()
    assert comp.shape == (36, 3042) and np.allclose(comp @ comp.T, np.eye(36), atol=1e-4)
    info = open_raster(landsat)
    img, valid = read_image(info, resolve_bands(info, None))
    gray = stretch_to_uint8(img, valid)
    kp = keypoints_from_opencv(SiftDetector(n_features=500).create().detect(gray, None), OPENCV_SIFT_BIAS_PX)
    v = gradient_vectors(gray, kp.xy, kp.size, -np.radians(kp.angle)) - mean
    captured = np.sum((v @ comp.T) ** 2) / np.sum(v ** 2)
    random = np.linalg.qr(np.random.default_rng(0).normal(size=(3042, 36)))[0].T
    assert captured > 0.4 and captured > 10 * np.sum((v @ random.T) ** 2) / np.sum(v ** 2)


def test_pca_sift_registers_a_rotated_pair(tmp_path, landsat):
    case = similarity_case(str(tmp_path), landsat, angle_deg=35, scale=0.9)
    result = register(case.target, case.reference, "pca-sift")
    assert np.sqrt(np.mean(case.errors(result.model) ** 2)) < 0.5
