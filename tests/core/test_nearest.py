"""Nearest-neighbour descriptor matching: the two nearest by L2, and the ratio test with its cross-checks."""
import numpy as np
import pytest

from hamta.core.matching.nearest import _two_nearest_l2, match_features, self_similar
from hamta.core.types import Features, Keypoints


def _features(d):
    n = len(d)
    return Features(Keypoints(np.zeros((n, 2)), np.ones(n), np.zeros(n), np.zeros(n)), d.astype(np.float32), "l2")


@pytest.mark.parametrize("block_values", [300, 1 << 22])
def test_two_nearest_are_the_brute_force_ones_with_exact_distances(block_values):
    rng = np.random.default_rng(11)
    q, t = rng.random((70, 128)).astype(np.float32), rng.random((90, 128)).astype(np.float32)
    full = np.sqrt(((q[:, None, :].astype(np.float64) - t[None].astype(np.float64)) ** 2).sum(axis=2))
    order = np.argsort(full, axis=1)[:, :2]
    dist, idx = _two_nearest_l2(q, t, block_values=block_values)
    assert np.array_equal(idx, order)
    assert np.array_equal(dist, np.take_along_axis(full, order, 1))


def test_ratio_and_mutual_checks_keep_only_distinct_correspondences():
    rng = np.random.default_rng(12)
    b = rng.random((40, 128))
    a = b[:30] + rng.normal(0, 0.01, (30, 128))
    a[25:] = rng.random((5, 128))  # five with no counterpart
    ia, ib, score = match_features(_features(a), _features(b), ratio=0.8)
    assert np.array_equal(ia, np.arange(25)) and np.array_equal(ib, np.arange(25))
    assert (score > 0.2).all()


def test_exact_duplicates_are_self_similar():
    rng = np.random.default_rng(13)
    d = rng.random((20, 128))
    d[7] = d[3]
    assert np.flatnonzero(self_similar(_features(d), 0.1)).tolist() == [3, 7]
