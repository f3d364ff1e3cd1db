"""The georeferenced target: a GeoTIFF warped by GDAL (through rasterio), and a GCP VRT.

GDAL warps from a VRT over the untouched target that carries our model exactly (in the target's
own CRS when the model was fitted in that frame, so GDAL also does the exact reprojection):
similarity/affine as a geotransform; polynomial 2/3 as the GCPs with ``MAX_GCP_ORDER``; thin plate
spline as its own values at its control points with ``SRC_METHOD=GCP_TPS`` (identical to the GCPs
when the spline interpolates). GDAL 3.6 has no homography transformer, so a
projective model is carried by a dense grid of exact GCPs interpolated by TPS (error far below
0.01 px over the grid, see the tests). The output is written in row blocks, so progress is
reported, cancellation is honoured and memory stays bounded for large scenes.
"""
from __future__ import annotations

import contextlib
import math
import os
import tempfile
import warnings
import xml.etree.ElementTree as ET
from typing import Optional

import numpy as np
import rasterio
import rasterio.shutil
from affine import Affine
from rasterio.crs import CRS
from rasterio.enums import Resampling
from rasterio.errors import NotGeoreferencedWarning
from rasterio.warp import reproject
from rasterio.windows import Window

from ..coords import affine_to_matrix, as_xy, compose, pixel_to_map
from ..errors import OutputError
from ..estimation.models import local_jacobian
from ..options import GRID, RESAMPLING
from ..progress import Monitor
from .tags import verdict_tags

_PLACEHOLDER_CRS = CRS.from_epsg(3857)  # lets GDAL warp between two grids of a raster without CRS
_BLOCK_ROWS = 512
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
    if kind in ("similarity", "affine"):
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
    with _scratch_dir(scratch) as tmp:
        plain = os.path.join(tmp, f"plain-{os.getpid()}.vrt")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", NotGeoreferencedWarning)
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
def _scratch_dir(scratch: Optional[str]):
    """``scratch`` (a run's staging folder, removed with it) or a temporary folder of our own."""
    if scratch is not None:
        yield scratch
        return
    with tempfile.TemporaryDirectory(prefix="hamta-") as tmp:
        yield tmp


def output_grid(result, grid: str = "auto", resolution: Optional[float] = None):
    """(transform, width, height, crs) of the warped output, north-up in the reference CRS.

    'reference' uses the reference pixel size and grid; 'native' keeps the target's own
    resolution (snapped to the reference grid origin); 'auto' picks 'reference' when the two
    resolutions are within 10 %. ``resolution`` (reference map units) overrides the pixel size.
    In pixel mode the output is the reference pixel grid itself.
    """
    GRID.check(grid)
    ref = result.reference
    if result.pixel_mode:
        return Affine.identity(), ref.width, ref.height, None
    t = result.target
    s = np.linspace(0, 1, 33)
    edge = np.concatenate([np.column_stack([s * t.width, 0 * s]), np.column_stack([s * t.width, 0 * s + t.height]),
                           np.column_stack([0 * s, s * t.height]), np.column_stack([0 * s + t.width, s * t.height])])
    mp = result.reference_to_map(result.model.apply(edge))
    centre = as_xy([t.width / 2.0, t.height / 2.0])
    scale = math.sqrt(abs(np.linalg.det(local_jacobian(result.model, centre)[0])))  # ref px per target px
    res_x, res_y = abs(ref.transform.a) or ref.pixel_size, abs(ref.transform.e) or ref.pixel_size
    if resolution is not None:
        res_x = res_y = float(resolution)
    elif grid == "native" or (grid == "auto" and not 0.9 <= scale <= 1.1):
        res_x, res_y = res_x * scale, res_y * scale
    x0, y0 = ref.transform.c, ref.transform.f
    xmin = x0 + math.floor((mp[:, 0].min() - x0) / res_x) * res_x
    xmax = x0 + math.ceil((mp[:, 0].max() - x0) / res_x) * res_x
    ymax = y0 - math.floor((y0 - mp[:, 1].max()) / res_y) * res_y
    ymin = y0 - math.ceil((y0 - mp[:, 1].min()) / res_y) * res_y
    width, height = int(round((xmax - xmin) / res_x)), int(round((ymax - ymin) / res_y))
    px_per_target_px = scale * scale * (ref.pixel_size ** 2) / (res_x * res_y)
    limit = 16 * t.width * t.height * max(px_per_target_px, 1.0) + 1e6
    if width * height > limit or width <= 0 or height <= 0:
        raise OutputError(f"The fitted model maps '{t.path}' onto an implausible {width} x {height} pixel "
                          "grid; the registration is probably wrong, so no raster was written.")
    return Affine(res_x, 0, xmin, 0, -res_y, ymax), width, height, ref.crs


def write_geotiff(path: str, result, resampling: str = "bilinear", grid: str = "auto",
                  resolution: Optional[float] = None, monitor: Optional[Monitor] = None,
                  scratch: Optional[str] = None) -> None:
    """Warp every band of the target onto the output grid and write a tiled, compressed GeoTIFF."""
    RESAMPLING.check(resampling)
    monitor = monitor or Monitor()
    transform, width, height, crs = output_grid(result, grid, resolution)
    warp_crs = crs or _PLACEHOLDER_CRS
    with _scratch_dir(scratch) as tmp:
        vrt = os.path.join(tmp, f"model-{os.getpid()}.vrt")
        options = write_model_vrt(vrt, result, warp_crs.to_wkt(), scratch=tmp)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", NotGeoreferencedWarning)
            with rasterio.open(vrt) as src:
                nodata = _output_nodata(src)
                profile = dict(driver="GTiff", width=width, height=height, count=src.count, dtype=src.dtypes[0],
                               nodata=nodata, tiled=True, blockxsize=256, blockysize=256, compress="deflate",
                               BIGTIFF="IF_SAFER", interleave="band")
                if crs is not None:
                    profile.update(crs=crs, transform=transform)
                with rasterio.open(path, "w", **profile) as dst:
                    _warp_blocks(src, dst, transform, warp_crs, width, height, nodata, resampling, options, monitor)
                    dst.colorinterp = src.colorinterp
                    dst.update_tags(**verdict_tags(result))
                    levels = [f for f in (2, 4, 8, 16, 32) if max(width, height) / f >= 256]
                    if levels:
                        dst.build_overviews(levels, Resampling.average)
    monitor.report(1.0, "writing")


def _output_nodata(src) -> float:
    if src.nodata is not None:
        return src.nodata
    return float("nan") if src.dtypes[0].startswith("float") else 0


def _warp_blocks(src, dst, transform, crs, width, height, nodata, resampling, options, monitor):
    bands = list(range(1, src.count + 1))
    for r0 in range(0, height, _BLOCK_ROWS):
        rows = min(_BLOCK_ROWS, height - r0)
        block = np.full((src.count, rows, width), nodata, dtype=src.dtypes[0])
        reproject(rasterio.band(src, bands), block, src_nodata=src.nodata,
                  dst_transform=compose(transform, Affine.translation(0, r0)), dst_crs=crs, dst_nodata=nodata,
                  resampling=Resampling[resampling], **options)
        dst.write(block, window=Window(0, r0, width, rows))
        monitor.report((r0 + rows) / height, "writing raster")


