"""The sheet's own grid (issue 56, first round: the core, not yet a method): printed crossings found to a
fraction of a pixel from a few hints on a synthetic sheet whose truth is exact."""
import math

import numpy as np
import pytest

from hamta.core.errors import InputError
from hamta.core.grid.lines import crossing
from hamta.core.grid.scan import LineSource
from hamta.core.grid.sheet import fit_sheet, grid_steps

STEP_M = 1000.0


def _sheet(angle_deg=12.0, spacing_px=80.0, size=(700, 900), seed=0):
    """A scan of a 1 km grid turned ``angle_deg``: thin dark lines on paper, map lines drawn across it, noise
    and JPEG. Returns the grey image and the truth: grid coordinates (metres) -> scan px."""
    import cv2

    rng = np.random.default_rng(seed)
    h, w = size
    a = math.radians(angle_deg)
    rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]) * spacing_px / STEP_M
    origin = np.array([w / 2, h / 2]) - rot @ (np.array([500000.0, 6000000.0]) * np.array([1.0, -1.0]))

    def to_px(xy):
        xy = np.atleast_2d(xy) * np.array([1.0, -1.0])
        return xy @ rot.T + origin

    image = np.full((h * 4, w * 4), 235, np.uint8)
    for i in range(-8, 9):
        for axis in (0, 1):
            ends = np.array([[500000.0 + i * STEP_M, 6000000.0 - 9 * STEP_M], [500000.0 + i * STEP_M,
                                                                               6000000.0 + 9 * STEP_M]])
            if axis:
                ends = np.array([[500000.0 - 9 * STEP_M, 6000000.0 + i * STEP_M], [500000.0 + 9 * STEP_M,
                                                                                   6000000.0 + i * STEP_M]])
            p = to_px(ends) * 4
            cv2.line(image, tuple(int(v) for v in p[0]), tuple(int(v) for v in p[1]), 70, 6, cv2.LINE_AA)
    for _ in range(40):  # roads and rivers: lines at any angle
        p = rng.uniform(0, 4 * min(h, w), (2, 2)) + rng.uniform(0, 4 * abs(w - h), 2) * [1, 0]
        cv2.line(image, tuple(int(v) for v in p[0]), tuple(int(v) for v in p[1]), int(rng.integers(40, 120)), 5)
    image = cv2.resize(image, (w, h), interpolation=cv2.INTER_AREA).astype(float)
    image += rng.normal(0, 6, image.shape)
    _, jpeg = cv2.imencode(".jpg", np.clip(image, 0, 255).astype(np.uint8), [cv2.IMWRITE_JPEG_QUALITY, 80])
    return cv2.imdecode(jpeg, cv2.IMREAD_GRAYSCALE), to_px


def test_a_crossing_is_found_to_a_fraction_of_a_pixel_from_a_point_near_it():
    grey, to_px = _sheet()
    node = np.array([501000.0, 6001000.0])
    px = to_px(node)[0]
    d1 = to_px(node + [0, 10])[0] - px
    d2 = to_px(node + [10, 0])[0] - px
    directions = [d1 / np.hypot(*d1), d2 / np.hypot(*d2)]
    got = crossing(LineSource.from_array(grey), px + [2.5, -2.0], directions, 6.0, along=30)
    assert got is not None and np.hypot(*(np.array(got.xy) - px)) < 0.3, (got, px)


@pytest.mark.parametrize("hints", [3, 2])
def test_hints_placed_roughly_find_every_crossing_of_the_sheet(hints):
    grey, to_px = _sheet()
    rng = np.random.default_rng(1)
    grid = np.array([[499000.0, 6001000.0], [502000.0, 5999000.0], [500000.0, 5998000.0]])[:hints]
    rows = np.column_stack([to_px(grid) + rng.uniform(-4, 4, (hints, 2)), grid])
    fit = fit_sheet(grey, rows, "EPSG:32633")
    errors = np.hypot(*(fit.gcps[:, :2] - to_px(fit.gcps[:, 4:6])).T)
    assert len(fit.gcps) >= 40 and np.median(errors) < 0.3 and errors.max() < 1.0, (len(fit.gcps), errors.max())
    assert fit.verified and fit.step == STEP_M and fit.loo_px < 0.5, fit.notes


def test_the_grid_steps_are_the_usual_steps_the_hints_fit_largest_first_and_a_stray_one_is_refused():
    assert grid_steps(np.array([[150.0, -30.0], [152.0, -33.0]]), (10, 5, 2, 1, 0.5)) == [1, 0.5]
    assert grid_steps(np.array([[502000.0, 6000000.0], [504000.0, 6004000.0]]), (10000, 5000, 2000, 1000)) == [2000,
                                                                                                             1000]
    with pytest.raises(InputError, match="usual step"):
        grid_steps(np.array([[501234.5, 6000000.0]]), (10000, 5000, 2000, 1000, 500, 200, 100))


def test_a_grid_line_shifted_as_a_whole_is_left_out_and_the_others_kept():
    """A line of the map's frame taken for a grid line: its crossings fit the others one by one but not as a
    line; it alone goes (and the search ends)."""
    from hamta.core.grid.crossings import without_stray_lines

    gx, gy = np.meshgrid(np.arange(8) * 1000.0, np.arange(7) * 1000.0)
    grid = np.column_stack([gx.ravel(), gy.ravel()])
    scan = grid @ np.array([[0.2, 0.01], [-0.01, -0.2]]) + [100.0, 1500.0]
    scan[grid[:, 0] == 3000.0] += [6.0, 0.0]
    found = np.column_stack([scan, grid, grid])  # scan x, y, crs x, y, grid x, y
    kept = without_stray_lines(found, 1)
    assert len(kept) == len(found) - 7 and not (kept[:, 4] == 3000.0).any()
