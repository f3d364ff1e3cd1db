"""Registering onto a tile service (issue 22): ``hamta bench --families basemap``.

A local tile server (:class:`hamta.bench.tileserver.TileServer`, started per unit on 127.0.0.1 and
stopped after) serves the Landsat sample (``landsat/RGB.byte.tif``, ~300 m pixels, UTM 18N) as
EPSG:3857 XYZ tiles in two styles: ``photo`` and ``map`` (flat-coloured, outlined classes standing in
for a street map). Targets are cut from the same raster with exact ground truth (target pixel ->
EPSG:3857):

- ``optical-4x`` / ``-10x`` / ``-25x``: a 1000 x 800 px un-georeferenced crop (upsampled x3, rotated
  15 degrees) searched in an area 4, 10 and 25 times its footprint, onto ``photo``;
- ``photo-onto-map``: the same target onto the ``map`` style (cross-modal), 4x area;
  ``map-onto-photo``: the target rendered in the map style onto ``photo``;
- ``georef-100m``: a georeferenced crop (upsampled x2) whose georeferencing is off by 100 m, no
  search area;
- ``miss-area`` (should fail): a 4x area that does not hold the target.

A unit is a case registered with one benchmarked method (plain names; the SIFT baseline the bench
always adds is left out, 'auto' when nothing else is asked for): once with an empty cache
(``HAMTA_CACHE`` pointing at a temporary folder of its own), then again from that cache (the 'rerun').
Errors are in pixels of the zoom level the result was registered at; a verified result whose RMS error
is beyond :data:`WRONG_PX`, or any verified result of a should-fail case, is a confident wrong answer.
"""
from __future__ import annotations

import math
import os
import shutil
import tempfile
import time
import warnings
from dataclasses import dataclass, field
from typing import Callable, Optional, Tuple

import numpy as np

from ...core.basemap.services import HALF_WORLD
from ..study import Study
from ..tables import cell

SOURCE = os.path.join("landsat", "RGB.byte.tif")
WRONG_PX = 3.0  # basemap pixels: a verified result beyond this is a confident wrong answer


@dataclass
class TargetCase:
    """A target raster on disk and its truth: target pixel (corner convention) -> EPSG:3857."""

    path: str
    shape: Tuple[int, int]  # (height, width)
    truth: Callable[[np.ndarray], np.ndarray]
    info: dict = field(default_factory=dict)

    def grid(self, n: int = 10) -> np.ndarray:
        """An ``n`` x ``n`` grid of target pixel centres, (n * n, 2) x, y in target px."""
        h, w = self.shape
        gx, gy = np.meshgrid((np.arange(n) + 0.5) * w / n, (np.arange(n) + 0.5) * h / n)
        return np.column_stack([gx.ravel(), gy.ravel()])

    def outline(self) -> np.ndarray:
        """The target's four corners in EPSG:3857 metres, (4, 2)."""
        h, w = self.shape
        return self.truth(np.array([[0, 0], [w, 0], [w, h], [0, h]], float))

    def footprint_area(self) -> float:
        """The area of the target's footprint, in square EPSG:3857 metres."""
        x, y = self.outline().T
        return 0.5 * abs(np.dot(x, np.roll(y, 1)) - np.dot(y, np.roll(x, 1)))

    def errors_px(self, result) -> np.ndarray:
        """The true error of ``result`` over a grid, in pixels of the zoom it was registered at."""
        grid = self.grid()
        _, mapped = result.map_points(grid)
        return np.hypot(*(mapped - self.truth(grid)).T) / zoom_resolution(result.reference_service["zoom"])

    def search_area(self, factor: float, offset=(0.3, -0.2), shift=(0.0, 0.0)) -> str:
        """``xmin,ymin,xmax,ymax,EPSG:3857``: a rectangle of ``factor`` times the target's footprint area
        with the aspect of the footprint's bounding box, holding it (off-centre by ``offset`` of the slack
        each way) or, with ``shift`` (in area widths/heights), moved away."""
        outline = self.outline()
        lo, hi = outline.min(0), outline.max(0)
        box = hi - lo
        side = box * math.sqrt(factor * self.footprint_area() / (box[0] * box[1]))
        side = np.maximum(side, box)
        centre = (lo + hi) / 2 + (side - box) / 2 * np.asarray(offset) + side * np.asarray(shift)
        x0, y0 = centre - side / 2
        x1, y1 = centre + side / 2
        return f"{x0:.1f},{y0:.1f},{x1:.1f},{y1:.1f},EPSG:3857"


def zoom_resolution(z: int) -> float:
    """EPSG:3857 metres per pixel of 256-px tiles at zoom ``z``."""
    return 2 * HALF_WORLD / 256 / 2 ** z


def _read_source(source: str):
    """(RGB (h, w, 3) uint8, valid mask (h, w), geotransform, CRS) of the raster ``source``'s first three bands."""
    import rasterio

    with rasterio.open(source) as ds:
        return np.moveaxis(ds.read([1, 2, 3]), 0, 2), ds.read_masks(1) > 0, ds.transform, ds.crs


def _to_3857(crs):
    """A pyproj transformer from ``crs`` to EPSG:3857 (x, y order)."""
    from pyproj import Transformer

    return Transformer.from_crs(crs, "EPSG:3857", always_xy=True)


def rotated_target(source: str, path: str, centre, shape, scale: float, angle_deg: float,
                   style: str = "photo") -> TargetCase:
    """An un-georeferenced target of ``shape`` (height, width) px: ``source`` around its pixel ``centre``
    (col, row), ``scale`` target px per source px, rotated by ``angle_deg`` (counter-clockwise as
    displayed); ``style`` 'map' renders it like the tile server's map style. Written as PNG or GeoTIFF
    (by the extension) without georeferencing."""
    import cv2

    from ..tileserver import map_style

    rgb, valid, transform, crs = _read_source(source)
    h, w = shape
    matrix, cv_matrix = window_matrix(centre, shape, scale, angle_deg)
    image = cv2.warpAffine(rgb, cv_matrix, (w, h), flags=cv2.INTER_CUBIC | cv2.WARP_INVERSE_MAP)
    inside = cv2.warpAffine(valid.astype(np.uint8), cv_matrix, (w, h), flags=cv2.INTER_NEAREST | cv2.WARP_INVERSE_MAP)
    if inside.mean() < 0.98:  # a few cloud-shadow pixels of the source are nodata
        raise ValueError(f"the target around {centre} leaves the source's valid pixels")
    if style == "map":
        from ..tileserver import TileServer

        image = map_style(image, TileServer(source).levels)
    _write_plain(path, image)
    to3857 = _to_3857(crs)

    def truth(uv):
        uv = np.asarray(uv, float)
        src = uv @ matrix[:, :2].T + matrix[:, 2]
        x, y = transform * (src[:, 0], src[:, 1])
        return np.column_stack(to3857.transform(x, y))

    return TargetCase(path, (h, w), truth, {"centre": list(centre), "scale": scale, "angle_deg": angle_deg,
                                            "style": style})


def window_matrix(centre, shape, scale: float, angle_deg: float):
    """(corner-convention, OpenCV pixel-centre) 2 x 3 matrices, target px -> source px, of the window of
    :func:`rotated_target`."""
    h, w = shape
    a = math.radians(angle_deg)
    lin = np.array([[math.cos(a), math.sin(a)], [-math.sin(a), math.cos(a)]]) / scale  # target -> source
    off = np.asarray(centre, float) - lin @ np.array([w / 2.0, h / 2.0])
    return np.column_stack([lin, off]), np.column_stack([lin, off + lin @ np.array([0.5, 0.5]) - 0.5])


def _write_plain(path: str, image: np.ndarray) -> None:
    """Write the RGB ``image`` (h, w, 3) without georeferencing: PNG or JPEG by OpenCV, else a GeoTIFF."""
    import cv2

    if path.lower().endswith((".png", ".jpg")):
        cv2.imwrite(path, np.ascontiguousarray(image[:, :, ::-1]))
        return
    import rasterio
    from rasterio.errors import NotGeoreferencedWarning

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NotGeoreferencedWarning)
        with rasterio.open(path, "w", driver="GTiff", width=image.shape[1], height=image.shape[0], count=3,
                           dtype="uint8", photometric="RGB") as dst:
            dst.write(np.moveaxis(image, 2, 0))


def georeferenced_target(source: str, path: str, window, scale: float, offset_m=(80.0, -60.0),
                         angle_deg: float = 0.0) -> TargetCase:
    """A GeoTIFF of ``source``'s pixel ``window`` (col, row, width, height) resampled by ``scale`` and
    rotated by ``angle_deg`` about its centre, in the source's CRS, whose geotransform is shifted by
    ``offset_m`` (metres east, north): a georeferencing error to correct."""
    import cv2
    import rasterio
    from affine import Affine

    rgb, valid, transform, crs = _read_source(source)
    c0, r0, ww, wh = window
    w, h = int(round(ww * scale)), int(round(wh * scale))
    a = math.radians(angle_deg)
    lin = np.array([[math.cos(a), math.sin(a)], [-math.sin(a), math.cos(a)]]) / scale
    centre = np.array([c0 + ww / 2.0, r0 + wh / 2.0])
    off = centre - lin @ np.array([w / 2.0, h / 2.0])
    cv_matrix = np.column_stack([lin, off + lin @ np.array([0.5, 0.5]) - 0.5])
    image = cv2.warpAffine(rgb, cv_matrix, (w, h), flags=cv2.INTER_CUBIC | cv2.WARP_INVERSE_MAP)
    inside = cv2.warpAffine(valid.astype(np.uint8), cv_matrix, (w, h), flags=cv2.INTER_NEAREST | cv2.WARP_INVERSE_MAP)
    if inside.mean() < 0.98:  # a few cloud-shadow pixels of the source are nodata
        raise ValueError(f"the window {window} leaves the source's valid pixels")
    true = transform * Affine(lin[0, 0], lin[0, 1], off[0], lin[1, 0], lin[1, 1], off[1])
    wrong = Affine.translation(*offset_m) * true
    with rasterio.open(path, "w", driver="GTiff", width=w, height=h, count=3, dtype="uint8", crs=crs,
                       transform=wrong, photometric="RGB") as dst:
        dst.write(np.moveaxis(image, 2, 0))
    to3857 = _to_3857(crs)

    def truth(uv):
        uv = np.asarray(uv, float)
        x, y = true * (uv[:, 0], uv[:, 1])
        return np.column_stack(to3857.transform(x, y))

    return TargetCase(path, (h, w), truth, {"window": list(window), "scale": scale, "offset_m": list(offset_m),
                                            "angle_deg": angle_deg})


# ----------------------------------------------------------------------------------------------
# The bench family
# ----------------------------------------------------------------------------------------------

BENCH_CENTRE = (330.0, 430.0)  # source px: the middle of the island, land and shallow sea around
BENCH_SHAPE = (800, 1000)
BENCH_SCALE = 3.0
BENCH_ANGLE = 15.0
CASES = {  # name -> (target kind, reference style, search area factor or None, shift of the area)
    "optical-4x": ("photo", "photo", 4.0, None),
    "optical-10x": ("photo", "photo", 10.0, None),
    "optical-25x": ("photo", "photo", 25.0, None),
    "photo-onto-map": ("photo", "map", 4.0, None),
    "map-onto-photo": ("map", "photo", 4.0, None),
    "georef-100m": ("georef", "photo", None, None),
    "miss-area": ("photo", "photo", 4.0, (1.05, 0.0)),
}
SHOULD_FAIL = ("miss-area",)
MAP_LIKE = ("photo-onto-map", "map-onto-photo")


def units(config):
    """(case name, method) pairs: each case (four with ``--quick``) with each plain benchmarked method."""
    from ..tables import BASELINE

    methods = [m for m in config.methods if m != BASELINE and "[" not in m] or ["auto"]  # plain names only
    names = ("optical-10x", "photo-onto-map", "georef-100m", "miss-area") if config.quick else tuple(CASES)
    return [(name, m) for name in names for m in methods]


def build(name: str, source: str, folder: str) -> Tuple[TargetCase, Optional[str]]:
    """The target of case ``name`` and its search area (None: the target's own georeferencing)."""
    kind, _, factor, shift = CASES[name]
    os.makedirs(folder, exist_ok=True)
    if kind == "georef":
        case = georeferenced_target(source, os.path.join(folder, "georef_target.tif"), (170, 300, 330, 260), 2.0,
                                    offset_m=(80.0, -60.0))
        return case, None
    case = rotated_target(source, os.path.join(folder, f"{kind}_target.tif"), BENCH_CENTRE, BENCH_SHAPE,
                          BENCH_SCALE, BENCH_ANGLE, style=kind)
    return case, case.search_area(factor, shift=shift or (0.0, 0.0))


def run_unit(unit, config) -> list:
    """One row: the case registered with the method onto a local tile server, first with an empty cache
    (judged), then again from that cache (timed)."""
    from ...core import RegisterOptions, run
    from ...core.basemap.fetch import Fetcher
    from ..tileserver import TileServer

    name, method = unit
    source = os.path.join(config.data_dir, SOURCE)
    folder = os.path.join(config.out_dir, "cases", "basemap", name)
    case, extent = build(name, source, folder)
    _, style, factor, _ = CASES[name]
    options = RegisterOptions(extent=extent)
    cache = tempfile.mkdtemp(prefix="hamta-bench-cache-")
    row = {"unit": name, "case": name, "method": method, "reference_style": style, "area_factor": factor,
           "should_fail": name in SHOULD_FAIL, "map_like": name in MAP_LIKE,
           "target_px": [case.shape[1], case.shape[0]]}
    try:
        with TileServer(source, zmax=14) as server:
            for attempt in ("first", "rerun"):
                fetcher = Fetcher(cache=cache)
                before = server.requests
                t0 = time.perf_counter()
                result, error = None, None
                try:
                    result, _ = run(case.path, server.xyz(style), None, method=method, options=options,
                                    fetcher=fetcher)
                except Exception as exc:  # a HamtaError is an honest failure; anything else is reported as such
                    error = exc
                wall = time.perf_counter() - t0
                if attempt == "first":
                    row.update(judge(case, result, error, name in SHOULD_FAIL), time_s=wall,
                               requests=server.requests - before, bytes=fetcher.stats.bytes,
                               fetch=fetcher.stats.to_dict())
                else:
                    row.update(rerun_s=wall, rerun_requests=server.requests - before,
                               rerun_cache_hits=fetcher.stats.cache_hits)
    finally:
        shutil.rmtree(cache, ignore_errors=True)
    return [row]


def judge(case: TargetCase, result, error, should_fail: bool) -> dict:
    """What a run of ``case`` gave: its verdict, true errors in px of the zoom registered at, and an
    ``outcome`` ('verified', 'unverified', 'failed', 'crash' or 'WRONG', a confident wrong answer)."""
    from ...core.errors import HamtaError

    out = {"verified": False, "verdict": None, "median_px": None, "rms_px": None, "max_px": None, "zoom": None,
           "method_used": None, "error": None if error is None else f"{type(error).__name__}: {error}",
           "crashed": error is not None and not isinstance(error, HamtaError)}
    if result is None:
        out["outcome"] = "crash" if out["crashed"] else "failed"
        return out
    err = case.errors_px(result)
    service = result.reference_service
    out.update(verified=bool(result.verified), verdict=result.verification.verdict if result.verification else None,
               median_px=float(np.median(err)), rms_px=float(np.sqrt(np.mean(err ** 2))), max_px=float(err.max()),
               zoom=service["zoom"], zooms_read=service["zooms_read"], method_used=result.method,
               notes=list(result.notes))
    if should_fail:
        out["outcome"] = "WRONG" if result.verified else "unverified"
    elif result.verified:
        out["outcome"] = "WRONG" if out["rms_px"] > WRONG_PX else "verified"
    else:
        out["outcome"] = "unverified"
    return out


def tables(rows) -> list:
    body = []
    for r in rows:
        first = r["time_s"]
        area = "–" if r["area_factor"] is None else f"{r['area_factor']:g}x"
        body.append([r["case"], r["method"], r["reference_style"], area, r["outcome"], r["method_used"] or "–",
                     cell(r["median_px"], ".2f"), cell(r["rms_px"], ".2f"), cell(r["max_px"], ".2f"),
                     cell(r["zoom"], "d"), f"{first:.1f}",
                     f"{r['fetch']['seconds']:.1f}", r["requests"], f"{r['bytes'] / 1e6:.1f}", f"{r['rerun_s']:.1f}",
                     f"{100 * r['rerun_s'] / first:.0f}%", r["rerun_requests"]])
    wrong = sum(r["outcome"] == "WRONG" for r in rows)
    return [{"title": f"basemap: registering onto a local XYZ tile server (Landsat sample, EPSG:3857); "
                      f"{wrong} confident wrong answer{'s' if wrong != 1 else ''}",
             "columns": ["case", "method", "reference", "area", "outcome", "via", "err med px", "err rms px",
                         "err max px", "zoom", "time s", "fetch s", "requests", "MB fetched", "rerun s",
                         "rerun / first", "rerun requests"],
             "rows": body,
             "note": "Errors: true error over a 10 x 10 grid of the target, in pixels of the zoom registered at. "
                     "outcome: verified, unverified or failed (honest), WRONG (verified with an RMS error beyond "
                     "3 px, or verified on a should-fail case); via: the method that gave the result. Time: end to "
                     "end (fetch, search coarse to fine, verification); fetch s: of which fetching tiles; rerun: the "
                     "same again from the disk cache. Goals: optical <= 1 px, map-like <= 2 px, 0 WRONG, <= 10 s, "
                     "<= 300 requests, rerun <= 20 % of the time. miss-area is a should-fail case."}]


STUDY = Study("basemap", ("auto",), ("basemap",), units, run_unit, tables)
