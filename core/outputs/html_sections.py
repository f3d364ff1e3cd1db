"""The report's numbered sections (1-6): images and GCPs, residuals, reference and warped target,
the independent check, model and statistics, the GCP table. Figures are drawn on the previews
(full-resolution target or reference px), residuals and check lengths are in reference px and, with
a map scale, in map units; the GCP table gives target px, map coordinates (reference CRS, or
reference px in pixel mode) and residuals.
"""
from __future__ import annotations

from typing import Optional, Tuple

import numpy as np

from .figures import (
    AGREE_BGR,
    CONTRADICT_BGR,
    ENABLED_BGR,
    OTHER_BGR,
    RAMP_RGB,
    REJECTED_BGR,
    _jpeg,
    _svg,
    arrow_factor,
    checkerboard_figure,
    gcp_figure,
    histogram_svg,
    residual_figure,
    sites_figure,
    swipe_top,
)
from .html_text import _e, _figure, _num, _rows, _swatch, _table
from .plain_check import _plain_check
from .preview import Preview
from .scale import MapScale, _both, _decimals

MAX_TABLE_ROWS = 200  # GCP rows listed; the rest are counted


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
    width, height = 640, 280
    hist = histogram_svg(mag, result.stats.rmse_px, (width, height))
    return ("<h2>2. Residuals</h2><div class=grid>"
            + _figure(_jpeg(arrows), "residual vectors", cap, *ref.shape[::-1])
            + _figure(_svg(hist), "residual histogram", hist_cap, width, height) + "</div>")


def _overlay_section(ref: Preview, warped: np.ndarray, valid: np.ndarray) -> str:
    rows, cols = ref.shape
    board = _figure(_jpeg(checkerboard_figure(ref, warped, valid)), "checkerboard",
                    "Checkerboard: grey tiles show the reference, warm tiles the target warped through the model "
                    "(darkened where the target does not reach). Edges and roads should run on across tiles.",
                    cols, rows)
    script = ("this.previousElementSibling.lastElementChild.style.clipPath="
              "'inset(0 '+(100-this.value)+'% 0 0)'")
    top = _jpeg(swipe_top(ref, warped, valid))
    swipe = (f'<figure><div class=swipebox><div class=swipe><img src="{_jpeg(ref.image)}" alt="reference" '
             f'width={cols} height={rows}><img class=top src="{top}" alt="warped target" '
             f'width={cols} height={rows}></div><input type=range min=0 max=100 value=50 aria-label="swipe" '
             f'oninput="{script}"></div>'
             "<figcaption>Swipe: the warped target left of the handle, the reference right of it. Drag the slider "
             "and watch whether features jump.</figcaption></figure>")
    return "<h2>3. Reference and warped target</h2><div class=grid>" + board + swipe + "</div>"


def _verification_section(result, ref: Preview, scale: Optional[MapScale] = None) -> str:
    v = result.verification
    if v is None:
        return "<h2>4. Independent check</h2><p>Not run.</p>"
    if v.check == "grid-held-out-lines":
        from .grid_check import grid_check_section

        return grid_check_section(result, ref, scale)
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
    s = result.stats.to_dict()
    stats = [("GCPs (enabled)", str(s.get("n_gcps", "–"))), ("RMSE", _both(s.get("rmse_px"), scale, ".3f")),
             ("leave-one-out RMS", _both(s.get("rms_loo_px"), scale, ".3f")),
             ("max residual", _both(s.get("max_residual_px"), scale, ".3f")),
             ("matches / inliers", f"{_e(s.get('n_matches', '–'))} / {_e(s.get('n_inliers', '–'))}"),
             ("keypoints target / reference",
              f"{_e(s.get('n_keypoints_target', '–'))} / {_e(s.get('n_keypoints_reference', '–'))}"),
             ("refined at full resolution", _e(s.get("refined", "–")))]
    times = [(k, _num(t, ".3f", " s")) for k, t in result.timings.to_dict().items()]
    unit = "reference px" if scale is None else (f"{scale.px_name} and {scale.symbol}" if scale.ground is None
                                                 else f"{scale.px_name} and m on the ground")
    out = ("<h2>5. Model and statistics</h2><div class=grid><div><h3>Model</h3>" + model_html(result.model)
           + f"</div><div><h3>GCP statistics ({_e(unit)})</h3>" + _rows(stats)
           + "<h3>Time per stage</h3>" + _rows(times) + "</div></div>")
    if result.notes:
        out += "<h3>Notes</h3><ul>" + "".join(f"<li>{_e(n)}</li>" for n in result.notes) + "</ul>"
    if result.auto:
        rows = [(_e(a.method) + (" <b>(chosen)</b>" if i == result.auto.chosen else ""), _e(a.outcome),
                 _num(a.time_s, ".2f", " s"), _e(a.reason)) for i, a in enumerate(result.auto.attempts)]
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
    ground = 1.0 if scale is None or scale.ground is None else scale.ground  # Web Mercator m -> ground m
    rows = [(str(i + 1), "yes" if g.enabled else "no", _num(g.target_px[0], ".2f"), _num(g.target_px[1], ".2f"),
             _num(g.map_xy[0], f".{dec}f"), _num(g.map_xy[1], f".{dec}f"), _num(g.residual_px, ".3f"))
            + (() if scale is None else (_num(g.residual_px * scale.pixel_size * ground, f".{dec}f"),))
            for i, g in enumerate(gcps[:MAX_TABLE_ROWS])]
    units = "reference px" if scale is None else f"reference CRS, {scale.symbol}"
    header = ["id", "enabled", "target x", "target y", f"map X ({units})", f"map Y ({units})", "residual (px)"]
    if scale is not None:
        header.append(f"residual ({scale.symbol})" if scale.ground is None else "residual (m on the ground)")
    omitted = len(gcps) - len(rows)
    more = f"<p>{omitted} more rows not shown (all are in report.json and the GCP files).</p>" if omitted > 0 else ""
    also = "" if scale is None else " and map units" if scale.ground is None else " and metres on the ground"
    return ("<h2>6. GCPs</h2><p class=note>Target px (x = column, y = row, from the top-left corner); residual = "
            "|model(target) − reference| in reference px" + also + ".</p>"
            + _table(header, rows, [True, False, True, True, True, True, True, True]) + more)
