"""QGIS Georeferencer GCP files (``.points``), in the layout QGIS 3.22 writes and reads.

Layout (QGIS 3.22, ``QgsGCPList::saveGcps``)::

    #CRS: <destination CRS as one line of WKT2_2019, empty when there is none>
    mapX,mapY,sourceX,sourceY,enable,dX,dY,residual
    <numbers written like qgsDoubleToString: 17 decimals, trailing zeros trimmed>

``sourceX, sourceY`` are the target's georeferenced coordinates when it has a geotransform, else
``(column, -row)`` as QGIS shows plain images. ``mapX, mapY`` are reference map coordinates, or
``(column, -row)`` of the reference in pixel mode, so the points land on the reference as QGIS
displays it. ``dX, dY, residual`` are residuals in target pixels (QGIS recomputes them on load).
"""
from __future__ import annotations

from typing import List, Optional, Tuple

import numpy as np

from ..coords import pixel_to_map
from ..estimation.models import local_jacobian

HEADER = "mapX,mapY,sourceX,sourceY,enable,dX,dY,residual"


def qgs_double(value: float) -> str:
    """Format like QGIS's ``qgsDoubleToString(value)`` (precision 17, trailing zeros trimmed)."""
    text = f"{value:.17f}"
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return "0" if text == "-0" else text


def crs_line(crs) -> str:
    if crs is None:
        return "#CRS: "
    from pyproj import CRS

    return "#CRS: " + CRS.from_user_input(crs.to_wkt()).to_wkt(version="WKT2_2019", pretty=False)


def source_coordinates(result, target_px: np.ndarray) -> np.ndarray:
    """Target pixels -> the source coordinates the QGIS Georeferencer uses for this target."""
    if result.target.georef_source == "geotransform":
        return pixel_to_map(result.target.transform, target_px)
    return np.column_stack([target_px[:, 0], -target_px[:, 1]])


def destination_coordinates(result, reference_px: np.ndarray, map_xy: np.ndarray) -> np.ndarray:
    if result.pixel_mode:
        return np.column_stack([reference_px[:, 0], -reference_px[:, 1]])
    return map_xy


def write_points(path: str, result) -> None:
    """Write every GCP of ``result`` (enabled and rejected) as a QGIS 3.22 ``.points`` file."""
    gcps = result.gcps
    tgt = np.array([g.target_px for g in gcps], float).reshape(-1, 2)
    ref = np.array([g.reference_px for g in gcps], float).reshape(-1, 2)
    mp = np.array([g.map_xy for g in gcps], float).reshape(-1, 2)
    res_ref = np.array([g.residual_xy for g in gcps], float).reshape(-1, 2)
    src = source_coordinates(result, tgt)
    dst = destination_coordinates(result, ref, mp)
    res_tgt = res_ref
    if len(tgt):
        res_tgt = np.einsum("nij,nj->ni", np.linalg.inv(local_jacobian(result.model, tgt)), res_ref)
    lines = [crs_line(None if result.pixel_mode else result.reference.crs), HEADER]
    for i, g in enumerate(gcps):
        dx, dy = res_tgt[i, 0], -res_tgt[i, 1]
        values = [dst[i, 0], dst[i, 1], src[i, 0], src[i, 1]]
        lines.append(",".join([qgs_double(v) for v in values] + ["1" if g.enabled else "0"]
                              + [qgs_double(v) for v in (dx, dy, float(np.hypot(dx, dy)))]))
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


def read_points(path: str) -> Tuple[Optional[str], List[tuple]]:
    """Read a ``.points`` file the way QGIS 3.22 does.

    Returns the CRS text (None when the file has no ``#CRS`` line) and rows
    ``(mapX, mapY, sourceX, sourceY, enabled)``. Accepts 4, 5 or 8 columns, comma or tab separated.
    """
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    crs = None
    if lines and lines[0].startswith("#CRS: "):
        crs = lines[0][len("#CRS: "):]
        lines = lines[1:]
    rows = []
    for n, line in enumerate(lines[1:], start=2):
        if not line.strip():
            continue
        parts = line.split("," if "," in line else "\t")
        if len(parts) < 4:
            raise ValueError(f"{path}: malformed content at line {n}")
        enabled = parts[4].strip() != "0" if len(parts) > 4 else True
        rows.append((float(parts[0]), float(parts[1]), float(parts[2]), float(parts[3]), enabled))
    return crs, rows
