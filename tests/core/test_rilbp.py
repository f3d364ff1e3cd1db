"""RILBP (spec 000): layout, invariances, baselines, and the method through ``register``."""
import cv2
import numpy as np
import pytest

from hamta.bench.cases import similarity_case
from hamta.core import RegisterOptions, register
from hamta.core.descriptors.cslbp import cslbp_descriptors
from hamta.core.descriptors.rilbp import RilbpParams, dimension, rilbp_descriptors, round_half_away, sub_region_counts
from hamta.core.descriptors.sift import sift_descriptors
from hamta.core.detectors.patches import dominant_orientation, sample_patches


@pytest.fixture(scope="module")
def texture():
    rng = np.random.default_rng(0)
    img = cv2.GaussianBlur((rng.random((500, 500)) * 255).astype(np.float32), (0, 0), 2.5)
    return cv2.normalize(img, None, 0, 255, cv2.NORM_MINMAX)


def _rotated(img, angle, pts):
    h, w = img.shape
    m = cv2.getRotationMatrix2D((w / 2 - 0.5, h / 2 - 0.5), angle, 1.0)
    rot = cv2.warpAffine(img, m, (w, h), flags=cv2.INTER_CUBIC, borderMode=cv2.BORDER_REFLECT)
    return rot, (m[:, :2] @ (pts - 0.5).T).T + m[:, 2] + 0.5


def test_default_layout_is_the_papers_128_dimensions():
    p = RilbpParams()
    assert sub_region_counts(p) == (2, 3, 3) and dimension(p) == 128
    assert round_half_away(2.5) == 3 and round_half_away(3.5) == 4  # MATLAB rounding, not banker's
    equal_width = RilbpParams(ring_fractions=(1 / 3, 2 / 3, 1.0))
    assert sub_region_counts(equal_width) == (2, 6, 10)  # why the spec rejects equal-width rings


@pytest.mark.parametrize("angle", [30, 45, 90, 137])
def test_descriptors_are_rotation_invariant_without_orientation(texture, angle):
    pts = np.random.default_rng(1).random((60, 2)) * 300 + 100
    rot, pts_rot = _rotated(texture, angle, pts)
    p = RilbpParams()
    a = rilbp_descriptors(sample_patches(texture, pts, np.full(60, 20.0), p.radius, p.margin), p)
    b = rilbp_descriptors(sample_patches(rot, pts_rot, np.full(60, 20.0), p.radius, p.margin), p)
    d = np.linalg.norm(a[:, None] - b[None], axis=2)
    same, other = np.diag(d), d[~np.eye(60, dtype=bool)]
    assert np.median(same) < 0.35 * np.median(other)
    assert (np.argmin(d, axis=1) == np.arange(60)).mean() > 0.95
    if angle == 90:
        assert np.allclose(same, 0, atol=1e-5)  # a 90-degree turn maps the pixel grid onto itself


def test_gain_and_offset_do_not_change_the_descriptor(texture):
    pts = np.array([[200.0, 220.0], [300.5, 180.25]])
    p = RilbpParams()
    a = rilbp_descriptors(sample_patches(texture, pts, np.full(2, 20.0), p.radius, p.margin), p)
    b = rilbp_descriptors(sample_patches(0.5 * texture + 40, pts, np.full(2, 20.0), p.radius, p.margin), p)
    assert np.allclose(a, b, atol=1e-6)


def test_cslbp_needs_its_orientation_and_has_256_dimensions(texture):
    pts = np.random.default_rng(2).random((40, 2)) * 300 + 100
    rot, pts_rot = _rotated(texture, 45, pts)
    support = np.full(40, 20.0)

    def describe(img, xy, oriented):
        angle = dominant_orientation(sample_patches(img, xy, support, 20, 2)) if oriented else None
        return cslbp_descriptors(sample_patches(img, xy, support, 20, 2, angle_rad=angle))

    with_o = np.linalg.norm(describe(texture, pts, True) - describe(rot, pts_rot, True), axis=1)
    without = np.linalg.norm(describe(texture, pts, False) - describe(rot, pts_rot, False), axis=1)
    assert describe(texture, pts, True).shape == (40, 256)
    assert np.median(with_o) < 0.6 * np.median(without)


def test_sift_descriptors_at_given_keypoints_follow_the_orientation(texture):
    pts = np.random.default_rng(3).random((30, 2)) * 300 + 100
    rot, pts_rot = _rotated(texture, 60, pts)
    u8, r8 = texture.astype(np.uint8), rot.astype(np.uint8)
    support = np.full(30, 20.0)
    a = sift_descriptors(u8, pts, support, np.zeros(30))
    b = sift_descriptors(r8, pts_rot, support, np.full(30, np.radians(60)))
    c = sift_descriptors(r8, pts_rot, support, np.zeros(30))
    assert a.shape == (30, 128)
    assert np.median(np.linalg.norm(a - b, axis=1)) < 0.5 * np.median(np.linalg.norm(a - c, axis=1))


@pytest.mark.split("angle", "scale")
@pytest.mark.parametrize("method", ["rilbp", "rilbp-faithful", "cslbp", "censure-sift"])
@pytest.mark.parametrize("angle,scale", [(45, 1.0), (137, 0.9)])
def test_methods_register_rotated_landsat_pairs(tmp_path, landsat, method, angle, scale):
    case = similarity_case(str(tmp_path), landsat, angle_deg=angle, scale=scale, shift_px=(9.0, -4.0))
    result = register(case.target, case.reference, method, options=RegisterOptions(model="affine"))
    assert np.sqrt(np.mean(case.errors(result.model) ** 2)) < 0.5
