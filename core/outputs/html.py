"""``report.html``: a self-contained visual report of one registration, read by looking.

One HTML file with inline CSS, a single line of inline JavaScript (the swipe handle) and every image
embedded as a base64 PNG, so it can be mailed or archived alone. It shows the verdict of the
independent check first, then the two rasters with their GCPs, the residual vectors and their
histogram, a checkerboard and a swipe view of the reference against the target warped through the
model, the verification sites, and the numbers (model, statistics, timings, the ``auto`` attempts,
the GCP table). Lengths are given in reference pixels and in the reference CRS's unit (metres,
degrees...), next to the CRS, the pixel sizes, the date and the files written; in pixel mode (a
reference without georeferencing) a banner says that coordinates are reference pixels.

Both rasters are read once, decimated to a preview whose longest side is :data:`PREVIEW_PX`
pixels (:func:`hamta.core.io.raster.read_image` with an output shape), so time and memory do not
grow with the raster size. Coordinates follow :mod:`hamta.core.coords`: full-resolution pixel
``(x, y)`` (corner origin) is preview pixel ``(x / sx, y / sy)``, and OpenCV draws at that minus
one half, since OpenCV puts pixel centres at integers.
"""
from __future__ import annotations

import base64
import html
import math
import os
from dataclasses import dataclass
from datetime import datetime, timezone
from typing import Iterable, List, Mapping, Optional, Sequence, Tuple

import cv2
import numpy as np
from pyproj import CRS as ProjCRS

from ..coords import as_xy
from ..estimation.inverse import invert_model
from ..estimation.models import local_jacobian
from ..io.raster import RasterInfo, read_image, resolve_bands
from ..progress import Monitor
from ..verify import VerifyParams
from ..version import __version__

PREVIEW_PX = 800  # longest side of the previews
MAX_TABLE_ROWS = 200  # GCP rows listed; the rest are counted
ARROW_PX = 25.0  # preview length given to the 90th-percentile residual arrow
GRID_STEP_PX = 20  # preview px between the nodes where the model is inverted exactly
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
VERDICT_CSS = {"verified": ("#1b7f3b", "#e3f4e8"), "suspect": ("#9a5b00", "#fff1d0"),
               "failed": ("#b3261e", "#fde4e1"), "not checked": ("#555555", "#eeeeee")}


@dataclass(frozen=True)
class Preview:
    """A raster read at preview size, contrast-stretched to uint8.

    ``scale`` is (sx, sy), full-resolution pixels per preview pixel.
    """

    image: np.ndarray
    valid: np.ndarray
    scale: Tuple[float, float]

    @property
    def shape(self) -> Tuple[int, int]:
        return self.image.shape[:2]

    def to_opencv(self, xy) -> np.ndarray:
        """Full-resolution pixels (corner origin) -> OpenCV coordinates of the preview."""
        return as_xy(xy) / np.asarray(self.scale) - 0.5

    def to_full(self, xy) -> np.ndarray:
        """Preview pixels (corner origin) -> full-resolution pixels (corner origin)."""
        return as_xy(xy) * np.asarray(self.scale)


def write_html_report(path: str, result, monitor: Optional[Monitor] = None, *,
                      outputs: Optional[Mapping[str, str]] = None) -> None:
    """Write the visual report of ``result`` to ``path`` as one self-contained HTML file.

    Parameters
    ----------
    path : str
        The ``.html`` file to write (overwritten).
    result : RegistrationResult
        The registration to report (:class:`hamta.core.result.RegistrationResult`).
    monitor : Monitor, optional
        Receives progress and raises :class:`hamta.core.errors.RegistrationCanceled` when the caller
        asks to stop.
    outputs : mapping of str to str, optional
        The files of the run, {kind: path} as :func:`hamta.core.outputs.write_outputs` returns them
        (``raster``, ``points``, ``gpkg``, ``vrt``, ``report``, ``html``); listed on the page.
        ``path`` may be a staging name: the page lists these paths, not ``path``.

    Notes
    -----
    Each raster is read once at preview size (longest side :data:`PREVIEW_PX` px); a 1000 px pair
    takes a fraction of a second, and larger rasters cost only the decimated read. The page is dated
    with the time of writing (UTC).
    """
    monitor = monitor or Monitor()
    monitor.report(0.0, "report: previews")
    ref = read_preview(result.reference, result.options.get("reference_band"))
    tgt = read_preview(result.target, result.options.get("target_band"))
    monitor.report(0.4, "report: warping the target")
    warped, warped_ok = warp_to_reference(result.model, tgt, ref)
    monitor.report(0.6, "report: figures")
    written = datetime.now(timezone.utc).replace(microsecond=0)
    page = _page(result, ref, tgt, warped, warped_ok, outputs or {}, written)
    monitor.check()
    with open(path, "w", encoding="utf-8") as f:
        f.write(page)
    monitor.report(1.0, "report written")


# ---------------------------------------------------------------------------------------------- map units

UNIT_SYMBOLS = {"metre": "m", "meter": "m", "kilometre": "km", "degree": "°", "foot": "ft",
                "US survey foot": "US ft", "Clarke's foot": "Clarke's ft"}


def describe_crs(crs) -> Tuple[str, str]:
    """``('WGS 84 / UTM zone 32N (EPSG:32632)', 'metre')``: a CRS's name with its EPSG code (when it
    has one) and the unit of its first axis (``'unknown unit'`` without axes)."""
    pcrs = ProjCRS.from_user_input(crs.to_wkt())
    code = pcrs.to_epsg()
    name = f"{pcrs.name} (EPSG:{code})" if code else f"{pcrs.name} (no EPSG code)"
    unit = pcrs.axis_info[0].unit_name if pcrs.axis_info else "unknown unit"
    return name, unit


def _decimals(size: float) -> int:
    """Decimals that resolve about a hundredth of ``size`` (a pixel's size)."""
    return int(min(10, max(2, math.ceil(-math.log10(size)) + 2))) if size > 0 and math.isfinite(size) else 3


@dataclass(frozen=True)
class MapScale:
    """How reference pixels read in the reference CRS: its label, unit and pixel size."""

    crs: str
    unit_name: str
    pixel_size: float  # map units per reference pixel (geometric mean of the two axes)

    @property
    def symbol(self) -> str:
        """The unit's symbol: ``'m'``, ``'°'``, ``'US ft'`` (the unit's name when it has none here)."""
        return UNIT_SYMBOLS.get(self.unit_name, self.unit_name)

    @property
    def unit(self) -> str:
        """The unit as printed after a number: ``' m'``, ``'°'``, ``' US ft'``."""
        return self.symbol if self.symbol == "°" else " " + self.symbol

    def length(self, size: Optional[float]) -> str:
        """A length in map units (escaped), to about a hundredth of a pixel."""
        return _num(size, f".{_decimals(self.pixel_size)}f", self.unit)

    def px(self, value_px: Optional[float]) -> str:
        """A length in reference px as map units (escaped); '–' when missing."""
        return self.length(None if value_px is None else value_px * self.pixel_size)


def map_scale(result) -> Optional[MapScale]:
    """The reference's map scale; None in pixel mode (no georeferencing)."""
    if result.pixel_mode or result.reference.crs is None:
        return None
    name, unit = describe_crs(result.reference.crs)
    return MapScale(name, unit, result.reference.pixel_size)


def _both(value_px: Optional[float], scale: Optional[MapScale], fmt: str = ".2f") -> str:
    """``'0.41 px (4.10 m)'``: a length in reference px and, outside pixel mode, in map units."""
    text = _num(value_px, fmt, " px")
    if scale is None or text == "–":
        return text
    return f"{text} ({scale.px(value_px)})"


def axis_sizes(info: RasterInfo) -> Tuple[float, float]:
    """Map units per pixel along the raster's columns and rows."""
    t = info.transform
    return math.hypot(t.a, t.d), math.hypot(t.b, t.e)


def registered_scale(result) -> Optional[float]:
    """Reference px per target px at the target's centre, through the model (None if not finite)."""
    centre = [[result.target.width / 2.0, result.target.height / 2.0]]
    try:
        det = float(np.linalg.det(local_jacobian(result.model, centre)[0]))
    except (ValueError, np.linalg.LinAlgError):
        return None
    return math.sqrt(abs(det)) if math.isfinite(det) and det != 0 else None


# ---------------------------------------------------------------------------------------------- previews


def preview_shape(width: int, height: int, longest: int = PREVIEW_PX) -> Tuple[int, int]:
    """(rows, cols) of a preview of a ``width x height`` raster with the longest side ``longest``."""
    f = longest / float(max(width, height))
    return max(1, int(round(height * f))), max(1, int(round(width * f)))


def read_preview(info: RasterInfo, band: Optional[int]) -> Preview:
    """Read ``info`` (the band or RGB luminance the registration used) at preview size.

    Larger rasters are decimated by the read; smaller ones are read whole and enlarged bilinearly,
    so that the drawings keep their size whatever the raster's.
    """
    rows, cols = preview_shape(info.width, info.height)
    shape = (min(rows, info.height), min(cols, info.width))
    image, valid = read_image(info, resolve_bands(info, band), out_shape=shape)
    if shape != (rows, cols):
        image = cv2.resize(image, (cols, rows), interpolation=cv2.INTER_LINEAR)
        valid = cv2.resize(valid.astype(np.uint8), (cols, rows), interpolation=cv2.INTER_NEAREST) > 0
    return Preview(stretch(image, valid), valid, (info.width / cols, info.height / rows))


def stretch(image: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """Linear 2-98 % stretch of the valid pixels to uint8; invalid pixels are black."""
    values = image[valid]
    if values.size == 0:
        return np.zeros(image.shape, np.uint8)
    lo, hi = np.percentile(values, [2.0, 98.0])
    hi = hi if hi > lo else lo + 1.0
    out = np.clip((image - lo) * (255.0 / (hi - lo)), 0, 255).astype(np.uint8)
    out[~valid] = 0
    return out


def warp_to_reference(model, tgt: Preview, ref: Preview) -> Tuple[np.ndarray, np.ndarray]:
    """The target preview resampled onto the reference preview grid through ``model``.

    The model (target px -> reference px) is inverted exactly at nodes every
    :data:`GRID_STEP_PX` preview pixels and bilinearly in between (an inverse map is smooth); the
    target's edge and mask are then applied pixel by pixel.

    Returns
    -------
    warped : (rows, cols) uint8
    valid : (rows, cols) bool
        False where the target does not cover the reference, or the model could not be inverted.
    """
    rows, cols = ref.shape
    nx, ny = max(2, math.ceil(cols / GRID_STEP_PX) + 1), max(2, math.ceil(rows / GRID_STEP_PX) + 1)
    node_x, node_y = np.linspace(0.5, cols - 0.5, nx), np.linspace(0.5, rows - 0.5, ny)
    gx, gy = np.meshgrid(node_x, node_y)
    full = ref.to_full(np.column_stack([gx.ravel(), gy.ravel()]))
    tgt_size = tgt.scale[0] * tgt.shape[1], tgt.scale[1] * tgt.shape[0]
    q, ok = invert_model(model, full, tgt_size, tolerance=0.1 * min(ref.scale))
    wx, wy = _hat_matrix(cols, node_x), _hat_matrix(rows, node_y)
    q = np.where(ok[:, None], q, 0.0)
    map_x = wy @ q[:, 0].reshape(ny, nx) @ wx.T
    map_y = wy @ q[:, 1].reshape(ny, nx) @ wx.T
    covered = (wy @ ok.reshape(ny, nx).astype(float) @ wx.T) > 0.999
    map_x = (map_x / tgt.scale[0] - 0.5).astype(np.float32)
    map_y = (map_y / tgt.scale[1] - 0.5).astype(np.float32)
    warped = cv2.remap(tgt.image, map_x, map_y, cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    inside = cv2.remap(tgt.valid.astype(np.uint8), map_x, map_y, cv2.INTER_NEAREST,
                       borderMode=cv2.BORDER_CONSTANT, borderValue=0) > 0
    return warped, inside & covered


def _hat_matrix(n: int, nodes: np.ndarray) -> np.ndarray:
    """(n, len(nodes)) weights of linear interpolation between evenly spaced ``nodes`` at pixel
    centres ``i + 0.5``."""
    x = np.arange(n) + 0.5
    spacing = nodes[1] - nodes[0]
    return np.maximum(0.0, 1.0 - np.abs(x[:, None] - nodes[None, :]) / spacing)


# ---------------------------------------------------------------------------------------------- figures


def _png(image: np.ndarray) -> str:
    """A data URI of a drawing (sharp lines, few colours: PNG)."""
    ok, buf = cv2.imencode(".png", image, [cv2.IMWRITE_PNG_COMPRESSION, 3])
    if not ok:
        raise ValueError("could not encode a report image as PNG")
    return "data:image/png;base64," + base64.b64encode(buf.tobytes()).decode("ascii")


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


def histogram_figure(residuals: np.ndarray, rmse: Optional[float], size=(640, 280)) -> np.ndarray:
    """Bar chart of residual magnitudes (reference px) with the RMSE marked, drawn with OpenCV."""
    w, h = size
    left, right, top, bottom = 52, 20, 34, 44
    img = np.full((h, w, 3), 255, np.uint8)
    step = _nice(max(float(residuals.max()), 1e-3) / 5)
    hi = step * max(1, math.ceil(float(residuals.max()) / step - 1e-9))
    n_bins = int(np.clip(round(math.sqrt(len(residuals))), 5, 30))
    counts, _ = np.histogram(residuals, bins=n_bins, range=(0.0, hi))
    cmax = max(int(counts.max()), 1)
    pw, ph = w - left - right, h - top - bottom
    black = (0, 0, 0)
    for i, c in enumerate(counts):
        x0, x1 = left + i * pw / n_bins, left + (i + 1) * pw / n_bins
        y0 = h - bottom - c / cmax * ph
        cv2.rectangle(img, (int(x0), int(y0)), (int(x1) - 1, h - bottom), (180, 120, 40), -1)
    cv2.line(img, (left, h - bottom), (w - right, h - bottom), black, 1)
    cv2.line(img, (left, top), (left, h - bottom), black, 1)
    for t in np.arange(0.0, hi + step / 2, step):
        x = int(left + t / hi * pw)
        cv2.line(img, (x, h - bottom), (x, h - bottom + 4), black, 1)
        _text(img, f"{t:g}", (x, h - bottom + 18), center=True)
    for c in sorted({0, cmax // 2, cmax}):
        y = int(h - bottom - c / cmax * ph)
        cv2.line(img, (left - 4, y), (left, y), black, 1)
        _text(img, str(c), (left - 8, y + 4), right=True)
    _text(img, "residual (reference px)", (left + pw // 2, h - 8), center=True)
    _text(img, "GCPs", (6, 14))
    if rmse is not None and np.isfinite(rmse):
        x = int(left + min(rmse, hi) / hi * pw)
        cv2.line(img, (x, top - 4), (x, h - bottom), (40, 40, 200), 2)
        _text(img, f"RMSE {rmse:.2f}", (min(x + 5, w - 90), top - 10), colour=(40, 40, 200))
    return img


def _text(img, text, org, center=False, right=False, colour=(0, 0, 0)) -> None:
    font, scale = cv2.FONT_HERSHEY_SIMPLEX, 0.45
    (tw, _), _ = cv2.getTextSize(text, font, scale, 1)
    x = org[0] - tw // 2 if center else org[0] - tw if right else org[0]
    cv2.putText(img, text, (x, org[1]), font, scale, colour, 1, cv2.LINE_AA)


def checkerboard_figure(ref: Preview, warped: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """Alternating tiles of the reference (grey) and the warped target (warm tint); target tiles
    the target does not cover show the reference darkened."""
    rows, cols = ref.shape
    tile = max(8, int(round(max(rows, cols) / CHECKER_TILES)))
    yy, xx = np.mgrid[0:rows, 0:cols]
    target_tile = ((yy // tile + xx // tile) % 2) == 1
    img = cv2.cvtColor(ref.image, cv2.COLOR_GRAY2BGR)
    show = target_tile & valid
    tint = np.array([0.78, 0.9, 1.0])  # BGR: warm
    img[show] = (warped[show][:, None] * tint).astype(np.uint8)
    empty = target_tile & ~valid
    img[empty] = (img[empty] * 0.35).astype(np.uint8)
    return img


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


def swipe_top(warped: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """The warped target as BGRA, transparent where it does not cover the reference."""
    out = cv2.cvtColor(warped, cv2.COLOR_GRAY2BGRA)
    out[..., 3] = np.where(valid, 255, 0).astype(np.uint8)
    return out


# ---------------------------------------------------------------------------------------------- HTML

CSS = """
body{font:15px/1.45 system-ui,-apple-system,'Segoe UI',Roboto,sans-serif;color:#1d1d1f;margin:0;background:#f5f5f4}
main{max-width:1360px;margin:0 auto;padding:20px 24px 40px}
h1{font-size:24px;margin:0 0 4px}h2{font-size:18px;margin:28px 0 10px;border-bottom:1px solid #ccc;padding-bottom:4px}
.sub{color:#555;margin:0 0 14px}.sub b{color:#1d1d1f}
.verdict{border-left:8px solid;border-radius:6px;padding:12px 16px;margin:12px 0}
.verdict .word{font-size:26px;font-weight:700;letter-spacing:.02em;text-transform:uppercase}
.verdict ul{margin:6px 0 0 18px;padding:0}.note{color:#444;font-size:14px}
.grid{display:grid;grid-template-columns:repeat(auto-fit,minmax(440px,1fr));gap:18px;align-items:start}
figure{margin:0;background:#fff;border:1px solid #ddd;border-radius:6px;padding:10px}
figure img{display:block;max-width:100%;height:auto;image-rendering:auto}
figcaption{font-size:13.5px;color:#333;margin-top:8px}
.swatch{display:inline-block;font-weight:700;padding:0 2px}
table{border-collapse:collapse;font-size:13.5px;background:#fff}
td,th{border:1px solid #ddd;padding:3px 8px;text-align:left;vertical-align:top}
th{background:#f0f0ee}td.n{text-align:right;font-variant-numeric:tabular-nums}
.swipebox{display:inline-block;max-width:100%}.swipe{position:relative}
.swipe img.top{position:absolute;left:0;top:0;width:100%;height:100%;clip-path:inset(0 50% 0 0)}
.swipe+input{display:block;width:100%;margin:8px 0 0;box-sizing:border-box}
.bar{display:inline-block;width:140px;height:10px;vertical-align:middle;border:1px solid #999;margin:0 4px}
details summary{cursor:pointer;color:#555}code{font-size:12.5px;word-break:break-all}
footer{margin-top:30px;color:#777;font-size:12.5px}
.banner{border:2px solid #1f5fa8;background:#e6f0fb;color:#123e6e;font-weight:600;border-radius:6px;
padding:10px 14px;margin:12px 0}
.facts table{width:100%}.facts th{width:260px;font-weight:600}.files{margin:0;padding-left:18px}
.facts{max-width:980px}.plain ul{margin:0;padding-left:20px}.plain li{margin:0 0 6px}
.tech{font-size:13px;margin-top:6px}
"""


def _e(value) -> str:
    return html.escape(str(value), quote=True)


def _num(value, fmt: str = ".3f", unit: str = "") -> str:
    """A number for the page; '–' when missing or not finite."""
    if value is None:
        return "–"
    if isinstance(value, (bool, str)):
        return _e(value)
    f = float(value)
    return _e(format(f, fmt) + unit) if math.isfinite(f) else "–"


def _rows(pairs: Iterable[Tuple[str, str]], numeric: bool = True) -> str:
    """A two-column table; values are HTML already escaped by the caller; ``numeric`` right-aligns them."""
    td = "<td class=n>" if numeric else "<td>"
    return "<table>" + "".join(f"<tr><th>{_e(k)}</th>{td}{v}</td></tr>" for k, v in pairs) + "</table>"


def _table(header: Sequence[str], rows: Iterable[Sequence[str]], numeric: Sequence[bool] = ()) -> str:
    """A table with ``header``; cells are escaped HTML; ``numeric`` right-aligns columns."""
    head = "".join(f"<th>{_e(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td{' class=n' if i < len(numeric) and numeric[i] else ''}>{c}</td>"
                                     for i, c in enumerate(r)) + "</tr>" for r in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def _figure(src: str, alt: str, caption: str, width: int, height: int) -> str:
    return (f'<figure><img src="{src}" alt="{_e(alt)}" width={width} height={height}>'
            f"<figcaption>{caption}</figcaption></figure>")


def _swatch(bgr, symbol: str, label: str) -> str:
    b, g, r = bgr
    return f'<span class=swatch style="color:rgb({r},{g},{b});text-shadow:0 0 1px #000">{symbol}</span> {_e(label)}'


def _page(result, ref: Preview, tgt: Preview, warped: np.ndarray, warped_ok: np.ndarray,
          outputs: Mapping[str, str], written: datetime) -> str:
    name_t, name_r = os.path.basename(result.target.path), os.path.basename(result.reference.path)
    scale = map_scale(result)
    parts = [
        "<!DOCTYPE html><html lang=en><head><meta charset=utf-8>",
        f"<title>Hamta report: {_e(name_t)} onto {_e(name_r)}</title><style>{CSS}</style></head><body><main>",
        _header(result, name_t, name_r, scale),
        _facts(result, scale, outputs, written),
        _gcp_section(result, ref, tgt),
        _residual_section(result, ref),
        _overlay_section(ref, warped, warped_ok),
        _verification_section(result, ref, scale),
        _numbers_section(result, scale),
        _gcp_table(result, scale),
        f"<footer>Hamta {_e(__version__)} · written {_e(_iso(written))}"
        + (f" · run {_e(result.run_id)}" if result.run_id else "") + "</footer></main></body></html>\n",
    ]
    return "\n".join(parts)


PIXEL_MODE_BANNER = ("Pixel-to-pixel registration: the reference has no georeferencing, so coordinates are reference "
                     "pixels and the outputs carry no CRS")
NO_CRS = "none (pixel mode)"


def _iso(when: datetime) -> str:
    """``2026-06-01T12:34:56Z``: UTC, ISO 8601, to the second."""
    return when.astimezone(timezone.utc).replace(tzinfo=None).isoformat(timespec="seconds") + "Z"


def _header(result, name_t: str, name_r: str, scale: Optional[MapScale]) -> str:
    v = result.verification
    verdict = "not checked" if v is None else v.verdict
    fg, bg = VERDICT_CSS.get(verdict, VERDICT_CSS["not checked"])
    reasons = "" if v is None or not v.reasons else "<ul>" + "".join(f"<li>{_e(r)}</li>" for r in v.reasons) + "</ul>"
    if v is None:
        detail = "The independent check was not run."
    else:
        detail = (f"Accuracy asked for: <b>{_both(v.tolerance_px, scale)}</b> · estimated error: "
                  f"<b>{_both(v.error_px, scale)}</b> · error bound (estimate plus a safety margin): "
                  f"<b>{_both(v.error_bound_px, scale)}</b>" + ("" if scale else " (reference px)"))
    banner = "" if not result.pixel_mode else f"<div class=banner>{_e(PIXEL_MODE_BANNER)}</div>"
    return (f"<h1>Registration report</h1><p class=sub>Target <b title=\"{_e(result.target.path)}\">{_e(name_t)}</b> "
            f"onto reference <b title=\"{_e(result.reference.path)}\">{_e(name_r)}</b> · method <b>{_e(result.method)}"
            f"</b> · model <b>{_e(result.model.kind)}</b></p>{banner}"
            f'<div class=verdict style="border-color:{fg};background:{bg}"><span class=word style="color:{fg}">'
            f"{_e(verdict)}</span>{reasons}<div>{detail}</div></div>"
            "<p class=note>The RMSE of the GCPs measures how consistent the points are with the model, not how "
            "accurate the registration is. The verdict and the error bound come from an independent check at sites "
            "the model was not fitted on (section 4).</p>")


OUTPUT_LABELS = {"raster": "registered raster", "points": "GCPs for the QGIS Georeferencer (.points)",
                 "gpkg": "GCP layer (GeoPackage)", "vrt": "GCP VRT", "report": "report (JSON)",
                 "html": "this report"}


def _facts(result, scale: Optional[MapScale], outputs: Mapping[str, str], written: datetime) -> str:
    """The run at a glance: CRS, pixel sizes, accuracy in map units, date, files written."""
    ref, tgt, v = result.reference, result.target, result.verification
    if scale is None:
        crs, ref_size = _e(NO_CRS), _e(NO_CRS + ": lengths are in reference px")
    else:
        crs = _e(scale.crs) + f" · unit: {_e(scale.unit_name)}"
        ref_size = _sizes(axis_sizes(ref), scale.unit) + " per px"
    if tgt.georeferenced and tgt.crs is not None:
        t_crs, t_unit = describe_crs(tgt.crs)
        t_sym = MapScale(t_crs, t_unit, tgt.pixel_size).unit
        t_own = (_sizes(axis_sizes(tgt), t_sym) + f" per px in {_e(t_crs)}"
                 + (" (georeferenced by GCPs)" if tgt.georef_source == "gcps" else ""))
    else:
        t_own = "not georeferenced"
    k = registered_scale(result)
    if k is None:
        t_reg = "–"
    elif scale is None:
        t_reg = _e(f"{k:.4g} reference px per target px")
    else:
        t_reg = f"{scale.px(k)} per px ({_e(f'{k:.4g}')} reference px per target px, at the target centre)"
    rmse = result.stats.get("rmse_px")
    rows = [("reference CRS", crs), ("reference pixel size", ref_size),
            ("target pixel size, own georeferencing", t_own), ("target pixel size, as registered", t_reg),
            ("GCP RMSE", _both(rmse, scale, ".3f")),
            ("estimated error (independent check)", "not checked" if v is None else _both(v.error_px, scale)),
            ("error bound (independent check)", "not checked" if v is None else _both(v.error_bound_px, scale)),
            ("date (UTC)", f"<time datetime=\"{_e(_iso(written))}\">{_e(_iso(written))}</time>")]
    if result.run_id:
        rows.append(("run id", _e(result.run_id)))
    if outputs:
        items = "".join(f"<li>{_e(OUTPUT_LABELS.get(kind, kind))}: <code>{_e(path)}</code></li>"
                        for kind, path in outputs.items())
        rows.append(("files written", f"<ul class=files>{items}</ul>"))
    return "<div class=facts>" + _rows(rows, numeric=False) + "</div>"


def _sizes(sizes: Tuple[float, float], unit: str) -> str:
    """``'10.00 m'`` for square pixels, ``'10.00 × 12.00 m (x × y)'`` otherwise (escaped)."""
    sx, sy = sizes
    fmt = f".{_decimals(math.sqrt(sx * sy))}f"
    if abs(sx - sy) <= 1e-6 * max(sx, sy):
        return _num(sx, fmt, unit)
    return _e(f"{format(sx, fmt)} × {format(sy, fmt)}{unit} (x × y)")


def _split_gcps(gcps) -> Tuple[np.ndarray, ...]:
    """Target px, reference px and residuals of enabled GCPs, then target and reference px of rejected ones."""
    def arr(items, attr):
        return np.array([getattr(g, attr) for g in items], float).reshape(-1, 2)

    on, off = [g for g in gcps if g.enabled], [g for g in gcps if not g.enabled]
    return (arr(on, "target_px"), arr(on, "reference_px"), arr(on, "residual_xy"), arr(off, "target_px"),
            arr(off, "reference_px"))


def _gcp_section(result, ref: Preview, tgt: Preview) -> str:
    t_on, r_on, _, t_off, r_off = _split_gcps(result.gcps)
    legend = (f"{_swatch(ENABLED_BGR, '○', f'{len(t_on)} GCPs used for the fit')} · "
              f"{_swatch(REJECTED_BGR, '✕', f'{len(t_off)} rejected matches (listed for inspection)')}")
    figs = [_figure(_jpeg(gcp_figure(tgt, t_on, t_off)), "target with GCPs", f"Target. {legend}", *tgt.shape[::-1]),
            _figure(_jpeg(gcp_figure(ref, r_on, r_off)), "reference with GCPs", f"Reference. {legend}",
                    *ref.shape[::-1])]
    return "<h2>1. Images and GCPs</h2><div class=grid>" + "".join(figs) + "</div>"


def _residual_section(result, ref: Preview) -> str:
    _, r_on, res, _, r_off = _split_gcps(result.gcps)
    mag = np.hypot(res[:, 0], res[:, 1])
    if not len(mag):
        return "<h2>2. Residuals</h2><p>No enabled GCPs.</p>"
    factor = arrow_factor(mag, float(np.mean(ref.scale)))
    vmax = max(float(np.percentile(mag, 95)), 1e-6)
    stops = ",".join(f"rgb{c}" for c in RAMP_RGB)
    arrows = residual_figure(ref, r_on, res, factor, vmax)
    cap = (f"Residual of each GCP (model(target) − reference), drawn from its reference position and "
           f"<b>exaggerated {factor:g}×</b>. Colour: 0 <span class=bar style=\"background:linear-gradient(90deg,"
           f"{stops})\"></span> {_num(vmax, '.2f')} px and more. Residuals that point the same way in one area show "
           "a distortion the model does not follow.")
    hist_cap = (f"Residual magnitudes of the {len(mag)} enabled GCPs (reference px); the {len(r_off)} rejected "
                f"matches are left out. Max {_num(mag.max(), '.2f')} px.")
    hist = histogram_figure(mag, result.stats.get("rmse_px"))
    return ("<h2>2. Residuals</h2><div class=grid>"
            + _figure(_jpeg(arrows), "residual vectors", cap, *ref.shape[::-1])
            + _figure(_png(hist), "residual histogram", hist_cap, hist.shape[1], hist.shape[0]) + "</div>")


def _overlay_section(ref: Preview, warped: np.ndarray, valid: np.ndarray) -> str:
    rows, cols = ref.shape
    board = _figure(_jpeg(checkerboard_figure(ref, warped, valid)), "checkerboard",
                    "Checkerboard: grey tiles show the reference, warm tiles the target warped through the model "
                    "(darkened where the target does not reach). Edges and roads should run on across tiles.",
                    cols, rows)
    script = ("this.previousElementSibling.lastElementChild.style.clipPath="
              "'inset(0 '+(100-this.value)+'% 0 0)'")
    swipe = (f'<figure><div class=swipebox><div class=swipe><img src="{_jpeg(ref.image)}" alt="reference" '
             f'width={cols} height={rows}><img class=top src="{_jpeg(swipe_top(warped, valid))}" alt="warped target" '
             f'width={cols} height={rows}></div><input type=range min=0 max=100 value=50 aria-label="swipe" '
             f'oninput="{script}"></div>'
             "<figcaption>Swipe: the warped target left of the handle, the reference right of it. Drag the slider "
             "and watch whether features jump.</figcaption></figure>")
    return "<h2>3. Reference and warped target</h2><div class=grid>" + board + swipe + "</div>"


def _odds(p: float) -> str:
    """A small probability as 'about once in 40 000 tries' (plain words for an analyst)."""
    if not math.isfinite(p) or p >= 0.5:
        return "easily"
    if p < 1e-9:
        return "less than once in a billion tries"
    n = 1.0 / p
    digits = 10 ** max(0, math.floor(math.log10(n)) - 1)  # two significant digits
    n = round(n / digits) * digits
    if n >= 1e6:
        return f"about once in {n / 1e6:.2g} million tries"
    return f"about once in {n:,.0f} tries".replace(",", "\u2009")


def _plain_check(v, scale: Optional[MapScale]) -> List[str]:
    """The independent check in plain words, one sentence per item; numbers escaped."""
    params = VerifyParams(tolerance_px=v.tolerance_px)
    other = int(v.n_sites - np.count_nonzero(v.agree | v.contradict))
    if v.n_sites == 0:
        return ["No site of the overlap could be compared (too small an overlap, masked pixels, or no detail)."]

    def sites(n: int) -> str:
        return f"{n} site" + ("" if n == 1 else "s")

    out = [f"At <b>{v.n_agree} of {sites(v.n_sites)}</b> checked, the two images line up where the model puts them: "
           f"the best match lies within {_both(params.agree_px, scale, '.0f')} of the model's position."]
    if v.n_contradict:
        out.append(f"At <b>{sites(v.n_contradict)}</b> the images clearly match better somewhere else: the ground "
                   "changed there, or the model is wrong there.")
    else:
        out.append("No site clearly matches better somewhere else.")
    if other:
        out.append(f"{sites(other)} gave no clear answer (too little detail, such as water or uniform fields, or "
                   "changes between the images).")
    by_peaks = v.chance <= params.max_chance
    by_shape = v.z_chance <= params.max_z_chance and v.z_mw <= params.max_rank_chance
    if by_peaks:
        out.append(f"A wrong alignment of these two images would line up at so many sites {_odds(v.chance)}: "
                   "the agreement is real.")
    elif by_shape:
        out.append(f"At <b>{v.z_hits} of {v.n_sites}</b> sites the two images match better at the model's position "
                   f"than when shifted slightly; a wrong alignment would not do this ({_odds(v.z_chance)}).")
    else:
        out.append(f"A wrong alignment of these two images would line up this well {_odds(min(v.chance, v.z_chance))}"
                   ", so this agreement alone does not prove the model.")
    if v.error_px is not None and v.error_bound_px is not None:
        out.append(f"From the sites that line up, the error of the alignment is estimated at "
                   f"<b>{_both(v.error_px, scale)}</b>, and at most <b>{_both(v.error_bound_px, scale)}</b> with a "
                   f"safety margin; the accuracy asked for was {_both(v.tolerance_px, scale)}.")
    else:
        out.append("Too few sites line up to estimate the error of the alignment.")
    if v.coverage is not None and math.isfinite(v.coverage):
        out.append(f"The sites that support the model spread over {v.coverage * 100:.0f} % of the compared area's "
                   f"width and height (at least {params.min_coverage * 100:.0f} % is needed to vouch for the whole "
                   "image).")
    if v.corroboration:
        c = v.corroboration
        out.append(f"Confirmed by a second method: <b>{_e(c.get('method', ''))}</b> found an alignment that agrees "
                   f"with this one within {_both(c.get('distance_px'), scale)}, and the check partly supported each.")
    return out


def _verification_section(result, ref: Preview, scale: Optional[MapScale] = None) -> str:
    v = result.verification
    if v is None:
        return "<h2>4. Independent check</h2><p>Not run.</p>"
    other = int(v.n_sites - np.count_nonzero(v.agree | v.contradict))
    legend = (f"{_swatch(AGREE_BGR, '□', f'{v.n_agree} line up')} · "
              f"{_swatch(CONTRADICT_BGR, '□', f'{v.n_contradict} match better elsewhere')} · "
              f"{_swatch(OTHER_BGR, '□', f'{other} no clear answer')}")
    cap = (f"Check sites (squares of {v.template_px} reference px) on the reference: at each, the target placed by "
           f"the model is compared with the reference. {legend}.")
    plain = "<div class=plain><ul>" + "".join(f"<li>{sentence}</li>" for sentence in _plain_check(v, scale)) + "</ul>"
    rows = [("verdict", _e(v.verdict)), ("sites compared", str(v.n_sites)), ("agree", str(v.n_agree)),
            ("contradict", str(v.n_contradict)), ("clear (agree + contradict)", str(v.n_clear)),
            ("chance rate per site", _num(v.chance_rate, ".3f")),
            ("probability that chance agrees this often", _num(v.chance, ".2e")),
            ("coverage of the overlap", _num(v.coverage * 100 if v.coverage is not None else None, ".0f", " %")),
            ("estimated error", _num(v.error_px, ".2f", " px")), ("error bound", _num(v.error_bound_px, ".2f", " px")),
            ("local scatter", _num(v.scatter_px, ".2f", " px")), ("tolerance", _num(v.tolerance_px, ".2f", " px")),
            ("zero-offset lifts / chance / Mann–Whitney p",
             f"{v.z_hits} / {_num(v.z_chance, '.2e')} / {_num(v.z_mw, '.2e')}"),
            ("time", _num(v.time_s, ".2f", " s"))]
    if v.corroboration:
        rows.append(("corroborated by", _e(v.corroboration.get("summary", v.corroboration.get("method", "")))))
    details = ("<details class=tech><summary>Technical details of the check (the names used in report.json's "
               "<code>quality</code>)</summary>" + _rows(rows) + "</details></div>")
    img = sites_figure(ref, v)
    return ("<h2>4. Independent check</h2><div class=grid>" + _figure(_jpeg(img), "check sites", cap, *ref.shape[::-1])
            + plain + details + "</div>")


def _numbers_section(result, scale: Optional[MapScale] = None) -> str:
    s = result.stats
    stats = [("GCPs (enabled)", str(s.get("n_gcps", "–"))), ("RMSE", _both(s.get("rmse_px"), scale, ".3f")),
             ("leave-one-out RMS", _both(s.get("rms_loo_px"), scale, ".3f")),
             ("max residual", _both(s.get("max_residual_px"), scale, ".3f")),
             ("matches / inliers", f"{_e(s.get('n_matches', '–'))} / {_e(s.get('n_inliers', '–'))}"),
             ("keypoints target / reference",
              f"{_e(s.get('n_keypoints_target', '–'))} / {_e(s.get('n_keypoints_reference', '–'))}"),
             ("refined at full resolution", _e(s.get("refined", "–")))]
    times = [(k, _num(t, ".3f", " s")) for k, t in result.timings.items()]
    unit = "reference px" if scale is None else f"reference px and {scale.symbol}"
    out = ("<h2>5. Model and statistics</h2><div class=grid><div><h3>Model</h3>" + model_html(result.model)
           + f"</div><div><h3>GCP statistics ({_e(unit)})</h3>" + _rows(stats)
           + "<h3>Time per stage</h3>" + _rows(times) + "</div></div>")
    if result.notes:
        out += "<h3>Notes</h3><ul>" + "".join(f"<li>{_e(n)}</li>" for n in result.notes) + "</ul>"
    if result.auto:
        chosen = result.auto.get("chosen")
        rows = [(_e(a.get("method")) + (" <b>(chosen)</b>" if i == chosen else ""), _e(a.get("outcome")),
                 _num(a.get("time_s"), ".2f", " s"), _e(a.get("reason", ""))) for i, a in
                enumerate(result.auto.get("attempts", []))]
        out += "<h3>Attempts of <code>auto</code></h3>" + _table(["method", "outcome", "time", "reason"], rows,
                                                                 [False, False, True])
    return out


def model_html(model) -> str:
    """The model's ``to_dict`` form as tables: small matrices in full, long arrays counted."""
    d = model.to_dict()
    rows = []
    for key, value in d.items():
        if isinstance(value, dict):
            rows.append((key, _dict_html(value)))
        elif value is not None:
            rows.append((key, _value_html(value)))
    return _rows(rows)


def _dict_html(d: dict) -> str:
    if {"terms", "coefficients_x", "coefficients_y"} <= set(d):
        coef = [(_e(t), _num(x, ".6g"), _num(y, ".6g")) for t, x, y in
                zip(d["terms"], d["coefficients_x"], d["coefficients_y"])]
        rest = {k: v for k, v in d.items() if k not in ("terms", "coefficients_x", "coefficients_y")}
        table = _table(["term", "x", "y"], coef, [False, True, True])
        return _rows((k, _value_html(v)) for k, v in rest.items()) + table
    return _rows((k, _value_html(v)) for k, v in d.items())


def _value_html(value) -> str:
    """Numbers formatted, small matrices as tables, long lists counted, long text folded."""
    if value is None or isinstance(value, bool):
        return _num(value)
    if isinstance(value, (int, float)):
        return _num(value, ".6g")
    if isinstance(value, str):
        if len(value) > 80:
            return f"<details><summary>{_e(value[:60])}…</summary><code>{_e(value)}</code></details>"
        return _e(value)
    a = np.asarray(value, dtype=object)
    if a.ndim == 2 and a.shape[0] <= 10 and a.shape[1] <= 10:
        return "<table>" + "".join("<tr>" + "".join(f"<td class=n>{_num(float(x), '.6g')}</td>" for x in row)
                                   + "</tr>" for row in a) + "</table>"
    if a.ndim == 1 and len(a) <= 10:
        return ", ".join(_value_html(x) for x in value)
    return _e(f"{' × '.join(map(str, a.shape))} values (in report.json)")


def _gcp_table(result, scale: Optional[MapScale] = None) -> str:
    gcps = result.gcps
    dec = _decimals(1.0 if scale is None else scale.pixel_size)
    rows = [(str(i + 1), "yes" if g.enabled else "no", _num(g.target_px[0], ".2f"), _num(g.target_px[1], ".2f"),
             _num(g.map_xy[0], f".{dec}f"), _num(g.map_xy[1], f".{dec}f"), _num(g.residual_px, ".3f"))
            + (() if scale is None else (_num(g.residual_px * scale.pixel_size, f".{dec}f"),))
            for i, g in enumerate(gcps[:MAX_TABLE_ROWS])]
    units = "reference px" if scale is None else f"reference CRS, {scale.symbol}"
    header = ["id", "enabled", "target x", "target y", f"map X ({units})", f"map Y ({units})", "residual (px)"]
    if scale is not None:
        header.append(f"residual ({scale.symbol})")
    omitted = len(gcps) - len(rows)
    more = f"<p>{omitted} more rows not shown (all are in report.json and the GCP files).</p>" if omitted > 0 else ""
    return ("<h2>6. GCPs</h2><p class=note>Target px (x = column, y = row, from the top-left corner); residual = "
            "|model(target) − reference| in reference px" + ("" if scale is None else " and map units") + ".</p>"
            + _table(header, rows, [True, False, True, True, True, True, True, True]) + more)
