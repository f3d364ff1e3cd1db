"""SAR onto optical (spec 003): line features, spectral matchers, triplet clustering, CFOG search and
the registered methods."""
import math

import cv2
import numpy as np
import pytest

from hamta.bench.families import CaseSpec, build_case
from hamta.core import RegisterOptions, register
from hamta.core.detectors import lines as ln
from hamta.core.estimation import triplets
from hamta.core.matching import spectral
from hamta.core.matching.multimodal import apply, dense_matches, search_similarity
from hamta.core.methods.lines_spectral import LinesParams, match_intersections, match_lines


def test_ggs_finds_a_speckled_step_edge_at_its_column():
    rng = np.random.default_rng(1)
    refl = np.full((120, 120), 20.0)
    refl[:, 60:] = 40.0  # contrast 2, as in Shui & Cheng's example
    img = np.sqrt(refl ** 2 * rng.gamma(3, 1 / 3, refl.shape)).astype(np.float32)
    strength, arg, normals = ln.ggs_strength(img)
    edges = ln.hysteresis(ln.non_maximum_suppression(strength, arg, normals), 0.15, 0.3)
    rows = edges[15:-15]
    cols = [np.flatnonzero(r) for r in rows]
    on_edge = sum(any(abs(c + 0.5 - 60) <= 1.5 for c in cs) for cs in cols)
    assert on_edge >= 0.9 * len(rows)
    assert edges[15:-15, 10:45].sum() + edges[15:-15, 75:110].sum() < 0.05 * edges.sum()
    assert abs(normals[np.bincount(arg[edges]).argmax()][0]) > 0.9  # the detected normal is horizontal


def test_ggs_windows_integrate_to_one_and_have_a_gap():
    for wu, wl, _ in ln.ggs_kernels(3.0, 1.5, 6.5 / math.sqrt(math.pi), 8):
        assert wu.sum() == pytest.approx(1.0) and wl.sum() == pytest.approx(1.0)
        assert (wu * wl).sum() == 0.0
    wu, _, _ = ln.ggs_kernels(3.0, 1.5, 3.0, 1)[0]
    c = wu.shape[0] // 2
    assert wu[c, c] == 0.0 and wu[c + 4, c] > wu[c + 1, c]  # the Gamma profile peaks away from the edge


def test_cleanup_removes_small_components_and_thins_to_one_pixel():
    img = np.zeros((60, 60), bool)
    img[10:13, 5:55] = True  # a 3 px thick bar
    img[40:45, 40:45] = True  # 25 px blob
    kept = ln.remove_small(img, 65)
    assert not kept[40:45, 40:45].any() and kept[10:13, 5:55].all()
    thin = ln.thin(kept)
    assert (thin[:, 10:50].sum(axis=0) == 1).all()
    assert cv2.connectedComponents(thin.astype(np.uint8), connectivity=8)[0] == 2


def test_radon_lines_and_intersection_of_two_drawn_lines():
    img = np.zeros((200, 300), np.uint8)
    cv2.line(img, (0, 50), (299, 170), 1)
    cv2.line(img, (220, 0), (100, 199), 1)
    lines = ln.cluster_lines(ln.radon_lines(img.astype(bool), peaks=10, min_votes=30))
    assert len(lines) == 2
    pts = ln.intersections(lines, img.shape)
    a = np.array([[120.0, -299.0], [199.0, 120.0]])  # both lines through pixel centres, solved directly
    expect = np.linalg.solve(a, [120 * 0.5 - 299 * 50.5, 199 * 220.5 + 120 * 0.5])
    assert len(pts) == 1 and np.linalg.norm(pts.xy[0] - expect) < 1.0
    assert pts.lines[0].tolist() == [0, 1] and 50 < pts.angle[0] < 90


def test_radon_places_a_pixel_column_exactly():
    img = np.zeros((80, 100), bool)
    img[:, 37] = True
    lines = ln.radon_lines(img, peaks=1, min_votes=10)
    assert lines.theta[0] == 0.0 and lines.rho[0] + lines.centre[0] == 37.5


def test_near_parallel_lines_are_not_intersected():
    lines = ln.Lines(np.radians([10.0, 15.0, 80.0]), np.array([0.0, 5.0, 3.0]), np.ones(3), (50.0, 50.0))
    pts = ln.intersections(lines, (100, 100), min_angle_deg=10.0)
    assert sorted(map(tuple, pts.lines.tolist())) == [(0, 2), (1, 2)]


def _point_sets(n=14, seed=3):
    rng = np.random.default_rng(seed)
    xy = rng.uniform(20, 280, (n, 2))
    a = math.radians(20)
    rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    perm = rng.permutation(n)
    moved = (xy - 150) @ rot.T + 150 + [7, -4]
    return xy, moved[perm], perm


def test_eigenvector_matching_recovers_a_rigidly_moved_permuted_set():
    xy, moved, perm = _point_sets()
    i, j, _ = spectral.eigenvector_match(xy, moved)
    assert len(i) >= 12
    assert np.all(perm[j] == i)


def test_voronoi_cells_tile_the_image_and_hausdorff_is_a_metric():
    rng = np.random.default_rng(0)
    xy = rng.uniform(0, 100, (12, 2)) * [2, 1]
    cells = spectral.voronoi_cells(xy, (100, 200))
    assert sum(cv2.contourArea(c.astype(np.float32)) for c in cells) == pytest.approx(200 * 100, rel=1e-6)
    assert all(cv2.pointPolygonTest(c.astype(np.float32), tuple(map(float, p)), False) >= 0
               for c, p in zip(cells, xy))
    hd = spectral.cell_hausdorff(cells)
    assert np.allclose(hd, hd.T) and np.all(np.diag(hd) == 0) and np.all(hd[~np.eye(12, dtype=bool)] > 0)
    square = np.array([[0, 0], [10, 0], [10, 10], [0, 10]], float)
    assert spectral.cell_hausdorff([square, square + [13, 4]])[0, 1] == pytest.approx(math.hypot(13, 4))


@pytest.mark.parametrize("proximity", spectral.VSPM_PROXIMITIES)
def test_vspm_matches_a_permuted_copy_by_its_spectrum_alone(proximity):
    xy, _, _ = _point_sets()
    perm = np.random.default_rng(5).permutation(len(xy))
    same = np.full(len(xy), 45.0)  # every crossing angle equal: the mask passes every pair
    c1, c2 = spectral.voronoi_cells(xy, (300, 300)), spectral.voronoi_cells(xy[perm], (300, 300))
    i, j, _ = spectral.vspm_match(c1, c2, same, same, proximity=proximity)
    assert len(i) >= 12 and np.all(perm[j] == i)


@pytest.mark.parametrize("rule", spectral.FUSIONS)
def test_fusion_matches_a_permuted_copy(rule):
    xy, _, _ = _point_sets()
    perm = np.random.default_rng(5).permutation(len(xy))
    same = np.full(len(xy), 45.0)
    c1, c2 = spectral.voronoi_cells(xy, (300, 300)), spectral.voronoi_cells(xy[perm], (300, 300))
    i, j, _ = spectral.fused_match(xy, xy[perm], c1, c2, same, same, rule=rule)
    assert len(i) >= 12 and np.all(perm[j] == i)


def test_angle_mask_excludes_pairs_whose_crossing_angles_differ():
    xy, _, _ = _point_sets()
    perm = np.random.default_rng(5).permutation(len(xy))
    angles = np.linspace(15, 85, len(xy))
    c1, c2 = spectral.voronoi_cells(xy, (300, 300)), spectral.voronoi_cells(xy[perm], (300, 300))
    assert len(spectral.vspm_match(c1, c2, angles, angles[perm])[0]) > 0
    shifted = angles[perm] + 10.0  # every true pair now differs by 10 degrees
    i, j, _ = spectral.vspm_match(c1, c2, angles, shifted)
    assert np.all(np.abs(angles[i] - shifted[j]) < 5.0) and not np.any(perm[j] == i)


def test_signs_are_aligned_between_point_sets_of_different_size():
    rng = np.random.default_rng(4)
    u = rng.normal(size=(30, 5))
    v = -u[rng.permutation(30)[:24]] + rng.normal(0, 0.05, (24, 5))  # a flipped, permuted subset
    assert np.allclose(spectral.align_signs(u, v), -v)


def test_degenerate_inputs_give_empty_results():
    empty = ln.Intersections(np.zeros((2, 2)), np.zeros((2, 2), int), np.zeros(2))
    i, j, s = match_intersections(empty, empty, (50, 50), (50, 50), LinesParams())
    assert len(i) == len(j) == len(s) == 0
    affine, inliers = triplets.triplet_clustering(np.zeros((2, 2)), np.zeros((2, 2)), radius_px=5, inlier_px=3)
    assert affine is None and not inliers.any()
    assert spectral.cell_hausdorff([]).shape == (0, 0)
    img = np.ones((40, 40), np.float32)
    candidates, _ = search_similarity(img, np.zeros((40, 40), bool), img, np.ones((40, 40), bool))
    assert all(c["z"] == -np.inf for c in candidates)
    tx, rx, pk = dense_matches(img, np.ones((40, 40), bool), img, np.ones((40, 40), bool), np.eye(2, 3))
    assert len(tx) == len(rx) == len(pk) == 0


def test_triplet_clustering_finds_the_transform_among_outliers():
    rng = np.random.default_rng(2)
    src = rng.uniform(0, 500, (30, 2))
    true = np.array([[0.95, -0.2, 30.0], [0.2, 0.95, -12.0]])
    dst = apply(true, src) + rng.normal(0, 0.5, src.shape)
    bad = rng.random(30) < 0.6
    dst[bad] = rng.uniform(0, 500, (bad.sum(), 2))
    affine, inliers = triplets.triplet_clustering(src, dst, radius_px=8.0, inlier_px=3.0)
    assert np.array_equal(inliers, ~bad)
    assert np.abs(apply(affine, src[~bad]) - apply(true, src[~bad])).max() < 2.0



def test_faithful_pipeline_matches_intersections_mutually_and_registers_or_says_why(tmp_path, shared):
    from hamta.core.errors import InsufficientMatchesError
    from hamta.core.io.raster import open_raster, resolve_bands
    from hamta.core.io.working import prepare_working_images
    from hamta.core.progress import Monitor

    case = build_case(CaseSpec("pairs", "sar_optical", {"pair": "sar_optical"}), str(tmp_path), 0,
                      str(shared / "data"))
    ti, ri = open_raster(case.target, "target"), open_raster(case.reference, "reference")
    tgt, ref, _ = prepare_working_images(ti, ri, target_bands=resolve_bands(ti, None),
                                         reference_bands=resolve_bands(ri, None), max_pixels=4_000_000)
    m = match_lines(tgt, ref, LinesParams(), Monitor())
    info = m.diagnostics
    assert info["target"]["lines"] >= 10 and info["reference"]["intersections"] >= len(m) >= 3
    assert len(np.unique(m.target_xy, axis=0)) == len(m) == len(np.unique(m.reference_xy, axis=0))
    for method in ("lines-spectral-faithful", "lines-eigen", "lines-vspm"):
        try:
            options = RegisterOptions(pixel_mode=True)
            assert register(case.target, case.reference, method, options=options).stats.n_gcps >= 5
        except InsufficientMatchesError as exc:  # the usual outcome: the thesis's lines rarely repeat
            assert "agree on one affine transform" in str(exc) and len(exc.correspondences) >= 3


def test_triplet_robust_option_registers_sift_matches(tmp_path, shared):
    spec = CaseSpec("rotation", "landsat_rot30_none", {"source": "landsat", "angle": 30, "radiometry": "none"})
    case = build_case(spec, str(tmp_path), 400, str(shared / "data"))
    result = register(case.target, case.reference, "sift", options=RegisterOptions(robust="triplets", refine="off"))
    assert np.sqrt(np.mean(case.errors(result.model) ** 2)) < 0.5
