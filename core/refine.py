"""Full-resolution refinement of correspondences by local template matching.

Matching runs on decimated working images; this stage restores full-resolution accuracy. Around
well-spread inliers it reads a small reference template and the matching target neighbourhood at
full resolution, resamples the target onto the reference pixel grid with the current (linear)
model, and measures the remaining offset by normalised cross-correlation with a sub-pixel peak.
This is the area-based refinement AROSICS performs with phase correlation (Scheffler et al. 2017,
Remote Sensing 9(7):676, :DOI:`10.3390/rs9070676`), applied at feature locations. Across modalities
it correlates CFOG descriptors (Ye et al. 2019), computed once for each tile of windows on the
reference read and the target warped onto the reference grid, as the whole images give them.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import List, Optional, Tuple

import cv2
import numpy as np
from rasterio.windows import Window

from .coords import as_xy, xy_bounds
from .descriptors.cfog import ncc_surface
from .errors import InsufficientMatchesError, UsageError
from .estimation.models import LinearModel
from .estimation.robust import Estimate, RobustRules, robust_linear
from .estimation.spread import spread_subset
from .io.raster import RasterInfo
from .io.windows import WindowReader
from .parallel import threaded
from .progress import Monitor
from .similarity.cfog import cfog
from .similarity.peak import peak_offset
from .types import Correspondences


@dataclass(frozen=True)
class RefineParams:
    """Settings of the full-resolution refinement.

    Attributes
    ----------
    template_px : int
        Side of the reference template, full-resolution reference pixels.
    search_px : int
        Largest offset searched in each direction, reference pixels.
    min_ncc : float
        Lowest accepted correlation peak; weaker points are dropped, not kept unrefined.
    max_points : int
        At most this many points are refined.
    points : {'matches', 'grid'}
        Refine well-spread inlier matches, or a regular grid over the overlap (for images where
        features are few and noisy but area correlation works, such as speckled SAR).
    passes : int
        Refinement passes; each later pass starts from the model fitted on the previous one
        (templates then line up better where the first model was off by a few pixels).
    similarity : {'ncc', 'cfog'}
        Correlation of intensities, or of CFOG structural descriptors (for images of different
        modality, see :mod:`hamta.core.similarity.cfog`).
    """

    template_px: int = 31
    search_px: int = 6
    min_ncc: float = 0.5
    max_points: int = 300
    points: str = "matches"
    passes: int = 1
    similarity: str = "ncc"

    def __post_init__(self):
        if self.points not in ("matches", "grid"):
            raise UsageError(f"refinement points must be 'matches' or 'grid', got {self.points!r}")
        if self.similarity not in ("ncc", "cfog"):
            raise UsageError(f"refinement similarity must be 'ncc' or 'cfog', got {self.similarity!r}")


POINTS_PER_REPORT = 32  # points refined between two progress reports

# For images of different modality: CFOG templates on a grid, found in the target at full resolution.
STRUCTURAL_REFINEMENT = RefineParams(template_px=64, search_px=4, min_ncc=0.1, points="grid", similarity="cfog")


def grid_points(model: LinearModel, target: RasterInfo, reference: RasterInfo, params: RefineParams) -> np.ndarray:
    """About ``params.max_points`` reference px (K, 2) on a regular grid over the part of the
    reference that ``model`` (target px -> reference px) says the target covers, a template's
    half-width plus the search range away from both images' edges."""
    margin = params.template_px / 2.0 + params.search_px + 2
    corners = np.array([[0, 0], [target.width, 0], [target.width, target.height], [0, target.height]], float)
    foot = model.apply(corners)
    lo = np.maximum(foot.min(axis=0), 0) + margin
    hi = np.minimum(foot.max(axis=0), [reference.width, reference.height]) - margin
    if np.any(hi <= lo):
        return np.zeros((0, 2))
    t = margin / max(np.sqrt(abs(np.linalg.det(model.matrix[:2, :2]))), 1e-6)  # the margin in target px
    if 2 * t >= min(target.width, target.height):
        return np.zeros((0, 2))
    inset = np.array([[t, t], [target.width - t, t], [target.width - t, target.height - t], [t, target.height - t]])
    poly = model.apply(inset).astype(np.float32)
    step = max(np.sqrt(cv2.contourArea(poly) / params.max_points), 1.0)
    gx, gy = np.meshgrid(np.arange(lo[0], hi[0], step), np.arange(lo[1], hi[1], step))
    pts = np.column_stack([gx.ravel(), gy.ravel()])
    inside = np.array([cv2.pointPolygonTest(poly, (float(x), float(y)), False) >= 0 for x, y in pts], bool)
    pts = pts[inside]
    if len(pts) > params.max_points:
        pts = pts[np.linspace(0, len(pts) - 1, params.max_points).round().astype(int)]
    return pts


def refine_estimate(estimate: Estimate, method, refine: str, tolerance_px: float, target, reference,
                    rules: RobustRules, monitor: Monitor) -> Tuple[Estimate, List[str]]:
    """Refine ``estimate`` at full resolution in ``method.refinement.passes`` passes, each fitted
    again with ``rules``; returns the last estimate that refined successfully (the working-resolution
    one when the first pass fails) and notes saying why a pass was not used.

    ``refine`` is the user's choice ('auto', 'on', 'off'); 'auto' refines when a working image was
    decimated by more than 1.25 or ``method.refine`` is 'always'. ``tolerance_px`` is the run's
    RANSAC tolerance in working pixels; refined points are fitted within ``max(1, tolerance_px)``
    full-resolution pixels. ``target`` and ``reference`` are the working images.
    """
    decimation = max(target.source_px_per_working_px, reference.source_px_per_working_px)
    if not (refine == "on" or (refine == "auto" and (method.refine == "always" or decimation > 1.25))):
        return estimate, []
    rp = replace(method.refinement,
                 search_px=max(method.refinement.search_px, int(math.ceil(2.5 * decimation)) + 4))
    threshold = max(1.0, tolerance_px)
    robust = "ransac" if rules.robust == "triplets" else rules.robust
    notes = []
    for i in range(rp.passes):
        sites = _refinement_sites(estimate, rp, target.info, reference.info)
        points = refine_points(estimate.model, sites, target.info, target.bands, reference.info, reference.bands, rp,
                               monitor.span(i / rp.passes, (i + 1) / rp.passes))
        fallback = "working-resolution matches" if i == 0 else "previous pass"
        if len(points) < rules.need:
            notes.append(f"refinement kept only {len(points)} points; using the {fallback}")
            break
        try:
            estimate = robust_linear(points, threshold, rules, robust, refined=True)
        except InsufficientMatchesError as exc:
            notes.append(f"refinement pass {i + 1} found no consistent model ({exc}); using the {fallback}")
            break
        rp = replace(rp, search_px=min(rp.search_px, 3))  # later passes start from the refined model
    return estimate, notes


def _refinement_sites(estimate: Estimate, params: RefineParams, target: RasterInfo, reference: RasterInfo):
    """Reference px to refine: a grid over the overlap, or well-spread inliers."""
    if params.points == "grid":
        return grid_points(estimate.model, target, reference, params)
    p = estimate.points
    kept = p.reference_px[p.inlier]
    return kept[spread_subset(kept, p.score[p.inlier], params.max_points)]


def refine_points(model: LinearModel, reference_xy: np.ndarray, target: RasterInfo, target_bands,
                  reference: RasterInfo, reference_bands, params: RefineParams = RefineParams(),
                  monitor: Optional[Monitor] = None) -> Correspondences:
    """Refine correspondences at ``reference_xy`` (full-resolution reference px).

    Returns
    -------
    Correspondences
        Refined correspondences in full-resolution pixels of each raster, scored by their
        correlation peak (not yet fitted).
    """
    monitor = monitor or Monitor()
    inverse = model.inverse()
    pts = as_xy(reference_xy)
    found = []
    # Intensity windows on one thread: each is many short calls that hold the GIL between them, so threads only
    # wait for each other (two were 25 % slower on the local correction's 2,000 windows, no faster on 300). A
    # structural window's nine correlations release it: two threads take 0.23 s instead of 0.32 s for 259.
    with WindowReader(target, target_bands) as targets, WindowReader(reference, reference_bands) as references:
        if params.similarity == "cfog":
            found = _refine_structural(pts, inverse, targets, references, params, monitor)
        else:
            for i, p in enumerate(pts):
                if i % POINTS_PER_REPORT == 0:
                    monitor.report(i / len(pts), "refining")
                f = _refine_one(p, inverse, targets, references, params.template_px, params.search_px,
                                params.min_ncc)
                if f is not None:
                    found.append(f)
    monitor.report(1.0, "refining")
    if not found:
        return Correspondences.unfitted(np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0))
    return Correspondences.unfitted(np.array([f[0] for f in found]), np.array([f[1] for f in found]),
                                    np.array([f[2] for f in found]))


def _refine_one(p, inverse, targets: WindowReader, references: WindowReader, t, s, min_ncc):
    """One refined (target px, reference px, ncc) by NCC of intensities, or None when the point cannot be
    refined."""
    target, reference = targets.info, references.info
    x0, y0 = int(np.floor(p[0])) - t // 2, int(np.floor(p[1])) - t // 2
    if x0 < 0 or y0 < 0 or x0 + t > reference.width or y0 + t > reference.height:
        return None
    tmpl, tmpl_ok = references.read(Window(x0, y0, t, t))
    tmpl = _filled(tmpl, tmpl_ok)
    if tmpl is None or tmpl.std() < 1e-6:
        return None
    size = t + 2 * s
    gx, gy = np.meshgrid(np.arange(size) + x0 - s + 0.5, np.arange(size) + y0 - s + 0.5)
    src = inverse.apply(np.column_stack([gx.ravel(), gy.ravel()]))
    lo, hi = xy_bounds(src)
    c0, r0 = np.floor(lo).astype(int) - 2
    c1, r1 = np.ceil(hi).astype(int) + 2
    if c0 < 0 or r0 < 0 or c1 > target.width or r1 > target.height:
        return None
    patch, patch_ok = targets.read(Window(c0, r0, c1 - c0, r1 - r0))
    patch = _filled(patch, patch_ok)
    if patch is None:
        return None
    mx = (src[:, 0] - c0 - 0.5).reshape(size, size).astype(np.float32)
    my = (src[:, 1] - r0 - 0.5).reshape(size, size).astype(np.float32)
    warped = cv2.remap(patch, mx, my, cv2.INTER_CUBIC, borderMode=cv2.BORDER_REPLICATE)
    surface = cv2.matchTemplate(warped.astype(np.float32), tmpl.astype(np.float32), cv2.TM_CCOEFF_NORMED)
    return _found(surface, s, min_ncc, inverse, x0, y0, t)


def _found(surface, s: int, min_ncc: float, inverse, x0: int, y0: int, t: int):
    """(target px, reference px, peak) of the template at reference px (x0, y0) from its correlation
    ``surface``, or None where the peak is on the border or weaker than ``min_ncc``."""
    offset, peak = peak_offset(surface, s)
    if offset is None or peak < min_ncc:
        return None
    ref_pt = np.array([x0 + t / 2.0, y0 + t / 2.0])
    return inverse.apply(ref_pt + offset)[0], ref_pt, peak


TILE_PX = 512  # reference px: the windows of one tile share their CFOG descriptors
CFOG_MARGIN_PX = 8  # beyond a window, wider than CFOG's support (gradient and smoothing): its values are the image's


def _refine_structural(pts, inverse, targets: WindowReader, references: WindowReader, params: RefineParams,
                       monitor: Monitor) -> list:
    """Refined (target px, reference px, ncc) of the points (reference px, in order) by NCC of CFOG
    descriptors, computed once for each tile of windows (the reference read, the target warped onto the
    reference grid through ``inverse``) instead of once per window: the same descriptors the whole images
    give, without a window's own padded border, in a third of the time."""
    t = params.template_px
    corners = np.floor(pts).astype(int) - t // 2  # the templates' top-left reference px
    tiles = {}
    for i, key in enumerate(map(tuple, corners // TILE_PX)):
        tiles.setdefault(key, []).append(i)
    found, done = {}, 0
    for members in tiles.values():
        span = monitor.span(done / len(pts), (done + len(members)) / len(pts))
        found.update(_refine_tile(corners[members], members, inverse, targets, references, params, span))
        done += len(members)
    return [found[i] for i in range(len(pts)) if i in found]


def _refine_tile(corners, members, inverse, targets: WindowReader, references: WindowReader, params: RefineParams,
                 monitor: Monitor):
    """{point index: (target px, reference px, ncc)} of the windows whose templates start at ``corners``, measured
    on threads; ``monitor`` reports the share of them done."""
    t, s, m = params.template_px, params.search_px, CFOG_MARGIN_PX
    target, reference = targets.info, references.info
    inside = ((corners >= 0) & (corners + t <= [reference.width, reference.height])).all(axis=1)
    corners, members = corners[inside], [i for i, ok in zip(members, inside) if ok]
    if not members:
        return {}
    # The reference around the templates, and the target warped onto the reference grid around the search areas.
    (rx0, ry0), (rx1, ry1) = np.maximum(corners.min(axis=0) - m, 0), np.minimum(
        corners.max(axis=0) + t + m, [reference.width, reference.height])
    ref, ref_ok = references.read(Window(int(rx0), int(ry0), int(rx1 - rx0), int(ry1 - ry0)))
    (wx0, wy0), (wx1, wy1) = corners.min(axis=0) - s - m, corners.max(axis=0) + t + s + m
    gx, gy = np.meshgrid(np.arange(wx0, wx1) + 0.5, np.arange(wy0, wy1) + 0.5)
    src = inverse.apply(np.column_stack([gx.ravel(), gy.ravel()]))
    spans = _target_spans(corners, inverse, t, s)  # each window's target patch: c0, r0, c1, r1
    usable = (spans[:, :2] >= 0).all(axis=1) & (spans[:, 2] <= target.width) & (spans[:, 3] <= target.height)
    if not usable.any():
        return {}
    lo, hi = xy_bounds(src)  # the region's target patch holds every window's
    c0, r0 = np.maximum(np.floor(lo).astype(int) - 2, 0)
    c1, r1 = np.minimum(np.ceil(hi).astype(int) + 2, [target.width, target.height])
    patch, patch_ok = targets.read(Window(int(c0), int(r0), int(c1 - c0), int(r1 - r0)))
    shape = (int(wy1 - wy0), int(wx1 - wx0))
    mx = (src[:, 0] - c0 - 0.5).reshape(shape).astype(np.float32)
    my = (src[:, 1] - r0 - 0.5).reshape(shape).astype(np.float32)
    warped = cv2.remap(_mean_filled(patch, patch_ok), mx, my, cv2.INTER_CUBIC, borderMode=cv2.BORDER_REPLICATE)
    ref = _mean_filled(ref, ref_ok)
    dr, dt = cfog(ref), cfog(warped)

    def window(k):
        (x0, y0), span = corners[k], spans[k]
        tx, ty = x0 - rx0, y0 - ry0
        if not usable[k] or ref_ok[ty:ty + t, tx:tx + t].mean() < 0.9 or ref[ty:ty + t, tx:tx + t].std() < 1e-6:
            return None
        if patch_ok[span[1] - r0:span[3] - r0, span[0] - c0:span[2] - c0].mean() < 0.9:
            return None
        ax, ay = x0 - s - wx0, y0 - s - wy0
        surface = ncc_surface(dt[:, ay:ay + t + 2 * s, ax:ax + t + 2 * s], dr[:, ty:ty + t, tx:tx + t])
        return _found(surface, s, params.min_ncc, inverse, x0, y0, t)

    found = threaded(window, range(len(members)), monitor, "refining")
    return {i: f for i, f in zip(members, found) if f is not None}


def _target_spans(corners, inverse, t: int, s: int) -> np.ndarray:
    """(K, 4) target px (c0, r0, c1, r1) each window's search area needs from the target, two px of
    interpolation support around it (the bounds of its corners' pixel centres: the model is linear)."""
    lo_x, lo_y = corners[:, 0] - s + 0.5, corners[:, 1] - s + 0.5
    hi_x, hi_y = lo_x + t + 2 * s - 1, lo_y + t + 2 * s - 1
    quad = inverse.apply(np.stack([np.column_stack(c) for c in ((lo_x, lo_y), (hi_x, lo_y), (hi_x, hi_y),
                                                                 (lo_x, hi_y))], axis=1).reshape(-1, 2))
    quad = quad.reshape(len(corners), 4, 2)
    lo, hi = np.floor(quad.min(axis=1)).astype(int) - 2, np.ceil(quad.max(axis=1)).astype(int) + 2
    return np.column_stack([lo, hi])


def _filled(image: np.ndarray, valid: np.ndarray, min_valid: float = 0.9):
    """``image`` with invalid pixels set to the valid mean, or None when too few are valid."""
    return None if valid.mean() < min_valid else _mean_filled(image, valid)


def _mean_filled(image: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """``image`` (float32) with invalid pixels set to the valid mean (0 without any)."""
    image = image.astype(np.float32, copy=False)
    if valid.all():
        return image
    return np.where(valid, image, image[valid].mean() if valid.any() else 0.0).astype(np.float32)
