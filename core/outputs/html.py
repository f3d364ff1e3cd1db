"""``report.html``: a self-contained visual report of one registration, read by looking.

One HTML file with inline CSS, a single line of inline JavaScript (the swipe handle) and every image
embedded (base64 JPEG pictures, an SVG chart), so it can be mailed or archived alone. It shows the verdict of the
independent check first, then the two rasters with their GCPs, the residual vectors and their
histogram, a checkerboard and a swipe view of the reference against the target warped through the
model, the verification sites, and the numbers (model, statistics, timings, the ``auto`` attempts,
the GCP table). Lengths are given in reference pixels and in the reference CRS's unit (metres,
degrees...), next to the CRS, the pixel sizes, the date and the files written; in pixel mode (a
reference without georeferencing) a banner says that coordinates are reference pixels.

This module holds the page: its head (title, CSS, verdict, facts at a glance) and footer, and
:func:`write_html_report`. The previews and their coordinates are in
:mod:`hamta.core.outputs.preview`, the drawings in :mod:`hamta.core.outputs.figures`, map units in
:mod:`hamta.core.outputs.scale`, the numbered sections in :mod:`hamta.core.outputs.html_sections`.
"""
from __future__ import annotations

import math
import os
from datetime import datetime, timezone
from typing import Mapping, Optional, Tuple

import numpy as np

from ..advice import advice, spelled
from ..progress import Monitor
from ..version import __version__
from .html_sections import (
    _gcp_section,
    _gcp_table,
    _numbers_section,
    _overlay_section,
    _residual_section,
    _verification_section,
)
from .html_text import _e, _num, _rows
from .preview import Preview, read_preview, warp_to_reference
from .scale import MapScale, _both, _decimals, axis_sizes, describe_crs, map_scale, registered_scale

VERDICT_CSS = {"verified": ("#1b7f3b", "#e3f4e8"), "suspect": ("#9a5b00", "#fff1d0"),
               "failed": ("#b3261e", "#fde4e1"), "not checked": ("#555555", "#eeeeee")}


def write_html_report(path: str, result, monitor: Optional[Monitor] = None, *,
                      outputs: Optional[Mapping[str, str]] = None, previews=None) -> None:
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
    previews : (Preview, Preview), optional
        The reference's and the target's previews (:func:`read_previews`), when already read.

    Notes
    -----
    Each raster is read once at preview size (longest side
    :data:`~hamta.core.outputs.preview.PREVIEW_PX` px); a 1000 px pair takes a fraction of a second,
    and larger rasters cost only the decimated read. The page is dated with the time of writing (UTC).
    """
    monitor = monitor or Monitor()
    monitor.report(0.0, "report: previews")
    ref, tgt = previews or read_previews(result)
    monitor.report(0.4, "report: warping the target")
    warped, warped_ok = warp_to_reference(result.model, tgt, ref)
    monitor.report(0.6, "report: figures")
    written = datetime.now(timezone.utc).replace(microsecond=0)
    page = _page(result, ref, tgt, warped, warped_ok, outputs or {}, written)
    monitor.check()
    with open(path, "w", encoding="utf-8") as f:
        f.write(page)
    monitor.report(1.0, "report written")


def read_previews(result) -> tuple:
    """The reference's and the target's previews (the bands the registration used)."""
    return (read_preview(result.reference, result.options.get("reference_band")),
            read_preview(result.target, result.options.get("target_band")))


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


def _page(result, ref: Preview, tgt: Preview, warped: np.ndarray, warped_ok: np.ndarray,
          outputs: Mapping[str, str], written: datetime) -> str:
    name_t, name_r = os.path.basename(result.target.path), os.path.basename(result.reference.path)
    service = result.reference_service
    if service:
        name_r = f"{service['service']} (zoom {service['zoom']}, {service['fetch']['requests']} requests)"
    scale = map_scale(result)
    parts = [
        "<!DOCTYPE html><html lang=en><head><meta charset=utf-8>",
        f"<title>Hamta report: {_e(name_t)} onto {_e(name_r)}</title><style>{CSS}</style></head><body><main>",
        _header(result, name_t, name_r, scale, outputs or {}),
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


KEPT = ("Kept anyway ('Keep unverified results'): the outputs were written although the check did not confirm "
        "them, and each is marked NOT VERIFIED; look at the overlays below before using them.")


def _header(result, name_t: str, name_r: str, scale: Optional[MapScale], outputs: Mapping[str, str]) -> str:
    v = result.verification
    verdict = "not checked" if v is None else v.verdict
    fg, bg = VERDICT_CSS.get(verdict, VERDICT_CSS["not checked"])
    reasons = "" if v is None or not v.reasons else "<ul>" + "".join(f"<li>{_e(r)}</li>" for r in v.reasons) + "</ul>"
    kept = v is not None and not v.verified and "raster" in outputs
    if kept:
        reasons += f"<div>{_e(KEPT)}</div>"
    tips = [t for t in advice(result) if not (kept and t.option == "accept_unverified")]
    if tips:
        reasons += "<div>What may help:</div><ul>" + "".join(
            f"<li><code>{_e(spelled(t))}</code>: {_e(t.why)}</li>" for t in tips) + "</ul>"
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
        if scale.ground is not None:
            ground = tuple(size * scale.ground for size in axis_sizes(ref))
            ref_size = (_sizes(ground, " m") + f" per px on the ground at {_e(_latitude(scale.latitude))} ("
                        + _sizes(axis_sizes(ref), " Web Mercator m") + ")")
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
    elif scale.ground is None:
        t_reg = f"{scale.px(k)} per px ({_e(f'{k:.4g}')} {_e(scale.px_name)} per target px, at the target centre)"
    else:
        size = k * scale.pixel_size
        t_reg = (_sizes((size * scale.ground,) * 2, " m") + " per px on the ground ("
                 + _sizes((size,) * 2, " Web Mercator m")
                 + f"; {_e(f'{k:.4g}')} {_e(scale.px_name)} per target px, at the target centre)")
    rmse = result.stats.rmse_px
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


def _latitude(degrees: float) -> str:
    """``'53.0° N'``, ``'33.9° S'``."""
    return f"{abs(degrees):.1f}° {'N' if degrees >= 0 else 'S'}"


def _sizes(sizes: Tuple[float, float], unit: str) -> str:
    """``'10.00 m'`` for square pixels, ``'10.00 × 12.00 m (x × y)'`` otherwise (escaped)."""
    sx, sy = sizes
    fmt = f".{_decimals(math.sqrt(sx * sy))}f"
    if abs(sx - sy) <= 1e-6 * max(sx, sy):
        return _num(sx, fmt, unit)
    return _e(f"{format(sx, fmt)} × {format(sy, fmt)}{unit} (x × y)")
