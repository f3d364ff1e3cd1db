"""Where a target may be in a search area: the places SIFT's and (with the 'learned' extra) XFeat's
features vote for (:mod:`hamta.core.matching.locate`) and those where the target's structure correlates
best (:mod:`hamta.core.matching.structure`), in the order a search registers them.

Pixels: target working pixels (the target read with its longer side at :data:`TARGET_SIDE`) and area
working pixels, corner convention.
"""
from __future__ import annotations

import math
from itertools import zip_longest
from typing import Optional

import numpy as np

from ..descriptors import xfeat
from ..io.raster import read_image, resolve_bands
from ..learned import available as learned_available
from .locate import features, learned_locate, locate
from .structure import structure_places

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
STRUCTURE_MIN_SIDE = 96  # px: the least target side (in area pixels) its structure is correlated at: 24 cells of 4
STRUCTURE_DISTINCT = 1.2  # a structure place scoring this many times the next one apart is registered before the
STRUCTURE_STRONG = 10.0  # whole area, when it also scores this much (right places scored 12.9-27 and 1.2-2.7 times
# the next on the basemap-real family's areas; the wrong best ones at most 1.19 times, most of them 1.01-1.15)
PLACE_SIDES = (16, 4.0)  # a place's footprint, its longer side: at least 16 area px (fewer hold no features to
# register with) and at most 4 times the area's longer side (a target that large is not in the area)
LEARNED_TARGET_K = 1024  # strongest XFeat keypoints of each turned target (384 px) and of each 1024 px block of an area
LEARNED_AREA_K = 2048


def target_features(info, band):
    """The target's locating features: (keypoints, descriptors, working shape), working px per target px,
    and the (grey image, validity) at that working shape they come from."""
    per_px = min(1.0, TARGET_SIDE / max(info.width, info.height))
    shape = (max(1, round(info.height * per_px)), max(1, round(info.width * per_px)))
    image, valid = read_image(info, resolve_bands(info, band), None, shape)
    per_px = shape[1] / info.width
    return (*features(image, valid), shape), per_px, (image, valid)


def learned_target_features(image, valid):
    """A function giving the XFeat features of the target's working ``image`` at each turn and scale of
    :data:`LEARNED_TURNS_DEG` and :data:`LEARNED_SCALES` (computed on first use: most searches SIFT settles),
    or None without the extra."""
    if not learned_available():
        return None
    cache = []

    def turned():
        if not cache:
            cache.extend(xfeat.turned_features(image, valid, a, s, LEARNED_TARGET_K) for s in LEARNED_SCALES
                         for a in LEARNED_TURNS_DEG)
        return cache
    return turned


def structure_sides(area_side: float, finer_by=None):
    """The target sides (area px) its structure is correlated at in an area of ``area_side`` px: from
    :data:`STRUCTURE_MIN_SIDE` to 2/3 of the area's side at the first zoom searched; at a zoom ``finer_by``
    times finer than the one before, the sides that one left out (below its least side)."""
    if finer_by is None:
        return STRUCTURE_MIN_SIDE, area_side / 1.5
    return STRUCTURE_MIN_SIDE, STRUCTURE_MIN_SIDE * finer_by


def candidates(target, learned, image, valid, whole: bool, structure=None):
    """Where to register, in order, as (what found it, :class:`Candidate`), the whole area as (None, None):
    SIFT's places with :data:`STRONG_INLIERS`; the target's structure's best place where it stands out
    (``structure``: (grey image, validity, (least, most target side in area px)), see
    :func:`hamta.core.matching.structure.structure_places`); then, with the 'learned' extra, XFeat's with
    :data:`LEARNED_STRONG_INLIERS`; the whole area (when ``whole``); then the weaker places, the best of each
    first. Lazy: the structure is correlated only when SIFT's strong places did not verify, XFeat only when
    neither did."""
    def sound(found):
        return [c for c in found if placement_problem(c, target[2], image.shape[:2]) is None]

    sift = sound(c for c in locate(target[0], target[1], *features(image, valid), target[2])
                 if c.inliers >= MIN_INLIERS)[:CANDIDATES]
    yield from (("SIFT", c) for c in sift if c.inliers >= STRONG_INLIERS)
    shaped = sound(structure_places(*structure[:2], image, valid, structure[2])) if structure is not None else []
    strong = [c for i, c in enumerate(shaped) if i == 0 and c.score >= STRUCTURE_STRONG and (
        len(shaped) == 1 or c.score >= STRUCTURE_DISTINCT * shaped[1].score)]
    yield from (("structure", c) for c in strong)
    xf = []
    if learned is not None:
        area = xfeat.features(image, valid, LEARNED_AREA_K, block=1024)
        xf = sound(c for c in learned_locate(learned(), area, target[2])
                   if c.inliers >= LEARNED_MIN_INLIERS)[:CANDIDATES]
        yield from (("XFeat", c) for c in xf if c.inliers >= LEARNED_STRONG_INLIERS)
    if whole:
        yield None, None
    weak = [[("SIFT", c) for c in sift if c.inliers < STRONG_INLIERS],
            [("structure", c) for c in shaped[len(strong):]],
            [("XFeat", c) for c in xf if c.inliers < LEARNED_STRONG_INLIERS]]
    yield from (step for rank in zip_longest(*weak) for step in rank if step is not None)


def placement_problem(c, target_shape, area_shape) -> Optional[str]:
    """Why candidate ``c`` (target working px of ``target_shape`` -> area px of ``area_shape``, both (rows,
    columns)) places nothing, or None: a matrix not finite, flat or mirrored (both spaces have rows running
    down), or a footprint outside :data:`PLACE_SIDES` in size or far outside the area."""
    m = np.asarray(c.matrix, float)
    if m.shape != (2, 3) or not np.isfinite(m).all():
        return "its placement is not a finite 2 x 3 matrix"
    with np.errstate(all="ignore"):
        det = float(np.linalg.det(m[:, :2]))
        columns = float(np.linalg.norm(m[:, 0]) * np.linalg.norm(m[:, 1]))
    if not det > 1e-6 * columns:  # the sine of the angle between the target's axes placed: round-off is no angle
        return "its placement is flat or mirrored"
    side = math.sqrt(det) * max(target_shape)
    least, most = PLACE_SIDES
    if not least <= side <= most * max(area_shape):
        return f"its footprint would be {side:.0f} area px across"
    centre = m @ [target_shape[1] / 2, target_shape[0] / 2, 1.0]
    if np.any(np.abs(centre - np.array(area_shape[::-1]) / 2) > most * max(area_shape)):
        return "its footprint would lie far outside the area"
    return None


def seen(placed, width: int, height: int, places) -> bool:
    """Whether the pose ``placed`` (an Affine, target px -> map) of a ``width`` x ``height`` target is one
    of ``places`` again: its centre within a quarter of its size, its scale within a quarter and its turn
    within 15 degrees (the same place at another scale or turn, as a coarser zoom may see it, is worth
    its own registration)."""
    centre = (width / 2.0, height / 2.0)
    scale = math.sqrt(abs(placed.determinant))
    x, y = placed * centre
    turn = math.atan2(placed.d, placed.a)
    for p in places:
        px, py = p * centre
        turned = abs((math.atan2(p.d, p.a) - turn + math.pi) % (2 * math.pi) - math.pi)
        if (math.hypot(x - px, y - py) < 0.25 * math.hypot(width, height) * scale
                and abs(math.log(math.sqrt(abs(p.determinant)) / scale)) < 0.25 and turned < math.radians(15)):
            return True
    return False
