"""Pure mapping from Processing parameter values to core settings (no QGIS import, unit-tested).

Option parameters are generated from :mod:`hamta.core.options` and mapped back by the same
definitions, so an enum index always means the value it was shown for.
"""
from __future__ import annotations

import dataclasses
import re
from typing import Any, Dict, Mapping, Tuple

from ..core.options import OutputOptions, RegisterOptions, option_fields, processing_key
from ..core.outputs import OutputPaths


def method_parameter_name(field_name: str) -> str:
    """Processing parameter name of a method parameter (``ratio`` -> ``P_RATIO``)."""
    return "P_" + field_name.upper()


def method_values(method, values: Mapping[str, Any]) -> Dict[str, Any]:
    """Method parameters from Processing values keyed by :func:`method_parameter_name`."""
    out = {}
    for f in dataclasses.fields(method.params_type):
        key = method_parameter_name(f.name)
        if key in values and values[key] is not None:
            v = values[key]
            choices = f.metadata.get("choices")
            out[f.name] = choices[v] if choices and isinstance(v, int) else v
    return out


def _option(f, spec, value):
    """The core value of one option from its Processing value (None: the option's default)."""
    if value is None or value == "" or (spec.above and value == 0):  # a 0 left in a field that must be above 0
        return f.default
    if spec.choice is not None:
        return spec.choice.at(value) if isinstance(value, int) else spec.choice.check(value)
    if spec.kind.startswith("band:"):
        return int(value) or None  # 0: no band chosen
    if spec.kind == "list":
        return creation_options(value)
    if isinstance(f.default, bool):
        return bool(value)
    return value


def register_settings(values: Mapping[str, Any]):
    """(RegisterOptions, OutputPaths, OutputOptions) from plain parameter values keyed by Processing name.

    ``values`` holds Python values already parsed by the algorithm (see
    :func:`hamta.processing.options.option_values`): enum indexes, ints, floats, bands as 1-based ints
    (0 = automatic), None for what was left empty, which takes the option's default; settings left open
    take the method's defaults in :func:`hamta.core.options.resolve_options`.
    """
    def build(cls):
        return cls(**{f.name: _option(f, spec, values.get(processing_key(f, spec))) for f, spec in option_fields(cls)})

    gpkg, layer = vector_destination(values.get("GCP_LAYER") or "")
    paths = OutputPaths(raster=values.get("OUTPUT") or None, points=values.get("GCP_POINTS") or None,
                        gpkg=gpkg or None, gpkg_layer=layer, vrt=values.get("GCP_VRT") or None,
                        report=values.get("REPORT") or None, html=values.get("OUTPUT_HTML") or None)
    return build(RegisterOptions), paths, build(OutputOptions)


def creation_options(text: str) -> Tuple[str, ...]:
    """GDAL creation options from Processing's text field: ``KEY=VALUE`` items separated by spaces, commas,
    semicolons or '|' (QGIS's own raster-options widget writes ``KEY=VALUE|KEY=VALUE``)."""
    return tuple(item for item in re.split(r"[\s,;|]+", text.strip()) if item)


_OGR_URI = re.compile(r"""^ogr:dbname=(?P<q>['"]?)(?P<path>.+?)(?P=q)(\s+table=(?P<t>['"]?)(?P<table>[^'"]+)(?P=t))?"""
                      r"""(\s+\(\w+\))?\s*$""")


def vector_destination(value: str) -> Tuple[str, str]:
    """(GeoPackage path, layer name) of a Processing vector destination: a plain path, or the
    ``ogr:dbname='x.gpkg' table="name" (geom)`` form QGIS uses to add a layer to an existing file."""
    value = (value or "").strip()
    match = _OGR_URI.match(value)
    if match:
        return match.group("path"), match.group("table") or "gcps"
    path, _, options = value.partition("|")
    layer = options.split("layername=", 1)[1].split("|")[0] if "layername=" in options else "gcps"
    return path, layer
