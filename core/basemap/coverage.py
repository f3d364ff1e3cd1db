"""Where a tile layer has data: the tiles worth asking for, and its finest zoom.

A plain tile template says neither where a layer has data nor how deep it goes; both are learned once
per run, so that no read asks for tiles that cannot exist:

- where: the alpha of the first area read (the coarsest). A finer read asks only for the tiles within
  :data:`MARGIN_TILES` tiles of that zoom's data; the rest are left empty without a request (a layer
  smaller than the search area, 204/404 islands inside it);
- how deep: :func:`finest_zoom` asks for the one tile over a point with data at zooms between one known
  to have data and the layer's stated limit, halving the interval each time (3-5 requests), and
  remembers the answer in the cache under the layer and that part of the world, so a rerun asks nothing.

Map coordinates are the service's grid CRS; pixels those of the area read (corner convention).
"""
from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass
from functools import partial
from typing import Optional, Tuple

import numpy as np

from ..coords import map_to_pixel, pixel_to_map
from .fetch import Fetcher
from .services import TileService

MARGIN_TILES = 1.0  # a finer tile is asked for when data lies within this many tiles of the first read's zoom of it:
# one missing tile of that zoom (a hole, not the layer's edge) leaves the finer tiles under it asked for
PLACE_ZOOM = 8  # the finest zoom is remembered per tile of this zoom (about 150 km at the equator): a layer may go
# deeper over cities than elsewhere


@dataclass(frozen=True)
class Coverage:
    """Where the first area read had data: ``mask`` (rows, cols) of its pixels, ``transform`` (its px -> map)
    and ``tile_side`` (the map units of one of its tiles)."""

    mask: np.ndarray
    transform: object
    tile_side: float

    @classmethod
    def of(cls, path: str, service: TileService) -> "Coverage":
        """The coverage an area file (:func:`hamta.core.basemap.tiles.fetch_area`) shows in its alpha band."""
        import rasterio

        with rasterio.open(path) as ds:
            mask = ds.read(4) > 0
            transform = ds.transform
        return cls(mask, transform, abs(transform.a) * service.tile_px)

    def wanted(self, service: TileService, tiles) -> np.ndarray:
        """(rows, cols) of ``tiles`` (a :class:`hamta.core.basemap.tiles.TileRange`): whether each lies within
        :data:`MARGIN_TILES` tiles of data; a tile not wholly inside the first read is asked for (nothing is
        known of it)."""
        (ox, oy), size = service.origin(), service.resolution(tiles.z) * service.tile_px
        pad_px = MARGIN_TILES * service.tile_px
        out = np.ones((tiles.y1 - tiles.y0 + 1, tiles.x1 - tiles.x0 + 1), bool)
        rows, cols = self.mask.shape
        for r in range(out.shape[0]):
            for c in range(out.shape[1]):
                x0, y0 = ox + (tiles.x0 + c) * size, oy - (tiles.y0 + r) * size
                (c0, r0), (c1, r1) = map_to_pixel(self.transform, np.array([[x0, y0], [x0 + size, y0 - size]]))
                if c0 < -1e-6 or r0 < -1e-6 or c1 > cols + 1e-6 or r1 > rows + 1e-6:
                    continue
                r0, c0 = max(0, int(math.floor(r0 - pad_px))), max(0, int(math.floor(c0 - pad_px)))
                out[r, c] = bool(self.mask[r0:int(math.ceil(r1 + pad_px)), c0:int(math.ceil(c1 + pad_px))].any())
        return out

    def nearest_data(self, x: float, y: float) -> Optional[Tuple[float, float]]:
        """The centre of the pixel with data nearest the map point (x, y), in map units; None without data."""
        ys, xs = np.nonzero(self.mask)
        if not len(xs):
            return None
        (c, r), = map_to_pixel(self.transform, np.array([[x, y]]))
        i = int(np.argmin((xs + 0.5 - c) ** 2 + (ys + 0.5 - r) ** 2))
        (px, py), = pixel_to_map(self.transform, np.array([[xs[i] + 0.5, ys[i] + 0.5]]))
        return float(px), float(py)


def finest_zoom(service: TileService, fetcher: Fetcher, point, lo: int, hi: int, also=None) -> int:
    """The finest zoom in ``lo..hi`` with data at ``point`` (map units), ``lo`` known to have data: the tile
    over the point asked for at the middle zoom of what is left, each answer halving it. Remembered in
    ``fetcher``'s cache per layer and :data:`PLACE_ZOOM` tile, of ``point`` and of the point ``also``."""
    from .tiles import decode_tile

    known = remembered_finest(fetcher, service, point)
    if known is not None and lo <= known <= hi:
        return known
    decode = partial(decode_tile, n=service.tile_px)
    while lo < hi:
        z = (lo + hi + 1) // 2
        (_, tile), = fetcher.each([service.tile_url(z, *_tile_of(service, point, z))], decode)
        if tile is not None and tile[3].any():
            lo = z
        else:
            hi = z - 1
    for where in (point, also) if also is not None else (point,):
        _remember(fetcher, _key(service, where), lo)
    return lo


def remembered_finest(fetcher: Fetcher, service: TileService, point) -> Optional[int]:
    """The finest zoom :func:`finest_zoom` found around ``point`` before, or None."""
    return _remembered(fetcher, _key(service, point))


def _tile_of(service: TileService, point, z: int) -> Tuple[int, int]:
    (ox, oy), size = service.origin(), service.resolution(z) * service.tile_px
    cols, rows = service.tile_count(z)
    x = min(cols - 1, max(0, int((point[0] - ox) // size)))
    y = min(rows - 1, max(0, int((oy - point[1]) // size)))
    return x, y


def _key(service: TileService, point) -> str:
    x, y = _tile_of(service, point, PLACE_ZOOM)
    return f"{service.id}-{PLACE_ZOOM}-{x}-{y}.json"


def _remembered(fetcher: Fetcher, key: str) -> Optional[int]:
    folder = fetcher.folder("coverage")
    body = None if folder is None or fetcher.store is None else fetcher.store.read(os.path.join(folder, key), 1024)
    try:
        return int(json.loads(body)["finest"]) if body else None
    except (ValueError, KeyError, TypeError):
        return None


def _remember(fetcher: Fetcher, key: str, zoom: int) -> None:
    folder = fetcher.folder("coverage")
    store = fetcher.store
    if folder is not None and store is not None:
        store.write(os.path.join(folder, key), json.dumps({"finest": zoom}).encode())
