"""Synthetic scanned sheets with a printed grid and an exact truth (issue 56's synthetic family).

A sheet is drawn north-up in its CRS (:class:`SheetSpec`: the CRS, what the printed coordinates count in and
their step, the area, the print's pixel size) over map content (a real image faded to a map's tints, with
roads and rivers drawn across it), with its grid as full lines or as crosses at each crossing. It is then
"printed and scanned": turned, warped smoothly (paper), yellowed, folded, a corner missing, noise and JPEG.
The truth is exact: :meth:`Sheet.to_scan` maps printed coordinates to scan px (corner convention) through
the same turn and warp. Written as a plain image (no georeferencing).
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class SheetSpec:
    """``crs``: the sheet's; ``grid_crs`` and ``step``: what the printed coordinates count in; ``centre``
    (grid_crs units) and ``size_px`` (width, height) at ``pixel_m`` (crs units per print px) place it. ``style``
    'lines' or 'crosses'; ``ink`` the grid's grey (0 black, 235 the paper); ``width_px`` its width. Scan:
    ``angle_deg``, ``warp_px`` (the paper's smooth distortion, at most), ``yellow``, ``fold``, ``corner`` (a
    missing corner), ``jpeg`` quality, ``noise`` (grey levels), ``grid`` False for a sheet without one,
    ``labels`` for a margin with the coordinates printed (:func:`_margin`)."""

    name: str
    crs: str
    grid_crs: str
    step: float
    centre: tuple
    size_px: tuple = (1100, 800)
    pixel_m: float = 5.0
    style: str = "lines"
    ink: int = 70
    width_px: float = 1.5
    angle_deg: float = 0.0
    warp_px: float = 0.0
    yellow: bool = False
    fold: bool = False
    corner: bool = False
    jpeg: int = 85
    noise: float = 4.0
    grid: bool = True
    labels: bool = False
    seed: int = 0
    content: dict = field(default_factory=dict)


SPECS = (
    SheetSpec("utm-km-lines", "EPSG:32633", "EPSG:32633", 1000.0, (500000.0, 5540000.0), angle_deg=1.5,
              warp_px=2.0, yellow=True),
    SheetSpec("utm-km-crosses", "EPSG:32633", "EPSG:32633", 1000.0, (455000.0, 5510000.0), style="crosses",
              width_px=2.0, ink=40, angle_deg=-3.0, jpeg=70, seed=1),
    SheetSpec("graticule-on-utm", "EPSG:32633", "EPSG:4326", 1 / 60, (15.1, 50.2), angle_deg=12.0, warp_px=3.0,
              fold=True, seed=2),
    SheetSpec("graticule-lambert-conic", "EPSG:2154", "EPSG:4326", 10 / 60, (2.5, 46.5), size_px=(1300, 950),
              pixel_m=100.0, ink=110, width_px=1.0, angle_deg=0.7, corner=True, yellow=True, seed=3),
    SheetSpec("mercator-chart", "EPSG:3395", "EPSG:4326", 5 / 60, (-70.5, 42.2), pixel_m=50.0, angle_deg=45.0,
              ink=90, jpeg=60, seed=4),
    SheetSpec("turned-sheet-faint", "EPSG:32618", "EPSG:32618", 1000.0, (500000.0, 4400000.0), ink=165,
              width_px=1.0, angle_deg=91.0, warp_px=1.5, yellow=True, noise=6.0, seed=5),
    SheetSpec("no-grid", "EPSG:32633", "EPSG:32633", 1000.0, (500000.0, 5540000.0), grid=False, seed=6),
    SheetSpec("utm-km-labelled", "EPSG:32633", "EPSG:32633", 1000.0, (480000.0, 5570000.0), size_px=(1100, 1000),
              labels=True,
              angle_deg=0.8, warp_px=1.5, yellow=True, seed=7),
    SheetSpec("graticule-labelled", "EPSG:32633", "EPSG:4326", 1 / 60, (14.6, 50.61), size_px=(1500, 1500),
              pixel_m=5.0, labels=True, angle_deg=-1.2, jpeg=75, seed=8),
)


@dataclass
class Sheet:
    """A rendered sheet: ``path`` (the scan), its spec, and the truth (:meth:`to_scan`)."""

    path: str
    spec: SheetSpec
    _to_canvas: object
    _canvas_to_scan: object

    def to_scan(self, grid_xy) -> np.ndarray:
        """Printed coordinates (n, 2, ``grid_crs``) -> scan px (corner convention)."""
        return self._canvas_to_scan(self._to_canvas(np.atleast_2d(np.asarray(grid_xy, float))))

    def nodes(self) -> np.ndarray:
        """Printed coordinates of every crossing on the scan (a step from its edges)."""
        g = np.asarray(self.spec.centre, float)
        r = np.arange(-40, 41) * self.spec.step
        gx, gy = np.meshgrid(np.round(g[0] / self.spec.step) * self.spec.step + r,
                             np.round(g[1] / self.spec.step) * self.spec.step + r)
        grid = np.column_stack([gx.ravel(), gy.ravel()])
        px = self.to_scan(grid)
        h, w = self.shape
        inside = (px[:, 0] > 20) & (px[:, 1] > 20) & (px[:, 0] < w - 20) & (px[:, 1] < h - 20)
        return grid[inside]

    @property
    def shape(self):
        import cv2

        return cv2.imread(self.path, cv2.IMREAD_GRAYSCALE).shape

    def hints(self, k: int, seed: int, noise_px: float = 3.0) -> np.ndarray:
        """``k`` crossings away from the edges, placed within ``noise_px``: rows of scan x, y, grid x, y."""
        rng = np.random.default_rng(seed)
        nodes = self.nodes()
        px = self.to_scan(nodes)
        h, w = self.shape
        inner = nodes[(px[:, 0] > 0.1 * w) & (px[:, 0] < 0.9 * w) & (px[:, 1] > 0.1 * h) & (px[:, 1] < 0.9 * h)]
        pick = inner[rng.choice(len(inner), k, replace=False)]
        return np.column_stack([self.to_scan(pick) + rng.uniform(-noise_px, noise_px, (k, 2)), pick])


def render(spec: SheetSpec, folder: str, background=None) -> Sheet:
    """Draw, print and scan ``spec`` into ``folder`` (a JPEG); ``background``: a grey image (any size) for the
    map's content (a generated texture without one)."""
    import cv2
    from pyproj import Transformer

    rng = np.random.default_rng(spec.seed)
    w, h = spec.size_px
    to_crs = Transformer.from_crs(spec.grid_crs, spec.crs, always_xy=True)
    cx, cy = to_crs.transform(*spec.centre)
    x0, y1 = cx - w / 2 * spec.pixel_m, cy + h / 2 * spec.pixel_m

    def to_canvas(grid_xy):
        mx, my = to_crs.transform(grid_xy[:, 0], grid_xy[:, 1])
        return np.column_stack([(np.asarray(mx) - x0) / spec.pixel_m, (y1 - np.asarray(my)) / spec.pixel_m])

    m = MARGIN_PX if spec.labels else 0
    if m:  # the map face inside a margin that carries the labels
        face = to_canvas
        w, h = w + 2 * m, h + 2 * m

        def to_canvas(grid_xy):
            return face(grid_xy) + m

    canvas = _content(background, (h, w), rng)
    if spec.grid:
        _draw_grid(canvas, spec, to_canvas)
    if m:
        _margin(canvas, spec, to_canvas, m)
    scan, canvas_to_scan = _scan(canvas, spec, rng)
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, f"{spec.name}.jpg")
    cv2.imwrite(path, scan, [cv2.IMWRITE_JPEG_QUALITY, spec.jpeg])
    return Sheet(path, spec, to_canvas, canvas_to_scan)


MARGIN_PX = 150  # a labelled sheet's margin around its map face


def _margin(canvas, spec: SheetSpec, to_canvas, m: int) -> None:
    """Paper around the map face, its neatline, and each grid line's tick and label where it meets the neatline:
    degrees and minutes (``15°10'``), or metres (in full on the first line of an edge, else the kilometres' two
    last digits, as topographic sheets print them)."""
    import cv2

    h, w = canvas.shape[:2]
    face = canvas[m:h - m, m:w - m].copy()
    canvas[:] = 238
    canvas[m:h - m, m:w - m] = face
    cv2.rectangle(canvas, (m, m), (w - m, h - m), (30, 30, 30), 2)
    g = np.asarray(spec.centre, float)
    base = np.round(g / spec.step) * spec.step
    t = np.linspace(-60, 60, 4801)
    for axis, edges in ((0, (("top", m), ("bottom", h - m))), (1, (("left", m), ("right", w - m)))):
        for side, edge in edges:
            first = True
            for k in range(-60, 61):
                value = base[axis] + k * spec.step
                pts = np.empty((len(t), 2))
                pts[:, axis], pts[:, 1 - axis] = value, base[1 - axis] + t * spec.step
                px = to_canvas(pts)
                across = px[:, 1 - axis]  # y along a meridian (axis 0), x along a parallel
                cross = np.flatnonzero(np.diff(np.sign(across - edge)) != 0)
                if not len(cross):
                    continue
                i = cross[0]
                f = (edge - across[i]) / (across[i + 1] - across[i])
                at = px[i, axis] + f * (px[i + 1, axis] - px[i, axis])  # along the edge
                if not (m + 30 < at < (w if axis == 0 else h) - m - 30):
                    continue
                _label(canvas, spec, value, side, at, edge, first)
                first = False


def _label(canvas, spec: SheetSpec, value: float, side: str, at: float, edge: float, full: bool) -> None:
    import cv2

    font, scale, thick = cv2.FONT_HERSHEY_SIMPLEX, 0.8, 2
    geographic = spec.grid_crs == "EPSG:4326"
    if geographic:
        deg = int(abs(value) + 1e-9)
        minutes = int(round((abs(value) - deg) * 60))
        parts = [f"{deg}", "deg", f"{minutes:02d}", "min"]
    else:
        parts = [f"{int(value)}" if full else f"{int(value / 1000) % 100:02d}"]
    widths = [cv2.getTextSize(p, font, scale, thick)[0][0] if p not in ("deg", "min") else 9 for p in parts]
    height = cv2.getTextSize("0", font, scale, thick)[0][1]
    total = sum(widths)
    if side in ("top", "bottom"):
        x, y = at - total / 2, edge - 14 if side == "top" else edge + 14 + height
        cv2.line(canvas, (int(at), int(edge)), (int(at), int(edge - 8 if side == "top" else edge + 8)), (30,) * 3, 2)
    else:
        x, y = (edge - 10 - total, at + height / 2) if side == "left" else (edge + 10, at + height / 2)
        cv2.line(canvas, (int(edge), int(at)), (int(edge - 8 if side == "left" else edge + 8), int(at)), (30,) * 3, 2)
    for part, width in zip(parts, widths):
        if part == "deg":
            cv2.circle(canvas, (int(x + 4), int(y - height + 3)), 3, (20,) * 3, 1, cv2.LINE_AA)
        elif part == "min":
            cv2.line(canvas, (int(x + 3), int(y - height)), (int(x + 1), int(y - height + 7)), (20,) * 3, 2)
        else:
            cv2.putText(canvas, part, (int(x), int(y)), font, scale, (20,) * 3, thick, cv2.LINE_AA)
        x += width


def _content(background, shape, rng) -> np.ndarray:
    """Map content (BGR uint8): an image faded to tints, roads and rivers, text-like marks."""
    import cv2

    h, w = shape
    if background is None:
        base = cv2.GaussianBlur(rng.normal(0, 1, (h // 8 + 1, w // 8 + 1)).astype(np.float32), (0, 0), 2)
        base = cv2.resize(base, (w, h), interpolation=cv2.INTER_CUBIC)
        base = 128 + 60 * base / (np.abs(base).max() + 1e-6)
    else:
        base = cv2.resize(np.asarray(background, np.float32), (w, h), interpolation=cv2.INTER_AREA)
    tint = np.array([0.80, 0.92, 0.97])  # greenish-cream map fills
    canvas = (235 - 0.35 * (235 - base[..., None])) * tint[None, None] + 20
    canvas = np.clip(canvas, 0, 255).astype(np.uint8)
    for i in range(14):  # roads (dark red, brown) and rivers (blue): winding strokes
        turns = np.cumsum(rng.normal(0, 0.35, 40))
        start, heading = rng.uniform([0, 0], [w, h]), rng.uniform(0, 2 * math.pi)
        path = start + np.cumsum(np.column_stack([np.cos(heading + turns), np.sin(heading + turns)]) * 25, axis=0)
        colour = (200, 120, 40) if i % 3 == 0 else (40, 60, int(rng.integers(120, 190)))
        cv2.polylines(canvas, [path.astype(np.int32)], False, colour, int(rng.integers(1, 3)), cv2.LINE_AA)
    for _ in range(120):  # names and symbols
        x, y = int(rng.integers(0, w)), int(rng.integers(0, h))
        cv2.putText(canvas, "abcdefgh"[int(rng.integers(0, 8)):][:int(rng.integers(2, 7))], (x, y),
                    cv2.FONT_HERSHEY_SIMPLEX, 0.35, (40, 40, 40), 1, cv2.LINE_AA)
    return canvas


def _draw_grid(canvas, spec: SheetSpec, to_canvas) -> None:
    import cv2

    h, w = canvas.shape[:2]
    g = np.asarray(spec.centre, float)
    span = np.arange(-60, 61)
    base = np.round(g / spec.step) * spec.step
    colour = (spec.ink,) * 3
    thick = max(int(round(spec.width_px * 4)), 1)
    big = np.zeros((h * 4, w * 4), np.uint8)  # drawn 4x finer, then reduced: sub-pixel places and widths
    for axis in (0, 1):
        for k in span:
            value = base[axis] + k * spec.step
            t = base[1 - axis] + np.linspace(-60, 60, 2400) * spec.step
            pts = np.empty((len(t), 2))
            pts[:, axis], pts[:, 1 - axis] = value, t
            px = to_canvas(pts)
            ok = np.all(np.isfinite(px), axis=1) & (np.abs(px) < 4 * max(w, h)).all(axis=1)
            if spec.style == "lines" and ok.sum() > 1:
                cv2.polylines(big, [_fine(px[ok])], False, 255, thick, cv2.LINE_AA, shift=2)
    if spec.style == "crosses":
        arm = 0.08 * spec.step
        nodes = np.array([[base[0] + i * spec.step, base[1] + j * spec.step] for i in span[::1] for j in span[::1]])
        centre = to_canvas(nodes)
        keep = (centre[:, 0] > -50) & (centre[:, 1] > -50) & (centre[:, 0] < w + 50) & (centre[:, 1] < h + 50)
        for node, c in zip(nodes[keep], centre[keep]):
            for d in ((arm, 0), (0, arm)):
                ends = to_canvas(np.array([node - d, node + d]))
                cv2.line(big, tuple(_fine(ends)[0]), tuple(_fine(ends)[1]), 255, thick, cv2.LINE_AA, shift=2)
    alpha = cv2.resize(big, (w, h), interpolation=cv2.INTER_AREA).astype(np.float32)[..., None] / 255.0
    canvas[:] = np.clip(canvas * (1 - alpha) + np.array(colour, np.float32) * alpha, 0, 255).astype(np.uint8)


def _fine(px) -> np.ndarray:
    """Canvas px (corner convention) as points of the 4 times finer drawing, in quarters (``shift=2``)."""
    return np.round((np.asarray(px) * 4 - 0.5) * 4).astype(np.int32)


def _scan(canvas, spec: SheetSpec, rng):
    """(the scanned image, canvas px -> scan px): turned about the centre, warped, with the paper's artefacts."""
    import cv2

    h, w = canvas.shape[:2]
    a = math.radians(spec.angle_deg)
    rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    corners = (np.array([[0, 0], [w, 0], [w, h], [0, h]]) - [w / 2, h / 2]) @ rot.T
    sw, sh = (np.ptp(corners, axis=0) + 40).astype(int)
    shift = np.array([sw / 2, sh / 2])
    phase = rng.uniform(0, 2 * math.pi, 4)

    def warp(xy):  # a smooth displacement of the paper, scan px
        u, v = xy[:, 0] / sw, xy[:, 1] / sh
        return spec.warp_px * np.column_stack([np.sin(2.1 * u + 1.3 * v + phase[0]) * np.cos(1.7 * v + phase[1]),
                                               np.sin(1.9 * v + 0.8 * u + phase[2]) * np.cos(1.4 * u + phase[3])])

    def scan_to_canvas(xy):
        return ((xy - warp(xy)) - shift) @ rot + [w / 2, h / 2]

    def canvas_to_scan(xy):
        s = (xy - [w / 2, h / 2]) @ rot.T + shift
        for _ in range(20):
            s = (xy - [w / 2, h / 2]) @ rot.T + shift + warp(s)
        return s

    yy, xx = np.mgrid[0:sh, 0:sw].astype(np.float64) + 0.5
    src = scan_to_canvas(np.column_stack([xx.ravel(), yy.ravel()])) - 0.5
    mx, my = src[:, 0].reshape(sh, sw).astype(np.float32), src[:, 1].reshape(sh, sw).astype(np.float32)
    scan = cv2.remap(canvas, mx, my, cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT, borderValue=(250, 250, 250))
    scan = scan.astype(np.float32)
    if spec.yellow:
        scan *= np.array([0.78, 0.93, 1.0]) * (0.92 + 0.08 * (xx / sw))[..., None]
    if spec.fold:
        d = np.abs((xx - sw * 0.55) * 0.9 + (yy - sh * 0.5) * 0.1)
        scan -= 35 * np.exp(-0.5 * (d / 2.0) ** 2)[..., None]
    if spec.corner:
        scan[(xx + yy) < 0.22 * (sw + sh) / 2] = 20
    scan += rng.normal(0, spec.noise, scan.shape)
    return np.clip(scan, 0, 255).astype(np.uint8), canvas_to_scan


@dataclass
class LargeSheet:
    """A scan too large to hold (a tiled GeoTIFF written tile by tile): a 1 km grid turned ``angle_deg``,
    ``spacing_px`` apart, on grainy paper with map strokes. Truth: :meth:`to_scan` (an affine)."""

    path: str
    width: int
    height: int
    matrix: np.ndarray  # (2, 3): grid metres (x, y, 1) -> scan px
    crs: str = "EPSG:32633"
    step: float = 1000.0

    def to_scan(self, grid_xy) -> np.ndarray:
        g = np.atleast_2d(np.asarray(grid_xy, float))
        return g @ self.matrix[:, :2].T + self.matrix[:, 2]

    def hints(self, k: int = 2) -> np.ndarray:
        """``k`` crossings near the middle, 3 px off: rows of scan x, y, grid x, y."""
        inverse = np.linalg.inv(np.vstack([self.matrix, [0, 0, 1]]))
        mid = inverse[:2] @ [self.width / 2, self.height / 2, 1]
        base = np.round(mid / self.step) * self.step
        grid = base + np.array([[0, 0], [3, 1], [-1, 3]])[:k] * self.step
        return np.column_stack([self.to_scan(grid) + [[3.0, -2.0], [-2.0, 3.0], [2.0, 2.0]][:k], grid])


def large_sheet(path: str, width: int, height: int, spacing_px: float = 700.0, angle_deg: float = 0.8,
                seed: int = 0, tile: int = 2048) -> LargeSheet:
    """Write a :class:`LargeSheet` of ``width`` x ``height`` px to ``path``, within a few tiles of memory."""
    import cv2
    import rasterio

    rng = np.random.default_rng(seed)
    a = math.radians(angle_deg)
    scale = spacing_px / 1000.0
    linear = scale * np.array([[math.cos(a), math.sin(a)], [math.sin(a), -math.cos(a)]])  # northings up, rows down
    origin = np.array([width / 2, height / 2]) - linear @ [500000.0, 5540000.0]
    sheet = LargeSheet(path, width, height, np.column_stack([linear, origin]))
    inverse = np.linalg.inv(np.vstack([sheet.matrix, [0, 0, 1]]))
    corners = np.array([[0, 0, 1], [width, 0, 1], [0, height, 1], [width, height, 1]]) @ inverse[:2].T
    lo, hi = np.floor(corners.min(axis=0) / 1000) - 1, np.ceil(corners.max(axis=0) / 1000) + 1
    strokes = [rng.uniform([0, 0], [width, height], (2, 2)) for _ in range(int(width * height / 4e6))]
    profile = dict(driver="GTiff", width=width, height=height, count=1, dtype="uint8", tiled=True, blockxsize=512,
                   blockysize=512, compress="deflate")
    with rasterio.open(path, "w", **profile) as ds:
        for y0 in range(0, height, tile):
            for x0 in range(0, width, tile):
                w, h = min(tile, width - x0), min(tile, height - y0)
                paper = (232 + rng.normal(0, 4, (h, w))).astype(np.float32)
                image = np.clip(paper, 0, 255).astype(np.uint8)
                for p, q in strokes:
                    cv2.line(image, _fine_at(p, x0, y0), _fine_at(q, x0, y0), 90, 2, cv2.LINE_AA, shift=2)
                for axis in (0, 1):
                    for k in np.arange(lo[axis], hi[axis] + 1) * 1000:
                        ends = np.empty((2, 2))
                        ends[:, axis], ends[:, 1 - axis] = k, [lo[1 - axis] * 1000, hi[1 - axis] * 1000]
                        p, q = sheet.to_scan(ends)
                        cv2.line(image, _fine_at(p, x0, y0), _fine_at(q, x0, y0), 60, 2, cv2.LINE_AA, shift=2)
                ds.write(image, 1, window=rasterio.windows.Window(x0, y0, w, h))
    return sheet


def _fine_at(xy, x0, y0):
    """Scan px (corner convention) as quarter-pixel points (``shift=2``) of the tile at (x0, y0)."""
    return tuple(int(v) for v in np.round((np.asarray(xy) - [x0, y0] - 0.5) * 4))
