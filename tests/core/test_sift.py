import numpy as np

from hamta.core.descriptors.sift import sift_features
from hamta.core.io.raster import open_raster, read_image, resolve_bands
from hamta.core.matching.nearest import match_features
from hamta.core.preprocess.normalize import detection_mask, stretch_to_uint8


def _grey(landsat):
    info = open_raster(landsat)
    img, valid = read_image(info, resolve_bands(info, None))
    return stretch_to_uint8(img, valid)[100:600, 150:650]


def test_sift_keypoints_are_unbiased_in_the_corner_convention(landsat):
    img = _grey(landsat)
    h, w = img.shape
    rot = img[::-1, ::-1].copy()  # 180 degrees: corner coordinates map x -> w - x, y -> h - y
    full = np.full(img.shape, 255, np.uint8)
    a, b = sift_features(img, full), sift_features(rot, full)
    ia, ib, _ = match_features(a, b, ratio=0.7)
    err = b.keypoints.xy[ib] - (np.array([w, h]) - a.keypoints.xy[ia])
    err = err[np.linalg.norm(err, axis=1) < 2]
    assert len(err) > 500
    assert np.abs(np.median(err, axis=0)).max() < 0.05  # OpenCV alone is off by 0.5 px here


def test_features_carry_their_metric_and_mutual_matching_is_one_to_one(landsat):
    img = _grey(landsat)
    f = sift_features(img, detection_mask(np.ones(img.shape, bool)))
    assert f.metric == "l2" and f.descriptors.shape == (len(f), 128)
    ia, ib, score = match_features(f, f, ratio=1.0, cross_check="mutual")
    assert len(np.unique(ib)) == len(ib) and (score >= 0).all()
