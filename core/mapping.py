"""Mapping points with the model stored in a ``report.json`` (every model type, TPS included)."""
from __future__ import annotations

from affine import Affine

from .coords import as_xy, pixel_to_map
from .estimation.models import model_from_dict
from .outputs.report import read_report


def map_points_from_report(report_path: str, target_px) -> list:
    """Target pixels -> reference pixels and map coordinates, as dicts per point."""
    report = read_report(report_path)
    ref = report["reference"]
    model = model_from_dict(report["model"], Affine.from_gdal(*ref["transform"]), ref["crs"])
    xy = as_xy(target_px)
    ref_px = model.apply(xy)
    mp = ref_px.copy() if ref.get("pixel_mode") else pixel_to_map(Affine.from_gdal(*ref["transform"]), ref_px)
    return [{"target_px": xy[i].tolist(), "reference_px": ref_px[i].tolist(), "map": mp[i].tolist()}
            for i in range(len(xy))]
