"""Shift in windows: what two georeferenced rasters' georeferencing makes likely, measured first.

When both rasters are georeferenced, the working target is resampled onto the reference's working
grid (:mod:`hamta.core.io.working`), so what remains is mostly a translation: a georeferencing
offset. This method measures it as AROSICS does (Scheffler et al. 2017, Remote Sensing 9(7):676,
:DOI:`10.3390/rs9070676`): phase correlation (Kuglin & Hines 1975) of the whole overlap at a coarse
scale for the offset, then in a grid of well-spread windows at the working resolution, each giving
its own sub-pixel shift. The windows' centres and shifts are the correspondences, so a small rotation
or scale left by the georeferencing is fitted too, and outlying windows (clouds, change) are
rejected by the shared robust fit. It is ``auto``'s first step for georeferenced pairs: fast, and
escalated to feature matching when its result does not verify.
"""
from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

from ..matching.phase_correlation import phase_correlate
from ..progress import Monitor
from ..refine import RefineParams
from ..types import Matches
from .registry import Method, param, register_method, validate


@dataclass(frozen=True)
class ShiftParams:
    """Parameters of the shift-in-windows method."""

    windows: int = param(5, "Windows per side of the grid over the overlap.", minimum=2)
    window_px: int = param(128, "Side of each correlation window, working px (halved for small overlaps).",
                           minimum=32)
    coarse_px: int = param(512, "Longest side of the coarse whole-overlap correlation, px.", minimum=64)
    min_valid: float = param(0.8, "Share of a window's pixels that must be valid in both images.",
                             minimum=0.0, maximum=1.0)
    min_response: float = param(0.03, "Lowest accepted phase-correlation peak of a window.", minimum=0.0,
                                maximum=1.0)

    def __post_init__(self):
        validate(self)


def match(target, reference, params: ShiftParams, monitor: Monitor, seed: int = 0) -> Matches:
    """Window centres in the target (working px) and where they lie in the reference (working px)."""
    offset = coarse_offset(target, reference, params.coarse_px)
    monitor.report(0.3, "coarse offset")
    if not np.isfinite(offset).all():  # nothing to correlate (no valid pixels in common, non-finite values)
        return Matches.empty(1, 1)
    h, w = reference.shape
    side = min(params.window_px, _even(min(h, w) // 2))
    out_t, out_r, scores = [], [], []
    dx, dy = int(round(offset[0])), int(round(offset[1]))
    for cx, cy in _centres(target.shape, reference.shape, (dx, dy), side, params.windows):
        t = _window(target, cx, cy, side)
        r = _window(reference, cx + dx, cy + dy, side)
        if t is None or r is None:
            continue
        valid = min(t[1].mean(), r[1].mean())
        if valid < params.min_valid:
            continue
        shift, response = phase_correlate(t[0], r[0], t[1], r[1])
        if not (np.isfinite(shift).all() and response >= params.min_response) or np.abs(shift).max() > side / 4:
            continue
        out_t.append((cx, cy))
        out_r.append((cx + dx + shift[0], cy + dy + shift[1]))
        scores.append(response)
    monitor.report(1.0, "windows")
    if not out_t:
        return Matches.empty(1, 1)
    return Matches(np.array(out_t, float), np.array(out_r, float), np.array(scores), len(out_t), len(out_t),
                   {"coarse_offset_working_px": [float(offset[0]), float(offset[1])], "window_px": side})


def coarse_offset(target, reference, longest: int) -> np.ndarray:
    """The offset (dx, dy) in working px such that reference(p + offset) ~ target(p), by phase
    correlation of both whole images decimated so that their longest side is at most ``longest``."""
    h, w = reference.shape
    k = max(1.0, max(h, w, *target.shape) / longest)

    def small(img):
        size = (max(1, int(round(img.shape[1] / k))), max(1, int(round(img.shape[0] / k))))
        data = cv2.resize(np.where(img.valid, img.data, 0).astype(np.float32), size, interpolation=cv2.INTER_AREA)
        share = cv2.resize(img.valid.astype(np.float32), size, interpolation=cv2.INTER_AREA)
        return np.where(share > 0.5, data / np.maximum(share, 1e-6), 0), share > 0.5

    (a, av), (b, bv) = small(target), small(reference)
    shift, _ = phase_correlate(a, b, av, bv)
    return shift * k


def _centres(t_shape, r_shape, offset, side, n):
    """An ``n`` x ``n`` grid of window centres (target working px) whose windows lie inside both images."""
    half = side / 2 + 1
    lo = np.maximum([half, half], np.array([half, half]) - offset)
    hi = np.minimum([t_shape[1] - half, t_shape[0] - half], np.array([r_shape[1] - half, r_shape[0] - half]) - offset)
    if np.any(hi < lo):
        return []
    xs, ys = np.linspace(lo[0], hi[0], n), np.linspace(lo[1], hi[1], n)
    return sorted({(int(round(x)), int(round(y))) for y in ys for x in xs})


def _window(img, cx, cy, side):
    """The ``side`` x ``side`` window of a working image whose centre is the pixel corner (cx, cy), or None."""
    x0, y0 = cx - side // 2, cy - side // 2
    if x0 < 0 or y0 < 0 or x0 + side > img.shape[1] or y0 + side > img.shape[0]:
        return None
    return img.data[y0:y0 + side, x0:x0 + side], img.valid[y0:y0 + side, x0:x0 + side]


def _even(n: int) -> int:
    return max(2, n - n % 2)


METHOD = register_method(Method(
    name="shift",
    title="Shift in windows (georeferenced pairs)",
    summary="Measures the offset between two georeferenced rasters as AROSICS does: phase correlation of the "
            "overlap at a coarse scale, then in a grid of well-spread windows, each window's sub-pixel shift a "
            "correspondence (a small rotation or scale is fitted too; windows on clouds or change are rejected). "
            "Refined at full resolution. What 'auto' tries first when both rasters are georeferenced.",
    citation="Scheffler et al. (2017), AROSICS, Remote Sensing 9(7):676, doi:10.3390/rs9070676; "
             "Kuglin & Hines (1975), phase correlation",
    params_type=ShiftParams,
    match=match,
    kind="method",
    min_inliers=6,
    refine="always",
    # A grid of templates: the windows are few, the refinement spreads the fit over the overlap.
    refinement=RefineParams(points="grid", max_points=120),
    use_when="both rasters georeferenced, off by a shift (a few to a few hundred pixels)"))
