"""The structure search finds a target anywhere in an area, at any turn and scale, through a change of
contrast; and a search registers each distinct pose once (:mod:`hamta.core.matching.structure`)."""
import math

import numpy as np
import pytest
from affine import Affine

from hamta.core.io.raster import open_raster, read_image
from hamta.core.matching.places import seen, structure_sides
from hamta.core.matching.structure import structure_places

from ..conftest import turned_window


@pytest.fixture(scope="module")
def area(landsat):
    return read_image(open_raster(landsat, "reference"), (1, 2, 3))


@pytest.mark.split
@pytest.mark.parametrize("angle, magnified", [(35.0, 2.5), (-150.0, 1.6), (100.0, 3.2)])
def test_a_turned_rescaled_target_of_inverted_contrast_is_found_first(area, angle, magnified):
    image, valid = area
    side = 384
    target, truth = turned_window(image, (430.0, 380.0), side, magnified, angle)
    target = 255.0 - 255.0 * (target / 255.0) ** 0.6  # another date, another sensor: contrast inverted and bent
    sides = structure_sides(max(image.shape), None)
    found = structure_places(target.astype(np.float32), np.ones(target.shape, bool), image, valid, sides)
    assert found
    corners = np.array([[0, 0], [side, 0], [side, side], [0, side]], float)
    error = np.hypot(*(found[0].apply(corners) - (corners @ truth[:, :2].T + truth[:, 2])).T)
    footprint = side / magnified
    assert error.max() < 0.1 * footprint, (error, found[0])
    assert abs(math.log(found[0].scale * magnified)) < 0.12


def test_sides_the_area_cannot_hold_give_no_place(area):
    image, valid = area
    target = np.full((300, 300), 100.0, np.float32)
    assert structure_places(target, np.ones(target.shape, bool), image, valid, (200.0, 100.0)) == []
    assert structure_places(target, np.ones(target.shape, bool), image, valid, (5000.0, 6000.0)) == []


def test_each_zoom_correlates_the_sides_the_coarser_ones_left_out():
    low, high = structure_sides(1024.0, None)
    assert high == pytest.approx(1024.0 / 1.5) and low < high / 4
    assert structure_sides(2048.0, 2.0) == (low, 2 * low)  # a target below `low` there is twice that here


def test_a_place_seen_again_is_the_same_pose_not_only_the_same_centre():
    first = Affine.translation(1000.0, 2000.0) * Affine.scale(2.0, -2.0)
    assert seen(Affine.translation(1010.0, 2000.0) * Affine.scale(2.1, -2.1), 300, 200, [first])
    assert not seen(Affine.translation(1000.0, 2000.0) * Affine.scale(3.0, -3.0), 300, 200, [first])  # another scale
    turned = Affine.translation(1000.0, 2000.0) * Affine.rotation(40.0) * Affine.scale(2.0, -2.0)
    assert not seen(turned, 300, 200, [first])
    assert not seen(Affine.translation(1400.0, 2000.0) * Affine.scale(2.0, -2.0), 300, 200, [first])
