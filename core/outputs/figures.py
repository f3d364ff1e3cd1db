"""The report's figures, drawn with OpenCV on the previews, and their encoding as data URIs.

Marks are given in full-resolution pixels (target px on the target, reference px on the reference)
and drawn in the preview's OpenCV coordinates (:meth:`hamta.core.outputs.preview.Preview.to_opencv`)
as fixed-point integers with :data:`SHIFT` fractional bits. The histogram is a chart of residuals in
reference px, drawn as SVG. Colours are BGR, as OpenCV draws them; the page's legends use the same ones.
"""
from __future__ import annotations

import base64
import math
from typing import List, Optional, Tuple

import cv2
import numpy as np

from ..coords import as_xy
from .preview import Preview

ARROW_PX = 25.0  # preview length given to the 90th-percentile residual arrow
CHECKER_TILES = 8  # checkerboard tiles along the longest side
SHIFT = 4  # fractional bits of OpenCV drawing coordinates
ONE = 1 << SHIFT

# BGR drawing colours; the legend uses the same ones.
ENABLED_BGR = (255, 190, 0)  # azure circles
REJECTED_BGR = (0, 90, 255)  # orange crosses
AGREE_BGR = (60, 190, 40)
CONTRADICT_BGR = (60, 30, 230)
OTHER_BGR = (200, 200, 200)
RAMP_RGB = ((40, 170, 255), (255, 220, 0), (230, 30, 30))  # residual colours, small to large


def _jpeg(image: np.ndarray) -> str:
    """A data URI of a picture (imagery with marks drawn on it: JPEG, a fifth of the PNG's size)."""
    ok, buf = cv2.imencode(".jpg", image, [cv2.IMWRITE_JPEG_QUALITY, 90])
    if not ok:
        raise ValueError("could not encode a report image as JPEG")
    return "data:image/jpeg;base64," + base64.b64encode(buf.tobytes()).decode("ascii")


def _fixed(xy) -> List[Tuple[int, int]]:
    """OpenCV coordinates as the fixed-point integers of ``shift=SHIFT`` drawing calls."""
    return [tuple(v) for v in np.round(as_xy(xy) * ONE).astype(np.int64).tolist()]


def _canvas(preview: Preview, contrast: float = 1.0, level: float = 128.0) -> np.ndarray:
    """A BGR copy of the preview to draw on, its grey range shrunk to ``contrast`` towards ``level``
    so that colours stand out."""
    grey = preview.image
    if contrast != 1.0:
        grey = (grey * contrast + level * (1 - contrast)).astype(np.uint8)
    return cv2.cvtColor(grey, cv2.COLOR_GRAY2BGR)


def gcp_figure(preview: Preview, enabled_xy: np.ndarray, rejected_xy: np.ndarray) -> np.ndarray:
    """The preview with enabled GCPs as circles and rejected matches as crosses."""
    img = _canvas(preview, 0.75)
    r = 4 * ONE
    for c in _fixed(preview.to_opencv(rejected_xy)) if len(rejected_xy) else []:
        for d in ((r, r), (r, -r)):
            a, b = (c[0] - d[0], c[1] - d[1]), (c[0] + d[0], c[1] + d[1])
            cv2.line(img, a, b, (0, 0, 0), 4, cv2.LINE_AA, SHIFT)
            cv2.line(img, a, b, REJECTED_BGR, 2, cv2.LINE_AA, SHIFT)
    for c in _fixed(preview.to_opencv(enabled_xy)) if len(enabled_xy) else []:
        cv2.circle(img, c, r, (0, 0, 0), 4, cv2.LINE_AA, SHIFT)
        cv2.circle(img, c, r, ENABLED_BGR, 2, cv2.LINE_AA, SHIFT)
    return img


def ramp(t: np.ndarray) -> np.ndarray:
    """Colours (N, 3) BGR uint8 of the residual ramp at ``t`` in [0, 1]."""
    t = np.clip(np.asarray(t, float), 0.0, 1.0)[:, None]
    lo, mid, hi = (np.array(c[::-1], float) for c in RAMP_RGB)
    out = np.where(t < 0.5, lo + (mid - lo) * (t * 2), mid + (hi - mid) * (t * 2 - 1))
    return np.round(out).astype(np.uint8)


def _nice(x: float, up: bool = True) -> float:
    """The next 1, 2 or 5 times a power of ten at or above (``up``) or below ``x`` > 0."""
    e = math.floor(math.log10(x))
    steps = [1, 2, 5, 10] if up else [10, 5, 2, 1]
    for m in steps:
        v = m * 10.0 ** e
        if (v >= x * (1 - 1e-9)) if up else (v <= x * (1 + 1e-9)):
            return v
    return 10.0 ** e


def arrow_factor(residuals: np.ndarray, scale: float) -> float:
    """Exaggeration of residual arrows: the 90th-percentile residual becomes about
    :data:`ARROW_PX` preview px long (a 1-2-5 number, at least 1)."""
    p90 = float(np.percentile(residuals, 90)) if len(residuals) else 0.0
    if p90 <= 1e-9:
        return 1.0
    return max(1.0, _nice(ARROW_PX * scale / p90, up=False))


def residual_figure(preview: Preview, xy: np.ndarray, res_xy: np.ndarray, factor: float, vmax: float) -> np.ndarray:
    """Arrows from each enabled GCP's reference position along ``factor`` times its residual,
    coloured by magnitude (ramp up to ``vmax``), largest drawn last."""
    img = _canvas(preview, 0.4, 30.0)
    if not len(xy):
        return img
    mag = np.hypot(res_xy[:, 0], res_xy[:, 1])
    order = np.argsort(mag, kind="stable")
    start = preview.to_opencv(xy[order])
    end = start + factor * res_xy[order] / np.asarray(preview.scale)
    colours = ramp(mag[order] / vmax)
    for a, b, c in zip(_fixed(start), _fixed(end), colours.tolist()):
        length = math.hypot(b[0] - a[0], b[1] - a[1]) / ONE
        cv2.circle(img, a, ONE + ONE // 2, tuple(c), -1, cv2.LINE_AA, SHIFT)
        if length >= 2:
            cv2.arrowedLine(img, a, b, tuple(c), 1, cv2.LINE_AA, SHIFT, min(0.5, 6.0 / length))
    return img


def histogram_svg(residuals: np.ndarray, rmse: Optional[float], size=(640, 280)) -> str:
    """Bar chart of residual magnitudes (reference px) with the RMSE marked, as SVG (its text set by the
    browser: OpenCV's fonts cost a twentieth of a second to load)."""
    w, h = size
    left, right, top, bottom = 52, 20, 34, 44
    step = _nice(max(float(residuals.max()), 1e-3) / 5)
    hi = step * max(1, math.ceil(float(residuals.max()) / step - 1e-9))
    n_bins = int(np.clip(round(math.sqrt(len(residuals))), 5, 30))
    counts, _ = np.histogram(residuals, bins=n_bins, range=(0.0, hi))
    cmax = max(int(counts.max()), 1)
    pw, ph = w - left - right, h - top - bottom
    base = h - bottom
    parts = [f'<rect x="{left + i * pw / n_bins:.1f}" y="{base - c / cmax * ph:.1f}" width="{pw / n_bins - 1:.1f}" '
             f'height="{c / cmax * ph:.1f}" fill="#2878b4"/>' for i, c in enumerate(counts)]
    parts.append(f'<path d="M{left} {top}V{base}H{w - right}" stroke="#000" fill="none"/>')
    for t in np.arange(0.0, hi + step / 2, step):
        x = left + t / hi * pw
        parts.append(f'<path d="M{x:.1f} {base}v4" stroke="#000"/><text x="{x:.1f}" y="{base + 18}" '
                     f'text-anchor="middle">{t:g}</text>')
    for c in sorted({0, cmax // 2, cmax}):
        y = base - c / cmax * ph
        parts.append(f'<path d="M{left - 4} {y:.1f}h4" stroke="#000"/><text x="{left - 8}" y="{y + 4:.1f}" '
                     f'text-anchor="end">{c}</text>')
    parts.append(f'<text x="{left + pw // 2}" y="{h - 8}" text-anchor="middle">residual (reference px)</text>'
                 '<text x="6" y="14">GCPs</text>')
    if rmse is not None and np.isfinite(rmse):
        x = left + min(rmse, hi) / hi * pw
        parts.append(f'<path d="M{x:.1f} {top - 4}V{base}" stroke="#c82828" stroke-width="2"/><text '
                     f'x="{min(x + 5, w - 90):.1f}" y="{top - 10}" fill="#c82828">RMSE {rmse:.2f}</text>')
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" '
            f'font-family="sans-serif" font-size="12"><rect width="{w}" height="{h}" fill="#fff"/>'
            + "".join(parts) + "</svg>")


def _svg(svg: str) -> str:
    """A data URI of an SVG drawing."""
    return "data:image/svg+xml;base64," + base64.b64encode(svg.encode("utf-8")).decode("ascii")


def checkerboard_figure(ref: Preview, warped: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """Alternating tiles of the reference (grey) and the warped target (warm tint); target tiles
    the target does not cover show the reference darkened."""
    rows, cols = ref.shape
    tile = max(8, int(round(max(rows, cols) / CHECKER_TILES)))
    target_tile = (np.arange(rows)[:, None] // tile % 2) != (np.arange(cols)[None, :] // tile % 2)
    grey = np.arange(256)
    tint = (grey[:, None] * np.array([0.78, 0.9, 1.0])).astype(np.uint8).reshape(256, 1, 3)  # BGR: warm
    dark = (grey * 0.35).astype(np.uint8)
    img = cv2.cvtColor(ref.image, cv2.COLOR_GRAY2BGR)
    img = cv2.copyTo(cv2.LUT(cv2.cvtColor(warped, cv2.COLOR_GRAY2BGR), tint), (target_tile & valid).view(np.uint8), img)
    return cv2.copyTo(cv2.LUT(img, dark), (target_tile & ~valid).view(np.uint8), img)


def sites_figure(ref: Preview, v) -> np.ndarray:
    """The check's site templates on the reference: agreeing, contradicting and other sites."""
    img = _canvas(ref, 0.6)
    half = v.template_px / 2.0
    groups = [(~v.agree & ~v.contradict, OTHER_BGR, 1), (v.contradict, CONTRADICT_BGR, 2), (v.agree, AGREE_BGR, 2)]
    for mask, colour, thickness in groups:
        for x, y in np.asarray(v.sites_xy)[mask]:
            a, b = _fixed(ref.to_opencv([[x - half, y - half], [x + half, y + half]]))
            cv2.rectangle(img, a, b, (0, 0, 0), thickness + 2, cv2.LINE_AA, SHIFT)
            cv2.rectangle(img, a, b, colour, thickness, cv2.LINE_AA, SHIFT)
    return img


def swipe_top(ref: Preview, warped: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """The swipe's top layer: the warped target, and the reference where the target does not cover it (what
    a transparent layer would show; a JPEG has no transparency)."""
    return np.where(valid, warped, ref.image)
