"""VRTs over the untouched target that carry a registration: the GCP VRT users get (``--vrt``) and
the model VRT GDAL warps from (:mod:`hamta.core.outputs.warp`).

The model VRT carries our model exactly (in the target's own CRS when the model was fitted in that
frame, so GDAL also does the exact reprojection): similarity/affine as a geotransform; polynomial
2/3 as the GCPs with ``MAX_GCP_ORDER``; thin plate spline as its own values at its control points
with ``SRC_METHOD=GCP_TPS`` (identical to the GCPs when the spline interpolates). GDAL 3.6 has no
homography transformer, so a projective model is carried by a dense grid of exact GCPs
interpolated by TPS (error far below 0.01 px over the grid, see the tests).
"""
from __future__ import annotations

import contextlib
import os
import tempfile
import xml.etree.ElementTree as ET
from typing import Optional

import numpy as np
import rasterio
import rasterio.shutil
from affine import Affine

from ..coords import affine_to_matrix, pixel_to_map
from .tags import verdict_tags

_PROJECTIVE_GRID = 17


def _inner(result):
    """(model from target px to its frame px, frame px -> map transform, frame CRS WKT or None)."""
    model = result.model
    frame = getattr(model, "frame", None)
    if frame is not None:
        return model.inner, frame.frame_transform, frame.frame_crs_wkt
    ref_tr = Affine.identity() if result.pixel_mode else result.reference.transform
    return model, ref_tr, _crs_wkt(result)


def model_georeferencing(result):
    """How GDAL is handed the model: (geotransform or None, GCP rows (pixel, line, X, Y) or None,
    CRS WKT of the map coordinates, transformer options)."""
    model, to_map, crs_wkt = _inner(result)
    kind = model.kind
    if kind in ("linear", "similarity", "affine"):
        g = affine_to_matrix(to_map) @ model.matrix
        return Affine(g[0, 0], g[0, 1], g[0, 2], g[1, 0], g[1, 1], g[1, 2]), None, crs_wkt, {}
    if kind == "projective":
        t = result.target
        gx, gy = np.meshgrid(np.linspace(0, t.width, _PROJECTIVE_GRID), np.linspace(0, t.height, _PROJECTIVE_GRID))
        px = np.column_stack([gx.ravel(), gy.ravel()])
        options = {"SRC_METHOD": "GCP_TPS"}
    elif kind == "tps":  # the spline's own values at its control points reproduce it exactly
        px, options = model.control, {"SRC_METHOD": "GCP_TPS"}
    else:
        px = np.array([g.target_px for g in result.enabled_gcps()], float)
        options = {"SRC_METHOD": "GCP_POLYNOMIAL", "MAX_GCP_ORDER": int(kind[-1])}
        if getattr(result.model, "frame", None) is None:  # the measured GCPs themselves
            return None, np.array([list(g.target_px) + list(g.map_xy) for g in result.enabled_gcps()]), crs_wkt, options
    return None, np.column_stack([px, pixel_to_map(to_map, model.apply(px))]), crs_wkt, options


def _crs_wkt(result) -> Optional[str]:
    if result.pixel_mode or result.reference.crs is None:
        return None
    return result.reference.crs.to_wkt()


def write_vrt(path: str, result, gcp_rows: Optional[np.ndarray] = None, geotransform: Optional[Affine] = None,
              crs_wkt: Optional[str] = None, scratch: Optional[str] = None) -> None:
    """A VRT over the target (absolute path, pixels untouched) carrying GCPs or a geotransform.

    By default it carries the enabled GCPs of ``result`` in the reference CRS.
    """
    if gcp_rows is None and geotransform is None:
        gcp_rows = np.array([list(g.target_px) + list(g.map_xy) for g in result.enabled_gcps()], float)
        crs_wkt = _crs_wkt(result)
    source = os.path.abspath(result.target.path)
    with scratch_dir(scratch) as tmp:
        plain = os.path.join(tmp, f"plain-{os.getpid()}.vrt")
        rasterio.shutil.copy(source, plain, driver="VRT")
        tree = ET.parse(plain)
        root = tree.getroot()
        for el in root.iter("SourceFilename"):  # a mosaic or a stack keeps each of its own sources
            if el.get("relativeToVRT") == "1":
                el.text = os.path.abspath(os.path.join(tmp, el.text))
                el.set("relativeToVRT", "0")
    for tag in ("SRS", "GeoTransform", "GCPList"):
        for el in root.findall(tag):
            root.remove(el)
    if result.verification is not None:
        metadata = next((el for el in root.findall("Metadata") if not el.get("domain")), None)
        if metadata is None:
            metadata = ET.Element("Metadata")
            root.insert(0, metadata)
        for key, value in verdict_tags(result).items():
            ET.SubElement(metadata, "MDI", key=key).text = value
    if geotransform is not None:
        if crs_wkt:
            srs = ET.Element("SRS")
            srs.text = crs_wkt
            root.insert(0, srs)
        gt = ET.Element("GeoTransform")
        gt.text = ", ".join(repr(float(v)) for v in geotransform.to_gdal())
        root.insert(1 if crs_wkt else 0, gt)
    else:
        gcps = ET.Element("GCPList", Projection=crs_wkt or "")
        for i, (px, ln, x, y) in enumerate(gcp_rows):
            ET.SubElement(gcps, "GCP", Id=str(i + 1), Pixel=repr(float(px)), Line=repr(float(ln)),
                          X=repr(float(x)), Y=repr(float(y)))
        root.insert(0, gcps)
    tree.write(path, encoding="UTF-8")


def write_model_vrt(path: str, result, fallback_crs_wkt: Optional[str] = None, scratch: Optional[str] = None) -> dict:
    """Write the VRT GDAL warps from (the target carrying the model); return the transformer options
    GDAL needs with it. ``fallback_crs_wkt`` labels map coordinates that have no CRS (pixel mode)."""
    geotransform, rows, crs_wkt, options = model_georeferencing(result)
    write_vrt(path, result, gcp_rows=rows, geotransform=geotransform, crs_wkt=crs_wkt or fallback_crs_wkt,
              scratch=scratch)
    return options


@contextlib.contextmanager
def scratch_dir(scratch: Optional[str]):
    """``scratch`` (a run's staging folder, removed with it) or a temporary folder of our own."""
    if scratch is not None:
        yield scratch
        return
    with tempfile.TemporaryDirectory(prefix="hamta-") as tmp:
        yield tmp
