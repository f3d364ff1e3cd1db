"""Any QGIS raster or vector layer as the reference: what the core reads for it.

- a GDAL layer (a file, a VRT, a ``/vsicurl/`` COG): its source;
- a vector layer of areas or lines (water, buildings, roads): its shapes over the area needed drawn into a
  GeoTIFF under Hamta's cache (:class:`Shapes`, :mod:`hamta.core.io.rasterize`), within the pixel budget;
- an XYZ or WMS layer of the 'wms' provider that :func:`hamta.core.basemap.services.parse_service`
  reads (no QGIS credentials or headers; a WMS in EPSG:3857 or EPSG:4326): its source, which the core
  reads tile by tile itself (:mod:`hamta.core.remote`: cache, retries, zoom choice, coarse to fine);
- anything else (WMTS, WCS, ArcGIS services, a layer needing QGIS's credentials): the needed area
  read through the layer's own provider into a GeoTIFF under Hamta's cache, within the pixel budget.
"""
from __future__ import annotations

import hashlib
import math
import os
import tempfile

from qgis.core import (
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsFeatureRequest,
    QgsProject,
    QgsRasterFileWriter,
    QgsRasterPipe,
    QgsRectangle,
    QgsVectorLayer,
    QgsVectorLayerFeatureSource,
)

from ..core.basemap.cache import Cache, Unusable, default_cache
from ..core.errors import InputError
from ..core.extent import parse_extent
from ..core.io.raster import open_raster
from ..core.reference import RasterReference, ServiceReference, resolve_reference


def reference_source(layer, extent, target: str, max_pixels: int):
    """The reference :func:`hamta.core.run` takes for ``layer`` (:mod:`hamta.core.reference`; ``extent``:
    the search area text, or None); a layer without a GDAL equivalent is rendered here (see
    :func:`prepare_reference`)."""
    prepared = prepare_reference(layer, extent, target, max_pixels)
    return RasterReference(prepared.write()) if isinstance(prepared, (Rendering, Shapes)) else prepared


def prepare_reference(layer, extent, target: str, max_pixels: int):
    """The resolved reference for ``layer``, or a :class:`Rendering` (a raster layer) or :class:`Shapes` (a vector
    layer) to write in a worker thread (made here, in the layer's thread: it holds a clone of the layer's
    provider, or a source of its features)."""
    if isinstance(layer, QgsVectorLayer):
        return Shapes(layer, _area(layer, extent, target), max_pixels)
    return layer_reference(layer) or Rendering(layer, _area(layer, extent, target), max_pixels)


def layer_reference(layer):
    """The resolved reference the core reads ``layer`` as (a GDAL layer's source, or a map service Hamta
    reads itself), or None for a layer only QGIS reads (:func:`prepare_reference` renders it)."""
    provider, source = layer.providerType(), layer.source()
    if provider == "gdal":
        return RasterReference(source)
    resolved = resolve_reference(source) if provider == "wms" else None
    return resolved if isinstance(resolved, ServiceReference) else None


def extent_text(rect, crs) -> str:
    """The core's search-area text of a QGIS rectangle in ``crs`` (None for an empty one); a CRS PROJ
    cannot name by a code is given as longitude and latitude."""
    if rect is None or rect.isNull() or rect.isEmpty():
        return None
    code = crs.authid() if crs is not None and crs.isValid() else ""
    if crs is not None and crs.isValid() and not code.startswith(("EPSG:", "ESRI:", "IGNF:")):
        wgs84 = QgsCoordinateReferenceSystem("EPSG:4326")
        rect, code = QgsCoordinateTransform(crs, wgs84, QgsProject.instance()).transformBoundingBox(rect), "EPSG:4326"
    return ",".join(f"{v:.10g}" for v in (rect.xMinimum(), rect.yMinimum(), rect.xMaximum(), rect.yMaximum())) + (
        f",{code}" if code else "")


def _area(layer, extent, target: str) -> QgsRectangle:
    """The rectangle to read, in the layer's CRS: the search area, else the target's footprint plus a margin."""
    from ..core.options import RegisterOptions
    from ..core.remote import footprint_bounds, uses_georeferencing  # the engine: not when QGIS starts

    info = open_raster(target, "target")
    if extent is None and isinstance(layer, QgsVectorLayer) and not uses_georeferencing(info, RegisterOptions()):
        return layer.extent()
    if extent is None:
        if not uses_georeferencing(info, RegisterOptions()):
            raise InputError(f"The target raster '{info.path}' has no georeferencing, so Hamta cannot tell which part "
                             f"of the layer '{layer.name()}' to read: give a search area.")
        return QgsRectangle(*footprint_bounds(info, layer.crs().toWkt()))
    area = parse_extent(extent)
    rect = QgsRectangle(*area.bounds)
    if area.crs:
        transform = QgsCoordinateTransform(QgsCoordinateReferenceSystem(area.crs), layer.crs(), QgsProject.instance())
        rect = transform.transformBoundingBox(rect)
    return rect


class Rendering:
    """``rect`` (layer CRS) of a layer, at its resolution or coarser to fit ``max_pixels``, to be written
    into a GeoTIFF under Hamta's cache (reused when the same area is asked again). The provider's values
    are written (a service's images as RGBA), not the layer's styled rendering, whose stretch may hide
    the data."""

    def __init__(self, layer, rect: QgsRectangle, max_pixels: int):
        provider = layer.dataProvider()
        native = layer.rasterUnitsPerPixelX() if provider.capabilities() & provider.Size else 0
        res = max(math.sqrt(rect.width() * rect.height() / max_pixels), native or 0)
        self.cols, self.rows = max(16, int(rect.width() / res)), max(16, int(rect.height() / res))
        self.provider, self.crs, self.rect = provider.clone(), layer.crs(), rect
        self.name, self.kind = layer.name(), layer.providerType()
        key = f"{self.kind}|{layer.source()}|{rect.toString(12)}|{self.cols}x{self.rows}"
        self.warnings = []  # why the cache is not used, when it is not
        self.path = os.path.join(_layers_folder(self.warnings), hashlib.sha256(key.encode()).hexdigest()[:24] + ".tif")

    def write(self, feedback=None) -> str:
        """The GeoTIFF's path (``feedback``: a ``QgsRasterBlockFeedback`` that may cancel)."""
        if os.path.isfile(self.path) and not os.path.islink(self.path):
            return self.path
        tmp = self.path + f".{os.getpid()}.part.tif"
        pipe = QgsRasterPipe()
        if not pipe.set(self.provider):
            raise InputError(f"The reference layer '{self.name}' cannot be read ({self.kind}).")
        error = QgsRasterFileWriter(tmp).writeRaster(pipe, self.cols, self.rows, self.rect, self.crs,
                                                    QgsProject.instance().transformContext(), feedback)
        if error != QgsRasterFileWriter.NoError or not os.path.exists(tmp):
            raise InputError(f"The reference layer '{self.name}' could not be read over the area needed "
                             f"({self.kind} provider, error {int(error)}).")
        os.replace(tmp, self.path)
        return self.path


class Shapes:
    """The areas and lines of a vector layer over ``rect`` (layer CRS), drawn at a pixel size that fits
    ``max_pixels`` into a GeoTIFF under Hamta's cache (drawn again each time: a layer's features may have been
    edited): what the layer holds, not its style (a shape drawn hollow or in the paper's colour is still a
    shape)."""

    def __init__(self, layer, rect: QgsRectangle, max_pixels: int):
        res = math.sqrt(max(rect.width() * rect.height(), 1e-12) / max_pixels)
        self.cols, self.rows = max(16, int(rect.width() / res)), max(16, int(rect.height() / res))
        self.source, self.crs, self.rect = QgsVectorLayerFeatureSource(layer), layer.crs(), rect
        self.name, self.kind = layer.name(), layer.providerType()
        key = f"shapes|{layer.id()}|{layer.source()}|{rect.toString(12)}|{self.cols}x{self.rows}"
        self.warnings = []
        self.path = os.path.join(_layers_folder(self.warnings), hashlib.sha256(key.encode()).hexdigest()[:24] + ".tif")

    def write(self, feedback=None) -> str:
        """The GeoTIFF's path (``feedback``: anything with ``isCanceled()``)."""
        from shapely import wkb

        from ..core.errors import RegistrationCanceled
        from ..core.io.rasterize import write_shapes

        def shapes():
            for feature in self.source.getFeatures(QgsFeatureRequest().setFilterRect(self.rect)):
                if feedback is not None and feedback.isCanceled():
                    raise RegistrationCanceled("canceled while the reference layer was read")
                geometry = feature.geometry()
                if not geometry.isNull():
                    yield wkb.loads(bytes(geometry.asWkb()))

        r = self.rect
        drawn = write_shapes(shapes(), (r.xMinimum(), r.yMinimum(), r.xMaximum(), r.yMaximum()),
                             (self.cols, self.rows), self.crs.toWkt(), self.path)
        if not drawn:
            os.remove(self.path)
            raise InputError(f"The reference layer '{self.name}' has no areas or lines over the area needed.")
        return self.path


def _layers_folder(warnings: list) -> str:
    """The cache's ``layers`` folder, or a private temporary one where the cache cannot be used safely."""
    store = Cache.open(default_cache(), warnings)
    try:
        if store is not None:
            return store.folder("layers")
    except Unusable as exc:
        warnings.append(f"The cache folder '{store.root}' is not used: {exc}.")
    return tempfile.mkdtemp(prefix="hamta-layer-")
