"""The GCP layer's default QGIS style: points coloured by residual, rejected matches as grey crosses.

QGIS loads a GeoPackage layer with the style stored for it in the ``layer_styles`` table (the table
QGIS and GDAL use, with ``useAsDefault``), so the layer opens styled in any QGIS 3.x without a
``.qml`` beside it. The style is a rule-based renderer in QGIS's own QML (symbol properties both as
``<Option>`` maps, read since 3.18, and as ``<prop>`` elements, read by older versions).
"""
from __future__ import annotations

from html import escape

STYLE_NAME = "Hamta GCPs by residual"
# (filter on the layer's fields, legend label, marker shape, fill colour, size mm)
RULES = (
    ('"enabled" AND "residual_px" < 0.5', "used, residual < 0.5 px", "circle", "26,150,65,255", 2.4),
    ('"enabled" AND "residual_px" >= 0.5 AND "residual_px" < 1', "used, 0.5 - 1 px", "circle", "166,217,106,255",
     2.4),
    ('"enabled" AND "residual_px" >= 1 AND "residual_px" < 2', "used, 1 - 2 px", "circle", "253,174,97,255", 2.6),
    ('"enabled" AND "residual_px" >= 2', "used, 2 px or more", "circle", "215,25,28,255", 2.8),
    ('NOT "enabled"', "rejected match (not used for the fit)", "cross2", "130,130,130,255", 2.0),
)


def _symbol(index: int, shape: str, colour: str, size: float) -> str:
    outline = colour if shape.startswith("cross") else "35,35,35,255"
    props = {"name": shape, "color": colour, "outline_color": outline, "outline_style": "solid",
             "outline_width": "0.2", "outline_width_unit": "MM", "size": f"{size:g}", "size_unit": "MM",
             "angle": "0", "scale_method": "diameter"}
    options = "".join(f'<Option type="QString" name="{k}" value="{v}"/>' for k, v in props.items())
    legacy = "".join(f'<prop k="{k}" v="{v}"/>' for k, v in props.items())
    return (f'<symbol type="marker" name="{index}" alpha="1" clip_to_extent="1" force_rhr="0">'
            f'<layer class="SimpleMarker" enabled="1" locked="0" pass="0"><Option type="Map">{options}</Option>'
            f"{legacy}</layer></symbol>")


def style_qml() -> str:
    """The QML document of the default style."""
    rules = "".join(f'<rule key="rule{i}" filter={_attr(f)} label={_attr(label)} symbol="{i}"/>'
                    for i, (f, label, *_rest) in enumerate(RULES))
    symbols = "".join(_symbol(i, shape, colour, size) for i, (_f, _l, shape, colour, size) in enumerate(RULES))
    return ("<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>"
            '<qgis version="3.22.0" styleCategories="Symbology">'
            '<renderer-v2 type="RuleRenderer" enableorderby="0" forceraster="0" symbollevels="0">'
            f'<rules key="root">{rules}</rules><symbols>{symbols}</symbols></renderer-v2></qgis>')


def write_default_style(con, layer: str, geometry_column: str = "geom") -> None:
    """Store the style as ``layer``'s default in the GeoPackage open on ``con`` (replacing an earlier one)."""
    con.execute("CREATE TABLE IF NOT EXISTS layer_styles (id INTEGER PRIMARY KEY AUTOINCREMENT, "
                "f_table_catalog TEXT(256), f_table_schema TEXT(256), f_table_name TEXT(256), "
                "f_geometry_column TEXT(256), styleName TEXT(30), styleQML TEXT, styleSLD TEXT, "
                "useAsDefault BOOLEAN, description TEXT, owner TEXT(30), ui TEXT(30), "
                "update_time DATETIME DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ','now')))")
    con.execute("INSERT OR IGNORE INTO gpkg_contents (table_name, data_type, identifier) "
                "VALUES ('layer_styles', 'attributes', 'layer_styles')")
    con.execute("UPDATE layer_styles SET useAsDefault = 0 WHERE f_table_name = ?", (layer,))
    con.execute("DELETE FROM layer_styles WHERE f_table_name = ? AND styleName = ?", (layer, STYLE_NAME))
    con.execute("INSERT INTO layer_styles (f_table_catalog, f_table_schema, f_table_name, f_geometry_column, "
                "styleName, styleQML, styleSLD, useAsDefault, description, owner, ui) "
                "VALUES ('', '', ?, ?, ?, ?, '', 1, ?, '', '')",
                (layer, geometry_column, STYLE_NAME, style_qml(),
                 "GCPs coloured by residual (reference px); rejected matches as grey crosses"))


def _attr(text: str) -> str:
    """``text`` as a quoted XML attribute value (what ``xml.sax.saxutils.quoteattr`` gives, without
    importing the network modules it pulls in)."""
    return '"' + escape(text, quote=True).replace("\n", "&#10;").replace("\r", "&#13;").replace("\t", "&#9;") + '"'
