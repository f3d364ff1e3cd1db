"""Where the check looks and what it reads there: the target's footprint and its overlap with the
reference, the regular grid of sites over the overlap (chosen by position alone), the template
side, and, per site, the CFOG stacks of the reference template and of the target resampled through
the model (a local affine inverse around the site) onto the template's search area, and, for a second
look, sites placed where both images show structure. Coordinates:
sites, the overlap and templates are full-resolution reference pixels (corner convention); the
inverse maps them into target pixels for reading.
"""
from __future__ import annotations

import math
from functools import lru_cache
from typing import List, Optional, Tuple

import cv2
import numpy as np
from rasterio.windows import Window
from shapely.geometry import Point, Polygon, box
from shapely.prepared import prep

from ..coords import raster_outline, xy_bounds
from ..estimation.models import local_jacobian
from ..io.raster import RasterInfo
from ..io.windows import WindowReader
from ..similarity.cfog import central_differences, cfog, gaussian_blur
from .params import VerifyParams


def footprint(model, target: RasterInfo) -> np.ndarray:
    """The target's outline in reference px (64 points), as ``model`` maps it."""
    return model.apply(raster_outline(target.width, target.height, 17))


def reference_overlap(outline: np.ndarray, reference: RasterInfo):
    """The part of the reference that ``outline`` covers (a shapely polygon); None when empty."""
    if not np.isfinite(outline).all():
        return None
    poly = Polygon(outline)
    poly = poly if poly.is_valid else poly.buffer(0)
    overlap = poly.intersection(box(0, 0, reference.width, reference.height))
    return None if overlap.is_empty or overlap.area <= 0 else overlap


def overlap_grid(overlap, n: int = 20) -> np.ndarray:
    """Points of a regular ``n x n`` grid over the overlap's bounding box that fall inside it."""
    if overlap is None:
        return np.zeros((0, 2))
    x0, y0, x1, y1 = overlap.bounds
    gx, gy = np.meshgrid(x0 + (np.arange(n) + 0.5) * (x1 - x0) / n, y0 + (np.arange(n) + 0.5) * (y1 - y0) / n)
    pts = np.column_stack([gx.ravel(), gy.ravel()])
    inside = prep(overlap)
    return pts[np.array([inside.contains(Point(x, y)) for x, y in pts], bool)]


def template_side(overlap, params: VerifyParams) -> int:
    """Template side for about ``params.target_sites`` sites over the overlap (even, within limits)."""
    area = 0.0 if overlap is None else float(overlap.area)
    side = math.sqrt(area / params.target_sites) if area > 0 else params.template_px
    return int(2 * round(min(max(side, params.template_px), params.max_template_px) / 2))


def site_grid(outline: np.ndarray, overlap, reference: RasterInfo, side: int, params: VerifyParams,
              step: Optional[float] = None) -> np.ndarray:
    """Site centres (K, 2) in reference px: a regular grid over the overlap, spacing ``step`` (by default
    at least one template, so that no two templates overlap, and about ``params.max_sites`` sites);
    templates lie inside the reference and the target neighbourhoods they are compared with inside the
    target."""
    if overlap is None:
        return np.zeros((0, 2))
    lo = np.maximum(outline.min(axis=0), 0) + side / 2.0 + 1
    hi = np.minimum(outline.max(axis=0), [reference.width, reference.height]) - side / 2.0 - 1
    if np.any(hi < lo):
        return np.zeros((0, 2))
    step = step or max(math.sqrt(float(overlap.area) / params.max_sites), float(side))
    gx, gy = np.meshgrid(*(_ticks(c, a, b, step) for c, a, b in zip(grid_centre(overlap), lo, hi)))
    pts = np.column_stack([gx.ravel(), gy.ravel()])
    margin = side / 2.0 + params.search_px + 2
    poly = outline.astype(np.float32)
    inside = np.array([cv2.pointPolygonTest(poly, (float(x), float(y)), True) >= margin for x, y in pts], bool)
    return pts[inside] if len(pts) else pts


def _ticks(c: float, a: float, b: float, step: float) -> np.ndarray:
    """Positions ``step`` apart within [a, b], symmetric about ``c``: one at ``c`` or two half a step from
    it, whichever fits more."""
    half = int(max(c - a, b - c) // step) + 1
    odd = c + np.arange(-half, half + 1) * step
    even = c + (np.arange(-half, half) + 0.5) * step
    odd, even = odd[(odd >= a) & (odd <= b)], even[(even >= a) & (even <= b)]
    return even if len(even) > len(odd) else odd


def grid_centre(overlap) -> np.ndarray:
    """The overlap's centroid, the centre of every grid :func:`site_grid` lays (whatever its step): the
    grids are symmetric about it, so a site's reflection through it is a site of the same grid unless
    that one was left out."""
    return np.array(overlap.centroid.coords[0], float)


def reflections(points: np.ndarray, centre: np.ndarray) -> np.ndarray:
    """For each of ``points`` (K, 2), the index of the point at its reflection through ``centre`` (within
    0.01 px), or -1."""
    if len(points) == 0:
        return np.zeros(0, int)
    d = np.linalg.norm((2 * centre - points)[:, None, :] - points[None, :, :], axis=2)
    nearest = np.argmin(d, axis=1)
    return np.where(d[np.arange(len(points)), nearest] <= 0.01, nearest, -1)


def inverse_at(model, p: np.ndarray, target: RasterInfo) -> Optional[Tuple[np.ndarray, np.ndarray]]:
    """(q, J^-1): the target px q that ``model`` maps onto reference px ``p`` (Newton's method), and
    the inverse of the model's Jacobian there, for a local affine inverse around ``p``."""
    if getattr(model, "matrix", None) is not None:
        q = model.inverse().apply(p[None])[0]
        return q, np.linalg.inv(local_jacobian(model, q[None])[0])
    c = np.array([target.width / 2.0, target.height / 2.0])
    j = local_jacobian(model, c[None])[0]
    q = c + np.linalg.solve(j, p - model.apply(c[None])[0])
    for _ in range(8):
        j = local_jacobian(model, q[None])[0]
        step = np.linalg.solve(j, p - model.apply(q[None])[0])
        q = q + step
        if np.abs(step).max() < 1e-4:
            break
    if not np.isfinite(q).all() or np.abs(model.apply(q[None])[0] - p).max() > 0.05:
        return None
    return q, np.linalg.inv(j)


def read_site(model, p, targets: WindowReader, references: WindowReader, side: int, search: int):
    """The reference template at ``p`` (and its valid pixels) and the target resampled through the model
    onto the template's search area (and its valid pixels); None when the site cannot be compared
    (outside an image, masked pixels, no structure)."""
    t, s = side, search
    target, reference = targets.info, references.info
    x0, y0 = int(math.floor(p[0])) - t // 2, int(math.floor(p[1])) - t // 2
    if x0 < 0 or y0 < 0 or x0 + t > reference.width or y0 + t > reference.height:
        return None
    tmpl, ok = references.read(Window(x0, y0, t, t))
    if ok.mean() < 0.95 or tmpl[ok].std() < 1e-6:
        return None
    inverse = inverse_at(model, np.asarray(p, float), target)
    if inverse is None:
        return None
    q, jinv = inverse
    size = t + 2 * s
    src = q + (_lattice(size) + [x0 - s + 0.5, y0 - s + 0.5] - p) @ jinv.T
    lo, hi = xy_bounds(src)
    c0, r0 = np.floor(lo).astype(int) - 2
    c1, r1 = np.ceil(hi).astype(int) + 2
    if c1 <= 0 or r1 <= 0 or c0 >= target.width or r0 >= target.height:
        return None
    k = finer_by(c1 - c0, r1 - r0, size)
    if k > MAX_REDUCTION:
        return None
    c0, r0 = c0 - c0 % k, r0 - r0 % k
    # The window may reach past the target (a turned square's bounding box); what is sampled must not.
    patch, pok = targets.read(Window(c0, r0, c1 - c0 + (-(c1 - c0)) % k, r1 - r0 + (-(r1 - r0)) % k))
    if k > 1:
        patch, pok = reduced(patch, pok, k)
    if pok.mean() < 0.5:
        return None
    patch = np.where(pok, patch, patch[pok].mean()).astype(np.float64)
    rows_cols = np.stack([((src[:, 1] - r0) / k - 0.5).reshape(size, size),
                          ((src[:, 0] - c0) / k - 0.5).reshape(size, size)])
    # Resampled with numpy in double precision (OpenCV's remap rounds positions to 1/32 px, and its
    # versions differ in the last digits): the check's numbers are the same on every library stack.
    warped = bilinear(patch, rows_cols)
    wok = nearest_valid(pok, rows_cols)
    if wok.mean() < 0.95:
        return None
    return tmpl, ok, warped, wok


MAX_REDUCTION = 4  # a target's window is averaged down by at most 4 x 4: targets up to about 12 times finer than
# the reference are compared (a scanned map on a layer or an image), beyond that the site is left out


def finer_by(width: int, height: int, size: int) -> int:
    """1 where the target's window (``width`` x ``height`` px) for a site ``size`` px square is at most 16
    times its area, as for images of like pixel sizes; else the whole factor that brings it there, by which
    the window is averaged down before it is resampled (a much finer target is not sampled sparsely)."""
    excess = width * height / (16 * size * size)
    return 1 if excess <= 1 else int(math.ceil(math.sqrt(excess)))


def reduced(patch: np.ndarray, valid: np.ndarray, k: int):
    """``patch`` averaged over ``k`` x ``k`` blocks (its valid pixels only) and where blocks are half valid."""
    h, w = patch.shape[0] // k, patch.shape[1] // k
    blocks = (h, k, w, k)
    weight = valid[:h * k, :w * k].reshape(blocks).sum(axis=(1, 3))
    total = np.where(valid, patch, 0)[:h * k, :w * k].reshape(blocks).sum(axis=(1, 3), dtype=np.float64)
    return (total / np.maximum(weight, 1)).astype(np.float32), weight >= k * k / 2


@lru_cache(maxsize=8)
def _lattice(size: int) -> np.ndarray:
    """(size * size, 2) pixel offsets (x, y) of a square, row by row (read only)."""
    gx, gy = np.meshgrid(np.arange(size), np.arange(size))
    out = np.column_stack([gx.ravel(), gy.ravel()])
    out.setflags(write=False)
    return out


def bilinear(img: np.ndarray, rows_cols: np.ndarray) -> np.ndarray:
    """``img`` sampled bilinearly at (rows, cols) in pixel-centre coordinates (0 = the first pixel's
    centre), positions clamped to the image (scipy's ``map_coordinates`` order 1, mode 'nearest')."""
    h, w = img.shape
    r = np.clip(rows_cols[0], 0, h - 1)
    c = np.clip(rows_cols[1], 0, w - 1)
    r0 = np.minimum(r.astype(np.intp), max(h - 2, 0))  # positions are clamped to >= 0: truncation is the floor
    c0 = np.minimum(c.astype(np.intp), max(w - 2, 0))
    fr, fc = r - r0, c - c0
    flat, first = img.ravel(), r0 * w + c0
    right, below = (1 if w > 1 else 0), (w if h > 1 else 0)
    top = flat.take(first) * (1 - fc) + flat.take(first + right) * fc
    bottom = flat.take(first + below) * (1 - fc) + flat.take(first + below + right) * fc
    return top * (1 - fr) + bottom * fr


def nearest_valid(valid: np.ndarray, rows_cols: np.ndarray) -> np.ndarray:
    """``valid`` at the nearest pixel of (rows, cols) in pixel-centre coordinates, False beyond the
    outer pixels' centres (scipy's ``map_coordinates`` order 0, mode 'constant')."""
    h, w = valid.shape
    rows, cols = rows_cols
    inside = (rows >= 0) & (rows <= h - 1) & (cols >= 0) & (cols <= w - 1)
    r, c = np.floor(rows + 0.5).astype(np.intp), np.floor(cols + 0.5).astype(np.intp)
    return inside & valid.ravel().take(np.clip(r, 0, h - 1) * w + np.clip(c, 0, w - 1))


def descriptors(pair) -> Tuple[np.ndarray, np.ndarray]:
    """The CFOG stacks of a site's template and search area (see :func:`read_site`), computed portably."""
    tmpl, ok, _, _ = pair
    return cfog(tmpl, valid=ok, portable=True), search_descriptors(pair)


def search_descriptors(pair) -> np.ndarray:
    """The CFOG stack of a site's search area alone."""
    _, _, warped, wok = pair
    return cfog(warped, valid=wok, portable=True)


def structure(image: np.ndarray, valid: np.ndarray) -> float:
    """Mean gradient magnitude of ``image`` smoothed at 1.5 px over its ``valid`` pixels: how much an
    area shows (edges and texture at the scale of a few pixels, not pixel noise or speckle)."""
    gx, gy = central_differences(gaussian_blur(image.astype(np.float64), 1.5))
    magnitude = np.sqrt(gx * gx + gy * gy)[valid]
    return float(magnitude.mean()) if magnitude.size else 0.0


def structured(candidates: np.ndarray, pairs, side: int, search: int, limit: int) -> List[int]:
    """Indices of at most ``limit`` ``candidates`` (reference px) whose template and target both show
    structure, best first and no two templates overlapping: each candidate's structure in each image,
    as a share of that image's median over the candidates, and the smaller of the two ranks it."""
    readable = [i for i, pair in enumerate(pairs) if pair is not None]
    if not readable:
        return []
    inner = (slice(search, -search),) * 2
    both = np.array([(structure(pairs[i][0], pairs[i][1]), structure(pairs[i][2][inner], pairs[i][3][inner]))
                     for i in readable])
    score = np.min(both / np.maximum(np.median(both, axis=0), 1e-9), axis=1)
    chosen: List[int] = []
    for j in np.argsort(-score, kind="stable"):
        p = candidates[readable[j]]
        if all(np.abs(p - candidates[c]).max() >= side for c in chosen):
            chosen.append(readable[j])
            if len(chosen) == limit:
                break
    return chosen
