"""Registering the target at one place a basemap search found (:mod:`hamta.core.remote`): its footprint read
at the zoom nearest its pixels and registered with the place as its prior, or the whole area registered when
no place verified. A place that gives nothing raises :class:`PlaceFailed`, which the search records as that
place's outcome.

Spaces: target px (x = column, y = row, corner convention) and the service's map CRS.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
from affine import Affine

from .basemap.areas import AreaReader
from .basemap.services import TileService
from .basemap.tiles import NoTiles
from .basemap.zooms import padded, zoom_in_budget
from .coords import pixel_to_map, raster_outline
from .errors import HamtaError, InsufficientMatchesError, NoOverlapError, RegistrationCanceled
from .options import RegisterOptions
from .progress import Monitor
from .verify import VerifyParams, result_rank

LOCATED_MARGIN = 0.1  # of the footprint found, each way, once a search has located the target (to a coarse pixel or so)


class PlaceFailed(HamtaError):
    """A place gave nothing to keep: ``zoom`` is the zoom it was read at."""

    def __init__(self, message: str, zoom: int):
        super().__init__(message)
        self.zoom = zoom


def failure(reader: AreaReader, exc: HamtaError) -> str:
    """A place's failure in a few words, naming no file of the cache."""
    if isinstance(exc, NoTiles):
        return "not read: the layer has no data there"
    if isinstance(exc, InsufficientMatchesError):
        return "no model (too few agreeing points)"
    if isinstance(exc, NoOverlapError):
        return "not registered: the place's read area does not hold it"
    return reader.plain(exc)


MAX_PLACES = 6  # places registered in all


PLACE_TRIES = 2  # registrations checked at one place: with the place as the prior, then without it

SEARCH_TRIES = 1 + PLACE_TRIES * (MAX_PLACES + 1)  # registrations a search may check: the whole area, coarse, then
# at the place it gives, and each place (on the basemap-dates family every verified result stood at least 15 times
# below one check's chance levels: none lost its verdict when this went from 8 to 15)


AREA_SHARE = 7  # the share of the area's pixels a target is assumed to cover when the whole area is registered


def register_whole_area(info, reader: AreaReader, bounds, z: int, options: RegisterOptions, register_onto,
                         monitor: Monitor):
    """When no place found verifies: the target registered onto the whole area read at zoom ``z`` as if it
    covered :data:`AREA_SHARE` of it (the methods of 'auto' match across a factor 2 of scale, so a target
    covering 1/25 to 1/2 of the area), then again at the zoom nearest its pixels where that registration
    put it. Areas a few times the target's size, where the area's features are too few to vote, are
    found this way; (result, zoom). Raises a :class:`HamtaError` when it gives nothing in the area."""
    path = reader.read(bounds, z, monitor.span(0.0, 0.1))
    coarse = register_onto(path, monitor.span(0.1, 0.5), within=bounds, options=options,
                           target_pixels=guess_pixels(bounds, reader.service, z), short=True)
    if not overlaps(coarse, info, bounds):
        raise PlaceFailed("the model puts the target outside the search area; not taken", z)
    coarse = held_to_the_search(coarse)
    try:
        fine, z_fine = register_placed(info, reader, placed_from(coarse, info), bounds, options, register_onto,
                                        monitor.span(0.5, 1.0))
    except RegistrationCanceled:
        raise
    except HamtaError:
        return coarse, z
    if result_rank(fine) > result_rank(coarse):
        return fine, z_fine
    return coarse, z


def held_to_the_search(result):
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


def overlaps(result, info, bounds) -> bool:
    """Whether ``result`` puts the target's footprint over the search area at all (the search answers where
    the user asked: a target found beside the area, through the margin read around a place, is not taken)."""
    from shapely.geometry import Polygon, box

    outline = pixel_to_map(result.reference.transform,
                           result.model.apply(raster_outline(info.width, info.height, 9, ends=True)))
    polygon = Polygon(outline).buffer(0)
    return polygon.is_valid and polygon.intersects(box(*bounds))


def register_placed(info, reader: AreaReader, placed, bounds, options: RegisterOptions, register_onto,
                     monitor: Monitor):
    """Register the target onto its footprint through ``placed`` (target px -> map), read at the zoom nearest
    its pixels, with the place as its prior; where that does not verify, onto the same area without it (any
    turn and scale), and the better of the two is kept; (result, zoom). A locator's place is coarse: a tenth
    of the footprint or a few per cent of scale off puts the target beyond the local radius of the matchers
    that start from a prior (on held-out Landsat dates 15 years apart, a place 13 px and 9 % off at zoom 11
    gave no agreement with the prior and verified at 1.2 px without it). Raises :class:`PlaceFailed` when
    the place gives nothing: no data there, no model, or a model that puts the target outside the search area
    ``bounds``."""
    outline = pixel_to_map(placed, raster_outline(info.width, info.height, 9, ends=True))
    around = padded((*outline.min(axis=0), *outline.max(axis=0)), LOCATED_MARGIN)
    pixel = math.sqrt(abs(placed.determinant))
    z = zoom_in_budget(reader.service, around, pixel, options.max_working_pixels)
    try:
        path = reader.read(around, z, monitor.span(0.0, 0.2))
    except RegistrationCanceled:
        raise
    except HamtaError as exc:
        raise PlaceFailed(failure(reader, exc), z) from exc
    z = reader.zooms[-1]
    pixels = round(info.width * info.height * abs(placed.determinant) / reader.service.resolution(z) ** 2)
    ways = ({"placed": placed}, {"within": around, "target_pixels": pixels})
    kept, first_failure = None, None
    for i, way in enumerate(ways):
        try:
            result = register_onto(path, monitor.span(0.2 + 0.4 * i, 0.6 + 0.4 * i), options=options, short=True,
                                   **way)
        except RegistrationCanceled:
            raise
        except HamtaError as exc:
            first_failure = first_failure or failure(reader, exc)
            continue
        if not overlaps(result, info, bounds):
            first_failure = first_failure or "the model puts the target outside the search area; not taken"
            continue
        result = held_to_the_search(result)
        if kept is None or result_rank(result) > result_rank(kept):
            kept = result
        if kept.verified:
            break
    if kept is None:
        raise PlaceFailed(first_failure, z)
    return kept, z


def placed_from(result, info) -> Affine:
    """The affine map (target px -> map) nearest ``result``'s model over the target (least squares on a grid)."""
    grid = raster_outline(info.width, info.height, 9, ends=True)
    xy = pixel_to_map(result.reference.transform, result.model.apply(grid))
    design = np.column_stack([grid, np.ones(len(grid))])
    (a, d), (b, e), (c, f) = np.linalg.lstsq(design, xy, rcond=None)[0]
    return Affine(a, b, c, d, e, f)


def guess_pixels(bounds, service: TileService, z: int) -> int:
    """The target's working size when the whole area is registered at zoom ``z``: :data:`AREA_SHARE` of it."""
    return int((bounds[2] - bounds[0]) * (bounds[3] - bounds[1]) / service.resolution(z) ** 2 / AREA_SHARE)
