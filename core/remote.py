"""Registering onto a map service (XYZ tiles, WMS): where to look, at which zoom, coarse to fine.

A tile layer covers the world at many zoom levels, so it is never read whole. The area to read is

- for a georeferenced target (its georeferencing used): its footprint plus a margin
  (``FOOTPRINT_MARGIN``), at the zoom whose pixels match the target's;
- otherwise the search area (``RegisterOptions.extent``), searched coarse to fine: read at the
  finest zoom where it fits the pixel budget and holds at most ``2 * AREA_SHARE`` times the target's
  pixels (a layer's finest zooms often only magnify coarser data), the target is located there;
  when another zoom is nearer the target's own pixels (finer or coarser), its footprint (plus
  ``LOCATED_MARGIN``) is read at that zoom and the target registered again onto it. The final
  registration is verified like any other; the coarse one only says where to look.

Each area becomes a local GeoTIFF in the service's CRS (EPSG:3857 for XYZ layers) under the cache
folder (a private temporary folder without one), so outputs are in the service's CRS and a rerun
fetches nothing.
"""
from __future__ import annotations

import dataclasses
import math
import os

import numpy as np

from .basemap.fetch import Fetcher, ServiceError
from .basemap.services import TileService
from .basemap.tiles import fetch_area, tile_range
from .coords import pixel_to_map, raster_outline
from .errors import InputError, InsufficientMatchesError
from .extent import bounds_in, parse_extent
from .io.raster import open_raster
from .io.working import footprint
from .options import RegisterOptions
from .pipeline import register
from .progress import Monitor

FOOTPRINT_MARGIN = 0.3  # of the footprint's larger side, each way: georeferencing off by up to a third of it
LOCATED_MARGIN = 0.1  # the same once the coarse search has located the target (to a coarse pixel or so)
MIN_AREA_PX = 64  # a search area narrower than this at the finest zoom cannot hold a target
AREA_SHARE = 7  # the target is first looked for as if it covered 1/7 of the search area: a target covering 1/25
# to 1/2 of it is then within a factor 2 of that scale, which every method of 'auto' matches across


def register_remote(target, service: TileService, options: RegisterOptions, monitor: Monitor, fetcher=None,
                    **kwargs):
    """Register ``target`` onto ``service`` (see the module docstring); ``kwargs`` go to
    :func:`hamta.core.pipeline.register`. The result's ``reference_service`` records the service
    (without credentials), the zoom levels read and the fetch statistics."""
    reader = _Reader(service, fetcher or Fetcher())
    info = open_raster(target, "target")
    local = dataclasses.replace(options, extent=None)

    def register_onto(path, span, within=None, **extra):
        """``within``: the part of the area file to search (bounds in its CRS); all of it by default."""
        area = None if within is None else ",".join(f"{v:.10g}" for v in within) + f",{service.crs}"
        return register(target, path, options=dataclasses.replace(local, extent=area), progress=span.report,
                        is_canceled=span.canceled, **extra, **kwargs)

    notes = []
    if uses_georeferencing(info, options):
        poly = _footprint(info, service.crs)
        bounds = _padded(poly.bounds, FOOTPRINT_MARGIN)
        pixel_size = math.sqrt(poly.area / (info.width * info.height))
        z = _zoom_in_budget(service, bounds, pixel_size, options.max_working_pixels)
        result = register_onto(reader.read(bounds, z, monitor.span(0.0, 0.15)), monitor.span(0.15, 1.0))
    elif options.extent is None:
        raise InputError(f"The target raster '{info.path}' has no usable georeferencing, so Hamta cannot tell where "
                         f"to look in the map service {service.label}: give a search area (CLI: --extent "
                         "xmin,ymin,xmax,ymax,EPSG:4326; in QGIS the search area, by default the map canvas).")
    else:
        result, z = _search(info, reader, options, monitor, register_onto, notes)
    record = {"service": service.label, "id": service.id, "kind": service.kind, "crs": service.crs,
              "zoom": z, "zooms_read": reader.zooms, "fetch": reader.fetcher.stats.to_dict()}
    return dataclasses.replace(result, reference_service=record, notes=notes + list(result.notes))


def uses_georeferencing(info, options: RegisterOptions) -> bool:
    """Whether the target's own georeferencing says where to look (else the search area must)."""
    return info.georeferenced and info.crs is not None and options.target_georef != "ignore"


def footprint_bounds(info, crs: str):
    """The bounds of the target's footprint in ``crs`` plus :data:`FOOTPRINT_MARGIN` each way (map units)."""
    return _padded(_footprint(info, crs).bounds, FOOTPRINT_MARGIN)


def _footprint(info, crs: str):
    from rasterio.crs import CRS

    return footprint(info, CRS.from_user_input(crs))


def _padded(bounds, margin: float):
    """``bounds`` widened by ``margin`` of their larger side each way."""
    x0, y0, x1, y1 = bounds
    pad = margin * max(x1 - x0, y1 - y0)
    return x0 - pad, y0 - pad, x1 + pad, y1 + pad


class _Reader:
    """Reads areas of ``service`` into GeoTIFFs under the fetcher's cache, recording the zooms read."""

    def __init__(self, service: TileService, fetcher: Fetcher):
        self.service, self.fetcher, self.zooms = service, fetcher, []
        if fetcher.cache:
            os.makedirs(fetcher.cache, mode=0o700, exist_ok=True)  # made private; an existing folder is as it is
        self.folder = os.path.join(fetcher.cache, "areas") if fetcher.cache else _temporary()

    def read(self, bounds, z: int, monitor: Monitor) -> str:
        tiles = tile_range(self.service, bounds, z)
        if tiles.count > self.fetcher.max_requests:
            raise ServiceError(f"Reading the area at zoom {z} from {self.service.label} needs {tiles.count} tiles, "
                               f"above the cap of {self.fetcher.max_requests}: choose a smaller search area.")
        self.zooms.append(z)
        return fetch_area(self.service, tiles, self.fetcher, self.folder, monitor)


def _search(info, reader: _Reader, options: RegisterOptions, monitor: Monitor, register_onto, notes):
    """Coarse to fine over the search area (see the module docstring); the result and the zoom it was
    registered onto. ``notes`` get what was searched."""
    service = reader.service
    bounds = _search_bounds(options.extent, service)
    pixels = min(options.max_working_pixels, 2 * AREA_SHARE * info.width * info.height)  # not far finer than the target
    z = _zoom_in_budget(service, bounds, 0.0, pixels)
    path = reader.read(bounds, z, monitor.span(0.0, 0.1))
    try:
        coarse = register_onto(path, monitor.span(0.1, 0.45), within=bounds,  # whole tiles reach beyond the area
                               target_pixels=_guess_pixels(bounds, service, z))
    except InsufficientMatchesError as exc:
        raise InsufficientMatchesError(
            f"The target raster '{info.path}' was not found in the search area read at zoom {z} "
            f"({_pixel_text(service, z)} pixels): {str(exc).rstrip('.')}. If the target covers less than about a "
            "twenty-fifth of the area, give a smaller search area; check that the area holds the target.", exc.found,
            exc.needed) from None
    scale = _target_pixel(coarse.model, info)  # coarse reference pixels per target pixel
    z_target = min(max(z + int(round(math.log2(1.0 / scale))), service.zmin), service.zmax)  # nearest its pixels
    found = "found" if coarse.verified else "placed, without verification,"
    notes.append(f"searched {_size_text(bounds, service)} at zoom {z} ({_pixel_text(service, z)} pixels) for the "
                 f"target at 1/{AREA_SHARE} of the area's size (scales from 1/{2 * AREA_SHARE} to 2/{AREA_SHARE} of "
                 f"it for most methods); it was {found} with pixels of {scale:.2g} of that zoom's")
    if z_target == z:
        return coarse, z
    around = _around(coarse, info)
    z_fine = _zoom_in_budget(service, around, service.resolution(z_target), options.max_working_pixels)
    path = reader.read(around, z_fine, monitor.span(0.45, 0.5))
    notes.append(f"then registered onto its footprint read at zoom {z_fine} ({_pixel_text(service, z_fine)} pixels)")
    try:
        result = register_onto(path, monitor.span(0.5, 1.0))
    except InsufficientMatchesError as exc:
        notes.append(f"the registration at zoom {z_fine} found no model ({exc}); the result is the one at zoom {z}")
        return coarse, z
    if not result.verified and coarse.verified:
        notes.append(f"the registration at zoom {z_fine} did not verify; the result is the one at zoom {z}")
        return coarse, z
    return result, z_fine


def _guess_pixels(bounds, service: TileService, z: int) -> int:
    """The target's working size when it is searched at zoom ``z``: :data:`AREA_SHARE` of the area."""
    return int((bounds[2] - bounds[0]) * (bounds[3] - bounds[1]) / service.resolution(z) ** 2 / AREA_SHARE)


def _zoom_in_budget(service: TileService, bounds, pixel_size: float, max_pixels: int) -> int:
    """The finest zoom whose pixels are at least 0.75 ``pixel_size`` (0: any) at which ``bounds`` fits
    ``max_pixels``; the coarsest zoom when none is that coarse."""
    area = (bounds[2] - bounds[0]) * (bounds[3] - bounds[1])
    for z in range(service.zmax, service.zmin - 1, -1):
        res = service.resolution(z)
        if area / res ** 2 <= max_pixels and (res >= pixel_size * 0.75 or z == service.zmin):
            return z
    raise InputError(f"The search area ({_size_text(bounds, service)}) is too large for {service.label}: even at its "
                     f"coarsest zoom ({service.zmin}) it exceeds the pixel budget. Give a smaller search area.")


def _search_bounds(text: str, service: TileService):
    """The search area in the service's CRS, clipped to its grid; refused when it is too small to hold a
    target (or its numbers look like metres given without their CRS)."""
    area = parse_extent(text)
    if area.crs is None and max(abs(v) for v in area.bounds) > 180:
        raise InputError(f"The search area '{text}' has no CRS, so it is read as longitudes and latitudes, but its "
                         "numbers are beyond 180: add the CRS they are in (e.g. ',EPSG:3857' for Web Mercator metres).")
    x0, y0, x1, y1 = bounds_in(area, service.crs, "EPSG:4326")
    (ox, oy), tile = service.origin(), service.resolution(0) * service.tile_px
    x0, x1 = max(x0, ox), min(x1, ox + tile * service.tile_count(0)[0])
    y0, y1 = max(y0, oy - tile * service.tile_count(0)[1]), min(y1, oy)
    if min(x1 - x0, y1 - y0) < MIN_AREA_PX * service.resolution(service.zmax):
        raise InputError(f"The search area '{text}' is only {_size_text((x0, y0, x1, y1), service)} in {service.crs}, "
                         "too small to hold a target at the layer's finest zoom.")
    return x0, y0, x1, y1


def _target_pixel(model, info) -> float:
    """Reference pixels per target pixel, from the model's mapping of the target's outline."""
    outline = raster_outline(info.width, info.height, 9, ends=True)
    mapped = model.apply(outline)
    from shapely.geometry import Polygon

    area = Polygon(mapped).buffer(0).area
    return math.sqrt(max(area, 1e-12) / (info.width * info.height))


def _around(result, info):
    """The bounds (map units) of the target's footprint through ``result``, plus :data:`LOCATED_MARGIN`."""
    xy = pixel_to_map(result.reference.transform, result.model.apply(raster_outline(info.width, info.height, 9,
                                                                                    ends=True)))
    return _padded((*np.nanmin(xy, axis=0), *np.nanmax(xy, axis=0)), LOCATED_MARGIN)


def _pixel_text(service: TileService, z: int) -> str:
    unit = "°" if service.crs == "EPSG:4326" else " m"
    return f"{service.resolution(z):.4g}{unit}"


def _size_text(bounds, service: TileService) -> str:
    if service.crs == "EPSG:4326":
        return f"{bounds[2] - bounds[0]:.4g}° x {bounds[3] - bounds[1]:.4g}°"
    return f"{(bounds[2] - bounds[0]) / 1000:.4g} x {(bounds[3] - bounds[1]) / 1000:.4g} km (map units)"


def _temporary() -> str:
    """A private folder of this process, removed at exit (areas read without a disk cache)."""
    import atexit
    import shutil
    import tempfile

    folder = tempfile.mkdtemp(prefix="hamta-areas-")
    atexit.register(shutil.rmtree, folder, True)
    return folder


