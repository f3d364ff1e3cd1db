"""Where a target may be in a search area: the places SIFT's and (with the 'learned' extra) XFeat's
features vote for (:mod:`hamta.core.matching.locate`), in the order a search registers them.

Pixels: target working pixels (the target read with its longer side at :data:`TARGET_SIDE`) and area
working pixels, corner convention.
"""
from __future__ import annotations

from itertools import zip_longest

from ..descriptors import xfeat
from ..io.raster import read_image, resolve_bands
from .locate import features, learned_locate, locate

MIN_INLIERS = 4  # agreeing features for a place to be registered there: the least a similarity fit can be
# told from chance with, since the independent check of the registration decides, not the count
CANDIDATES = 3  # places registered per zoom, most agreeing features first
STRONG_INLIERS = 8  # places with fewer agreeing features are registered after the whole area (at the first zoom
# searched: areas a few times the target's size, whose features are too few to vote, are found that way faster)
TARGET_SIDE = 384  # px: the target's longer side when it is located: at this size, the shapes that last (field
# boundaries, roads, shores) outweigh what changes between dates (crops, water levels); 768 px found less on the
# basemap-real family
LEARNED_TURNS_DEG = tuple(range(0, 360, 45))  # XFeat is upright: the target turned every 45 degrees (its matches
# hold to about 25 degrees either way) ...
LEARNED_SCALES = (1.0, 0.667, 0.444, 0.333)  # ... and scaled: its features hold across about a factor of 1.5
LEARNED_MIN_INLIERS = 8  # XFeat's mutual neighbours over 32 turns and scales of the target gather 5 or so on
# chance places, where SIFT's ratio-tested votes rarely reach 4
LEARNED_STRONG_INLIERS = 16  # XFeat places registered before the whole area (right places: 9-45, the best wrong
# ones up to 23 on the basemap-real family's areas)
LEARNED_TARGET_K = 1024  # strongest XFeat keypoints of each turned target (384 px) and of each 1024 px block of an area
LEARNED_AREA_K = 2048


def target_features(info, band):
    """The target's locating features: (keypoints, descriptors, working shape) and working px per target px."""
    per_px = min(1.0, TARGET_SIDE / max(info.width, info.height))
    shape = (max(1, round(info.height * per_px)), max(1, round(info.width * per_px)))
    image, valid = read_image(info, resolve_bands(info, band), None, shape)
    per_px = shape[1] / info.width
    return (*features(image, valid), shape), per_px


def learned_target_features(shape, info, band):
    """A function giving the target's XFeat features at each turn and scale of :data:`LEARNED_TURNS_DEG` and
    :data:`LEARNED_SCALES` (computed on first use: most searches SIFT settles), or None without the extra."""
    if not xfeat.available():
        return None
    cache = []

    def turned():
        if not cache:
            image, valid = read_image(info, resolve_bands(info, band), None, shape)
            cache.extend(xfeat.turned_features(image, valid, a, s, LEARNED_TARGET_K) for s in LEARNED_SCALES
                         for a in LEARNED_TURNS_DEG)
        return cache
    return turned


def candidates(target, learned, image, valid, whole: bool):
    """Where to register, in order, as (what found it, :class:`Candidate`), the whole area as (None, None):
    SIFT's places with :data:`STRONG_INLIERS`; then, with the 'learned' extra, XFeat's with
    :data:`LEARNED_STRONG_INLIERS`; the whole area (when ``whole``); then the weaker places, the best of each
    first. Lazy: XFeat runs only when SIFT's strong places did not verify."""
    sift = [c for c in locate(target[0], target[1], *features(image, valid), target[2])
            if c.inliers >= MIN_INLIERS][:CANDIDATES]
    yield from (("SIFT", c) for c in sift if c.inliers >= STRONG_INLIERS)
    xf = []
    if learned is not None:
        area = xfeat.features(image, valid, LEARNED_AREA_K, block=1024)
        xf = [c for c in learned_locate(learned(), area, target[2]) if c.inliers >= LEARNED_MIN_INLIERS][:CANDIDATES]
        yield from (("XFeat", c) for c in xf if c.inliers >= LEARNED_STRONG_INLIERS)
    if whole:
        yield None, None
    weak = [[("SIFT", c) for c in sift if c.inliers < STRONG_INLIERS],
            [("XFeat", c) for c in xf if c.inliers < LEARNED_STRONG_INLIERS]]
    yield from (step for rank in zip_longest(*weak) for step in rank if step is not None)
