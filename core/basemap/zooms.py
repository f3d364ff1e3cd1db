"""The zooms of a map service a registration reads: the search area's, a place's, the target's footprint's.

Map units are those of the service's grid CRS (EPSG:3857 metres for XYZ layers).
"""
from __future__ import annotations

import math

from ..errors import InputError
from ..extent import bounds_in, parse_extent
from .services import TileService

MIN_AREA_PX = 64  # a search area narrower than this at the finest zoom cannot hold a target
AREA_SIDES = (1024, 2048, 4096)  # px: the search area's longer side at each zoom searched, coarse to fine: the target
# at 1/30 of the area's side is still 136 px at the last


def search_zooms(service: TileService, bounds) -> list:
    """The zooms at which the search area's longer side is about each of :data:`AREA_SIDES` (coarsest
    first; fewer where the layer's finest zoom is reached)."""
    side = max(bounds[2] - bounds[0], bounds[3] - bounds[1])
    zooms = []
    for px in AREA_SIDES:
        z = int(math.floor(math.log2(px * service.resolution(0) / side) + 0.2))
        z = min(max(z, service.zmin), service.zmax)
        if z not in zooms:
            zooms.append(z)
    return zooms


def zoom_in_budget(service: TileService, bounds, pixel_size: float, max_pixels: int) -> int:
    """The finest zoom whose pixels are at least 0.75 ``pixel_size`` (0: any) at which ``bounds`` fits
    ``max_pixels``; the coarsest zoom when none is that coarse."""
    area = (bounds[2] - bounds[0]) * (bounds[3] - bounds[1])
    for z in range(service.zmax, service.zmin - 1, -1):
        res = service.resolution(z)
        if area / res ** 2 <= max_pixels and (res >= pixel_size * 0.75 or z == service.zmin):
            return z
    raise InputError(f"The search area ({size_text(bounds, service)}) is too large for {service.label}: even at its "
                     f"coarsest zoom ({service.zmin}) it exceeds the pixel budget. Give a smaller search area.")


def padded(bounds, margin: float):
    """``bounds`` widened by ``margin`` of their larger side each way."""
    x0, y0, x1, y1 = bounds
    pad = margin * max(x1 - x0, y1 - y0)
    return x0 - pad, y0 - pad, x1 + pad, y1 + pad


def search_bounds(text: str, service: TileService):
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
        raise InputError(f"The search area '{text}' is only {size_text((x0, y0, x1, y1), service)} in {service.crs}, "
                         "too small to hold a target at the layer's finest zoom.")
    return x0, y0, x1, y1


def pixel_text(service: TileService, z: int) -> str:
    unit = "°" if service.crs == "EPSG:4326" else " m"
    return f"{service.resolution(z):.4g}{unit}"


def size_text(bounds, service: TileService) -> str:
    if service.crs == "EPSG:4326":
        return f"{bounds[2] - bounds[0]:.4g}° x {bounds[3] - bounds[1]:.4g}°"
    return f"{(bounds[2] - bounds[0]) / 1000:.4g} x {(bounds[3] - bounds[1]) / 1000:.4g} km (map units)"
