"""The sheet's own grid, its parts: crossings to a fraction of a pixel, the lattice judged against the sheet's
own background, the steps a grid may have, the plane a graticule is drawn in, the check's model and verdict."""
import math

import numpy as np
import pytest
from pyproj import CRS

from hamta.core.errors import InputError
from hamta.core.grid.check import judge
from hamta.core.grid.lines import crossing
from hamta.core.grid.scan import LineSource
from hamta.core.grid.sheet import NoGridFound, fit_sheet
from hamta.core.grid.steps import degree_steps, describe, describe_pair, hint_steps, linear_steps

STEP_M = 1000.0
UTM = CRS.from_user_input("EPSG:32633")


def _sheet(angle_deg=12.0, spacing_px=80.0, size=(700, 900), seed=0, grid=True):
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
    for i in range(-8, 9) if grid else ():
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


def _hints(to_px, grid, seed=1, noise=4.0):
    rng = np.random.default_rng(seed)
    grid = np.asarray(grid, float)
    return np.column_stack([to_px(grid) + rng.uniform(-noise, noise, (len(grid), 2)), grid])


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
    grid = [[499000.0, 6001000.0], [502000.0, 5999000.0], [500000.0, 5998000.0]][:hints]
    fit = fit_sheet(grey, _hints(to_px, grid), UTM)
    errors = np.hypot(*(fit.crossings[:, :2] - to_px(fit.crossings[:, 4:6])).T)
    assert len(fit.crossings) >= 40 and np.median(errors) < 0.3 and errors.max() < 1.0, (len(fit.crossings),
                                                                                         errors.max())
    assert tuple(fit.step) == (STEP_M, STEP_M) and fit.evidence.printed
    frame_px = (fit.crossings[:, 4:6] - [490000.0, 6010000.0]) * [0.08, -0.08]  # a frame of 12.5 m px
    kind, check = judge(fit, frame_px, 1.0, None, 2.0, None, 0.0)
    assert check.verified and check.held_out_scan_px < 0.5 and kind == "affine", (kind, check.reasons)


def test_a_sheet_without_a_grid_is_refused_naming_the_lattices_tried():
    grey, to_px = _sheet(grid=False)
    with pytest.raises(NoGridFound, match="No printed grid was found") as caught:
        fit_sheet(grey, _hints(to_px, [[499000.0, 6001000.0], [502000.0, 5999000.0]]), UTM)
    assert caught.value.tried and all(not a.evidence.printed for a in caught.value.tried if a.evidence)


def test_a_hint_typed_one_step_off_is_named():
    grey, to_px = _sheet()
    rows = _hints(to_px, [[499000.0, 6001000.0], [502000.0, 5999000.0], [500000.0, 5998000.0]])
    rows[2, 2] += STEP_M
    with pytest.raises(InputError, match="hint 3|No printed grid|too few to place the sheet"):
        fit_sheet(grey, rows, UTM)


def test_the_steps_are_the_usual_ones_in_any_unit_largest_first_and_a_stray_one_is_refused():
    assert hint_steps(np.array([150.0, 152.0]), True, 10)[:3] == [2.0, 1.0, 0.5]
    assert hint_steps(np.array([-156.99583333, -156.99166667]), True, 10)[0] == pytest.approx(15 / 3600)
    assert hint_steps(np.array([502000.0, 504000.0]), False, 10) == [2000.0, 1000.0, 500.0, 250.0, 200.0]
    assert 9144.0 not in linear_steps() and 10000.0 in linear_steps()  # 10 000 yards: in a CRS counting yards
    assert 7.5 / 60 in degree_steps() and 0.5 / 60 in degree_steps()
    with pytest.raises(InputError, match="usual step"):
        hint_steps(np.array([501234.5]), False, 10)
    assert describe(2 / 60, True) == "2'" and describe(15 / 3600, True) == '15"' and describe(5, True) == "5°"
    assert describe_pair((0.5, 1.0), True) == "30' x 1°" and describe_pair((1000, 1000), False) == "1000"


def test_a_graticule_is_found_drawn_in_the_projection_it_was_drawn_in():
    """Degrees of a Lambert conic chart: its meridians converge; a plane that converges them (a cone, or the
    transverse Mercator and polyconic planes, alike over a sheet) fits them straight, Mercator does not."""
    import cv2
    from pyproj import Transformer

    lcc = "+proj=lcc +lat_1=47.5 +lat_2=49.5 +lat_0=48.5 +lon_0=-92 +ellps=GRS80"
    to_lcc = Transformer.from_crs("EPSG:4269", lcc, always_xy=True)
    scale = 1 / 120.0  # metres of the plane per scan px
    h, w = 1300, 1400
    centre = np.array(to_lcc.transform(-92.0, 48.5))

    def to_px(g):
        x, y = to_lcc.transform(*np.atleast_2d(g).T)
        x, y = (np.asarray(x) - centre[0]) * scale + w / 2, (centre[1] - np.asarray(y)) * scale + h / 2
        return np.column_stack([x, y])

    big = np.full((h * 2, w * 2), 235, np.uint8)
    for v in np.arange(-95.0, -88.9, 0.5):
        t = np.linspace(46.0, 51.0, 200)
        cv2.polylines(big, [np.round(to_px(np.column_stack([np.full_like(t, v), t])) * 2).astype(np.int32)], False,
                      60, 3, cv2.LINE_AA)
    for v in np.arange(46.0, 51.1, 0.5):
        t = np.linspace(-95.0, -89.0, 200)
        cv2.polylines(big, [np.round(to_px(np.column_stack([t, np.full_like(t, v)])) * 2).astype(np.int32)], False,
                      60, 3, cv2.LINE_AA)
    grey = cv2.resize(big, (w, h), interpolation=cv2.INTER_AREA)
    grid = np.array([[-93.0, 49.0], [-91.5, 48.5]])
    fit = fit_sheet(grey, np.column_stack([to_px(grid), grid]), CRS.from_user_input("EPSG:4269"))
    assert fit.plane.name != "Mercator" and fit.plane_fits[fit.plane.name] < 1.0, fit.plane_fits
    assert fit.plane_fits["Mercator"] > 3 * fit.plane_fits["Lambert conformal conic"]


def test_a_grid_line_shifted_as_a_whole_is_left_out_and_the_others_kept():
    """A line of the map's frame taken for a grid line: its crossings fit the others one by one but not as a
    line; it alone goes (and the search ends)."""
    from hamta.core.grid.crossings import without_stray_lines

    gx, gy = np.meshgrid(np.arange(8) * 1000.0, np.arange(7) * 1000.0)
    grid = np.column_stack([gx.ravel(), gy.ravel()])
    scan = grid @ np.array([[0.2, 0.01], [-0.01, -0.2]]) + [100.0, 1500.0]
    scan[grid[:, 0] == 3000.0] += [6.0, 0.0]
    found = np.column_stack([scan, grid, grid])  # scan x, y, plane x, y, grid x, y
    kept = without_stray_lines(found, 1)
    assert len(kept) == len(found) - 7 and not (kept[:, 4] == 3000.0).any()
