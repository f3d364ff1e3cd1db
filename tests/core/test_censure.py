"""CenSurE with octagon filters (Agrawal et al. 2008) as spec 000 uses it."""
import cv2
import numpy as np
import pytest

from hamta.core.detectors.censure import (
    OCTAGONS,
    CensureDetector,
    OctagonSums,
    censure_keypoints,
    censure_responses,
    octagon_area,
    octagon_mask,
)


def test_filter_bank_is_table_1_of_the_paper():
    inner = [o[0] for o in OCTAGONS]
    outer = [o[1] for o in OCTAGONS]
    assert inner == [(3, 0), (3, 1), (3, 2), (5, 2), (5, 3), (5, 4), (5, 5)]
    assert outer == [(5, 2), (5, 3), (7, 3), (9, 4), (9, 7), (13, 7), (15, 10)]


def test_octagon_geometry():
    assert octagon_mask(3, 0).all() and octagon_mask(3, 0).shape == (3, 3)
    m = octagon_mask(5, 2)
    assert m.shape == (9, 9) and m[0].sum() == 5 and m[1].sum() == 7 and m[4].sum() == 9
    assert np.array_equal(m, m.T) and np.array_equal(m, m[::-1])
    assert all(octagon_area(*o) == octagon_mask(*o).sum() for pair in OCTAGONS for o in pair)


@pytest.mark.parametrize("m,n", sorted({o for pair in OCTAGONS for o in pair}))
def test_constant_time_octagon_sums_equal_direct_convolution(m, n):
    img = np.random.default_rng(m * 100 + n).random((57, 63))
    direct = cv2.filter2D(img, -1, octagon_mask(m, n).astype(np.float64), borderType=cv2.BORDER_REFLECT_101)
    assert np.allclose(OctagonSums(img, 19).octagon(m, n), direct, atol=1e-9)


def test_bright_blob_is_found_at_its_centre_and_scale():
    img = np.zeros((120, 120), np.float32)
    cv2.circle(img, (60, 60), 6, 200, -1)  # disk of radius 6 centred on pixel (60, 60)
    kp, scale = censure_keypoints(img, np.ones(img.shape, bool), CensureDetector(n_features=5))
    assert np.allclose(kp.xy[0], (60.5, 60.5), atol=0.5) and kp.response[0] > 0
    responses = censure_responses(img)[:, 60, 60]
    assert scale[0] == int(np.argmax(responses)) and scale[0] >= 3


def test_edges_are_rejected_by_the_line_test():
    img = np.zeros((100, 100), np.float32)
    img[:, 50:] = 200  # one straight edge, no corner
    kp, _ = censure_keypoints(img, np.ones(img.shape, bool), CensureDetector())
    assert len(kp) == 0


def test_keypoints_respect_the_mask_and_count(landsat):
    from hamta.core.io.raster import open_raster, read_image, resolve_bands
    from hamta.core.preprocess.normalize import stretch_to_uint8

    info = open_raster(landsat)
    img, valid = read_image(info, resolve_bands(info, None))
    kp, scale = censure_keypoints(stretch_to_uint8(img, valid).astype(np.float32), valid, CensureDetector())
    assert len(kp) == 2500 and set(np.unique(scale)) <= set(range(7))
    ix = kp.xy.astype(int)
    assert valid[ix[:, 1], ix[:, 0]].all()
    assert np.all(np.diff(np.abs(kp.response)) <= 1e-6)  # strongest first
