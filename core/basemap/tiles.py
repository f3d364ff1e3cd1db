"""Reading an area of a tiled map service at one zoom level into a local GeoTIFF.

The GeoTIFF (RGBA, the alpha band marking where the service had no data) is written once per
(service, zoom, tile range) under the cache folder and then read like any reference file; a
rerun over the same area reuses it without a request.
"""
from __future__ import annotations

import hashlib
import math
import os
import stat
import tempfile
import warnings
from dataclasses import dataclass
from functools import partial
from typing import Tuple

import numpy as np
from rasterio.errors import NotGeoreferencedWarning, RasterioError, RasterioIOError
from rasterio.io import MemoryFile

from ..errors import InputError
from ..text import printable
from .fetch import BadAnswer, Fetcher, ServiceError, host
from .redact import without_secrets_of
from .services import TileService

Bounds = Tuple[float, float, float, float]  # xmin, ymin, xmax, ymax in the service's grid CRS


class NoTiles(ServiceError):
    """Every tile of an area is missing or transparent (outside the layer, or beyond its finest zoom)."""


@dataclass(frozen=True)
class TileRange:
    """Tiles ``x0..x1``, ``y0..y1`` (inclusive) of zoom ``z``."""

    z: int
    x0: int
    y0: int
    x1: int
    y1: int

    @property
    def count(self) -> int:
        return (self.x1 - self.x0 + 1) * (self.y1 - self.y0 + 1)


def tile_range(service: TileService, bounds: Bounds, z: int) -> TileRange:
    """The tiles of zoom ``z`` covering ``bounds``, clipped to the grid."""
    (ox, oy), size = service.origin(), service.resolution(z) * service.tile_px
    cols, rows = service.tile_count(z)
    x0 = int(math.floor((bounds[0] - ox) / size))
    x1 = int(math.ceil((bounds[2] - ox) / size)) - 1
    y0 = int(math.floor((oy - bounds[3]) / size))
    y1 = int(math.ceil((oy - bounds[1]) / size)) - 1
    x0, x1 = max(0, x0), min(cols - 1, max(x0, x1))
    y0, y1 = max(0, y0), min(rows - 1, max(y0, y1))
    if x0 > x1 or y0 > y1:
        raise InputError(f"The search area {_fmt(bounds)} ({service.crs}) lies outside the map service's grid.")
    return TileRange(z, x0, y0, x1, y1)


def fetch_area(service: TileService, tiles: TileRange, fetcher: Fetcher, folder: str, monitor=None,
               wanted=None) -> str:
    """Fetch ``tiles`` and write them as one GeoTIFF in ``folder``; its path (reused when present and
    readable). ``wanted`` (rows, cols of booleans; all by default) says which tiles to ask for: the others
    are left empty (where the layer has no data, :mod:`hamta.core.basemap.coverage`). A tile that fails
    fails the area: an area with holes is never written as whole."""
    everything = wanted is None or bool(np.all(wanted))
    skipped = "" if everything else hashlib.sha256(np.packbits(wanted).tobytes()).hexdigest()[:12]
    key = hashlib.sha256(f"{service}|{tiles}|{skipped}".encode()).hexdigest()[:24]
    path = os.path.join(folder, f"area-{key}.tif")
    if _readable(path):
        fetcher.stats.cache_hits += tiles.count  # the area's tiles, from the cache as one file
        return path
    cells = [(r, c) for r in range(tiles.y1 - tiles.y0 + 1) for c in range(tiles.x1 - tiles.x0 + 1)
             if everything or wanted[r, c]]
    urls = [service.tile_url(tiles.z, tiles.x0 + c, tiles.y0 + r) for r, c in cells]
    n, width = service.tile_px, tiles.x1 - tiles.x0 + 1
    where = host(service.tile_url(tiles.z, tiles.x0, tiles.y0))
    if not urls:
        raise NoTiles(f"The map service at {where} has no data there: the layer's coarser tiles are empty around "
                      f"the {tiles.count} tiles of zoom {tiles.z} that would cover it.")
    mosaic = np.zeros((4, (tiles.y1 - tiles.y0 + 1) * n, width * n), np.uint8)
    found = 0
    for i, tile in fetcher.each(urls, partial(decode_tile, n=n), monitor):
        if tile is not None:
            r, c = cells[i]
            mosaic[:, r * n:(r + 1) * n, c * n:(c + 1) * n] = tile
            found += 1
    if not found:
        raise NoTiles(f"The map service at {where} has no data in the search area: each of the "
                      f"{len(urls)} tiles of zoom {tiles.z} was answered 'HTTP 404 Not Found', 'HTTP 204 No "
                      "Content' or empty.")
    if not mosaic[3].any():
        raise NoTiles(f"The map service at {where} has no data in the search area: the {len(urls)} "
                      f"tiles of zoom {tiles.z} are fully transparent.")
    try:
        _write(path, mosaic, service, tiles)
    except (OSError, RasterioError) as exc:  # a full or failing cache disk: the area is kept for this run only
        fetcher.warnings.append(f"The area read from the map service could not be kept in the cache ({exc}); a "
                                "rerun fetches it again.")
        path = os.path.join(tempfile.mkdtemp(prefix="hamta-area-"), os.path.basename(path))
        _write(path, mosaic, service, tiles)
    return path


def _readable(path: str) -> bool:
    """Whether an area file kept earlier is there (a file, not a link) and opens; one that does not is removed."""
    import rasterio

    try:
        if not stat.S_ISREG(os.lstat(path).st_mode):
            os.unlink(path)
            return False
    except FileNotFoundError:
        return False
    try:
        with rasterio.open(path) as ds:
            return ds.count == 4
    except (RasterioError, RasterioIOError):
        os.unlink(path)
        return False


IMAGE_MAGIC = (b"\x89PNG", b"\xff\xd8\xff", b"GIF8", b"RIFF", b"II*\x00", b"MM\x00*")  # PNG JPEG GIF WebP TIFF
MAX_TILE_SIDE = 4  # tiles larger than this many times the grid's tile side are refused before decoding


def decode_tile(url: str, body: bytes, n: int) -> np.ndarray:
    """A tile's (4, n, n) RGBA pixels. Raises :class:`BadAnswer` for an answer that is not an image (the
    service's error message, made printable), one whose header declares more than ``MAX_TILE_SIDE`` × n
    pixels a side (a decompression bomb: refused before decoding), or one that cannot be decoded."""
    import cv2

    if not body.startswith(IMAGE_MAGIC):
        text = body[:200].decode("utf-8", "replace").strip()
        raise BadAnswer(f"sent something that is not an image: '{printable(without_secrets_of(url, text), 120)}'")
    width, height = _declared_size(body)
    if not (0 < width <= MAX_TILE_SIDE * n and 0 < height <= MAX_TILE_SIDE * n):
        raise BadAnswer(f"sent an image of {width} x {height} px for a tile of {n} x {n} px")
    image = cv2.imdecode(np.frombuffer(body, np.uint8), cv2.IMREAD_UNCHANGED)
    if image is None or image.ndim not in (2, 3) or image.shape[0] * image.shape[1] > width * height:
        raise BadAnswer(f"sent an image that cannot be decoded ({len(body)} bytes)")
    if image.dtype != np.uint8:
        image = (image / 257).astype(np.uint8) if image.dtype == np.uint16 else image.astype(np.uint8)
    if image.ndim == 2:
        image = np.dstack([image, image, image, np.full_like(image, 255)])
    elif image.shape[2] == 3:
        image = np.dstack([image[:, :, ::-1], np.full(image.shape[:2], 255, np.uint8)])
    elif image.shape[2] == 4:
        image = np.dstack([image[:, :, 2::-1], image[:, :, 3]])
    else:
        raise BadAnswer(f"sent an image of {image.shape[2]} bands")
    if image.shape[:2] != (n, n):
        image = cv2.resize(image, (n, n), interpolation=cv2.INTER_AREA)
    return np.moveaxis(image, 2, 0)


def _declared_size(body: bytes):
    """Width and height an image's header declares, read by GDAL without decoding its pixels."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", NotGeoreferencedWarning)
            with MemoryFile(body) as memory, memory.open() as ds:
                return ds.width, ds.height
    except (RasterioError, RasterioIOError, ValueError):  # rasterio 1.3's IO error is not a RasterioError
        raise BadAnswer(f"sent an image that cannot be decoded ({len(body)} bytes)") from None


def _write(path: str, mosaic: np.ndarray, service: TileService, tiles: TileRange) -> None:
    """Write the mosaic whole or not at all (a temporary name, then a rename)."""
    import rasterio
    from affine import Affine
    from rasterio.enums import ColorInterp

    res, (ox, oy) = service.resolution(tiles.z), service.origin()
    size = res * service.tile_px
    transform = Affine(res, 0, ox + tiles.x0 * size, 0, -res, oy - tiles.y0 * size)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(path), suffix=".part.tif")
    os.close(fd)
    try:
        with rasterio.open(tmp, "w", driver="GTiff", width=mosaic.shape[2], height=mosaic.shape[1], count=4,
                           dtype="uint8", crs=service.crs, transform=transform, photometric="RGB", alpha="YES",
                           tiled=True, compress="deflate") as ds:
            ds.write(mosaic)
            ds.colorinterp = [ColorInterp.red, ColorInterp.green, ColorInterp.blue, ColorInterp.alpha]
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise


def _fmt(bounds: Bounds) -> str:
    return "(" + ", ".join(f"{v:.6g}" for v in bounds) + ")"
