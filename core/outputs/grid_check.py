"""The report's section 4 for a sheet georeferenced by its own printed grid: the check that was made, in its own
words (:mod:`hamta.core.grid.check`): each grid line held out, the model each kind of model gives, the plane the
graticule is drawn in, the lattice's evidence and how the labels agree. The figure shows the crossings on the
frame (reference px), each coloured by how far the model fitted without its grid line puts it."""
from __future__ import annotations

from typing import Optional

import numpy as np

from .figures import AGREE_BGR, CONTRADICT_BGR, _canvas, _fixed
from .html_text import _e, _figure, _num, _rows, _swatch, _table
from .preview import Preview
from .scale import MapScale


def grid_check_section(result, ref: Preview, scale: Optional[MapScale] = None) -> str:
    from .figures import _jpeg

    v = result.verification
    agree = v.agree
    plain = [f"Each of the <b>{sum(v.lines)}</b> grid lines ({v.lines[0]} of constant x, {v.lines[1]} of constant y) "
             f"was left out in turn and its crossings predicted by the {_e(v.model)} model fitted on the others: "
             f"<b>{v.held_out_scan_px:.2f} scan px RMS</b>, the worst line {_num(v.worst_line_scan_px, '.2f')} px "
             f"(accuracy asked for: {v.tolerance_scan_px:g} scan px).",
             f"{v.crossings} crossings (and ticks on the frame) cover {v.coverage:.0%} of the sheet; "
             f"{v.share_found:.0%} of those the lattice puts among them were found on printed lines.",
             f"The graticule or grid is drawn in: <b>{_e(v.plane)}</b>"
             + ("" if v.plane_affine_scan_px is None else
                f" (an affine there predicts each line held out within {v.plane_affine_scan_px:.2f} scan px)") + "."]
    if v.labels is not None:
        plain.append("The labels read agree with the grid found on {} lines of x and {} of y (at least 2 each way, "
                     "so that one misread label cannot move the sheet){}.".format(
                         *v.labels.agreeing, "" if not any(v.labels.contradicting) else
                         "; contradicting: " + ", ".join(_e(t) for axis in v.labels.contradicting for t in axis[:4])))
    legend = (f"{_swatch(AGREE_BGR, '●', 'within the accuracy asked for')} · "
              f"{_swatch(CONTRADICT_BGR, '●', 'beyond it')}")
    models = _table(["model", "each line held out (scan px RMS)"],
                    [[_e(k), _num(val / max(v.tolerance_px / v.tolerance_scan_px, 1e-12), ".2f")]
                     for k, val in v.models.items()], [False, True])
    rows = [("verdict", _e(v.verdict)), ("check", _e(v.check)), ("step", _e(v.step_text)),
            ("lines held out (x, y)", f"{v.lines[0]}, {v.lines[1]}"),
            ("held-out RMS", _num(v.held_out_scan_px, ".2f", " scan px")),
            ("tolerance", _num(v.tolerance_scan_px, ".2f", " scan px")),
            ("lattice", _e(_lattice_text(v.evidence))), ("time", _num(v.time_s, ".2f", " s"))]
    img = _crossings_figure(ref, v.sites_xy, agree)
    cap = f"Crossings found, on the frame drawn in the output CRS: {legend}."
    return ("<h2>4. The grid's own check</h2><div class=grid>" + _figure(_jpeg(img), "crossings", cap, *ref.shape[::-1])
            + "<div class=plain><ul>" + "".join(f"<li>{p}</li>" for p in plain) + "</ul>" + models
            + "<details class=tech><summary>Technical details (report.json's <code>quality</code>)</summary>"
            + _rows(rows) + "</details></div></div>")


def _lattice_text(evidence: dict) -> str:
    families = evidence.get("families") or []
    text = " · ".join(f"{f['printed']} of {f['lines']} lines of constant {f['axis']} printed" for f in families)
    return f"{text} (chance {evidence.get('chance_probability', float('nan')):.0e})"


def _crossings_figure(ref: Preview, xy, agree) -> np.ndarray:
    import cv2

    img = _canvas(ref, 0.6)
    for mask, colour in ((~agree, CONTRADICT_BGR), (agree, AGREE_BGR)):
        for p in np.asarray(xy)[mask]:
            (a,) = _fixed(ref.to_opencv([p]))
            cv2.circle(img, a, 4 << 4, (0, 0, 0), 3, cv2.LINE_AA, 4)
            cv2.circle(img, a, 4 << 4, colour, 2, cv2.LINE_AA, 4)
    return img
