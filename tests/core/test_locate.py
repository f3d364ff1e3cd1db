"""Locating a small target in a large search area (:mod:`hamta.core.matching.locate`), and a layer's
finest zoom found when a tile template does not say it."""

import math

import hypothesis.strategies as st
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis.extra.numpy import arrays

from hamta.bench.synthetic import make_landscape
from hamta.bench.tileserver import TileServer
from hamta.core.basemap.areas import AreaReader
from hamta.core.basemap.fetch import Fetcher
from hamta.core.basemap.services import parse_service
from hamta.core.basemap.tiles import NoTiles
from hamta.core.matching.locate import Candidate, features, locate
from tests.conftest import grey, turned_window


@pytest.mark.split
@pytest.mark.parametrize("angle, scale", [(0.0, 1.0), (37.0, 2.0), (-150.0, 0.7)])
def test_a_turned_rescaled_target_is_found_in_an_area_16_times_its_size(angle, scale):
    area = grey(make_landscape((1600, 1600), seed=3))
    side = 400
    centre = (1100.0, 450.0)
    target, truth = turned_window(area, centre, side, scale, angle)
    found = locate(*features(target, np.ones(target.shape, bool)), *features(area, np.ones(area.shape, bool)),
                   target.shape)
    assert found, "no candidate"
    best = found[0]
    corners = np.array([[0, 0], [side, 0], [side, side], [0, side]], float)
    error = np.hypot(*(best.apply(corners) - (corners @ truth[:, :2].T + truth[:, 2])).T)
    assert error.max() < 2.0, (error, best)  # area px: a candidate is where to look, not yet the result
    assert best.inliers >= 20 and abs(best.scale - 1 / scale) < 0.02 / scale


def test_unrelated_images_give_no_strong_candidate():
    area = grey(make_landscape((1200, 1200), seed=3))
    other = grey(make_landscape((400, 400), seed=11))
    found = locate(*features(other, np.ones(other.shape, bool)), *features(area, np.ones(area.shape, bool)),
                   other.shape)
    assert all(c.inliers < 6 for c in found), found  # places.MIN_INLIERS: none would be registered


def test_features_of_a_large_area_are_detected_block_by_block_like_the_whole():
    """Blocks with a margin find the keypoints a whole-image detection finds (the same scale space inside)."""
    from scipy.spatial import cKDTree

    area = grey(make_landscape((1100, 1000), seed=5))
    valid = np.ones(area.shape, bool)
    whole, _ = features(area, valid, per_block=100_000, block=4096)
    blocks, _ = features(area, valid, per_block=100_000, block=512)
    inner = (whole.xy > 60).all(axis=1) & (whole.xy < np.array([940, 1040])).all(axis=1)
    distance, _ = cKDTree(blocks.xy).query(whole.xy[inner])
    assert (distance < 0.5).mean() > 0.9, (distance < 0.5).mean()


def test_a_layer_s_finest_zoom_is_found_below_the_zoom_asked(landsat, tmp_path):
    """A plain template does not say its finest zoom: an area whose tiles are all missing at zoom 14 is
    read at 12, the server's finest, and later reads stop there; an area outside the layer stays an error."""
    with TileServer(landsat, zmax=12) as server:
        service = parse_service(server.xyz())
        reader = AreaReader(service, Fetcher(cache=str(tmp_path / "cache")), 400)
        bounds = (-8.68e6, 2.80e6, -8.66e6, 2.82e6)  # inside the Landsat sample, EPSG:3857
        reader.read(bounds, 14, None)
        reader.read(bounds, 13, None)
        assert reader.zooms == [12, 12]
        with pytest.raises(NoTiles, match="no data"):
            reader.read((1.0e6, 1.0e6, 1.02e6, 1.02e6), 11, None)


def test_a_place_found_stands_in_for_the_target_s_georeferencing(landsat, tmp_path):
    """``register(placed=...)``: a target without georeferencing, placed 6 px and 1 degree off where it is,
    is registered from there like a georeferenced one (the shift first) and keeps its own description."""
    import rasterio
    from affine import Affine

    from hamta.bench.goals.basemap import rotated_target
    from hamta.core.coords import map_to_pixel
    from hamta.core.pipeline import register

    case = rotated_target(landsat, str(tmp_path / "target.tif"), (300.0, 300.0), (320, 420), 2.0, 15.0)
    with rasterio.open(landsat) as ds:
        transform, crs = ds.transform, ds.crs
    from pyproj import Transformer

    back = Transformer.from_crs("EPSG:3857", crs, always_xy=True)
    corners = np.array([[0.0, 0.0], [420.0, 0.0], [0.0, 320.0]])
    true_map = np.column_stack(back.transform(*case.truth(corners).T))
    (x0, y0), (x1, y1), (x2, y2) = true_map
    truth = Affine((x1 - x0) / 420, (x2 - x0) / 320, x0, (y1 - y0) / 420, (y2 - y0) / 320, y0)
    off = Affine.translation(6 * transform.a, -4 * transform.a) * Affine.rotation(1.0, pivot=(x0, y0))
    result = register(case.path, landsat, placed=off * truth)
    assert result.verified, result.notes
    grid = case.grid()
    expected = map_to_pixel(transform, np.column_stack(back.transform(*case.truth(grid).T)))
    assert np.abs(result.model.apply(grid) - expected).max() < 0.5
    assert not result.target.georeferenced and result.plan.mode == "search"
    assert result.auto.attempts[0].method == "shift"


def test_a_search_holds_each_candidate_to_its_share_of_one_checks_risk(demo_pair):
    """A check verified at one of the search's candidates stands only when its agreement would be
    SEARCH_TRIES times as unlikely by chance; else it is 'suspect', saying why."""
    import dataclasses

    from hamta.core import register
    from hamta.core.remote_places import SEARCH_TRIES, held_to_the_search

    result = register(demo_pair["target"], demo_pair["reference"], "sift")
    v = dataclasses.replace(result.verification, look="grid", z_chance=1.0, z_mw=1.0)
    assert result.verified
    single = dataclasses.replace(result, verification=dataclasses.replace(v, chance=1e-5 / SEARCH_TRIES * 2))
    held = held_to_the_search(single)
    assert held.verification.verdict == "suspect" and "checked up to" in held.verification.reasons[-1]
    strong = dataclasses.replace(result, verification=dataclasses.replace(v, chance=1e-5 / SEARCH_TRIES / 2))
    assert held_to_the_search(strong) is strong
    by_shape = dataclasses.replace(v, chance=1.0, z_chance=1e-6 / SEARCH_TRIES / 1.5, z_mw=1e-3 / SEARCH_TRIES / 1.5)
    assert held_to_the_search(dataclasses.replace(result, verification=by_shape)).verified
    second_look = dataclasses.replace(by_shape, look="structure")  # held to half the levels: not enough now
    assert not held_to_the_search(dataclasses.replace(result, verification=second_look)).verified


@settings(max_examples=300, deadline=None, derandomize=True)
@given(arrays(np.float64, (2, 3), elements=st.floats(allow_nan=True, allow_infinity=True, width=64)))
def test_a_placement_is_sound_or_says_why_never_raises(matrix):
    """Any 2 x 3 matrix a locator may make: refused with a reason, or a placement the search's seen-before test
    and zoom choice can use (finite, positive scale)."""
    from affine import Affine

    from hamta.core.matching.places import placement_problem, seen

    problem = placement_problem(Candidate(matrix, 9, 9), (288, 384), (1024, 1024))
    if problem is None:
        placed = Affine(*matrix.ravel()) * Affine.scale(0.5)
        assert math.isfinite(math.log(math.sqrt(abs(placed.determinant))))
        assert seen(placed, 768, 576, [placed])
    else:
        assert problem.startswith("its ")
