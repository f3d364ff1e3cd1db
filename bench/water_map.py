"""A scanned map drawn from real water, and references of the same place (issue 56, onto a reference).

The map is drawn from the open water of a NAIP image (``../shared/data/timeseries``, North Dakota prairie
potholes): cream paper, lakes in light blue with a dark shore line, wetland tint, a 1 km grid, place names;
then enlarged ``zoom`` times (a scan finer than the reference), turned and saved as a JPEG without
georeferencing. The references are a NAIP image (imagery) or its water as a layer (a rasterized vector layer:
water 255, land 0), of the same date or another one. The truth is exact: :meth:`WaterMap.to_reference` maps
scan px to the NAIP grid's px (corner convention; every NAIP date here shares that grid within 0.2 px).
"""
from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np

FOLDER = "timeseries"
AREA = (150, 120, 620, 480)  # x0, y0, width, height in NAIP px: the part of the quarter-quad the sheet shows
WATER_INDEX = 0.05  # NDWI (green - NIR) / (green + NIR) above which a NAIP pixel is open water
MIN_LAKE_PX = 12


@dataclass
class WaterMap:
    """``path``: the scan; ``matrix``: scan px -> map-canvas px (2 x 3, corner convention); ``zoom``."""

    path: str
    matrix: np.ndarray
    zoom: float

    def to_reference(self, scan_xy) -> np.ndarray:
        """Scan px (n, 2, corner convention) -> NAIP px (corner convention)."""
        canvas = np.asarray(scan_xy, float) @ self.matrix[:, :2].T + self.matrix[:, 2]
        return canvas / self.zoom + np.asarray(AREA[:2], float)


def naip(data_dir: str, date: str):
    """The NAIP bands (4, h, w: R, G, B, NIR, float32) and the file's profile."""
    import rasterio

    with rasterio.open(os.path.join(data_dir, FOLDER, f"naip_{date}.tif")) as src:
        return src.read().astype(np.float32), src.profile


def water(bands) -> np.ndarray:
    """Open water (uint8 0/1) of NAIP bands: the water index above :data:`WATER_INDEX`, specks removed."""
    import cv2

    _, g, _, nir = bands
    mask = ((g - nir) / (g + nir + 1e-6) > WATER_INDEX).astype(np.uint8)
    mask = cv2.morphologyEx(mask, cv2.MORPH_OPEN, np.ones((3, 3), np.uint8))
    n, labels, stats, _ = cv2.connectedComponentsWithStats(mask)
    keep = np.zeros(n, bool)
    keep[1:] = stats[1:, cv2.CC_STAT_AREA] >= MIN_LAKE_PX
    return keep[labels].astype(np.uint8)


def draw(data_dir: str, date: str, path: str, zoom: float, angle_deg: float, seed: int = 0) -> WaterMap:
    """Draw the map of ``date``'s water, enlarged ``zoom`` times and turned ``angle_deg``, into ``path``."""
    import cv2

    bands, profile = naip(data_dir, date)
    x0, y0, w, h = AREA
    lakes = water(bands)[y0:y0 + h, x0:x0 + w].astype(np.float32)
    r, nir = bands[0], bands[3]
    wet = (((nir - r) / (nir + r + 1e-6)) > 0.45)[y0:y0 + h, x0:x0 + w].astype(np.float32)
    big = [cv2.GaussianBlur(cv2.resize(m, None, fx=zoom, fy=zoom), (0, 0), zoom * s) > 0.5
           for m, s in ((lakes, 0.6), (wet, 0.8))]
    canvas = np.full(big[0].shape + (3,), (225, 240, 246), np.uint8)
    canvas[big[1]] = (190, 225, 200)
    canvas[big[0]] = (235, 205, 150)
    shore = cv2.morphologyEx(big[0].astype(np.uint8), cv2.MORPH_GRADIENT, np.ones((3, 3), np.uint8)) > 0
    canvas[shore] = (160, 90, 40)
    _grid_and_names(canvas, profile["transform"], zoom, np.random.default_rng(seed))
    scan, matrix = _turned(canvas, angle_deg)
    cv2.imwrite(path, scan, [cv2.IMWRITE_JPEG_QUALITY, 80])
    return WaterMap(path, matrix, zoom)


def write_reference(data_dir: str, date: str, path: str, kind: str) -> str:
    """The NAIP image of ``date`` (``kind`` 'imagery': RGB), its water as a layer ('water': 255 on land 0), or
    that layer flipped left to right ('water-mirrored': a place the map does not show)."""
    import rasterio

    bands, profile = naip(data_dir, date)
    data = bands[:3].astype(np.uint8) if kind == "imagery" else water(bands)[None] * np.uint8(255)
    if kind == "water-mirrored":
        data = data[:, :, ::-1]
    profile.update(driver="GTiff", count=len(data), dtype="uint8", nodata=None)
    with rasterio.open(path, "w", **profile) as dst:
        dst.write(data)
    return path


def _grid_and_names(canvas, transform, zoom: float, rng) -> None:
    import cv2

    h, w = canvas.shape[:2]
    px_m = transform.a / zoom
    east0 = transform.c + AREA[0] * transform.a
    north0 = transform.f + AREA[1] * transform.e
    for k in range(int(w * px_m / 1000) + 2):
        x = int(round(((np.ceil(east0 / 1000) + k) * 1000 - east0) / px_m))
        cv2.line(canvas, (x, 0), (x, h), (60, 60, 60), 2)
    for k in range(int(h * px_m / 1000) + 2):
        y = int(round((north0 - (np.floor(north0 / 1000) - k) * 1000) / px_m))
        cv2.line(canvas, (0, y), (w, y), (60, 60, 60), 2)
    for _ in range(25):
        name = str(rng.choice(["Lake", "Slough", "Twp", "Sec 12", "Pond"]))
        at = (int(rng.uniform(0, w - 200)), int(rng.uniform(30, h)))
        cv2.putText(canvas, name, at, cv2.FONT_HERSHEY_SIMPLEX, zoom * 0.35, (40, 40, 40), 2)


def _turned(canvas, angle_deg: float):
    """The canvas turned on a larger sheet (grey-beige around it) and scan px -> canvas px (corner)."""
    import cv2

    h, w = canvas.shape[:2]
    m = cv2.getRotationMatrix2D((w / 2, h / 2), angle_deg, 1.0)
    c, s = abs(m[0, 0]), abs(m[0, 1])
    size = (int(h * s + w * c), int(h * c + w * s))
    m[0, 2] += size[0] / 2 - w / 2
    m[1, 2] += size[1] / 2 - h / 2
    scan = cv2.warpAffine(canvas, m, size, flags=cv2.INTER_LINEAR, borderValue=(200, 215, 220))
    inverse = cv2.invertAffineTransform(m)  # pixel-centre indices; to corners: shift by half a pixel each way
    inverse[:, 2] += 0.5 - inverse[:, :2] @ np.array([0.5, 0.5])
    return (scan * np.array([0.93, 0.98, 1.0])).clip(0, 255).astype(np.uint8), inverse
