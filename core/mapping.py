"""Mapping points with the model stored in a ``report.json`` (every model type, TPS included).

Every problem with the report (missing, a folder, not JSON, not a Hamta report, a model that
cannot be rebuilt or evaluated) is an :class:`InputError` naming the file.
"""
from __future__ import annotations

import json
import os

import numpy as np
from affine import Affine

from .coords import as_xy, pixel_to_map
from .errors import InputError, UsageError
from .estimation.models import model_from_dict


def load_report_model(report_path: str):
    """(model, reference geotransform, pixel mode) from a ``report.json``."""
    path = os.fspath(report_path)
    if not os.path.exists(path):
        raise InputError(f"The report '{path}' does not exist.")
    if os.path.isdir(path):
        raise InputError(f"The report '{path}' is a folder, not a report.json file.")
    if not os.path.isfile(path):
        raise InputError(f"The report '{path}' is not a regular file (a pipe, socket or device).")
    try:
        with open(path, encoding="utf-8") as f:
            report = json.load(f)
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise InputError(f"The report '{path}' is not readable JSON ({exc}).") from None
    except RecursionError:
        raise InputError(f"The report '{path}' is not readable JSON (nested too deeply).") from None
    try:
        ref = report["reference"]
        transform = Affine.from_gdal(*[float(v) for v in ref["transform"]])
        model = model_from_dict(report["model"], transform, ref.get("crs"))
    except (TypeError, KeyError, ValueError, IndexError, AttributeError, np.linalg.LinAlgError) as exc:
        raise InputError(f"The report '{path}' is not a Hamta report with a usable model "
                         f"({type(exc).__name__}: {exc}).") from None
    return model, transform, bool(ref.get("pixel_mode"))


def map_points_from_report(report_path: str, target_px) -> list:
    """Target pixels -> reference pixels and map coordinates, as dicts per point."""
    model, transform, pixel_mode = load_report_model(report_path)
    xy = as_xy(target_px)
    if not np.isfinite(xy).all():
        raise UsageError("target pixel coordinates must be finite numbers")
    try:
        with np.errstate(all="ignore"):
            ref_px = model.apply(xy)
            mp = ref_px.copy() if pixel_mode else pixel_to_map(transform, ref_px)
    except Exception as exc:  # a malformed model (wrong matrix shape, unknown CRS...) from a hand-edited report
        raise InputError(f"The model in the report '{report_path}' cannot be evaluated "
                         f"({type(exc).__name__}: {exc}).") from None
    if not (np.isfinite(ref_px).all() and np.isfinite(mp).all()):
        raise InputError(f"The model in the report '{report_path}' does not map these points to finite "
                         "coordinates (a degenerate or corrupted model).")
    return [{"target_px": xy[i].tolist(), "reference_px": ref_px[i].tolist(), "map": mp[i].tolist()}
            for i in range(len(xy))]
