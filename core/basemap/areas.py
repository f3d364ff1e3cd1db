"""Reading areas of a map service for one run: only tiles that can exist, within the run's requests.

:class:`AreaReader` learns the layer's coverage from its first area read (:mod:`.coverage`): later reads
ask only for tiles near data and no finer than the layer's finest zoom. Every area's tiles are counted
against the run's request budget before it is read, whether or not the cache holds them, so a rerun
reads what the first run did and reaches the same verdict.
"""
from __future__ import annotations

import math
import re

import numpy as np

from ..coords import map_to_pixel
from ..scratch import process_folder
from .coverage import Coverage, finest_zoom, remembered_finest
from .fetch import Fetcher, ServiceError
from .services import TileService
from .tiles import NoTiles, fetch_area, tile_range

PROBES = 5  # requests learning a layer's finest zoom may take (a bisection of zooms 0-19 or 0-22)
COARSER_BY = 4  # zooms between the first area read, when it has no data, and the read that looks for any
# (16 times coarser: a tile or four), from which the finest zoom with data is found by bisection


class AreaReader:
    """Reads areas of ``service`` into GeoTIFFs (map units of the service's grid CRS) under the fetcher's
    cache, within ``budget`` requests; ``zooms`` records the zooms read, ``known`` the finest zoom seen
    with data."""

    def __init__(self, service: TileService, fetcher: Fetcher, budget: int):
        self.service, self.fetcher, self.budget = service, fetcher, budget
        self.zooms, self.planned, self.read_before = [], 0, set()
        self.finest, self.known, self.coverage = service.zmax, None, None
        self.folder = fetcher.folder("areas") or process_folder("hamta-areas-")

    def read(self, bounds, z: int, monitor) -> str:
        """The GeoTIFF of ``bounds`` at zoom ``z``, or at the layer's finest zoom where ``z`` is finer.
        Raises :class:`NoTiles` where the layer has no data there (for the first area read: at no zoom), and
        :class:`ServiceError` past the budget or when the service fails."""
        if self.known is None:
            return self._first(bounds, z, monitor)
        return self._read(bounds, self.learn_finest(bounds, z), monitor)

    def learn_finest(self, bounds, z: int) -> int:
        """The zoom an area of ``bounds`` asked at ``z`` is read at (:meth:`zoom_for`), once the layer's finest
        zoom is learned where ``z`` is finer than any read before (an XYZ layer: a few requests over the data
        nearest ``bounds``'s centre, counted in the plan)."""
        z = min(z, self.finest)
        if self.known is not None and z > self.known and self.service.kind == "xyz":
            point = self.coverage.nearest_data(*_centre(bounds)) or _centre(bounds)
            self.planned += PROBES
            self.finest = self.known = finest_zoom(self.service, self.fetcher, point, self.known, self.finest)
        return self.zoom_for(z)

    def zoom_for(self, z: int) -> int:
        """``z``, or the finest zoom the layer is known to have where that is coarser (nothing is asked)."""
        return min(z, self.finest)

    def cost(self, bounds, z: int) -> int:
        """The requests reading ``bounds`` at zoom ``z`` (:meth:`zoom_for`: as far as the layer is known) would
        add to the plan."""
        tiles, wanted = self._tiles(bounds, self.zoom_for(z))
        return 0 if _range_key(tiles, wanted) in self.read_before else _count(tiles, wanted)

    def plain(self, exc: BaseException) -> str:
        """``exc``'s message with the area files it names called what they are to a user."""
        return re.sub(re.escape(self.folder) + r"[^'\s]*", "the map area read", str(exc))

    def _first(self, bounds, z: int, monitor) -> str:
        """The first area read: at ``z`` (no finer than the finest zoom remembered here); where the layer has no
        data at ``z``, :data:`COARSER_BY` zooms coarser and coarser until one has (else the area has none),
        then at the finest zoom with data there, found by bisection."""
        remembered = remembered_finest(self.fetcher, self.service, _centre(bounds))
        z = min(z, self.finest, self.finest if remembered is None else remembered)
        try:
            return self._read(bounds, z, monitor)
        except NoTiles:
            if self.service.kind != "xyz" or z <= self.service.zmin:
                raise
        coarse = z
        while True:
            coarse = max(self.service.zmin, coarse - COARSER_BY)
            try:
                path = self._read(bounds, coarse, monitor)
                break
            except NoTiles:
                if coarse <= self.service.zmin:
                    raise NoTiles(f"The map service {self.service.label} has no data in the search area at any "
                                  f"zoom from {self.service.zmin} to {z} (every tile was answered 'HTTP 404 Not "
                                  "Found', 'HTTP 204 No Content', empty or transparent).") from None
        self.planned += PROBES
        point = self.coverage.nearest_data(*_centre(bounds))
        self.finest = self.known = finest_zoom(self.service, self.fetcher, point, coarse, z - 1,
                                               also=_centre(bounds))
        if self.finest == coarse:
            return path
        self.zooms.pop()  # the coarse area only told where the data is; the finest zoom's is the one read
        return self._read(bounds, self.finest, monitor)

    def _read(self, bounds, z: int, monitor) -> str:
        tiles, wanted = self._tiles(bounds, z)
        self._plan(tiles, wanted)
        path = fetch_area(self.service, tiles, self.fetcher, self.folder, monitor, wanted)
        if self.coverage is None:
            self.coverage = Coverage.of(path, self.service)
        self.known = max(z, self.known or z)
        self.zooms.append(z)
        return path

    def _tiles(self, bounds, z: int):
        tiles = tile_range(self.service, bounds, z)
        if self.coverage is None or _range_key(tiles, None) in self.read_before:  # read whole before: again
            return tiles, None
        return tiles, self.coverage.wanted(self.service, tiles)

    def _plan(self, tiles, wanted) -> None:
        key = _range_key(tiles, wanted)
        if key in self.read_before:
            return
        count = _count(tiles, wanted)
        if self.planned + count > self.budget:
            left = f" ({self.budget - self.planned} left)" if self.planned else ""
            raise ServiceError(f"Reading the area at zoom {tiles.z} from {self.service.label} needs {count} tiles, "
                               f"above the cap of {self.budget} requests a run may send{left}: choose a smaller "
                               "search area.")
        self.planned += count
        self.read_before.add(key)


def mask_outside(valid: np.ndarray, transform, bounds) -> None:
    """Mark the pixels of an area read as whole tiles that lie outside the search area ``bounds`` invalid:
    a target is looked for where the user asked, not in the tiles' margins."""
    (c0, r0), (c1, r1) = map_to_pixel(transform, np.array([[bounds[0], bounds[3]], [bounds[2], bounds[1]]]))
    c0, r0 = max(0, int(math.floor(c0))), max(0, int(math.floor(r0)))
    c1, r1 = int(math.ceil(c1)), int(math.ceil(r1))
    valid[:r0] = False
    valid[r1:] = False
    valid[:, :c0] = False
    valid[:, c1:] = False


def _centre(bounds):
    return (bounds[0] + bounds[2]) / 2, (bounds[1] + bounds[3]) / 2


def _range_key(tiles, wanted):
    return tiles, None if wanted is None else wanted.tobytes()


def _count(tiles, wanted) -> int:
    return tiles.count if wanted is None else int(wanted.sum())
