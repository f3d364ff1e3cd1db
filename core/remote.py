"""Registering onto a map service (XYZ tiles, WMS): where to look, at which zoom, coarse to fine.

A tile layer covers the world at many zoom levels, so it is never read whole. The area to read is

- for a georeferenced target (its georeferencing used): its footprint plus a margin
  (``FOOTPRINT_MARGIN``), at the zoom whose pixels match the target's;
- otherwise the search area (``RegisterOptions.extent``), searched coarse to fine: read at the zoom
  where its longer side is about 1024, 2048, then 4096 px (``AREA_SIDES``), the target is located by
  features voting for a pose (:mod:`hamta.core.matching.locate`: any rotation, scale and place; SIFT's
  features, then, with the 'learned' extra, XFeat's where SIFT's best places did not verify) and by its
  structure correlated at every turn and scale (:mod:`hamta.core.matching.structure`: each zoom the
  target sides the coarser ones were too coarse for, so the finest finds targets 1/40 of the area's
  side); each of the few places found has its footprint (plus ``LOCATED_MARGIN``) read at the
  zoom nearest the target's own pixels, and the target is registered there with that place as its
  prior, as if it had been georeferenced there. At the first zoom, before the places with few agreeing
  features, the whole area is registered once as well (the target assumed to cover ``AREA_SHARE`` of
  it). Each registration is verified like any other, held to its share of one check's risk of
  verifying a wrong model (``SEARCH_TRIES``: a search checks several); the first verified one is the
  result (else the best unverified one). A place found is only where to look, never a result; one that puts the target
  outside the search area is not taken. The run's time budget bounds the whole search.

Each area becomes a local GeoTIFF in the service's CRS (EPSG:3857 for XYZ layers) under the cache
folder (a private temporary folder without one), so outputs are in the service's CRS and a rerun
fetches nothing.
"""
from __future__ import annotations

import dataclasses
import math
import time

import numpy as np
from affine import Affine

from .basemap.fetch import Fetcher, ServiceError
from .basemap.services import TileService
from .basemap.tiles import NoTiles, fetch_area, tile_range
from .coords import map_to_pixel, pixel_to_map, raster_outline
from .errors import InputError, InsufficientMatchesError
from .extent import bounds_in, parse_extent
from .io.raster import open_raster, read_image
from .io.working import footprint
from .matching.places import (
    CANDIDATES,
    MIN_INLIERS,
    candidates,
    learned_target_features,
    seen,
    structure_sides,
    target_features,
)
from .options import RegisterOptions
from .pipeline import register
from .progress import Monitor
from .verify import VerifyParams, result_rank

FOOTPRINT_MARGIN = 0.3  # of the footprint's larger side, each way: georeferencing off by up to a third of it
LOCATED_MARGIN = 0.1  # the same once the coarse search has located the target (to a coarse pixel or so)
MIN_AREA_PX = 64  # a search area narrower than this at the finest zoom cannot hold a target


def register_remote(target, service: TileService, options: RegisterOptions, monitor: Monitor, fetcher=None,
                    **kwargs):
    """Register ``target`` onto ``service`` (see the module docstring); ``kwargs`` go to
    :func:`hamta.core.pipeline.register`. The result's ``reference_service`` records the service
    (without credentials), the zoom levels read and the fetch statistics."""
    reader = _Reader(service, fetcher or Fetcher())
    info = open_raster(target, "target")
    local = dataclasses.replace(options, extent=None)

    def register_onto(path, span, within=None, options=None, **extra):
        """``within``: the part of the area file to search (bounds in its CRS); all of it by default.
        ``options``: the run's unless given (a search's places get what is left of its time budget)."""
        area = None if within is None else ",".join(f"{v:.10g}" for v in within) + f",{service.crs}"
        return register(target, path, options=dataclasses.replace(options or local, extent=area),
                        progress=span.report, is_canceled=span.canceled, **extra, **kwargs)

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
    return dataclasses.replace(result, reference_service=record,
                               notes=reader.fetcher.warnings + notes + list(result.notes))


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
        self.finest, self.empty_from = service.zmax, None
        self.folder = fetcher.folder("areas") or _temporary()

    def read(self, bounds, z: int, monitor: Monitor) -> str:
        """The GeoTIFF of ``bounds`` at zoom ``z`` or, where the layer has no tile there, at the nearest
        coarser zoom that has (a plain tile template does not say its finest zoom; reads after that one
        stop there); ``self.zooms`` records the zoom read."""
        z = min(z, self.finest)
        while True:
            tiles = tile_range(self.service, bounds, z)
            if tiles.count > self.fetcher.max_requests:
                raise ServiceError(f"Reading the area at zoom {z} from {self.service.label} needs {tiles.count} "
                                   f"tiles, above the cap of {self.fetcher.max_requests}: choose a smaller search "
                                   "area.")
            try:
                path = fetch_area(self.service, tiles, self.fetcher, self.folder, monitor)
            except NoTiles:
                if self.empty_from is None:
                    self.empty_from = z
                if z <= self.service.zmin or z <= self.empty_from - FINER_STEPS:
                    raise
                self.finest = z = z - 1
                continue
            self.zooms.append(z)
            return path


FINER_STEPS = 3  # zooms tried below one whose tiles were all missing, before the area counts as empty


def _search(info, reader: _Reader, options: RegisterOptions, monitor: Monitor, register_onto, notes):
    """Locate the target in the search area, coarse to fine, and register it where it was found (see the
    module docstring); the result and the zoom it was registered onto. ``notes`` get what was searched."""
    service = reader.service
    bounds = _search_bounds(options.extent, service)
    target, per_px, (grey, grey_valid) = target_features(info, options.target_band)
    learned = learned_target_features(grey, grey_valid)
    zooms = _search_zooms(service, bounds)
    deadline = time.monotonic() + options.auto_budget_s

    def budgeted():
        """The options of one place: what is left of the run's time budget."""
        return dataclasses.replace(options, auto_budget_s=max(0.0, deadline - time.monotonic()))

    best, places, searched, whole_tried = None, [], [], False
    spent = f"the time budget of {options.auto_budget_s:g} s was spent before every place was tried"
    for i, z in enumerate(zooms):
        if time.monotonic() > deadline:  # a finer zoom costs its tiles and its locating before any place
            notes.extend([spent] if spent not in notes else [])
            break
        span = monitor.span(i / len(zooms), (i + 1) / len(zooms))
        path = reader.read(bounds, z, span.span(0.0, 0.3))
        z = reader.zooms[-1]
        if z in searched:  # the layer's finest zoom was reached: this one was searched already
            continue
        searched.append(z)
        span.report(0.3, f"locating the target at zoom {z}")
        area = open_raster(path, "reference")
        image, valid = read_image(area, (1, 2, 3))
        _outside(valid, area.transform, bounds)
        tried = []
        side = max(bounds[2] - bounds[0], bounds[3] - bounds[1]) / service.resolution(z)
        structure = grey, grey_valid, structure_sides(side, 2.0 ** (z - searched[-2]) if len(searched) > 1 else None)
        for j, (found_by, c) in enumerate(candidates(target, learned, image, valid, not whole_tried, structure)):
            step = span.span(0.4 + 0.6 * j / STEPS_PER_ZOOM, 0.4 + 0.6 * min(j + 1, STEPS_PER_ZOOM) / STEPS_PER_ZOOM)
            if time.monotonic() > deadline:
                notes.append(spent)
                break
            if c is None:
                whole_tried = True
                result, z_fine = _register_whole_area(info, reader, bounds, z, budgeted(), register_onto, step, notes)
            else:
                placed = area.transform * Affine(*c.matrix.ravel()) * Affine.scale(per_px)
                if seen(placed, info.width, info.height, places) or len(places) >= MAX_PLACES:
                    continue
                places.append(placed)
                tried.append(f"a place {found_by} features found ({c.inliers} agreeing)" if c.inliers else
                             f"a place the target's structure matched (score {c.score:.1f})")
                result, z_fine = _register_placed(info, reader, placed, bounds, budgeted(), register_onto, step,
                                                  notes)
            if result is not None and (best is None or result_rank(result) > result_rank(best[0])):
                best = result, z_fine
            if best is not None and best[0].verified:
                break
        notes.append(f"searched {_size_text(bounds, service)} at zoom {z} ({_pixel_text(service, z)} pixels): "
                     + (", ".join(tried) or "no place with enough agreeing features"))
        del image, valid
        if best is not None and best[0].verified:
            return best
    if best is None:
        raise InsufficientMatchesError(
            f"The target raster '{info.path}' was not found in the search area ({_size_text(bounds, service)}, "
            f"read at zoom{'s' if len(searched) > 1 else ''} {', '.join(map(str, searched))}): "
            + (f"none of the {len(places)} places that looked alike registered. " if places else
               "no place in it looked enough like the target. ")
            + "Zoom the map closer to where the target is (a search area a few times its size), and check that the "
              "area holds it; a target that is mirrored, or whose ground has mostly changed since, may not be found.",
            0, MIN_INLIERS) from None
    return best


MAX_PLACES = 6  # places registered in all
STEPS_PER_ZOOM = 3 * CANDIDATES + 1  # places of both features, of the structure and the whole area: progress steps
SEARCH_TRIES = MAX_PLACES + 2  # registrations a search may check: the places and the whole area (coarse, then fine)
AREA_SHARE = 7  # the share of the area's pixels a target is assumed to cover when the whole area is registered
AREA_SIDES = (1024, 2048, 4096)  # px: the search area's longer side at each zoom searched, coarse to fine: the target
# at 1/30 of the area's side is still 136 px at the last


def _search_zooms(service: TileService, bounds) -> list:
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


def _register_whole_area(info, reader: _Reader, bounds, z: int, options: RegisterOptions, register_onto,
                         monitor: Monitor, notes):
    """When no place found verifies: the target registered onto the whole area read at zoom ``z`` as if it
    covered :data:`AREA_SHARE` of it (the methods of 'auto' match across a factor 2 of scale, so a target
    covering 1/25 to 1/2 of the area), then again at the zoom nearest its pixels where that registration
    put it. Areas a few times the target's size, where the area's features are too few to vote, are
    found this way; (result, zoom), or (None, zoom) when it gave nothing in the area."""
    path = reader.read(bounds, z, monitor.span(0.0, 0.1))
    try:
        coarse = register_onto(path, monitor.span(0.1, 0.5), within=bounds, options=options,
                               target_pixels=_guess_pixels(bounds, reader.service, z), short=True)
    except InsufficientMatchesError as exc:
        notes.append(f"the target registered onto the whole area at zoom {z} gave no model ({exc})")
        return None, z
    if not _overlaps(coarse, info, bounds):
        return None, z
    coarse = _held_to_the_search(coarse)
    notes.append(f"the target registered onto the whole area at zoom {z}: {coarse.verification.verdict}")
    fine, z_fine = _register_placed(info, reader, _placed_from(coarse, info), bounds, options, register_onto,
                                    monitor.span(0.5, 1.0), notes)
    if fine is not None and result_rank(fine) > result_rank(coarse):
        return fine, z_fine
    return coarse, z


def _held_to_the_search(result):
    """``result``, made 'suspect' where its check verified it but would not have at a :data:`SEARCH_TRIES`-th
    of the chance levels: a search checks up to that many candidates, and a wrong one passes a single check
    by chance more often the more are tried (on the basemap-real family, once in 29 searches)."""
    v = result.verification
    if not v.verified or VerifyParams(tolerance_px=v.tolerance_px).tried(SEARCH_TRIES).significant(v):
        return result
    reason = (f"the search checked up to {SEARCH_TRIES} candidates, and this one's agreement is not {SEARCH_TRIES} "
              "times as unlikely by chance as one check asks")
    return dataclasses.replace(result, verification=dataclasses.replace(v, verdict="suspect",
                                                                        reasons=v.reasons + (reason,)))


def _outside(valid: np.ndarray, transform, bounds) -> None:
    """Mark the pixels of an area read as whole tiles that lie outside the search area ``bounds`` invalid:
    a target is looked for where the user asked, not in the tiles' margins."""
    (c0, r0), (c1, r1) = map_to_pixel(transform, np.array([[bounds[0], bounds[3]], [bounds[2], bounds[1]]]))
    c0, r0 = max(0, int(math.floor(c0))), max(0, int(math.floor(r0)))
    c1, r1 = int(math.ceil(c1)), int(math.ceil(r1))
    valid[:r0] = False
    valid[r1:] = False
    valid[:, :c0] = False
    valid[:, c1:] = False


def _overlaps(result, info, bounds) -> bool:
    """Whether ``result`` puts the target's footprint over the search area at all (the search answers where
    the user asked: a target found beside the area, through the margin read around a place, is not taken)."""
    from shapely.geometry import Polygon, box

    outline = pixel_to_map(result.reference.transform,
                           result.model.apply(raster_outline(info.width, info.height, 9, ends=True)))
    polygon = Polygon(outline).buffer(0)
    return polygon.is_valid and polygon.intersects(box(*bounds))


def _register_placed(info, reader: _Reader, placed, bounds, options: RegisterOptions, register_onto, monitor: Monitor,
                     notes):
    """Register the target onto its footprint through ``placed`` (target px -> map), read at the zoom
    nearest its pixels; (result, zoom), or (None, zoom) when no method found a model there or the model
    puts the target outside the search area ``bounds``."""
    outline = pixel_to_map(placed, raster_outline(info.width, info.height, 9, ends=True))
    around = _padded((*outline.min(axis=0), *outline.max(axis=0)), LOCATED_MARGIN)
    pixel = math.sqrt(abs(placed.determinant))
    z = _zoom_in_budget(reader.service, around, pixel, options.max_working_pixels)
    path = reader.read(around, z, monitor.span(0.0, 0.2))
    z = reader.zooms[-1]
    try:
        result = register_onto(path, monitor.span(0.2, 1.0), options=options, placed=placed, short=True)
    except InsufficientMatchesError as exc:
        notes.append(f"a place registered at zoom {z} gave no model ({exc})")
        return None, z
    if not _overlaps(result, info, bounds):
        notes.append(f"a place registered at zoom {z} put the target outside the search area; it was not taken")
        return None, z
    return _held_to_the_search(result), z


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


def _placed_from(result, info) -> Affine:
    """The affine map (target px -> map) nearest ``result``'s model over the target (least squares on a grid)."""
    grid = raster_outline(info.width, info.height, 9, ends=True)
    xy = pixel_to_map(result.reference.transform, result.model.apply(grid))
    design = np.column_stack([grid, np.ones(len(grid))])
    (a, d), (b, e), (c, f) = np.linalg.lstsq(design, xy, rcond=None)[0]
    return Affine(a, b, c, d, e, f)


def _guess_pixels(bounds, service: TileService, z: int) -> int:
    """The target's working size when the whole area is registered at zoom ``z``: :data:`AREA_SHARE` of it."""
    return int((bounds[2] - bounds[0]) * (bounds[3] - bounds[1]) / service.resolution(z) ** 2 / AREA_SHARE)


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


