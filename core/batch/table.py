"""A batch's results table: a GeoPackage layer of the targets' footprints, and the same as CSV.

One feature per pair: its footprint (the target's outline mapped through the registration, in
the reference CRS, or WGS 84 when the references' CRSs differ; no geometry for failed pairs),
status, verdict, error bound (verified pairs only), self-reported RMSE, GCP count, method, time,
message and output paths (status and verdict: see :mod:`.task`). Written whole or not at all,
through the same staging as every output.
"""
from __future__ import annotations

import csv
import os
from typing import List

import numpy as np

from ..basemap.redact import redact
from ..outputs.atomic import OutputSet
from ..outputs.gpkg import add_feature_layer, add_srs, connect_staged, create_metadata, polygon_blob, srs_entry
from ..text import printable

LAYER = "pairs"
MESSAGE_LIMIT = 2000  # characters of a pair's message in the table (one line: control characters escaped)
FIELDS = [("name", "TEXT"), ("status", "TEXT"), ("verdict", "TEXT"), ("method", "TEXT"), ("method_used", "TEXT"),
          ("error_bound_px", "REAL"), ("rmse_px", "REAL"), ("n_gcps", "INTEGER"), ("time_s", "REAL"),
          ("resumed", "BOOLEAN"), ("message", "TEXT"), ("target", "TEXT"), ("reference", "TEXT"), ("out", "TEXT"),
          ("raster", "TEXT"), ("report", "TEXT")]


def write_results(folder: str, records: List[dict]) -> dict:
    """Write ``batch.gpkg`` and ``batch.csv`` into ``folder``; returns their paths."""
    paths = {"gpkg": os.path.join(folder, "batch.gpkg"), "csv": os.path.join(folder, "batch.csv")}
    with OutputSet() as out:
        _write_gpkg(out.temp_for(paths["gpkg"]), records)
        _write_csv(out.temp_for(paths["csv"]), records)
    return paths


def _row(r: dict) -> list:
    outputs = r.get("outputs") or {}
    return [r["name"], r["status"], r.get("verdict"), r["method"], r.get("method_used"), r.get("error_bound_px"),
            r.get("rmse_px"), r.get("n_gcps"), r["time_s"], int(bool(r.get("resumed"))),
            printable(redact(r.get("message") or ""), MESSAGE_LIMIT), r["target"], redact(r["reference"]), r["out"],
            outputs.get("raster"), outputs.get("report")]


def _write_csv(path: str, records: List[dict]) -> None:
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        writer.writerow([n for n, _ in FIELDS])
        writer.writerows(_row(r) for r in records)


def _write_gpkg(path: str, records: List[dict]) -> None:
    crs_wkt, footprints = _footprints(records)
    srs = srs_entry(crs_wkt)
    con = connect_staged(path)
    try:
        create_metadata(con)
        add_srs(con, srs)
        rows = [(polygon_blob(f, srs[0]) if f is not None else None, *_row(r)) for r, f in zip(records, footprints)]
        shapes = [f for f in footprints if f is not None]
        add_feature_layer(con, LAYER, "POLYGON", FIELDS, rows, np.vstack(shapes) if shapes else None,
                          "Hamta batch: one footprint per registered target", srs[0])
        con.commit()
    finally:
        con.close()


def _footprints(records: List[dict]):
    """(CRS WKT of the layer or None, footprint array per record or None)."""
    crss = {r.get("crs") for r in records if r.get("footprint") and not r.get("pixel_mode")}
    if len(crss) <= 1:
        crs = next(iter(crss), None)
        return crs, [np.asarray(r["footprint"], float) if r.get("footprint") and not r.get("pixel_mode")
                     and r.get("crs") == crs else None for r in records]
    from pyproj import CRS, Transformer

    out = []
    for r in records:
        if not r.get("footprint") or r.get("pixel_mode"):
            out.append(None)
            continue
        to_wgs84 = Transformer.from_crs(CRS.from_user_input(r["crs"]), CRS.from_epsg(4326), always_xy=True)
        xy = np.asarray(r["footprint"], float)
        lon, lat = to_wgs84.transform(xy[:, 0], xy[:, 1])
        out.append(np.column_stack([lon, lat]))
    return CRS.from_epsg(4326).to_wkt(), out
