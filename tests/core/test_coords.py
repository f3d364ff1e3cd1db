import numpy as np
from affine import Affine

from hamta.core.coords import (
    apply_matrix,
    corner_to_opencv,
    map_to_pixel,
    matrix_corner_to_opencv,
    opencv_to_corner,
    pixel_to_map,
    xy_bounds,
)


def test_opencv_and_corner_conventions_differ_by_half_a_pixel():
    assert np.allclose(opencv_to_corner([[0, 0]]), [[0.5, 0.5]])
    assert np.allclose(corner_to_opencv(opencv_to_corner([[3.25, 7.5]])), [[3.25, 7.5]])


def test_matrix_conversion_matches_point_conversion():
    h = np.array([[0.9, -0.3, 12.0], [0.25, 1.1, -4.0], [1e-4, 2e-4, 1.0]])
    p = np.array([[10.0, 20.0], [300.5, 7.25]])
    via_points = corner_to_opencv(apply_matrix(h, opencv_to_corner(p)))
    assert np.allclose(apply_matrix(matrix_corner_to_opencv(h), p), via_points)


def test_pixel_map_round_trip_uses_corner_origin():
    t = Affine(10, 0, 500000, 0, -10, 4000000)
    assert np.allclose(pixel_to_map(t, [[0, 0]]), [[500000, 4000000]])
    assert np.allclose(pixel_to_map(t, [[0.5, 0.5]]), [[500005, 3999995]])
    xy = np.array([[12.3, 45.6]])
    assert np.allclose(map_to_pixel(t, pixel_to_map(t, xy)), xy)


def test_xy_bounds_are_the_lowest_and_highest_of_each_column():
    xy = np.random.default_rng(3).normal(0, 500, (1001, 2))
    xy[17] = [np.nextafter(xy[:, 0].min(), -np.inf), 1e9]
    lo, hi = xy_bounds(xy)
    assert np.array_equal(lo, xy.min(axis=0)) and np.array_equal(hi, xy.max(axis=0))
    assert np.array_equal(xy_bounds([[3.0, -2.0]])[0], [3.0, -2.0])
