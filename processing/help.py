"""The Help button of every Hamta algorithm: a page written from the algorithm's own definition
(its description, each parameter with the name ``qgis_process`` takes, its default and whether it
is advanced, and the outputs), so it never disagrees with the dialog."""
from __future__ import annotations

import html
import os

from qgis.core import QgsApplication, QgsProcessingParameterDefinition, QgsProcessingParameterEnum
from qgis.PyQt.QtCore import QUrl


def help_page(alg) -> str:
    rows = []
    for p in alg.parameterDefinitions():
        default = p.defaultValue()
        if isinstance(p, QgsProcessingParameterEnum) and isinstance(default, int):
            default = f"{default}: {p.options()[default]}"
        where = "advanced" if p.flags() & QgsProcessingParameterDefinition.FlagAdvanced else ""
        rows.append("<tr>" + "".join(f"<td>{html.escape(str(v))}</td>" for v in (
            p.help() or p.description(), p.name(), "" if default is None else default, where)) + "</tr>")
    outputs = "".join(f"<li>{html.escape(o.description())} (<code>{html.escape(o.name())}</code>)</li>"
                      for o in alg.outputDefinitions())
    title = html.escape(alg.displayName())
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{title}</title>"
            "<style>body{font-family:sans-serif;max-width:60em;margin:1em auto}td,th{border-bottom:1px solid #ddd;"
            "padding:3px 8px;text-align:left}</style></head><body>"
            f"<h1>{title}</h1><p>{html.escape(alg.shortHelpString())}</p>"
            f"<p>Headless: <code>qgis_process run hamta:{html.escape(alg.name())} -- NAME=value ...</code> with the "
            "names below (enums take the number before the colon).</p>"
            "<h2>Parameters</h2><table><tr><th>parameter</th><th>name</th><th>default</th><th></th></tr>"
            + "".join(rows) + f"</table><h2>Outputs</h2><ul>{outputs}</ul></body></html>")


def help_url(alg) -> str:
    """A file URL of ``alg``'s help page, written into the QGIS profile's folder."""
    folder = os.path.join(QgsApplication.qgisSettingsDirPath(), "hamta", "help")
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, f"{alg.name()}.html")
    with open(path, "w", encoding="utf-8") as f:
        f.write(help_page(alg))
    return QUrl.fromLocalFile(path).toString()
