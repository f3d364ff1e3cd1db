"""Regions: the connected areas that stay apart at some grey level (lakes, fields, forests, blocks).

The image is cut at ``levels`` grey levels (half at percentiles, half evenly between the 1st and 99th: a
map's flat paper holds most percentiles); at each, the areas darker and the areas brighter
are opened (thin lines such as a printed grid, roads or labels no longer join them) and taken as connected
components, as maximally stable extremal regions are (Matas et al. 2002), without their stability test:
a region seen at several levels is kept once. Each region keeps its centroid, area, whether it is darker
than its surroundings, and its outline as a radial profile (its reach from the centroid in ``BINS``
directions, over the square root of its area), which a turn of the image shifts circularly.

Coordinates: working pixels, corner convention (the top-left corner of the top-left pixel is 0, 0).
"""
from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

BINS = 64


@dataclass(frozen=True)
class Regions:
    """``xy`` (n, 2) centroids, ``area`` (n,) px, ``dark`` (n,) bool, ``profile`` (n, BINS), ``blocky`` (n,)
    bool: a convex four-sided region (a cell of a printed grid, a map's frame) rather than a natural shape."""

    xy: np.ndarray
    area: np.ndarray
    dark: np.ndarray
    profile: np.ndarray
    blocky: np.ndarray

    def __len__(self) -> int:
        return len(self.area)

    def subset(self, keep) -> "Regions":
        """The regions ``keep`` (indexes or a mask) picks, every array alike."""
        return Regions(*(getattr(self, f.name)[keep] for f in fields(self)))


def find_regions(grey: np.ndarray, valid: np.ndarray, *, levels: int = 12, min_area: int = 25,
                 max_share: float = 0.05) -> Regions:
    """The regions of ``grey`` (float, working px) inside ``valid``, between ``min_area`` px and ``max_share``
    of the image; one touching the image's edge or an invalid pixel is left out (its outline is cut)."""
    import cv2

    g = cv2.GaussianBlur(np.where(valid, grey, 0).astype(np.float32), (0, 0), 1.0)
    outside = cv2.dilate((~valid).astype(np.uint8), np.ones((3, 3), np.uint8)) > 0
    outside[[0, -1], :] = outside[:, [0, -1]] = True
    kernel = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (3, 3))
    found = []
    values = g[valid]
    low, high = np.percentile(values, [1, 99])
    steps = np.concatenate([np.percentile(values, np.linspace(4, 96, levels - levels // 2)),
                            np.linspace(low, high, levels // 2 + 2)[1:-1]])
    for level in np.unique(steps):
        for dark in (True, False):
            mask = ((g < level) if dark else (g > level)) & valid
            mask = cv2.morphologyEx(mask.astype(np.uint8), cv2.MORPH_OPEN, kernel)
            found += _components(mask, outside, dark, min_area, max_share * g.size)
    return _distinct(found)


def _components(mask, outside, dark: bool, min_area: int, max_area: float) -> list:
    import cv2

    n, labels, stats, centroids = cv2.connectedComponentsWithStats(mask, connectivity=4)
    cut = np.zeros(n, bool)
    cut[np.unique(labels[outside & (labels > 0)])] = True
    out = []
    for i in np.flatnonzero((stats[:, cv2.CC_STAT_AREA] >= min_area) & (stats[:, cv2.CC_STAT_AREA] <= max_area)
                            & ~cut):
        if i == 0:
            continue
        x, y, w, h, area = stats[i]
        shape = (labels[y:y + h, x:x + w] == i).astype(np.uint8)
        outline, _ = cv2.findContours(shape, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_NONE)
        points = np.vstack([c[:, 0] for c in outline]).astype(np.float64) + (x, y)
        centre = centroids[i]  # pixel-centre indices, as the outline's points
        out.append((centre + 0.5, float(area), dark, _profile(points - centre, area), _blocky(points, area)))
    return out


def _profile(offsets, area: float) -> np.ndarray:
    """The outline's reach in each of ``BINS`` directions (the farthest point), over sqrt(area)."""
    angle = np.arctan2(offsets[:, 1], offsets[:, 0])
    bins = ((angle + np.pi) / (2 * np.pi) * BINS).astype(int) % BINS
    reach = np.zeros(BINS)
    np.maximum.at(reach, bins, np.hypot(offsets[:, 0], offsets[:, 1]) + 0.5)
    if (reach == 0).any():
        seen = np.flatnonzero(reach > 0)
        reach = np.interp(np.arange(BINS), seen, reach[seen], period=BINS)
    return reach / np.sqrt(area)


def _blocky(points, area: float) -> bool:
    import cv2

    hull = cv2.convexHull(points.astype(np.float32))
    corners = cv2.approxPolyDP(hull, 0.02 * cv2.arcLength(hull, True), True)
    return len(corners) == 4 and area > 0.95 * max(cv2.contourArea(hull), 1.0)


def _distinct(found: list) -> Regions:
    """One of each region seen at several levels: the largest first; a smaller one within 0.15 sqrt(its area)
    of a kept centroid and of at least a third of its area is the same region (a shape's core and its blurred rim
    are cut at different levels)."""
    if not found:
        return Regions(np.zeros((0, 2)), np.zeros(0), np.zeros(0, bool), np.zeros((0, BINS)), np.zeros(0, bool))
    from scipy.spatial import cKDTree

    found.sort(key=lambda f: -f[1])
    xy = np.array([f[0] for f in found])
    area = np.array([f[1] for f in found])
    near = cKDTree(xy).query_ball_point(xy, 0.15 * np.sqrt(area))
    kept = np.zeros(len(found), bool)
    for i, others in enumerate(near):
        kept[i] = not any(kept[j] and j < i and area[i] >= area[j] / 3 for j in others)
    keep = np.flatnonzero(kept)
    return Regions(xy[keep], area[keep], np.array([found[i][2] for i in keep]),
                   np.array([found[i][3] for i in keep]), np.array([found[i][4] for i in keep]))
