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
  it had been georeferenced there, and where that does not verify, onto the same area without it (a place is
  coarse). At the first zoom, before the places with few agreeing features, the
  whole area is registered once as well (the target assumed to cover ``AREA_SHARE`` of it). Each
  registration is verified like any other, held to its share of one check's risk of verifying a wrong model
  (``SEARCH_TRIES``: a search checks several); the first verified one is the result (else the best
  unverified one). A place found is only where to look, never a result; one that puts the target
  outside the search area is not taken. Counts bound the whole search (the zooms of :func:`search_zooms`,
``MAX_PLACES`` places, ``SEARCH_REQUESTS`` requests, each place's short chain of methods), so it tries the
same places with the same outcomes on any machine and under any load; a time cap
(``RegisterOptions.auto_budget_s``) is the user's choice, off by default.

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
from typing import Callable, NamedTuple

from affine import Affine

from .basemap.areas import AreaReader, mask_outside
from .basemap.fetch import Fetcher
from .basemap.services import TileService
from .basemap.zooms import padded, pixel_text, search_bounds, search_zooms, size_text, zoom_in_budget
from .errors import HamtaError, InputError, InsufficientMatchesError, RegistrationCanceled
from .io.raster import open_raster, read_image
from .io.working import footprint
from .matching.places import (
    MIN_INLIERS,
    candidates,
    learned_target_features,
    placement_problem,
    seen,
    structure_sides,
    target_features,
)
from .options import RegisterOptions
from .pipeline import register
from .progress import Monitor
from .remote_places import (
    MAX_PLACES,
    SEARCH_TRIES,
    PlaceFailed,
    failure,
    register_placed,
    register_whole_area,
)
from .verify import result_rank

FOOTPRINT_MARGIN = 0.3  # of the footprint's larger side, each way: georeferencing off by up to a third of it
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
        ``options``: the run's unless given (a search's places get what is left of its time cap)."""
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
        found = _search(info, reader, options, monitor, register_onto)
        result, z, notes, places = found.result, found.zoom, found.notes, found.places
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


class Found(NamedTuple):
    """What a search registered (its best result, verified or not, and the zoom it was read at), with the notes
    and the places it tried ({found_by, zoom, outcome} each)."""

    result: object
    zoom: int
    notes: list
    places: list


class _Attempt(NamedTuple):
    """A place about to be registered: how it is named in the notes, the registration (a callable of the
    options, ``register_onto`` and a monitor, giving (result, zoom)) and its progress label."""

    what: str
    register: Callable
    label: str


def _search(info, reader: AreaReader, options: RegisterOptions, monitor: Monitor, register_onto) -> Found:
    """Locate the target in the search area, coarse to fine, and register it where it was found (see the
    module docstring). A place's failure (no data there, no model, a read area that misses, the requests
    spent, a fault) is that place's outcome: :class:`Found` holds a record per place tried and a note each;
    only the first area read, the user's search area itself, ends the run with an error."""
    bounds = search_bounds(options.extent, reader.service)
    features = target_features(info, options.target_band)
    learned = learned_target_features(*features[2])
    zooms = search_zooms(reader.service, bounds)
    search = _Search(info, reader, options, monitor, register_onto, bounds, len(zooms))
    for z in zooms:
        if search.capped():  # a finer zoom costs its tiles and its locating before any place
            search.notes.extend([search.spent] if search.spent not in search.notes else [])
            break
        span = search.ahead(f"zoom {z}")
        if search.searched and search.leaves_too_few_requests(z):
            break
        try:
            path = reader.read(bounds, z, span.span(0.0, 0.3))
        except RegistrationCanceled:
            raise
        except HamtaError as exc:
            if not search.searched:
                raise
            search.notes.append(f"zoom {z} was not searched: {reader.plain(exc)}")
            continue
        z = reader.zooms[-1]
        if z in search.searched:  # the layer's finest zoom was reached: this one was searched already
            continue
        search.searched.append(z)
        span.report(0.3, "locating the target")
        search.try_places(path, z, features, learned)
        if search.best is not None and search.best[0].verified:
            break
    if search.best is None:
        raise search.not_found() from None
    return Found(*search.best, search.notes, search.places)


class _Search:
    """What one search has done so far: the zooms searched, the places tried, the best result and zoom, and,
    where the user set a time cap, when it ends. ``zooms``: how many zooms it may read."""

    def __init__(self, info, reader: AreaReader, options: RegisterOptions, monitor: Monitor, register_onto, bounds,
                 zooms: int):
        self.info, self.reader, self.options, self.monitor = info, reader, options, monitor
        self.register_onto, self.bounds, self.notes, self.places = register_onto, bounds, [], []
        cap = options.auto_budget_s
        self.cap_ends = None if cap is None else time.monotonic() + cap
        self.spent = "" if cap is None else f"the time cap of {cap:g} s was spent before every place was tried"
        self.steps = zooms + SEARCH_TRIES  # the bar's parts: each zoom's reading and locating, each registration
        self.best, self.placed_at, self.searched, self.whole_tried = None, [], [], False

    def capped(self) -> bool:
        """Whether the user's time cap, where set, is spent."""
        return self.cap_ends is not None and time.monotonic() > self.cap_ends

    def budgeted(self) -> RegisterOptions:
        """The options of one place: the run's, with what is left of its time cap."""
        if self.cap_ends is None:
            return self.options
        return dataclasses.replace(self.options, auto_budget_s=max(0.0, self.cap_ends - time.monotonic()))

    def ahead(self, label):
        """The next part of the bar, by the work done (zooms read, places tried) out of the most the search
        may do, its messages labelled: the same bar on any machine."""
        start = min(0.95, (len(self.searched) + len(self.places)) / self.steps)
        return self.monitor.span(start, min(1.0, start + 1.0 / self.steps)).labelled(label)

    def tried(self, found_by, z, outcome) -> None:
        """Record what became of the place ``found_by``, read at zoom ``z``, in ``places`` and ``notes``."""
        self.places.append({"found_by": found_by, "zoom": z, "outcome": outcome})
        self.notes.append(f"{found_by}, read at zoom {z}: {outcome}")

    def leaves_too_few_requests(self, z: int) -> bool:
        """Whether reading the area at zoom ``z`` would leave too few requests for the places (noted)."""
        reader = self.reader
        z = reader.learn_finest(self.bounds, z)
        cost = reader.cost(self.bounds, z)
        if reader.planned + cost + PLACE_RESERVE <= reader.budget:
            return False
        self.notes.append(f"zoom {z} was not searched: its {cost} tiles would leave "
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
        for found_by, c in self._guarded(candidates(target, learned, image, valid, not self.whole_tried, structure), z):
            if self.capped():
                self.notes.append(self.spent)
                break
            what = f"a place {found_by} found at zoom {z}"
            problem = None if c is None else placement_problem(c, target[2], image.shape[:2])
            if problem is not None:
                self.tried(what, z, f"not tried: {problem}")
                continue
            try:
                placed = None if c is None else area.transform * Affine(*c.matrix.ravel()) * Affine.scale(per_px)
                attempt = self.attempt(found_by, c, z, placed)
                if attempt is None:
                    continue
                what = attempt.what
                result, z_fine = attempt.register(self.budgeted(), self.register_onto, self.ahead(attempt.label))
            except RegistrationCanceled:
                raise
            except HamtaError as exc:
                self.tried(what, *((exc.zoom, str(exc)) if isinstance(exc, PlaceFailed) else
                                   (z, failure(self.reader, exc))))
                continue
            except Exception as exc:  # a fault in one place (a bug) is that place's outcome; the search goes on
                self.tried(what, z, f"failed: internal error ({type(exc).__name__}: {exc}); please report it")
                continue
            self.tried(what, z_fine, _checked(result))
            if self.best is None or result_rank(result) > result_rank(self.best[0]):
                self.best = result, z_fine
            if self.best[0].verified:
                break
        if len(self.places) == count:
            self.notes.append(f"searched {size_text(self.bounds, self.reader.service)} at zoom {z} "
                              f"({pixel_text(self.reader.service, z)} pixels): no place with enough agreeing features")

    def _guarded(self, found, z: int):
        """The places ``found`` yields until it fails: a fault while locating (a bug) ends this zoom's places,
        noted, not the search."""
        try:
            yield from found
        except (RegistrationCanceled, HamtaError):
            raise
        except Exception as exc:
            self.notes.append(f"locating the target at zoom {z} failed: internal error ({type(exc).__name__}: "
                              f"{exc}); please report it")

    def attempt(self, found_by, c, z: int, placed):
        """(what, how to register there, its progress label) for candidate ``c`` found at zoom ``z`` (None: the
        whole area; else ``placed``, target px -> map), or None for a place tried already or one too many."""
        if c is None:
            self.whole_tried = True
            whole = partial(register_whole_area, self.info, self.reader, self.bounds, z)
            return _Attempt(f"the whole area at zoom {z}", whole, "the whole area")
        if seen(placed, self.info.width, self.info.height, self.placed_at) or len(self.placed_at) >= MAX_PLACES:
            return None
        self.placed_at.append(placed)
        what = (f"a place {found_by} features found at zoom {z} ({c.inliers} agreeing)" if c.inliers else
                f"a place the target's structure matched at zoom {z} (score {c.score:.1f})")
        register_there = partial(register_placed, self.info, self.reader, placed, self.bounds)
        return _Attempt(what, register_there, f"place {len(self.placed_at)}")

    def not_found(self) -> InsufficientMatchesError:
        """The error of a search that registered nothing: what was read and tried, and what may help."""
        places, searched = self.places, self.searched
        return InsufficientMatchesError(
            f"The target raster '{self.info.path}' was not found in the search area "
            f"({size_text(self.bounds, self.reader.service)}, "
            f"read at zoom{'s' if len(searched) > 1 else ''} {', '.join(map(str, searched))}): "
            + (f"none of the {len(places)} places tried registered ({_outcomes(places)}). " if places else
               "no place in it looked enough like the target. ")
            + "".join(f"{n[0].upper()}{n[1:]}. " for n in self.notes if "was not searched" in n or
                      (self.spent and n == self.spent))
            + "Zoom the map closer to where the target is (a search area a few times its size), and check that the "
              "area holds it; a target that is mirrored, or whose ground has mostly changed since, may not be found.",
            0, MIN_INLIERS)


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


