"""RIFT features, the RIFT2 baseline and ``xmodal`` on real cross-modal pairs at any rotation."""
import math

import cv2
import numpy as np
import pytest

from hamta.bench.multimodal_set import build
from hamta.core import RegisterOptions, register
from hamta.core.descriptors import rift
from hamta.core.detectors.phase_congruency import log_gabor_maps
from hamta.core.methods.xmodal import nearest


def _scene(size=256, seed=4):
    rng = np.random.default_rng(seed)
    img = np.zeros((size, size), np.float32)
    for _ in range(40):
        x, y = rng.integers(10, size - 40, 2)
        w, h = rng.integers(8, 40, 2)
        cv2.rectangle(img, (int(x), int(y)), (int(x + w), int(y + h)), float(rng.uniform(60, 250)), -1)
    return cv2.GaussianBlur(img, (0, 0), 1.0)


def test_maximum_index_map_follows_a_rotation_by_index_shifts():
    img = _scene()
    turned = np.ascontiguousarray(np.rot90(img))  # 90 degrees = 3 of the 6 orientations
    a, b = log_gabor_maps(img)["mim"], log_gabor_maps(turned)["mim"]
    inner = (slice(20, -20), slice(20, -20))
    back = np.rot90(b, -1)[inner]
    strong = log_gabor_maps(img)["cs"].max(axis=0)[inner] > np.percentile(log_gabor_maps(img)["cs"].max(axis=0), 70)
    assert np.mean(((a[inner] + 3) % 6 == back)[strong]) > 0.8


def test_rotation_invariant_descriptors_match_across_a_turn():
    img = _scene()
    valid = np.ones(img.shape, bool)
    fa = rift.rotated_features(img, valid, 300)
    turned = np.ascontiguousarray(np.rot90(img))
    fb = rift.rotated_features(turned, valid, 300)
    d2 = ((fa.descriptors[:, None] - fb.descriptors[None]) ** 2).sum(2)
    j = d2.argmin(axis=1)
    # np.rot90 (counter-clockwise) sends (x, y) to (y, W - x)
    expected = np.column_stack([fa.keypoints.xy[:, 1], img.shape[1] - fa.keypoints.xy[:, 0]])
    right = np.linalg.norm(fb.keypoints.xy[j] - expected, axis=1) < 3
    assert right.mean() > 0.3 and right.sum() > 20


@pytest.mark.parametrize("category,pair", [("mm-night", 13), ("mm-map", 1)])  # infrared 1: the test of threads
def test_xmodal_registers_real_cross_modal_pairs_and_the_check_verifies_them(shared, category, pair):
    case = build(category, pair, str(shared / "data"))
    result = register(case.target, case.reference, "xmodal", options=RegisterOptions(tolerance_px=15, pixel_mode=True))
    error = math.sqrt(np.mean(case.errors(result.model) ** 2))
    assert error < 5.0 and result.verified, (error, result.verification.reasons)
    assert result.diagnostics["local_inliers"] >= 20


def test_xmodal_handles_a_further_half_turn(shared, tmp_path, raster_writer):
    import rasterio

    case = build("mm-infrared", 1, str(shared / "data"))
    with rasterio.open(case.target) as ds:
        data = ds.read()
    turned = raster_writer("turned.tif", np.ascontiguousarray(data[:, ::-1, ::-1]))
    result = register(turned, case.reference, "xmodal", options=RegisterOptions(tolerance_px=15, pixel_mode=True))
    h, w = data.shape[1:]
    pts = case.check_points
    flipped = np.column_stack([w - pts[:, 0], h - pts[:, 1]])  # the same ground points in the turned target
    error = math.sqrt(np.mean(np.sum((result.model.apply(flipped) - case.truth(pts)) ** 2, axis=1)))
    assert error < 8.0 and result.verified


def test_rift_baseline_matches_a_pair_without_scale_change(shared):
    case = build("mm-map", 1, str(shared / "data"))
    result = register(case.target, case.reference, "rift", options=RegisterOptions(tolerance_px=15, pixel_mode=True))
    assert math.sqrt(np.mean(case.errors(result.model) ** 2)) < 10.0
    assert result.stats.n_inliers >= 20


@pytest.mark.parametrize("rows", [7, 512])
def test_nearest_descriptors_by_blocks_of_rows(rows):
    rng = np.random.default_rng(5)
    a, b = rng.random((50, 216)), rng.random((80, 216))
    brute = ((a[:, None, :] - b[None, :, :]) ** 2).sum(axis=2).argmin(axis=1)
    assert np.array_equal(nearest(a, b, rows=rows), brute)
    assert np.array_equal(nearest(a.astype(np.float32), b.astype(np.float32), rows=rows), brute)


def test_rotated_descriptors_do_not_depend_on_how_many_keypoints_are_sampled_at_once():
    img = _scene()
    valid = np.ones(img.shape, bool)
    valid[:30, :50] = False
    m = rift.maps(img, valid)
    xy, angle = rift.orientations(m["M"], rift.corners(m["M"], valid, 300))
    assert len(xy) > 100
    for step in (1, 2):
        many = rift.describe_rotated(m["mim"], xy, angle, step, chunk=300)
        for chunk in (1, 7, 64):
            assert np.array_equal(rift.describe_rotated(m["mim"], xy, angle, step, chunk=chunk), many)


@pytest.mark.parametrize("rows", [1, 7, 128])
def test_mutual_nearest_within_a_radius_by_blocks_of_rows(rows):
    from hamta.core.methods.xmodal import mutual_nearest_within

    rng = np.random.default_rng(rows)
    a, b = np.round(rng.random((300, 8)), 1), np.round(rng.random((260, 8)), 1)  # rounded: many equal distances
    b[:40] = b[0]
    p, q = rng.uniform(0, 200, (300, 2)), rng.uniform(0, 200, (260, 2))
    d2 = ((a[:, None, :] - b[None, :, :]) ** 2).sum(axis=2)
    far = ((p[:, None, :] - q[None, :, :]) ** 2).sum(axis=2) > 25.0 ** 2
    masked = np.where(far, np.inf, d2)
    want_j = masked.argmin(axis=1)
    want_ok = np.isfinite(masked[np.arange(300), want_j]) & (masked.argmin(axis=0)[want_j] == np.arange(300))
    j, ok = mutual_nearest_within(d2.copy(), p, q, 25.0, rows=rows)
    assert 20 < want_ok.sum() < 300
    assert np.array_equal(ok, want_ok) and np.array_equal(j, want_j)


def test_xmodal_and_its_check_give_the_same_answer_on_one_thread_as_on_three(shared, monkeypatch):
    """The pyramid levels of both images, the pose checks beside the reference's local features, the
    full-resolution windows and the check's sites run on threads: the same model, points and evidence
    whatever the number of cores (and the right answer, on a real infrared-optical pair)."""
    from hamta.core import parallel

    case = build("mm-infrared", 1, str(shared / "data"))
    runs = []
    for threads in (1, 3):
        monkeypatch.setattr(parallel, "THREADS", threads)
        r = register(case.target, case.reference, "xmodal", options=RegisterOptions(tolerance_px=15, pixel_mode=True))
        v = r.verification
        runs.append((r.model.matrix, np.array([g.target_px + g.reference_px for g in r.gcps]), r.diagnostics,
                     v.verdict, v.offset_xy, v.peak, v.chance, v.error_bound_px))
    (m1, g1, d1, *v1), (m3, g3, d3, *v3) = runs
    assert np.array_equal(m1, m3) and np.array_equal(g1, g3) and len(g1) >= 100
    untimed = [{k: v for k, v in d.items() if not k.endswith("_s")} for d in (d1, d3)]
    assert untimed[0] == untimed[1]
    assert v1[0] == v3[0] == "verified" and d1["local_inliers"] >= 20
    assert math.sqrt(np.mean(case.errors(r.model) ** 2)) < 5.0
    assert all(np.array_equal(a, b, equal_nan=True) for a, b in zip(v1[1:3], v3[1:3])) and v1[3:] == v3[3:]
