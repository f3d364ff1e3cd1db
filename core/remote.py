"""Registering onto a map service (XYZ tiles, WMS): where to look, at which zoom, coarse to fine.

A tile layer covers the world at many zoom levels, so it is never read whole. The area to read is

- for a georeferenced target (its georeferencing used): its footprint plus a margin
  (``FOOTPRINT_MARGIN``), at the zoom whose pixels match the target's;
- otherwise the search area (``RegisterOptions.extent``), searched coarse to fine: read at the zoom where
  its longer side is about 1024, 2048, then 4096 px (``AREA_SIDES``, :mod:`hamta.core.basemap.zooms`), the
  target is located by features voting for a pose (:mod:`hamta.core.matching.locate`: any rotation, scale
  and place; SIFT's features, then, with the 'learned' extra, XFeat's where SIFT's best places did not
  verify) and by its structure correlated at every turn and scale (:mod:`hamta.core.matching.structure`:
  each zoom the target sides the coarser ones were too coarse for, so the finest finds targets 1/40 of the
  area's side); each of the few places found has its footprint (plus ``LOCATED_MARGIN``) read at the zoom
  nearest the target's own pixels, and the target is registered there with that place as its prior, as if
  it had been georeferenced there. At the first zoom, before the places with few agreeing features, the
  whole area is registered once as well (the target assumed to cover ``AREA_SHARE`` of it). Each
  registration is verified like any other, held to its share of one check's risk of verifying a wrong model
  (``SEARCH_TRIES``: a search checks several); the first verified one is the result (else the best
  unverified one). A place found is only where to look, never a result; one that puts the target
  outside the search area is not taken. The run's time budget bounds the whole search.

A place's failure is that place's outcome (no data there, no model, a read area that misses it, the
requests spent): it is noted with the place in the result's notes and ``reference_service['places']``,
and the search goes on. Only the user's own input ends a run with an error: a service that cannot be
reached, an area with no data at any zoom (the first area read), a target that cannot be read. Areas are
read through :class:`hamta.core.basemap.areas.AreaReader`: only tiles near the layer's data and no finer
than its finest zoom, within ``SEARCH_REQUESTS`` requests (a finer zoom of the whole area only where it
leaves ``PLACE_RESERVE`` of them for the places).

Each area becomes a local GeoTIFF in the service's CRS (EPSG:3857 for XYZ layers) under the cache
folder (a private temporary folder without one), so outputs are in the service's CRS and a rerun
fetches nothing.
"""
from __future__ import annotations

import dataclasses
import math
import time
from collections import Counter
from functools import partial

import numpy as np
from affine import Affine

from .basemap.areas import AreaReader, mask_outside
from .basemap.fetch import Fetcher
from .basemap.services import TileService
from .basemap.tiles import NoTiles
from .basemap.zooms import padded, pixel_text, search_bounds, search_zooms, size_text, zoom_in_budget
from .coords import pixel_to_map, raster_outline
from .errors import HamtaError, InputError, InsufficientMatchesError, NoOverlapError, RegistrationCanceled
from .io.raster import open_raster, read_image
from .io.working import footprint
from .matching.places import (
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


def register_remote(target, service: TileService, options: RegisterOptions, monitor: Monitor, fetcher=None,
                    **kwargs):
    """Register ``target`` onto ``service`` (see the module docstring); ``kwargs`` go to
    :func:`hamta.core.pipeline.register`. The result's ``reference_service`` records the service
    (without credentials), the zoom levels read and the fetch statistics."""
    fetcher = fetcher or Fetcher()
    info = open_raster(target, "target")
    searching = not uses_georeferencing(info, options)
    reader = AreaReader(service, fetcher, min(SEARCH_REQUESTS, fetcher.max_requests) if searching else
                     fetcher.max_requests)
    local = dataclasses.replace(options, extent=None)

    def register_onto(path, span, within=None, options=None, **extra):
        """``within``: the part of the area file to search (bounds in its CRS); all of it by default.
        ``options``: the run's unless given (a search's places get what is left of its time budget)."""
        area = None if within is None else ",".join(f"{v:.10g}" for v in within) + f",{service.crs}"
        return register(target, path, options=dataclasses.replace(options or local, extent=area),
                        progress=span.report, is_canceled=span.canceled, **extra, **kwargs)

    notes, places = [], []
    if not searching:
        poly = _footprint(info, service.crs)
        bounds = padded(poly.bounds, FOOTPRINT_MARGIN)
        pixel_size = math.sqrt(poly.area / (info.width * info.height))
        z = zoom_in_budget(service, bounds, pixel_size, options.max_working_pixels)
        result = register_onto(reader.read(bounds, z, monitor.span(0.0, 0.15)), monitor.span(0.15, 1.0))
    elif options.extent is None:
        raise InputError(f"The target raster '{info.path}' has no usable georeferencing, so Hamta cannot tell where "
                         f"to look in the map service {service.label}: give a search area (CLI: --extent "
                         "xmin,ymin,xmax,ymax,EPSG:4326; in QGIS the search area, by default the map canvas).")
    else:
        result, z = _search(info, reader, options, monitor, register_onto, notes, places)
    record = {"service": service.label, "id": service.id, "kind": service.kind, "crs": service.crs,
              "zoom": z, "zooms_read": reader.zooms, "finest_zoom": reader.known, "fetch": fetcher.stats.to_dict()}
    if searching:
        record["places"] = places
    return dataclasses.replace(result, reference_service=record,
                               notes=reader.fetcher.warnings + notes + list(result.notes))


def uses_georeferencing(info, options: RegisterOptions) -> bool:
    """Whether the target's own georeferencing says where to look (else the search area must)."""
    return info.georeferenced and info.crs is not None and options.target_georef != "ignore"


def footprint_bounds(info, crs: str):
    """The bounds of the target's footprint in ``crs`` plus :data:`FOOTPRINT_MARGIN` each way (map units)."""
    return padded(_footprint(info, crs).bounds, FOOTPRINT_MARGIN)


def _footprint(info, crs: str):
    from rasterio.crs import CRS

    return footprint(info, CRS.from_user_input(crs))


SEARCH_REQUESTS = 400  # the requests a search may send (the fetcher's own cap, when lower, rules)
PLACE_RESERVE = 120  # requests kept for the places when a finer zoom of the whole area is read: two places of
# about 1000 x 1000 px, each read at its own pixels with a margin


def _search(info, reader: AreaReader, options: RegisterOptions, monitor: Monitor, register_onto, notes, places):
    """Locate the target in the search area, coarse to fine, and register it where it was found (see the
    module docstring); the result and the zoom it was registered onto. A place's failure (no data there,
    no model, a read area that misses, the requests spent) is that place's outcome: ``places`` gets one
    record per place tried ({found_by, zoom, outcome}) and ``notes`` a line each; only the first area
    read, the user's search area itself, ends the run with an error."""
    bounds = search_bounds(options.extent, reader.service)
    features = target_features(info, options.target_band)
    learned = learned_target_features(*features[2])
    zooms = search_zooms(reader.service, bounds)
    search = _Search(info, reader, options, monitor, register_onto, bounds, notes, places)
    for i, z in enumerate(zooms):
        if time.monotonic() > search.deadline:  # a finer zoom costs its tiles and its locating before any place
            notes.extend([search.spent] if search.spent not in notes else [])
            break
        span = search.ahead(f"zoom {z}", len(zooms) - i + MAX_PLACES - len(search.placed_at))
        if search.searched and search.leaves_too_few_requests(z):
            break
        try:
            path = reader.read(bounds, z, span.span(0.0, 0.3))
        except RegistrationCanceled:
            raise
        except HamtaError as exc:
            if not search.searched:
                raise
            notes.append(f"zoom {z} was not searched: {reader.plain(exc)}")
            continue
        z = reader.zooms[-1]
        if z in search.searched:  # the layer's finest zoom was reached: this one was searched already
            continue
        search.searched.append(z)
        span.report(0.3, "locating the target")
        search.try_places(path, z, features, learned)
        if search.best is not None and search.best[0].verified:
            return search.best
    if search.best is None:
        raise search.not_found() from None
    return search.best


class _Search:
    """What one search has done so far: the zooms searched, the places tried, the best result and zoom, and
    when its time budget ends."""

    def __init__(self, info, reader: AreaReader, options: RegisterOptions, monitor: Monitor, register_onto, bounds,
                 notes, places):
        self.info, self.reader, self.options, self.monitor = info, reader, options, monitor
        self.register_onto, self.bounds, self.notes, self.places = register_onto, bounds, notes, places
        self.deadline = time.monotonic() + options.auto_budget_s
        self.spent = f"the time budget of {options.auto_budget_s:g} s was spent before every place was tried"
        self.best, self.placed_at, self.searched, self.whole_tried = None, [], [], False

    def budgeted(self) -> RegisterOptions:
        """The options of one place: what is left of the run's time budget."""
        return dataclasses.replace(self.options, auto_budget_s=max(0.0, self.deadline - time.monotonic()))

    def ahead(self, label, parts_left):
        """The part of the bar from where the search stands in its time budget to a share of what is left,
        its messages labelled (the bar moves on while places are tried, whatever their number)."""
        start = min(0.9, 1.0 - (self.deadline - time.monotonic()) / max(self.options.auto_budget_s, 1e-3))
        return self.monitor.span(start, start + (1.0 - start) / max(1, parts_left)).labelled(label)

    def tried(self, found_by, z, outcome) -> None:
        """Record what became of the place ``found_by``, read at zoom ``z``, in ``places`` and ``notes``."""
        self.places.append({"found_by": found_by, "zoom": z, "outcome": outcome})
        self.notes.append(f"{found_by}, read at zoom {z}: {outcome}")

    def leaves_too_few_requests(self, z: int) -> bool:
        """Whether reading the area at zoom ``z`` would leave too few requests for the places (noted)."""
        reader = self.reader
        cost = reader.cost(self.bounds, z)
        if reader.planned + cost + PLACE_RESERVE <= reader.budget:
            return False
        self.notes.append(f"zoom {reader.zoom_for(self.bounds, z)} was not searched: its {cost} tiles would leave "
                          f"too few of the {reader.budget} requests a search may send for the places")
        return True

    def try_places(self, path: str, z: int, features, learned) -> None:
        """Register the target at each place located in the area file ``path`` (read at zoom ``z``) until one
        verifies, and onto the whole area the first time; ``features``, ``learned``: the target's."""
        target, per_px, (grey, grey_valid) = features
        area = open_raster(path, "reference")
        image, valid = read_image(area, (1, 2, 3))
        mask_outside(valid, area.transform, self.bounds)
        count = len(self.places)
        side = max(self.bounds[2] - self.bounds[0], self.bounds[3] - self.bounds[1]) / self.reader.service.resolution(z)
        searched = self.searched
        structure = grey, grey_valid, structure_sides(side, 2.0 ** (z - searched[-2]) if len(searched) > 1 else None)
        for found_by, c in candidates(target, learned, image, valid, not self.whole_tried, structure):
            if time.monotonic() > self.deadline:
                self.notes.append(self.spent)
                break
            placed = None if c is None else area.transform * Affine(*c.matrix.ravel()) * Affine.scale(per_px)
            attempt = self.attempt(found_by, c, z, placed)
            if attempt is None:
                continue
            what, register_there, label = attempt
            try:
                result, z_fine = register_there(self.budgeted(), self.register_onto,
                                                self.ahead(label, MAX_PLACES + 1 - len(self.placed_at)))
            except RegistrationCanceled:
                raise
            except HamtaError as exc:
                self.tried(what, *((exc.zoom, str(exc)) if isinstance(exc, _PlaceFailed) else
                                   (z, _failure(self.reader, exc))))
                continue
            self.tried(what, z_fine, _checked(result))
            if self.best is None or result_rank(result) > result_rank(self.best[0]):
                self.best = result, z_fine
            if self.best[0].verified:
                break
        if len(self.places) == count:
            self.notes.append(f"searched {size_text(self.bounds, self.reader.service)} at zoom {z} "
                              f"({pixel_text(self.reader.service, z)} pixels): no place with enough agreeing features")

    def attempt(self, found_by, c, z: int, placed):
        """(what, how to register there, its progress label) for candidate ``c`` found at zoom ``z`` (None: the
        whole area; else ``placed``, target px -> map), or None for a place tried already or one too many."""
        if c is None:
            self.whole_tried = True
            whole = partial(_register_whole_area, self.info, self.reader, self.bounds, z)
            return f"the whole area at zoom {z}", whole, "the whole area"
        if seen(placed, self.info.width, self.info.height, self.placed_at) or len(self.placed_at) >= MAX_PLACES:
            return None
        self.placed_at.append(placed)
        what = (f"a place {found_by} features found at zoom {z} ({c.inliers} agreeing)" if c.inliers else
                f"a place the target's structure matched at zoom {z} (score {c.score:.1f})")
        register_there = partial(_register_placed, self.info, self.reader, placed, self.bounds)
        return what, register_there, f"place {len(self.placed_at)}"

    def not_found(self) -> InsufficientMatchesError:
        """The error of a search that registered nothing: what was read and tried, and what may help."""
        places, searched = self.places, self.searched
        return InsufficientMatchesError(
            f"The target raster '{self.info.path}' was not found in the search area "
            f"({size_text(self.bounds, self.reader.service)}, "
            f"read at zoom{'s' if len(searched) > 1 else ''} {', '.join(map(str, searched))}): "
            + (f"none of the {len(places)} places tried registered ({_outcomes(places)}). " if places else
               "no place in it looked enough like the target. ")
            + "".join(f"{n[0].upper()}{n[1:]}. " for n in self.notes if "was not searched" in n or n == self.spent)
            + "Zoom the map closer to where the target is (a search area a few times its size), and check that the "
              "area holds it; a target that is mirrored, or whose ground has mostly changed since, may not be found.",
            0, MIN_INLIERS)


class _PlaceFailed(HamtaError):
    """A place gave nothing to keep: ``zoom`` is the zoom it was read at."""

    def __init__(self, message: str, zoom: int):
        super().__init__(message)
        self.zoom = zoom


def _failure(reader: AreaReader, exc: HamtaError) -> str:
    """A place's failure in a few words, naming no file of the cache."""
    if isinstance(exc, NoTiles):
        return "not read: the layer has no data there"
    if isinstance(exc, InsufficientMatchesError):
        return "no model (too few agreeing points)"
    if isinstance(exc, NoOverlapError):
        return "not registered: the place's read area does not hold it"
    return reader.plain(exc)


def _checked(result) -> str:
    """What the independent check said of a place's registration, in words."""
    v = result.verification
    if v is None or v.verdict == "failed":
        return "registered; the check found no agreement"
    if v.verdict == "suspect":
        return "registered; the check found some agreement, not enough to verify"
    return "verified"


def _outcomes(places) -> str:
    """How many places ended each way, most common first."""
    return "; ".join(f"{n} {outcome}" for outcome, n in Counter(p["outcome"] for p in places).most_common())


MAX_PLACES = 6  # places registered in all
SEARCH_TRIES = MAX_PLACES + 2  # registrations a search may check: the places and the whole area (coarse, then fine)
AREA_SHARE = 7  # the share of the area's pixels a target is assumed to cover when the whole area is registered


def _register_whole_area(info, reader: AreaReader, bounds, z: int, options: RegisterOptions, register_onto,
                         monitor: Monitor):
    """When no place found verifies: the target registered onto the whole area read at zoom ``z`` as if it
    covered :data:`AREA_SHARE` of it (the methods of 'auto' match across a factor 2 of scale, so a target
    covering 1/25 to 1/2 of the area), then again at the zoom nearest its pixels where that registration
    put it. Areas a few times the target's size, where the area's features are too few to vote, are
    found this way; (result, zoom). Raises a :class:`HamtaError` when it gives nothing in the area."""
    path = reader.read(bounds, z, monitor.span(0.0, 0.1))
    coarse = register_onto(path, monitor.span(0.1, 0.5), within=bounds, options=options,
                           target_pixels=_guess_pixels(bounds, reader.service, z), short=True)
    if not _overlaps(coarse, info, bounds):
        raise _PlaceFailed("the model puts the target outside the search area; not taken", z)
    coarse = _held_to_the_search(coarse)
    try:
        fine, z_fine = _register_placed(info, reader, _placed_from(coarse, info), bounds, options, register_onto,
                                        monitor.span(0.5, 1.0))
    except RegistrationCanceled:
        raise
    except HamtaError:
        return coarse, z
    if result_rank(fine) > result_rank(coarse):
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


def _overlaps(result, info, bounds) -> bool:
    """Whether ``result`` puts the target's footprint over the search area at all (the search answers where
    the user asked: a target found beside the area, through the margin read around a place, is not taken)."""
    from shapely.geometry import Polygon, box

    outline = pixel_to_map(result.reference.transform,
                           result.model.apply(raster_outline(info.width, info.height, 9, ends=True)))
    polygon = Polygon(outline).buffer(0)
    return polygon.is_valid and polygon.intersects(box(*bounds))


def _register_placed(info, reader: AreaReader, placed, bounds, options: RegisterOptions, register_onto,
                     monitor: Monitor):
    """Register the target onto its footprint through ``placed`` (target px -> map), read at the zoom
    nearest its pixels; (result, zoom). Raises a :class:`HamtaError` when the place gives nothing: no data
    there, no model, or a model that puts the target outside the search area ``bounds``."""
    outline = pixel_to_map(placed, raster_outline(info.width, info.height, 9, ends=True))
    around = padded((*outline.min(axis=0), *outline.max(axis=0)), LOCATED_MARGIN)
    pixel = math.sqrt(abs(placed.determinant))
    z = zoom_in_budget(reader.service, around, pixel, options.max_working_pixels)
    try:
        path = reader.read(around, z, monitor.span(0.0, 0.2))
        z = reader.zooms[-1]
        result = register_onto(path, monitor.span(0.2, 1.0), options=options, placed=placed, short=True)
    except RegistrationCanceled:
        raise
    except HamtaError as exc:
        raise _PlaceFailed(_failure(reader, exc), z) from exc
    if not _overlaps(result, info, bounds):
        raise _PlaceFailed("the model puts the target outside the search area; not taken", z)
    return _held_to_the_search(result), z


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
