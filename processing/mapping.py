"""Pure mapping from Processing parameter values to core settings (no QGIS import, unit-tested)."""
from __future__ import annotations

import dataclasses
from typing import Any, Dict, Mapping

from ..core.estimation.models import MODEL_CHOICES
from ..core.io.working import TARGET_GEOREF_CHOICES
from ..core.outputs import GRID_CHOICES, RESAMPLING_CHOICES, OutputPaths
from ..core.pipeline import REFINE_CHOICES, RegisterOptions

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


def register_settings(values: Mapping[str, Any], default_model: str):
    """(RegisterOptions, output keyword arguments) from plain parameter values.

    ``values`` holds Python values already parsed by the algorithm: enum indexes, ints, floats,
    bands as 1-based ints (0 = automatic).
    """
    model = MODEL_CHOICES[values["MODEL"]] if values.get("MODEL") is not None else default_model
    d = RegisterOptions()
    options = RegisterOptions(
        model=model,
        max_working_pixels=int(values.get("MAX_WORKING_PIXELS") or d.max_working_pixels),
        ransac_threshold_px=float(values["RANSAC_THRESHOLD"]) if values.get("RANSAC_THRESHOLD") else None,
        seed=int(values.get("SEED") or 0),
        refine=REFINE_CHOICES[values.get("REFINE") or 0],
        max_gcps=int(values.get("MAX_GCPS") or d.max_gcps),
        target_georef=TARGET_GEOREF_CHOICES[values.get("TARGET_GEOREF") or 0],
        target_band=values.get("TARGET_BAND") or None,
        reference_band=values.get("REFERENCE_BAND") or None,
    )
    outputs = dict(
        paths=OutputPaths(geotiff=values.get("OUTPUT") or None, points=values.get("GCP_POINTS") or None,
                          gpkg=values.get("GCP_LAYER") or None, vrt=values.get("GCP_VRT") or None,
                          report=values.get("REPORT") or None),
        resampling=RESAMPLING_CHOICES[values.get("RESAMPLING", 1)],
        grid=GRID_CHOICES[values.get("GRID") or 0],
    )
    return options, outputs
