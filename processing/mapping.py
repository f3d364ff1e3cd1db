"""Pure mapping from Processing parameter values to core settings (no QGIS import, unit-tested).

Enum parameters are built from :mod:`hamta.core.options` choices and mapped back with the same
choice, so an enum index always means the value it was shown for.
"""
from __future__ import annotations

import dataclasses
import re
from typing import Any, Dict, Mapping, Tuple

from ..core.options import FILL, FORMAT, GRID, MODEL, REFINE, RESAMPLING, TARGET_GEOREF, OutputOptions, RegisterOptions
from ..core.outputs import OutputPaths

# Processing parameter name -> the choice its enum shows.
ENUMS = {"MODEL": MODEL, "RESAMPLING": RESAMPLING, "GRID": GRID, "REFINE": REFINE, "TARGET_GEOREF": TARGET_GEOREF,
         "FORMAT": FORMAT, "FILL": FILL}


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


def _enum(values: Mapping[str, Any], name: str) -> str:
    """The choice value of enum parameter ``name`` (its default when absent)."""
    index = values.get(name)
    return ENUMS[name].default if index is None else ENUMS[name].at(index)


def register_settings(values: Mapping[str, Any]):
    """(RegisterOptions, OutputPaths, OutputOptions) from plain parameter values.

    ``values`` holds Python values already parsed by the algorithm: enum indexes, ints, floats,
    bands as 1-based ints (0 = automatic). The model's enum always carries a value (its default
    is the method's default model, see the algorithm); other settings left empty take the
    method's defaults in :func:`hamta.core.options.resolve_options`.
    """
    d = RegisterOptions()
    options = RegisterOptions(
        model=_enum(values, "MODEL") if values.get("MODEL") is not None else None,
        max_working_pixels=int(values.get("MAX_WORKING_PIXELS") or d.max_working_pixels),
        ransac_threshold_px=float(values["RANSAC_THRESHOLD"]) if values.get("RANSAC_THRESHOLD") else None,
        seed=int(values.get("SEED") or 0),
        refine=_enum(values, "REFINE"),
        max_gcps=int(values.get("MAX_GCPS") or d.max_gcps),
        target_georef=_enum(values, "TARGET_GEOREF"),
        target_band=values.get("TARGET_BAND") or None,
        reference_band=values.get("REFERENCE_BAND") or None,
        tolerance_px=float(values.get("TOLERANCE") or d.tolerance_px),
        local=bool(values.get("LOCAL")),
        local_window_px=int(values.get("LOCAL_WINDOW") or 0),
        local_spacing_px=float(values.get("LOCAL_SPACING") or 0.0),
        pixel_mode=bool(values.get("PIXEL_MODE")),
    )
    gpkg, layer = vector_destination(values.get("GCP_LAYER") or "")
    paths = OutputPaths(raster=values.get("OUTPUT") or None, points=values.get("GCP_POINTS") or None,
                        gpkg=gpkg or None, gpkg_layer=layer, vrt=values.get("GCP_VRT") or None,
                        report=values.get("REPORT") or None, html=values.get("OUTPUT_HTML") or None)
    output = OutputOptions(resampling=_enum(values, "RESAMPLING"), grid=_enum(values, "GRID"),
                           resolution=float(values["RESOLUTION"]) if values.get("RESOLUTION") else None,
                           crs=values.get("OUTPUT_CRS") or None, format=_enum(values, "FORMAT"),
                           creation_options=creation_options(values.get("CREATION_OPTIONS") or ""),
                           fill=_enum(values, "FILL"),
                           nodata=float(values["NODATA"]) if values.get("NODATA") is not None else None)
    return options, paths, output


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
