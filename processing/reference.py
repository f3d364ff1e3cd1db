"""Any QGIS raster layer as the reference: what the core reads for it.

- a GDAL layer (a file, a VRT, a ``/vsicurl/`` COG): its source;
- an XYZ or WMS layer of the 'wms' provider without stored credentials: its source, which the core
  reads tile by tile itself (:mod:`hamta.core.remote`: cache, retries, zoom choice, coarse to fine);
- anything else (WMTS, WCS, ArcGIS services, a layer using a QGIS authentication configuration):
  the needed area read through the layer's own provider into a GeoTIFF, within the pixel budget.
"""
from __future__ import annotations

import math
import os
import tempfile

from qgis.core import (
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsProject,
    QgsRasterFileWriter,
    QgsRasterPipe,
    QgsRectangle,
)

from ..core.basemap.services import parse_service
from ..core.errors import InputError
from ..core.extent import parse_extent
from ..core.io.raster import open_raster
from ..core.io.working import footprint

MARGIN = 0.3  # of the target footprint's larger side, as the core's own reading of map services


def reference_source(layer, extent, target: str, max_pixels: int) -> str:
    """What :func:`hamta.core.run` takes as the reference for ``layer`` (``extent``: the search area
    text, or None)."""
    provider, source = layer.providerType(), layer.source()
    if provider == "gdal":
        return source
    if provider == "wms" and "authcfg=" not in source and parse_service(source) is not None:
        return source
    return render_area(layer, _area(layer, extent, target), max_pixels)


def extent_text(rect, crs) -> str:
    """The core's search-area text of a QGIS rectangle in ``crs`` (None for an empty one)."""
    if rect is None or rect.isNull() or rect.isEmpty():
        return None
    code = crs.authid() if crs is not None and crs.isValid() else ""
    return ",".join(f"{v:.10g}" for v in (rect.xMinimum(), rect.yMinimum(), rect.xMaximum(), rect.yMaximum())) + (
        f",{code}" if code else "")


def _area(layer, extent, target: str) -> QgsRectangle:
    """The rectangle to read, in the layer's CRS: the search area, else the target's footprint plus a margin."""
    info = open_raster(target, "target")
    layer_crs = layer.crs()
    if extent is None:
        if not info.georeferenced or info.crs is None:
            raise InputError(f"The target raster '{info.path}' has no georeferencing, so Hamta cannot tell which part "
                             f"of the layer '{layer.name()}' to read: give a search area.")
        from rasterio.crs import CRS

        x0, y0, x1, y1 = footprint(info, CRS.from_user_input(layer_crs.toWkt())).bounds
        pad = MARGIN * max(x1 - x0, y1 - y0)
        return QgsRectangle(x0 - pad, y0 - pad, x1 + pad, y1 + pad)
    area = parse_extent(extent)
    rect = QgsRectangle(*area.bounds)
    if area.crs:
        transform = QgsCoordinateTransform(QgsCoordinateReferenceSystem(area.crs), layer_crs, QgsProject.instance())
        rect = transform.transformBoundingBox(rect)
    return rect


def render_area(layer, rect: QgsRectangle, max_pixels: int) -> str:
    """Write ``rect`` (layer CRS) of ``layer`` into a temporary GeoTIFF at the layer's resolution, or
    coarser to fit ``max_pixels``; its path. The provider's values are written (a service's images as
    RGBA), not the layer's styled rendering, whose stretch may hide the data."""
    provider = layer.dataProvider()
    res_x = layer.rasterUnitsPerPixelX() if provider.capabilities() & provider.Size else 0
    scale = math.sqrt(rect.width() * rect.height() / max_pixels)
    res = max(scale, res_x or 0)
    cols, rows = max(16, int(rect.width() / res)), max(16, int(rect.height() / res))
    path = os.path.join(tempfile.mkdtemp(prefix="hamta-layer-"), "reference.tif")
    pipe = QgsRasterPipe()
    if not pipe.set(provider.clone()):
        raise InputError(f"The reference layer '{layer.name()}' cannot be read ({layer.providerType()}).")
    writer = QgsRasterFileWriter(path)
    error = writer.writeRaster(pipe, cols, rows, rect, layer.crs(), QgsProject.instance().transformContext())
    if error != QgsRasterFileWriter.NoError or not os.path.exists(path):
        raise InputError(f"The reference layer '{layer.name()}' could not be read over the area needed "
                         f"({layer.providerType()} provider, error {int(error)}).")
    return path
