"""A local XYZ tile and WMS server cut from a real georeferenced raster, for tests and the ``basemap`` family.

``TileServer(raster).start()`` listens on 127.0.0.1 (a free port) and serves, in EPSG:3857:

- ``/{style}/{z}/{x}/{y}.png`` — XYZ tiles; ``style`` is ``photo`` (the raster's colours) or ``map``
  (a flat-coloured, outlined rendering standing in for a street map: a cross-modal reference);
- ``/wms?…REQUEST=GetMap…`` — the same ``photo`` rendering for any BBOX, WIDTH and HEIGHT
  (SRS EPSG:3857);
- coverage as real layers have it: ``/sparse/…`` answers 404 (even columns) or 204 (odd) instead of a
  transparent tile where the raster has no data, as a ``gdal2tiles`` folder does; ``/islands/…`` also
  answers 404 to every tile wholly inside ``hole`` (EPSG:3857 bounds), at every zoom;
- ``/texture/…``: a world basemap's worst case, every tile of every zoom an image (a blurred noise, the same
  for the same tile), the raster nowhere;
- faults: ``/missing/…`` answers 404 to every tile, ``/holes/…`` to every third, ``/broken/…`` 500,
  ``/html/…`` an HTML page with status 200, ``/flaky/…`` 503 the first time each tile is asked
  for, ``/slow/…`` waits ``slow_s`` seconds before answering.

Tiles outside the raster are transparent. ``requests`` counts what was served. Nothing here is
imported by the product.
"""
from __future__ import annotations

import threading
import time
import warnings
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from urllib.parse import parse_qsl, urlsplit

import cv2
import numpy as np
import rasterio
from affine import Affine
from rasterio.errors import NotGeoreferencedWarning
from rasterio.warp import Resampling, reproject

from ..core.basemap.services import HALF_WORLD


class TileServer:
    def __init__(self, raster: str, slow_s: float = 5.0, zmax: int = 14, hole=None):
        self.raster = raster
        self.hole = hole
        self.slow_s = slow_s
        self.zmax = zmax
        self.requests = 0
        self._lock = threading.Lock()
        self._asked = {}  # tile -> times asked, for 'flaky'

        with rasterio.open(raster) as ds:
            self._bands = ds.read([1, 2, 3])
            self._valid = ds.read_masks(1) > 0
            self._transform, self._crs = ds.transform, ds.crs
        grey = cv2.cvtColor(np.ascontiguousarray(np.moveaxis(self._bands, 0, 2)), cv2.COLOR_RGB2GRAY)
        self.levels = np.percentile(grey[self._valid], [35, 65, 85])  # map classes of about equal share
        self._server = None

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self._server.server_address[1]}"

    def xyz(self, style: str = "photo") -> str:
        return f"{self.url}/{style}/{{z}}/{{x}}/{{y}}.png"

    def start(self) -> "TileServer":
        server = self

        class Handler(BaseHTTPRequestHandler):
            def do_GET(self):
                server._answer(self)

            def log_message(self, *args):
                pass

        self._server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self._server.daemon_threads = True
        threading.Thread(target=self._server.serve_forever, daemon=True).start()
        return self

    def stop(self) -> None:
        if self._server is not None:
            self._server.shutdown()
            self._server.server_close()
            self._server = None

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()

    def _answer(self, handler) -> None:
        with self._lock:
            self.requests += 1
        parts = urlsplit(handler.path)
        steps = [p for p in parts.path.split("/") if p]
        try:
            if steps and steps[0] == "wms":
                q = {k.upper(): v for k, v in parse_qsl(parts.query)}
                bbox = [float(v) for v in q["BBOX"].split(",")]
                png = self.render(bbox, int(q["WIDTH"]), int(q["HEIGHT"]), "photo")
                return _send(handler, 200, png)
            style, z, x, y = steps[0], int(steps[1]), int(steps[2]), int(steps[3].split(".")[0])
        except (KeyError, ValueError, IndexError):
            return _send(handler, 400, b"bad request", "text/plain")
        if style == "missing" or z > self.zmax:
            return _send(handler, 404, b"no such tile", "text/plain")
        if style == "broken":
            return _send(handler, 500, b"internal error", "text/plain")
        if style == "html":
            return _send(handler, 200, b"<html><body>Rate limit exceeded</body></html>", "text/html")
        if style == "holes" and (x + y) % 3 == 0:
            return _send(handler, 404, b"no such tile", "text/plain")
        if style == "flaky":
            with self._lock:
                self._asked[(z, x, y)] = self._asked.get((z, x, y), 0) + 1
                first = self._asked[(z, x, y)] == 1
            if first:
                return _send(handler, 503, b"busy", "text/plain")
        if style == "slow":
            time.sleep(self.slow_s)
        if style == "texture":
            noise = np.random.default_rng([z, x, y]).integers(0, 256, (256, 256, 3), dtype=np.uint8)
            return _send(handler, 200, cv2.imencode(".png", cv2.GaussianBlur(noise, (7, 7), 2.0))[1].tobytes())
        size = 2 * HALF_WORLD / 2 ** z
        bbox = [-HALF_WORLD + x * size, HALF_WORLD - (y + 1) * size, -HALF_WORLD + (x + 1) * size,
                HALF_WORLD - y * size]
        hole = self.hole
        if style == "islands" and hole is not None and (
                hole[0] <= bbox[0] and bbox[2] <= hole[2] and hole[1] <= bbox[1] and bbox[3] <= hole[3]):
            return _send(handler, 404, b"no such tile", "text/plain")
        png = self.render(bbox, 256, 256, "map" if style == "map" else "photo", empty=style in ("sparse", "islands"))
        if png is None:
            return _send(handler, 404, b"no such tile", "text/plain") if x % 2 == 0 else _send(handler, 204, b"")
        _send(handler, 200, png)

    def render(self, bbox, width: int, height: int, style: str, empty: bool = False):
        """PNG of ``bbox`` (EPSG:3857) at ``width`` x ``height``; None where it would be wholly transparent and
        ``empty`` is set."""
        transform = Affine((bbox[2] - bbox[0]) / width, 0, bbox[0], 0, -(bbox[3] - bbox[1]) / height, bbox[3])
        rgb = np.zeros((3, height, width), np.uint8)
        mask = np.zeros((height, width), np.uint8)
        common = dict(src_transform=self._transform, src_crs=self._crs, dst_transform=transform,
                      dst_crs="EPSG:3857")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", NotGeoreferencedWarning)  # rasterio's about arrays, not our grids
            reproject(self._bands, rgb, src_nodata=0, dst_nodata=0, resampling=Resampling.bilinear, **common)
            reproject(self._valid.astype(np.uint8), mask, src_nodata=None, dst_nodata=0,
                      resampling=Resampling.nearest, **common)
        if empty and not mask.any():
            return None
        image = np.moveaxis(rgb, 0, 2)
        if style == "map":
            image = map_style(image, self.levels)
        rgba = np.dstack([image[:, :, ::-1], mask * 255])
        ok, png = cv2.imencode(".png", rgba)
        return png.tobytes()


PALETTE = np.array([[170, 211, 223], [242, 239, 233], [205, 235, 176], [224, 223, 223]], np.uint8)  # RGB


def map_style(rgb: np.ndarray, levels) -> np.ndarray:
    """Flat colours by brightness class (``levels``: the class limits) and grey class outlines: a
    street-map-like rendering of ``rgb``."""
    grey = cv2.GaussianBlur(cv2.cvtColor(np.ascontiguousarray(rgb), cv2.COLOR_RGB2GRAY), (5, 5), 1.5)
    classes = np.digitize(grey, levels).astype(np.uint8)
    out = PALETTE[classes]
    edges = cv2.morphologyEx(classes, cv2.MORPH_GRADIENT, np.ones((3, 3), np.uint8)) > 0
    out[edges] = (150, 150, 150)
    return out


def _send(handler, status: int, body: bytes, kind: str = "image/png") -> None:
    try:
        handler.send_response(status)
        handler.send_header("Content-Type", kind)
        handler.send_header("Content-Length", str(len(body)))
        handler.end_headers()
        handler.wfile.write(body)
    except (BrokenPipeError, ConnectionResetError):
        pass
