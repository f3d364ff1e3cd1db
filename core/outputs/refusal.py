"""The report of a run that found nothing to register (:class:`hamta.core.errors.Refused`): ``report.json`` and
``report.html`` say what was read and tried and why the method stopped, so that the user (and we) can see it.

A refusal's ``report.json`` has ``outcome`` ``refused``, the ``reason``, the ``target`` and the method's
``findings`` (for a sheet by its grid: every label read with its text, value, place and whether it was kept
or why not, the hints made of them, the lattices tried and what the scan said of each), beside ``request``,
``run_id``, ``outputs`` and ``versions`` as in any report (docs/report.md).
"""
from __future__ import annotations

import os
import uuid
from datetime import datetime, timezone
from typing import Dict, Optional

from ..version import __version__
from .html_text import _e, _num, _table
from .report import write_report


def write_refusal(findings: dict, paths, request: Optional[dict] = None) -> Dict[str, str]:
    """Write ``paths.report`` and ``paths.html`` (whichever are asked for) of a refusal; {name: path} written."""
    from ..result import REPORT_SCHEMA_VERSION, versions
    from .atomic import OutputSet

    wanted = {k: os.path.abspath(v) for k, v in paths.as_dict().items() if k in ("report", "html")}
    if not wanted:
        return {}
    run_id = uuid.uuid4().hex
    report = {"schema_version": REPORT_SCHEMA_VERSION, "outcome": "refused", "method": "grid",
              "reason": findings.get("reason"), "target": findings.get("target"), "findings": findings,
              "quality": {"verdict": "refused", "reasons": [findings.get("reason")], "check": "grid-held-out-lines"},
              "request": request, "run_id": run_id, "outputs": wanted, "versions": versions()}
    owned = type(paths)(report=paths.report, html=paths.html, folder=paths.folder, overwrite=paths.overwrite).owned()
    with OutputSet(run_id, owned) as out:
        if "report" in wanted:
            write_report(out.temp_for(wanted["report"]), report)
        if "html" in wanted:
            with open(out.temp_for(wanted["html"]), "w", encoding="utf-8") as f:
                f.write(refusal_html(findings, wanted))
    return wanted


def refusal_html(findings: dict, outputs: Dict[str, str]) -> str:
    """The page of a refusal: why, what may help, the labels read, the lattices tried."""
    from .html import CSS, VERDICT_CSS

    fg, bg = VERDICT_CSS["failed"]
    target = findings.get("target") or ""
    parts = [f"<!doctype html><html><head><meta charset=utf-8><title>Hamta: {_e(os.path.basename(target))} "
             f"refused</title><style>{CSS}</style></head><body>",
             f"<h1>Registration report</h1><p class=sub>Scan <b title=\"{_e(target)}\">{_e(os.path.basename(target))}"
             "</b> · by its own printed grid</p>",
             f'<div class=verdict style="border-color:{fg};background:{bg}"><span class=word style="color:{fg}">'
             f"refused</span><div>{_e(findings.get('reason') or '')}</div>{_help(findings)}</div>"]
    labels = findings.get("labels")
    if labels:
        parts.append(_labels_section(labels))
    hints = findings.get("hints")
    if hints:
        parts.append("<h2>Hints</h2>" + _table(["scan x", "scan y", "x", "y"],
                                                [[_num(v, ".1f") if i < 2 else _num(v, ".6g") for i, v in enumerate(r)]
                                                 for r in hints], [True] * 4))
    lattices = findings.get("lattices")
    if lattices:
        parts.append(_lattices_section(lattices))
    written = datetime.now(timezone.utc).replace(tzinfo=None).isoformat(timespec="seconds") + "Z"
    parts.append(f"<p class=note>Written {written} by Hamta {__version__}; files: "
                 + ", ".join(_e(os.path.basename(p)) for p in outputs.values()) + "</p></body></html>")
    return "".join(parts)


def _help(findings: dict) -> str:
    tips = []
    labels = findings.get("labels") or {}
    if not findings.get("hints"):
        tips.append("Place two or three crossings of the printed grid roughly in the QGIS Georeferencer, type their "
                    "coordinates as printed, save the GCP points (.points) and give them as hints (--gcps).")
    if labels and not labels.get("engine_available", True):
        tips.append("Install the OCR engine (Tesseract) to read the labels printed in the margins (docs/"
                    "scanned-maps.md says how on Debian, Windows and macOS).")
    if findings.get("lattices"):
        tips.append("Where the grid's step is not one of the usual ones, give it (--param step=...).")
    tips.append("Check the sheet's CRS (--sheet-crs): what the printed coordinates count in.")
    return "<div>What may help:</div><ul>" + "".join(f"<li>{_e(t)}</li>" for t in tips) + "</ul>"


def _labels_section(labels: dict) -> str:
    rows = [[_e(lab.get("text")), _num(lab.get("value"), ".6g"), _e(lab.get("axis") or "–"), _e(lab.get("side")),
             _num(lab["xy"][0], ".0f") + ", " + _num(lab["xy"][1], ".0f"), _e(lab.get("fate"))]
            for lab in labels.get("labels", [])]
    head = (f"<h2>Labels read</h2><p>{_e(labels.get('summary', ''))}</p>")
    return head + _table(["text", "value", "axis", "edge", "scan px", "kept, or why not"], rows,
                         [False, True, False, False, True, False])


def _lattices_section(lattices) -> str:
    rows = []
    for a in lattices:
        ev = a.get("evidence") or {}
        fam = ev.get("families") or []
        rows.append([_e(a.get("plane")), _e(a.get("step_text")), _num(a.get("spacing_px"), ".0f"),
                     " · ".join(f"{f['printed']}/{f['lines']}" for f in fam) or "–",
                     _num(ev.get("chance_probability"), ".0e"), "yes" if ev.get("printed") else "no"])
    return ("<h2>Lattices tried</h2><p>Each lattice of grid lines placed on the scan from the hints, in each plane the "
            "sheet may be drawn in; a line counts as printed where it holds more ink than every copy of itself moved "
            "across by part of a step.</p>"
            + _table(["plane", "step", "step (scan px)", "lines printed (x · y)", "chance", "printed"], rows,
                     [False, False, True, True, True, False]))
