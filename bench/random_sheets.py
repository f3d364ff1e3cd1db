"""Scanned map sheets drawn at random, each with a printed grid and an exact truth.

Every parameter of a sheet is drawn from a distribution by its seed (:func:`draw_spec`): what the printed
coordinates count in (a graticule in degrees drawn in a map projection, or a projected grid in metres, US
survey feet or yards), the step and how many lines cross the sheet, how the grid is printed (full lines,
crosses, ticks on the neatline, or nothing), the labels (format, font, size, edges, placement), the map's
content (a window of a real image faded to map tints, or a generated texture; areas, contours, roads,
rivers, names and numbers), the paper and the scan (turn, warp, fold, missing corner, noise, blur, JPEG).
:func:`render_random` draws, prints and scans the sheet and returns a :class:`RandomSheet`, whose
:meth:`RandomSheet.to_scan` is the exact truth. No grid reader was tuned on this family: it measures one on
sheets nobody has looked at.

Pixel spaces (x = column, y = row, origin at the top-left corner of the top-left pixel):

* face px: the print's pixels, from the top-left corner of the map face's bounding box;
* canvas px: the whole printed sheet, face px shifted by the left and top margins;
* scan px: the written image, the canvas turned, warped and placed on the scanner's bed.

Lines, the neatline and ticks are drawn four times finer and reduced, so their places and widths hold to a
quarter pixel before the scan's interpolation.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

FONT_DIR = "/usr/share/fonts/truetype/dejavu"
TRUETYPE_FONTS = ("DejaVuSans", "DejaVuSans-Bold", "DejaVuSans-Oblique", "DejaVuSerif", "DejaVuSerif-Bold",
                  "DejaVuSerif-Italic", "DejaVuSansMono", "DejaVuSansMono-Bold", "DejaVuSansCondensed",
                  "DejaVuSansCondensed-Bold", "DejaVuSansCondensed-Oblique", "DejaVuSerifCondensed")
HERSHEY_FONTS = ("hershey_simplex", "hershey_duplex", "hershey_complex", "hershey_triplex", "hershey_plain",
                 "hershey_simplex_italic")
GRATICULE_STEPS_S = (18000, 7200, 3600, 1800, 1200, 900, 600, 300, 120, 60, 30, 15)  # 5 deg .. 15 seconds
PROJECTIONS = ("merc", "lcc", "tmerc", "poly", "eqc")
METRE_STEPS = (100, 200, 250, 500, 1000, 2000, 2500, 5000, 10000, 20000, 25000, 50000)
IMPERIAL_STEPS = (500, 1000, 2000, 2500, 5000, 10000, 20000, 25000, 50000)
PROJECTED = {  # name: (weight, the centres' lon/lat box, steps in the CRS's unit)
    "utm_north": (0.27, None, METRE_STEPS),
    "utm_south": (0.14, None, METRE_STEPS),
    "EPSG:2154": (0.12, (-4.5, 42.5, 7.5, 51.0), METRE_STEPS),
    "EPSG:27700": (0.12, (-5.5, 50.3, 1.5, 58.5), METRE_STEPS),
    "EPSG:3857": (0.11, (-170.0, -70.0, 170.0, 70.0), METRE_STEPS + (100000, 200000)),
    "EPSG:2263": (0.12, (-74.2, 40.5, -72.0, 41.2), IMPERIAL_STEPS),  # US survey feet
    "EPSG:27291": (0.12, (173.0, -41.5, 178.4, -34.5), IMPERIAL_STEPS[:-1]),  # British yards
}
INKS = {"black": (25, 25, 25), "grey": (90, 90, 90), "blue": (30, 70, 170), "brown": (125, 70, 30),
        "magenta": (170, 40, 150), "red": (190, 35, 35), "green": (35, 120, 55)}
TINTS = ((214, 232, 196), (196, 220, 238), (238, 232, 200), (232, 214, 210), (222, 222, 214), (205, 226, 180))
BACKGROUND_FILES = ("timeseries/naip_20090818.tif", "timeseries/naip_20100629.tif", "timeseries/naip_20140720.tif",
                    "timeseries/naip_20150926.tif", "timeseries/naip_20160816.tif", "timeseries/landsat_1990.tif",
                    "timeseries/landsat_2005.tif", "landsat/RGB.byte.tif")
GEO_FORMATS = ("dm", "dm_space", "dm_prime", "dm_nopad", "hemi_pre", "hemi_post", "hemi_post_space", "dms",
               "dec_min", "deg_hemi", "deg_sign", "decimal")
GRID_FORMATS = ("full", "spaced", "abbrev")
EDGES = ("top", "bottom", "left", "right")
BAND = 128  # canvas rows drawn at a time
SCAN_LONG = (900, 3500)  # the scan's long side, px
STEP_PX = (60.0, 700.0)  # a grid step on the scan, px


@dataclass(frozen=True)
class RandomSpec:
    """Every parameter of one random sheet, as drawn by :func:`draw_spec` (plain values: JSON through
    ``dataclasses.asdict``). Lengths in px are print px, which the scan keeps (it turns, never scales).

    Attributes
    ----------
    seed, kind : the seed; 'graticule' (degrees) or 'grid' (a projected CRS's units).
    sheet_crs, units : what the printed coordinates count in, and the name of their unit.
    projection : the CRS (EPSG code or PROJ string) the sheet is drawn in; ``sheet_crs`` for a projected grid.
    step, label_step : the printed grid's step, and the step between labelled lines (``sheet_crs`` units).
    style : 'lines', 'crosses', 'ticks' (short ticks on the neatline, at most 2 full lines) or 'none'.
    centre, face_cells : the map face's centre (``sheet_crs`` units) and its width and height in steps.
    neatline : 'lines' (the face is bounded by four lines of the grid, curved where the projection bends them)
        or 'rectangle' (a rectangle of the print, across the lines).
    pixel_size : projection units per print px.
    ink, line_px, cross_arm, tick_frac, tick_side, full_lines : the grid's colour (RGB) and width; a cross's
        arm and a tick's length in steps (a tick at least 4 px); ticks 'in', 'out' or 'across' the neatline;
        the lines a 'ticks' sheet prints in full, as (axis, place 0..1 across the face).
    frame_ink, frame_px, border_px, border_gap_px : the neatline's colour and width; an outer border around the
        labels (0: none) and its distance from them.
    labelled, label_format, label_abbrev, label_sep, label_small_zeros, dms_short : whether labels are printed;
        their format (:data:`GEO_FORMATS`, :data:`GRID_FORMATS`); minutes (or kilometres) only between full
        labels; the thousands' separator; small trailing zeros on full abbreviated labels; seconds ('s') or
        minutes and seconds ('ms') between full labels.
    label_edges, label_placement, label_side, label_turn : the labelled edges; 'outside' (centred outside the
        neatline on a tick), 'inside' (just inside, beside the line) or 'between' (outside, beside the tick,
        between it and the next); to which side of the line (+1, -1); left and right labels turned 90 (reading
        upwards), -90 (downwards) or 0.
    label_boxed, label_dark_band, label_font, glyph_px, label_ink : a rectangle around each label; light labels
        in a dark band outside the neatline; the font (DejaVu file name or a Hershey face); the capitals' height
        on the scan; the labels' colour.
    paper, yellow, yellow_dir : the paper's colour; how much it darkens and yellows across the sheet, and which
        way (degrees).
    background, background_file, background_window, fade, content, contours : map content 'tints' (areas of
        flat colour), 'faded' (a faded image) or 'plain'; the image (under ``data_dir``, 'texture' for a
        generated one) and its window (x, y, width, height as fractions); how strong the colours are; how much
        content (roads, names, numbers; 1 is average); whether contour lines are drawn.
    paper_margin, margin_notes : paper beyond the labels (left, top, right, bottom px); a title, a scale and
        sheet numbers in the margins.
    angle_deg, warp_px, warp_phase : the scan's turn (clockwise on the screen), the paper's smooth warp (at
        most, px) and its phases.
    scanner_margin, scanner_tone, scanner_offset : the bed around the sheet (px), its grey, and where the sheet
        lies on it (fractions of the slack).
    fold, corner : a fold (place 0..1 across the long side, angle, depth in grey levels, width px) or None; a
        missing corner (which: 0 top-left, 1 top-right, 2 bottom-right, 3 bottom-left; size as a fraction of
        the short side) or None.
    noise, blur, jpeg : Gaussian noise (grey levels), blur (sigma px), JPEG quality (0: a PNG).
    """

    seed: int
    sheet_crs: str
    projection: str
    step: float
    label_step: float
    style: str
    kind: str
    units: str
    centre: tuple
    face_cells: tuple
    neatline: str
    pixel_size: float
    ink: tuple
    line_px: float
    cross_arm: float
    tick_frac: float
    tick_side: str
    full_lines: tuple
    frame_ink: tuple
    frame_px: float
    border_px: float
    border_gap_px: float
    labelled: bool
    label_format: str
    label_abbrev: bool
    label_sep: str
    label_small_zeros: bool
    dms_short: str
    label_edges: tuple
    label_placement: str
    label_side: int
    label_turn: int
    label_boxed: bool
    label_dark_band: bool
    label_font: str
    glyph_px: float
    label_ink: tuple
    paper: tuple
    yellow: float
    yellow_dir: float
    background: str
    background_file: str
    background_window: tuple
    fade: float
    content: float
    contours: bool
    paper_margin: tuple
    margin_notes: bool
    angle_deg: float
    warp_px: float
    warp_phase: tuple
    scanner_margin: float
    scanner_tone: float
    scanner_offset: tuple
    fold: tuple | None
    corner: tuple | None
    noise: float
    blur: float
    jpeg: int


# ---------------------------------------------------------------------------------------------------- drawing


def draw_spec(seed: int) -> RandomSpec:
    """Draw every parameter of a sheet from its distributions, with one ``numpy.random.default_rng(seed)``.

    Parameters
    ----------
    seed : int
        The seed; the same seed gives the same spec.

    Returns
    -------
    RandomSpec
        The sheet's parameters: a step 60-700 scan px, 4-12 lines across each way, a scan 900-3500 px on its
        long side (give or take the labels' margins).
    """
    rng = np.random.default_rng(seed)
    place = _draw_graticule(rng) if rng.random() < 0.55 else _draw_projected(rng)
    scan = _draw_scan(rng)
    look = _draw_look(rng)
    label = _draw_labels(rng, place)
    values = {**place, **scan, **look, **label}
    values.update(_fit_size(rng, values))
    return RandomSpec(seed=int(seed), **values)


def _choice(rng, options, weights=None):
    p = None if weights is None else np.asarray(weights, float) / np.sum(weights)
    return options[int(rng.choice(len(options), p=p))]


def _draw_graticule(rng) -> dict:
    nad83 = rng.random() < 0.2
    if nad83:  # North America
        lon, lat = rng.uniform(-165.0, -55.0), rng.uniform(15.0, 72.0)
    else:
        lon, lat = rng.uniform(-180.0, 180.0), rng.uniform(0.0, 72.0) * (1 if rng.random() < 0.6 else -1)
    return dict(kind="graticule", sheet_crs="EPSG:4269" if nad83 else "EPSG:4326", units="degree",
                projection=_choice(rng, PROJECTIONS), step=_choice(rng, GRATICULE_STEPS_S) / 3600.0,
                centre=(float(lon), float(lat)), neatline=_choice(rng, ("lines", "rectangle")))


def _draw_projected(rng) -> dict:
    from pyproj import CRS, Transformer

    names = tuple(PROJECTED)
    name = _choice(rng, names, [PROJECTED[n][0] for n in names])
    if name.startswith("utm"):
        zone, north = int(rng.integers(1, 61)), name == "utm_north"
        crs = f"EPSG:{(32600 if north else 32700) + zone}"
        lon = -183.0 + 6 * zone + rng.uniform(-3.5, 3.5)  # a little beyond the zone, as sheets reach
        lat = rng.uniform(0.5, 72.0) * (1 if north else -1)
    else:
        crs = name
        x0, y0, x1, y1 = PROJECTED[name][1]
        lon, lat = rng.uniform(x0, x1), rng.uniform(y0, y1)
    geodetic = CRS.from_user_input(crs)
    centre = Transformer.from_crs(geodetic.geodetic_crs, geodetic, always_xy=True).transform(lon, lat)
    return dict(kind="grid", sheet_crs=crs, units=geodetic.axis_info[0].unit_name, projection=crs,
                step=float(_choice(rng, PROJECTED[name][2])), centre=(float(centre[0]), float(centre[1])),
                neatline=_choice(rng, ("lines", "rectangle"), (0.35, 0.65)))


def _draw_scan(rng) -> dict:
    u = rng.random()
    if u < 0.7:
        angle = rng.uniform(-3.0, 3.0)
    elif u < 0.9:
        angle = rng.uniform(-180.0, 180.0)
    else:
        angle = (_choice(rng, (90.0, 180.0, 270.0)) + rng.uniform(-2.0, 2.0) + 180.0) % 360.0 - 180.0
    wide = rng.random() < 0.3
    tone = rng.uniform(10, 60) if wide and rng.random() < 0.5 else rng.uniform(232, 255)
    fold = None
    if rng.random() < 0.25:
        fold = (float(rng.uniform(0.3, 0.7)), float(rng.uniform(-4, 4)), float(rng.uniform(12, 45)),
                float(rng.uniform(1.5, 4.0)))
    corner = (int(rng.integers(0, 4)), float(rng.uniform(0.04, 0.15))) if rng.random() < 0.12 else None
    png = rng.random() < 0.15
    return dict(angle_deg=float(angle), warp_px=float(rng.uniform(0, 4)),
                warp_phase=tuple(float(p) for p in rng.uniform(0, 2 * math.pi, 4)),
                scanner_margin=float(rng.uniform(30, 200) if wide else rng.uniform(0, 8)), scanner_tone=float(tone),
                scanner_offset=tuple(float(v) for v in rng.uniform(-0.5, 0.5, 2)), fold=fold, corner=corner,
                noise=float(rng.uniform(0, 8)), blur=float(rng.uniform(0, 1.2)),
                jpeg=0 if png else int(rng.integers(40, 96)))


def _draw_look(rng) -> dict:
    tone = rng.uniform(200, 250)
    kind = _choice(rng, ("white", "cream", "yellowed"))
    paper = (tone, tone, tone) if kind == "white" else (tone, tone - rng.uniform(3, 9), tone - rng.uniform(12, 32))
    base = np.array(INKS[_choice(rng, tuple(INKS))], float)
    ink = np.asarray(paper) + rng.uniform(0.3, 1.0) * (base - np.asarray(paper))
    style = _choice(rng, ("lines", "crosses", "ticks", "none"), (0.52, 0.25, 0.15, 0.08))
    full = tuple((int(rng.integers(0, 2)), float(rng.uniform(0.2, 0.8))) for _ in range(int(rng.integers(0, 3))))
    dark = tuple(float(v) for v in np.full(3, rng.uniform(10, 60)))
    return dict(style=style, ink=_rgb(ink), line_px=float(np.exp(rng.uniform(np.log(0.6), np.log(3.5)))),
                cross_arm=float(rng.uniform(0.03, 0.25)), tick_frac=float(rng.uniform(0.01, 0.04)),
                tick_side=_choice(rng, ("in", "out", "across")), full_lines=full if style == "ticks" else (),
                frame_ink=_rgb(dark if rng.random() < 0.8 else ink), frame_px=float(rng.uniform(0.8, 3.5)),
                border_px=float(rng.uniform(1, 4)) if rng.random() < 0.4 else 0.0,
                border_gap_px=float(rng.uniform(4, 14)), paper=_rgb(paper),
                yellow=float(rng.uniform(0.04, 0.15)) if kind == "yellowed" else 0.0,
                yellow_dir=float(rng.uniform(0, 360)),
                background=_choice(rng, ("tints", "faded", "plain"), (0.5, 0.35, 0.15)),
                background_file=_choice(rng, BACKGROUND_FILES + ("texture",), (1,) * 8 + (2,)),
                background_window=tuple(float(v) for v in np.r_[rng.uniform(0, 1, 2), rng.uniform(0.3, 0.8, 2)]),
                fade=float(rng.uniform(0.3, 1.0)), content=float(rng.uniform(0.3, 1.5)),
                contours=bool(rng.random() < 0.5),
                paper_margin=tuple(float(v) for v in rng.uniform(6, 150, 4)), margin_notes=bool(rng.random() < 0.6))


def _rgb(values) -> tuple:
    return tuple(float(round(float(v), 1)) for v in values)


def _draw_labels(rng, place) -> dict:
    mult = _choice(rng, (1, 2, 5), (0.5, 0.3, 0.2))
    if place["kind"] == "graticule":
        fmt, abbrev = _geo_format(rng, round(place["step"] * 3600) * mult)
    else:
        fmt = _grid_format(rng, place, place["step"] * mult)
        abbrev = fmt == "abbrev"
    which = _choice(rng, ("all", "opposite", "adjacent", "one"), (0.4, 0.2, 0.2, 0.2))
    if which == "all":
        edges = EDGES
    elif which == "opposite":
        edges = _choice(rng, (("top", "bottom"), ("left", "right")))
    elif which == "adjacent":
        edges = (_choice(rng, ("top", "bottom")), _choice(rng, ("left", "right")))
    else:
        edges = (_choice(rng, EDGES),)
    band = rng.random() < 0.15
    truetype = rng.random() < 0.7
    font = _choice(rng, TRUETYPE_FONTS) if truetype else _choice(rng, HERSHEY_FONTS)
    dark = rng.uniform(10, 50)
    return dict(labelled=bool(rng.random() < 0.85), label_step=float(place["step"] * mult), label_format=fmt,
                label_abbrev=bool(abbrev), label_sep=_choice(rng, (" ", "\u2009")),
                label_small_zeros=bool(rng.random() < 0.5), dms_short=_choice(rng, ("s", "ms")), label_edges=edges,
                label_placement="outside" if band else _choice(rng, ("outside", "inside", "between"),
                                                                (0.55, 0.25, 0.2)),
                label_side=_choice(rng, (1, -1)), label_turn=_choice(rng, (0, 90, -90), (0.75, 0.125, 0.125)),
                label_boxed=bool(rng.random() < (0.35 if fmt.startswith("deg") else 0.1)), label_dark_band=band,
                label_font=font, glyph_px=float(np.exp(rng.uniform(np.log(7), np.log(45)))),
                label_ink=_rgb((dark, dark, dark) if rng.random() < 0.7 else INKS[_choice(rng, tuple(INKS))]))


def _geo_format(rng, label_s: int):
    """A format for labels every ``label_s`` seconds of arc, and whether minutes alone come between full ones."""
    if label_s % 60:
        return _choice(rng, ("dms", "dec_min")), bool(rng.random() < 0.5)
    dm = ("dm", "dm_space", "dm_prime", "dm_nopad", "hemi_pre", "hemi_post", "hemi_post_space")
    options, weights = dm, [1.0] * 7
    if label_s % 900 == 0:
        options, weights = options + ("decimal",), weights + [2.0]
    if label_s % 3600 == 0:
        options, weights = options + ("deg_hemi", "deg_sign"), weights + [2.5, 2.5]
    fmt = _choice(rng, options, weights)
    return fmt, bool(label_s % 3600 and fmt in dm and rng.random() < 0.5)


def _grid_format(rng, place, label_step: float) -> str:
    km = place["units"] == "metre" and label_step % 1000 == 0 and label_step <= 10000 and min(place["centre"]) > 1e5
    return _choice(rng, GRID_FORMATS if km else GRID_FORMATS[:2], (1, 1, 2) if km else (1, 1))


def _fit_size(rng, v: dict) -> dict:
    """The face's size in steps, its centre, the projection and the print's pixel size, so that a step is
    60-700 px and the scan 900-3500 px; then the labels' size (or their step) so that they never touch."""
    geographic = v["kind"] == "graticule"
    step = v["step"]
    lines = np.array([rng.integers(4, 13), rng.integers(4, 13)], float)
    frac = np.zeros(2) if v["neatline"] == "lines" else rng.uniform(0.15, 0.95, 2)
    first = rng.uniform(0.1, 0.9, 2) * frac  # from the face's low edge to its first line, in steps
    turn = abs(math.cos(math.radians(v["angle_deg"]))) + abs(math.sin(math.radians(v["angle_deg"])))
    margin = _margin_estimate(v)
    budget = max(1000.0, (SCAN_LONG[1] - 50 - 2 * v["scanner_margin"]) / turn - margin)
    if geographic:  # keep the face off the poles and within a plausible sheet
        lines = np.minimum(lines, [math.floor(60 / step) + 1, math.floor(40 / step) + 1])
    for _ in range(60):
        cells = np.maximum(lines - 1 + frac, 1.15)
        centre = _snap_centre(v, cells, first, geographic)
        projection = _projection(v, centre, cells) if geographic else v["sheet_crs"]
        low, high, face_long = _measure(v["sheet_crs"], projection, centre, cells, step, v["neatline"])
        lo = max(high / STEP_PX[1], face_long / budget)
        hi = min(low / (STEP_PX[0] + 2), face_long / 850)
        if lo <= hi:
            break
        before = lines.copy()
        if high / STEP_PX[1] > low / (STEP_PX[0] + 2) or face_long / budget > low / (STEP_PX[0] + 2):
            lines = np.maximum(lines - 1, 4)
        else:
            lines = np.minimum(lines + 1, 12)
        if np.array_equal(before, lines):
            break
    pixel_size = float(np.exp(rng.uniform(np.log(lo), np.log(max(hi, lo)))))
    out = dict(centre=tuple(float(c) for c in centre), face_cells=tuple(float(c) for c in cells),
               projection=projection, pixel_size=pixel_size)
    out.update(_fit_labels(v, low / pixel_size))
    return out


def _margin_estimate(v: dict) -> float:
    """Both margins across the sheet's long way, px (labels, border, paper), at most."""
    width = _label_chars(v) * 0.95 * v["glyph_px"]
    across = width if v["label_turn"] == 0 else 1.6 * v["glyph_px"]
    label = (1.5 * v["glyph_px"] + max(across, 1.6 * v["glyph_px"]) + 8) if v["labelled"] else 0
    return 2 * label + 2 * (v["border_px"] + v["border_gap_px"]) + sum(v["paper_margin"]) / 2 + 20


def _snap_centre(v, cells, first, geographic):
    """The face's centre, off the poles and the antimeridian for a graticule, so that its low edges lie
    ``first`` steps before a line (none for a 'lines' neatline, whose edges are lines): as many lines cross the
    face as were drawn."""
    centre = np.array(v["centre"], float)
    span = cells * v["step"]
    if geographic:
        centre[1] = np.clip(centre[1], -78 + span[1] / 2, 78 - span[1] / 2)
        centre[0] = np.clip(centre[0], -179 + span[0] / 2, 179 - span[0] / 2)
    return (np.round((centre - span / 2) / v["step"]) - first) * v["step"] + span / 2


def _projection(v, centre, cells) -> str:
    """The PROJ string a graticule sheet is drawn in, centred on it, on the datum of ``sheet_crs``."""
    lon, lat = float(centre[0]), float(centre[1])
    span = cells[1] * v["step"]
    lon0, lat0 = round(lon * 4) / 4, round(lat * 4) / 4
    lat1, lat2 = round((lat - span / 3) * 60) / 60, round((lat + span / 4) * 60) / 60
    kind = v["projection"]
    if kind == "lcc" and abs(lat1 + lat2) < 1:  # a cone that opens into a cylinder
        kind = "tmerc"
    params = {"merc": f"+proj=merc +lat_ts={lat0:g} +lon_0={lon0:g} +x_0=0 +y_0=0",
              "lcc": f"+proj=lcc +lat_1={lat1:.6g} +lat_2={lat2:.6g} +lat_0={lat0:g} +lon_0={lon0:g} +x_0=0 +y_0=0",
              "tmerc": f"+proj=tmerc +lat_0=0 +lon_0={lon0:g} +k=0.9996 +x_0=500000 +y_0=0",
              "poly": f"+proj=poly +lat_0={lat0:g} +lon_0={lon0:g} +x_0=0 +y_0=0",
              "eqc": f"+proj=eqc +lat_ts={lat0:g} +lon_0={lon0:g} +x_0=0 +y_0=0"}[kind]
    datum = "+datum=NAD83" if v["sheet_crs"] == "EPSG:4269" else "+datum=WGS84"
    return f"{params} {datum} +units=m +no_defs"


def _measure(sheet_crs, projection, centre, cells, step, neatline):
    """The lines' least and greatest distance apart over the face, and the face's long side (projection
    units)."""
    proj = _projector(sheet_crs, projection)
    u = np.linspace(-1, 1, 5)
    grid = np.column_stack([g.ravel() for g in np.meshgrid(u, u)]) * np.asarray(cells) * step / 2 + centre
    p = proj.forward(grid)
    apart = np.concatenate([np.hypot(*(proj.forward(grid + d) - p).T) for d in ([step, 0], [0, step])])
    outline = _outline(proj, np.asarray(centre), np.asarray(cells), step, neatline)
    return float(apart.min()), float(apart.max()), float(np.ptp(outline, axis=0).max())


def _fit_labels(v: dict, step_px: float) -> dict:
    """The labels' capitals (px), step and placement, so that a label takes at most 3/4 of the distance
    between labelled lines, and half a step where it sits beside its line: shrunk, then spread to a larger
    step, then moved outside."""
    start = round(v["label_step"] / v["step"])
    sides = [e for e in v["label_edges"] if e in ("left", "right")]
    for placement in dict.fromkeys((v["label_placement"], "outside")):
        for mult in [m for m in (1, 2, 5, 10) if m >= start]:
            along = max(_label_chars({**v, "label_step": v["step"] * mult}) * 0.95, 2.2)
            room = 0.75 * mult * step_px
            if placement != "outside":
                room = min(room, 0.5 * step_px - 6)
            need = max([along] * (len(sides) < len(v["label_edges"]))
                       + [along if v["label_turn"] else 1.7] * bool(sides))
            if room / need >= 7:
                return dict(glyph_px=float(min(v["glyph_px"], room / need)), label_step=float(v["step"] * mult),
                            label_placement=placement)
    return dict(glyph_px=7.0, label_step=float(v["step"] * mult), label_placement="outside")


def _label_chars(v: dict) -> float:
    """The longest label's width in capitals' heights, roughly (0.6 for a small digit)."""
    step = v["label_step"]
    widest = 0.0
    for axis in (0, 1):
        for value in (v["centre"][axis] + 8 * step, v["centre"][axis] - 8 * step):
            value = round(value / step) * step
            runs = _runs(_style(v), value, axis, True)
            widest = max(widest, sum(len(t) * r for t, r, _ in runs))
    return widest + (0.8 if v["label_boxed"] else 0)


# ------------------------------------------------------------------------------------------------- labels text


def _style(v) -> dict:
    """What formats a label: from a spec or the dict :func:`draw_spec` builds."""
    get = v.get if isinstance(v, dict) else v.__getattribute__
    return dict(geographic=get("kind") == "graticule", fmt=get("label_format"), abbrev=get("label_abbrev"),
                label_step=get("label_step"), sep=get("label_sep"), zeros=get("label_small_zeros"),
                short=get("dms_short"))


def _runs(style: dict, value: float, axis: int, full: bool) -> list:
    """What is printed for the line at ``value``: runs of (text, size relative to the capitals, raised)."""
    if style["geographic"]:
        return [(_geo_text(style, value, axis, full), 1.0, False)]
    return _grid_runs(style, value, full)


def _geo_text(style: dict, value: float, axis: int, full: bool) -> str:
    fmt = style["fmt"]
    total = int(round(abs(value) * 3600))
    d, m, s = total // 3600, total // 60 % 60, total % 60
    hemi = ("EW" if axis == 0 else "NS")[value < 0] if total else ""
    if fmt == "decimal":
        return f"{value:.{0 if style['label_step'] % 1 == 0 else 2}f}"
    if fmt == "deg_hemi":
        return f"{d}{hemi}"
    if fmt == "deg_sign":
        return f"{d}°"
    if fmt == "dec_min":
        minutes = f"{m + s / 60:.{1 if round(style['label_step'] * 3600) % 30 == 0 else 2}f}'"
        return f"{d}°{minutes}" if full else minutes
    if fmt == "dms":
        if full:
            return f"{d}°{m:02d}'{s:02d}\""
        return f"{s:02d}\"" if style["short"] == "s" and s else f"{m:02d}'{s:02d}\""
    prime = "′" if fmt == "dm_prime" else "'"
    minutes = f"{m}{prime}" if fmt == "dm_nopad" else f"{m:02d}{prime}"
    if not full:
        return minutes
    text = f"{d}° {minutes}" if fmt == "dm_space" else f"{d}°{minutes}"
    return {"hemi_pre": f"{hemi}{text}", "hemi_post": f"{text}{hemi}",
            "hemi_post_space": f"{text} {hemi}"}.get(fmt, text)


def _grid_runs(style: dict, value: float, full: bool) -> list:
    n = int(round(value))
    if style["fmt"] == "full":
        return [(str(n), 1.0, False)]
    if style["fmt"] == "spaced":
        return [(f"{n:,}".replace(",", style["sep"]), 1.0, False)]
    km = n // 1000
    if not full:
        return [(f"{km % 100:02d}", 1.0, False)]
    runs = [(str(km)[:-2], 0.6, True), (str(km)[-2:], 1.0, False)]
    return runs + [("000", 0.6, True)] if style["zeros"] else runs


# --------------------------------------------------------------------------------------------------- geometry


class _Projector:
    """``sheet_crs`` coordinates <-> the projection's (the identity where they are the same CRS)."""

    def __init__(self, sheet_crs: str, projection: str):
        from pyproj import Transformer

        self._t = None if sheet_crs == projection else Transformer.from_crs(sheet_crs, projection, always_xy=True)

    def forward(self, xy) -> np.ndarray:
        xy = np.atleast_2d(np.asarray(xy, float))
        if self._t is None:
            return xy.copy()
        return np.column_stack(self._t.transform(xy[:, 0], xy[:, 1]))

    def inverse(self, xy) -> np.ndarray:
        from pyproj.enums import TransformDirection

        xy = np.atleast_2d(np.asarray(xy, float))
        if self._t is None:
            return xy.copy()
        return np.column_stack(self._t.transform(xy[:, 0], xy[:, 1], direction=TransformDirection.INVERSE))


@lru_cache(maxsize=32)
def _projector(sheet_crs: str, projection: str) -> _Projector:
    return _Projector(sheet_crs, projection)


def _outline(proj, centre, cells, step, neatline) -> np.ndarray:
    """The neatline (projection units, a closed ring): four lines of the grid, or the rectangle through the
    midpoints of the face's sides."""
    lo, hi = centre - cells * step / 2, centre + cells * step / 2
    if neatline == "lines":
        t = np.linspace(0, 1, 2 if proj._t is None else 120)[:-1]
        ring = np.concatenate([np.column_stack([lo[0] + t * (hi[0] - lo[0]), np.full_like(t, hi[1])]),
                               np.column_stack([np.full_like(t, hi[0]), hi[1] - t * (hi[1] - lo[1])]),
                               np.column_stack([hi[0] - t * (hi[0] - lo[0]), np.full_like(t, lo[1])]),
                               np.column_stack([np.full_like(t, lo[0]), lo[1] + t * (hi[1] - lo[1])])])
        return proj.forward(ring)
    p = proj.forward([[lo[0], centre[1]], [hi[0], centre[1]], [centre[0], lo[1]], [centre[0], hi[1]]])
    return np.array([[p[0, 0], p[3, 1]], [p[1, 0], p[3, 1]], [p[1, 0], p[2, 1]], [p[0, 0], p[2, 1]]])


class _Face:
    """The map face of a spec: ``sheet_crs`` -> face px, its outline, and the range of lines crossing it."""

    def __init__(self, spec: RandomSpec):
        self.spec, self.step = spec, spec.step
        self.proj = _projector(spec.sheet_crs, spec.projection)
        self.centre, self.cells = np.asarray(spec.centre, float), np.asarray(spec.face_cells, float)
        ring = _outline(self.proj, self.centre, self.cells, self.step, spec.neatline)
        self.x0, self.y1 = ring[:, 0].min(), ring[:, 1].max()
        self.outline = self.from_projection(ring)
        self.size = np.ptp(ring, axis=0) / spec.pixel_size  # width, height
        dense = _densify(ring, max(2, 400 // len(ring)))
        units = self.proj.inverse(dense)
        lo, hi = units.min(axis=0), units.max(axis=0)
        self.k_range = [(math.floor(lo[a] / self.step) - 1, math.ceil(hi[a] / self.step) + 1) for a in (0, 1)]
        self.bounds = (lo, hi)  # of the face, sheet_crs units

    def from_projection(self, p) -> np.ndarray:
        """Projection units -> face px."""
        p = np.atleast_2d(p)
        s = self.spec.pixel_size
        return np.column_stack([(p[:, 0] - self.x0) / s, (self.y1 - p[:, 1]) / s])

    def to_face(self, xy) -> np.ndarray:
        """``sheet_crs`` coordinates (n, 2) -> face px."""
        return self.from_projection(self.proj.forward(xy))

    def line(self, axis: int, k: int) -> np.ndarray:
        """The line ``k`` steps along ``axis`` as a polyline in face px, a step beyond the face each way."""
        lo, hi = self.bounds[0][1 - axis] - self.step, self.bounds[1][1 - axis] + self.step
        n = 2 if self.proj._t is None else int(np.clip((hi - lo) / self.step * 48, 64, 1200))
        pts = np.empty((n, 2))
        pts[:, axis], pts[:, 1 - axis] = k * self.step, np.linspace(lo, hi, n)
        px = self.to_face(pts)
        return px[np.all(np.isfinite(px), axis=1)]

    def edges(self) -> tuple:
        """Each edge: its name, the axis of the lines that meet it, where it lies across (face px, y for top
        and bottom, x for left and right; used for a rectangle), the line that it is (``sheet_crs`` units;
        used for a 'lines' neatline), and the way into the face (face px)."""
        lo, hi = self.centre - self.cells * self.step / 2, self.centre + self.cells * self.step / 2
        w, h = self.size
        return (("top", 0, 0.0, hi[1], (0, 1)), ("bottom", 0, h, lo[1], (0, -1)),
                ("left", 1, 0.0, lo[0], (1, 0)), ("right", 1, w, hi[0], (-1, 0)))

    def span(self, edge: str) -> tuple:
        """Where an edge begins and ends along itself (x for top and bottom, y for left and right; face px)."""
        axis = 0 if edge in ("top", "bottom") else 1
        if self.spec.neatline == "rectangle":
            return 0.0, float(self.size[axis])
        lo, hi = self.centre - self.cells * self.step / 2, self.centre + self.cells * self.step / 2
        ends = {"top": [[lo[0], hi[1]], [hi[0], hi[1]]], "bottom": [[lo[0], lo[1]], [hi[0], lo[1]]],
                "left": [[lo[0], lo[1]], [lo[0], hi[1]]], "right": [[hi[0], lo[1]], [hi[0], hi[1]]]}[edge]
        along = np.sort(self.to_face(ends)[:, axis])
        return float(along[0]), float(along[1])


def _densify(ring, n):
    closed = np.vstack([ring, ring[:1]])
    t = np.linspace(0, 1, n, endpoint=False)[:, None]
    return np.concatenate([a + t * (b - a) for a, b in zip(closed[:-1], closed[1:])])


@dataclass
class _Anchor:
    """Where a line meets an edge of the neatline (face px), the way into the face along the line, and the
    place along the edge."""

    k: int
    value: float
    axis: int
    at: np.ndarray
    inward: np.ndarray
    along: float


def _anchors(face: _Face) -> dict:
    """Every line's meeting with each edge of the neatline, in reading order (left to right, bottom to top)."""
    out = {}
    for name, axis, where, bound, inward in face.edges():
        found = []
        for k in range(face.k_range[axis][0], face.k_range[axis][1] + 1):
            hit = _meet(face, axis, k, where, bound, np.asarray(inward, float))
            if hit is not None:
                found.append(_Anchor(k, k * face.step, axis, hit[0], hit[1], float(hit[0][axis])))
        found.sort(key=lambda a: a.along if axis == 0 else -a.along)
        out[name] = found
    return out


def _meet(face: _Face, axis, k, where, bound, inward):
    """(face px, unit vector inwards) where line ``k`` of ``axis`` meets an edge, or None."""
    step = face.step
    if face.spec.neatline == "lines":
        lo, hi = face.centre - face.cells * step / 2, face.centre + face.cells * step / 2
        if not lo[axis] + 1e-6 * step < k * step < hi[axis] - 1e-6 * step:
            return None
        pts = np.empty((2, 2))
        pts[:, axis] = k * step
        pts[:, 1 - axis] = bound, bound + 1e-3 * step * np.sign(face.centre[1 - axis] - bound)
        at, near = face.to_face(pts)
        return at, (near - at) / np.hypot(*(near - at))
    line = face.line(axis, k)
    across = line[:, 1 - axis] - where
    cross = np.flatnonzero(np.sign(across[:-1]) != np.sign(across[1:]))
    if not len(cross):
        return None
    i = cross[0]
    f = across[i] / (across[i] - across[i + 1])
    at = line[i] + f * (line[i + 1] - line[i])
    if not 0 < at[axis] < face.size[axis]:
        return None
    d = (line[i + 1] - line[i]) / np.hypot(*(line[i + 1] - line[i]))
    return at, d if d @ inward > 0 else -d


# ---------------------------------------------------------------------------------------------------- truth


class _Turn:
    """Canvas px -> scan px: the canvas turned about its centre, placed on the scanner's bed, and warped
    smoothly (the paper's waves)."""

    def __init__(self, spec: RandomSpec, canvas_wh):
        w, h = canvas_wh
        a = math.radians(spec.angle_deg)
        self.rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        corners = (np.array([[0, 0], [w, 0], [w, h], [0, h]]) - [w / 2, h / 2]) @ self.rot.T
        turned = np.ptp(corners, axis=0)
        size = np.ceil(turned + 2 * spec.scanner_margin + 4)
        size[np.argmax(size)] = max(size.max(), SCAN_LONG[0])
        self.scan_wh = (int(size[0]), int(size[1]))
        slack = (size - turned) / 2 - 2
        self.canvas_centre = np.array([w / 2, h / 2])
        self.scan_centre = size / 2 + np.asarray(spec.scanner_offset) * slack
        self.warp_px, self.phase = spec.warp_px, np.asarray(spec.warp_phase)

    def warp(self, xy) -> np.ndarray:
        """The paper's displacement at scan px ``xy`` (scan px)."""
        u, v, p = xy[:, 0] / self.scan_wh[0], xy[:, 1] / self.scan_wh[1], self.phase
        return self.warp_px * np.column_stack([np.sin(2.1 * u + 1.3 * v + p[0]) * np.cos(1.7 * v + p[1]),
                                               np.sin(1.9 * v + 0.8 * u + p[2]) * np.cos(1.4 * u + p[3])])

    def canvas_to_scan(self, xy) -> np.ndarray:
        """Canvas px -> scan px, the warp solved by fixed-point iteration (it moves less than 1 % of a px
        per px)."""
        with np.errstate(invalid="ignore"):  # points off the projection stay NaN
            base = (np.atleast_2d(xy) - self.canvas_centre) @ self.rot.T + self.scan_centre
            s = base
            for _ in range(12):
                s = base + self.warp(s)
        return s

    def scan_to_canvas(self, xy) -> np.ndarray:
        """Scan px -> canvas px."""
        return (xy - self.warp(xy) - self.scan_centre) @ self.rot + self.canvas_centre

    def source_maps(self, r0: int, r1: int):
        """For OpenCV's remap, where each scan px of rows ``r0``..``r1`` comes from: canvas x and y of its
        centre (float32, OpenCV's convention: pixel centres at whole numbers). :meth:`scan_to_canvas` with the
        warp's sines of sums split into products of a column's and a row's terms."""
        (sw, sh), p, a = self.scan_wh, self.phase, self.warp_px
        x = np.arange(sw) + 0.5
        y = np.arange(r0, r1)[:, None] + 0.5
        u, v = x / sw, y / sh
        wx = a * (np.sin(2.1 * u + p[0]) * np.cos(1.3 * v) + np.cos(2.1 * u + p[0]) * np.sin(1.3 * v)) \
            * np.cos(1.7 * v + p[1])
        wy = a * (np.sin(1.9 * v + p[2]) * np.cos(0.8 * u) + np.cos(1.9 * v + p[2]) * np.sin(0.8 * u)) \
            * np.cos(1.4 * u + p[3])
        dx, dy = x - wx - self.scan_centre[0], y - wy - self.scan_centre[1]
        (r00, r01), (r10, r11) = self.rot
        mx = dx * r00 + dy * r10 + self.canvas_centre[0] - 0.5
        my = dx * r01 + dy * r11 + self.canvas_centre[1] - 0.5
        return mx.astype(np.float32), my.astype(np.float32)


@dataclass
class _Truth:
    face: _Face
    offset: np.ndarray  # face px -> canvas px
    turn: _Turn
    corner: np.ndarray | None  # the missing corner's triangle, canvas px

    def to_canvas(self, xy) -> np.ndarray:
        return self.face.to_face(xy) + self.offset


@dataclass
class RandomSheet:
    """A rendered random sheet: the scan, its spec, what was printed as labels, and the exact truth.

    ``labels``: one dict per printed label: ``text``, ``value`` (the line's signed coordinate, ``sheet_crs``
    units), ``axis`` (0: x, longitude or easting; 1: y, latitude or northing), ``xy`` (the centre of its ink on
    the scan, scan px), ``glyph_px`` (its capitals' height on the scan), ``edge``, ``size`` (its ink's width and
    height on the print, px, before the scan's turn), ``full`` (False for minutes or kilometres alone), ``turn``.
    """

    path: str
    spec: RandomSpec
    labels: list
    _truth: _Truth = field(repr=False)

    def to_scan(self, grid_xy) -> np.ndarray:
        """``sheet_crs`` coordinates (n, 2) -> scan px (corner convention), through the projection, the print
        and the same turn and warp as the image."""
        t = self._truth
        return t.turn.canvas_to_scan(t.to_canvas(np.atleast_2d(np.asarray(grid_xy, float))))

    def nodes(self) -> np.ndarray:
        """``sheet_crs`` coordinates (n, 2) of every crossing of the grid inside the map face (or on its
        neatline, within 1 px), more than 20 px inside the scan and off a missing corner; printed or not (a
        'ticks' sheet prints only ticks, a 'none' sheet nothing)."""
        import cv2

        t = self._truth
        (kx0, kx1), (ky0, ky1) = t.face.k_range
        kx, ky = np.meshgrid(np.arange(kx0, kx1 + 1), np.arange(ky0, ky1 + 1))
        grid = np.column_stack([kx.ravel(), ky.ravel()]) * t.face.step
        canvas = t.to_canvas(grid)
        ring = (t.face.outline + t.offset).astype(np.float32).reshape(-1, 1, 2)
        inside = np.array([cv2.pointPolygonTest(ring, (float(x), float(y)), True) >= -1 if np.isfinite(x) else False
                           for x, y in canvas])
        if t.corner is not None:
            inside &= ~_in_triangle(canvas, t.corner, 20.0)
        px = t.turn.canvas_to_scan(canvas)
        h, w = self.shape
        inside &= (px[:, 0] > 20) & (px[:, 1] > 20) & (px[:, 0] < w - 20) & (px[:, 1] < h - 20)
        return grid[inside]

    def hints(self, k: int, seed: int, noise_px: float = 3.0) -> np.ndarray:
        """``k`` crossings away from the face's edges (a tenth of it in), each placed within ``noise_px`` of
        its truth: rows of (scan x, scan y, grid x, grid y), scan px and ``sheet_crs`` units."""
        rng = np.random.default_rng(seed)
        nodes = self.nodes()
        face = self._truth.face.to_face(nodes)
        w, h = self._truth.face.size
        inner = nodes[(face[:, 0] > 0.1 * w) & (face[:, 0] < 0.9 * w) & (face[:, 1] > 0.1 * h)
                      & (face[:, 1] < 0.9 * h)]
        pool = inner if len(inner) >= k else nodes
        if len(pool) < k:
            raise ValueError(f"the sheet has {len(pool)} crossings, fewer than the {k} hints asked for")
        pick = pool[np.sort(rng.choice(len(pool), k, replace=False))]
        angle, radius = rng.uniform(0, 2 * math.pi, k), noise_px * np.sqrt(rng.uniform(0, 1, k))
        offset = np.column_stack([np.cos(angle), np.sin(angle)]) * radius[:, None]
        return np.column_stack([self.to_scan(pick) + offset, pick])

    @property
    def shape(self) -> tuple:
        """(height, width) of the scan, px."""
        return self._truth.turn.scan_wh[1], self._truth.turn.scan_wh[0]


def _in_triangle(xy, tri, pad: float) -> np.ndarray:
    """Whether canvas px ``xy`` lie within ``pad`` px of the triangle ``tri`` (its right angle first)."""
    corner, a, b = tri
    u, v = (a - corner), (b - corner)
    lu, lv = np.hypot(*u), np.hypot(*v)
    p = xy - corner
    s, t = p @ u / lu, p @ v / lv  # distances along the legs
    return (s > -pad) & (t > -pad) & (s / lu + t / lv < 1 + pad * math.sqrt(2) / min(lu, lv))


# -------------------------------------------------------------------------------------------------- rendering


def render_random(seed_or_spec, folder: str, data_dir: str | None = None) -> RandomSheet:
    """Draw, print and scan a random sheet into ``folder``.

    Parameters
    ----------
    seed_or_spec : int or RandomSpec
        The seed (drawn through :func:`draw_spec`) or a spec.
    folder : str
        Where the scan is written (``random_<seed>.jpg``, or ``.png`` where the spec says so; no georeferencing).
    data_dir : str, optional
        The development data (``timeseries/``, ``landsat/``) a window of the map's content is read from; a
        generated texture without it or where the file is missing.

    Returns
    -------
    RandomSheet
        The scan's path, the spec, the labels printed, and the truth (scan px, corner convention).
    """
    import cv2

    spec = seed_or_spec if isinstance(seed_or_spec, RandomSpec) else draw_spec(int(seed_or_spec))
    rng = np.random.default_rng([spec.seed, 7])  # the content's details, not parameters of the sheet
    face = _Face(spec)
    anchors = _anchors(face)
    labels = _plan_labels(spec, face, anchors)
    margins, bands, border = _margins(spec, face, labels)
    offset = np.array(margins[:2], float)
    canvas_wh = (int(math.ceil(face.size[0] + margins[0] + margins[2])),
                 int(math.ceil(face.size[1] + margins[1] + margins[3])))
    canvas = _content(spec, rng, canvas_wh, face, offset, data_dir)
    layers = _layers(spec, face, anchors, labels, offset, border)
    bands = [tuple(np.r_[b[:2] + offset, b[2:] + offset]) for b in bands]
    _composite(canvas, layers, face.outline + offset, spec.paper, bands)
    printed = _print_labels(canvas, spec, labels, offset)
    _margin_notes(canvas, spec, rng)
    corner = _age(canvas, spec)
    turn = _Turn(spec, canvas_wh)
    scan = _scan(canvas, spec, turn, rng)
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, f"random_{spec.seed:05d}.{'png' if spec.jpeg == 0 else 'jpg'}")
    png = [cv2.IMWRITE_PNG_COMPRESSION, 1, cv2.IMWRITE_PNG_STRATEGY, cv2.IMWRITE_PNG_STRATEGY_HUFFMAN_ONLY]  # noisy
    params = [cv2.IMWRITE_JPEG_QUALITY, spec.jpeg] if spec.jpeg else png
    cv2.imwrite(path, np.ascontiguousarray(scan[..., ::-1]), params)
    truth = _Truth(face, offset, turn, corner)
    for label in printed:
        label["xy"] = [float(v) for v in turn.canvas_to_scan(np.asarray(label.pop("canvas_xy")))[0]]
    return RandomSheet(path, spec, printed, truth)


# ------------------------------------------------------------------------------------------------ label plan


@dataclass
class _Label:
    text: str
    value: float
    axis: int
    edge: str
    full: bool
    mask: np.ndarray  # alpha of the ink, uint8, cropped to it
    centre: np.ndarray  # face px
    tick: np.ndarray | None  # a tick beside it: two ends, face px


def _plan_labels(spec: RandomSpec, face: _Face, anchors: dict) -> list:
    """The labels: their ink and where each goes (face px), at every labelled line's meeting with a labelled
    edge, a corner's worth of room kept free."""
    if not spec.labelled:
        return []
    style, mult = _style(spec), max(1, round(spec.label_step / spec.step))
    out = []
    for edge in [e for e in EDGES if e in spec.label_edges]:
        first = True
        for a in anchors[edge]:
            if a.k % mult:
                continue
            full = first or not spec.label_abbrev or (style["geographic"] and round(abs(a.value) * 3600) % 3600 == 0)
            runs = _runs(style, a.value, a.axis, full)
            mask = _text_mask(spec.label_font, spec.glyph_px, runs)
            if a.axis == 1 and spec.label_turn:
                mask = np.ascontiguousarray(np.rot90(mask, 1 if spec.label_turn > 0 else -1))
            centre, tick = _place(spec, a, edge, mask.shape)
            half = mask.shape[1 - a.axis] / 2
            lo, hi = face.span(edge)
            if not lo + 3 < centre[a.axis] - half < centre[a.axis] + half < hi - 3:
                continue
            out.append(_Label("".join(r[0] for r in runs), float(a.value), a.axis, edge, bool(full), mask, centre,
                              tick))
            first = False
    return out


def _gap(spec) -> float:
    return max(2.0, 0.3 * spec.glyph_px)


def _place(spec: RandomSpec, a: _Anchor, edge: str, shape):
    """A label's centre (face px) beside its anchor, and its tick (two ends, or None)."""
    bh, bw = shape
    out = np.array({"top": (0, -1), "bottom": (0, 1), "left": (-1, 0), "right": (1, 0)}[edge], float)
    along = np.array((1, 0) if a.axis == 0 else (0, -1), float) * spec.label_side
    across, length = (bh, bw) if a.axis == 0 else (bw, bh)
    g = _gap(spec)
    tick_len = max(4.0, 0.7 * spec.glyph_px)
    if spec.label_placement == "outside":
        centre = a.at + out * (tick_len + g + across / 2)
    elif spec.label_placement == "between":
        tick_len = across + 2 * g
        centre = a.at + out * (g + across / 2) + along * (length / 2 + g)
    else:
        return a.at - out * (g + across / 2) + along * (length / 2 + g), None
    return centre, np.array([a.at, a.at - a.inward * tick_len])


def _margins(spec: RandomSpec, face: _Face, labels: list):
    """The margins (left, top, right, bottom px) around the face's bounding box, the dark bands behind
    labels (x0, y0, x1, y1, face px) and the outer border (a rectangle, face px, or None)."""
    w, h = face.size
    lo, hi = np.zeros(2), np.array([w, h])
    tick = _grid_tick_px(spec, face)
    if spec.style == "ticks" and spec.tick_side != "in":
        lo, hi = lo - tick, hi + tick
    for lab in labels:
        half = np.array(lab.mask.shape[::-1]) / 2 + (4 if spec.label_boxed else 0)
        lo, hi = np.minimum(lo, lab.centre - half - 2), np.maximum(hi, lab.centre + half + 2)
    bands = []
    if spec.label_dark_band and labels:
        g = _gap(spec)
        edges = {lab.edge for lab in labels}
        box = (lo[0] - g, lo[1] - g, hi[0] + g, hi[1] + g)
        for e in [e for e in EDGES if e in edges]:
            bands.append({"top": (box[0], box[1], box[2], 0), "bottom": (box[0], h, box[2], box[3]),
                          "left": (box[0], box[1], 0, box[3]), "right": (w, box[1], box[2], box[3])}[e])
        lo, hi = np.array(box[:2]), np.array(box[2:])
    border = None
    if spec.border_px:
        border = np.r_[lo - spec.border_gap_px, hi + spec.border_gap_px]
        lo, hi = lo - spec.border_gap_px - spec.border_px, hi + spec.border_gap_px + spec.border_px
    pm = spec.paper_margin
    margins = (math.ceil(-lo[0] + pm[0]), math.ceil(-lo[1] + pm[1]), math.ceil(hi[0] - w + pm[2]),
               math.ceil(hi[1] - h + pm[3]))
    return margins, bands, border


def _grid_tick_px(spec: RandomSpec, face: _Face) -> float:
    """A 'ticks' sheet's tick length, px: a fraction of the step at the face's centre, at least 4 px."""
    c = face.centre
    step_px = np.hypot(*(face.to_face([c + [spec.step, 0]]) - face.to_face([c]))[0])
    return max(4.0, spec.tick_frac * step_px)


# ---------------------------------------------------------------------------------------------- the ink layers


def _layers(spec: RandomSpec, face: _Face, anchors: dict, labels: list, offset, border) -> list:
    """What is drawn four times finer: [(primitives, colour, clipped to the face)], each primitive (points
    canvas px, width px or 0 for a filled polygon)."""
    grid, ticks = [], []
    w = spec.line_px
    if spec.style == "lines":
        grid = [(face.line(a, k) + offset, w) for a in (0, 1)
                for k in range(face.k_range[a][0], face.k_range[a][1] + 1)]
    elif spec.style == "crosses":
        grid = _crosses(spec, face, offset)
    elif spec.style == "ticks":
        ticks = _ticks(spec, face, anchors, offset)
        for axis, place in spec.full_lines:
            pool = anchors["top" if axis == 0 else "left"]
            if pool:
                grid.append((face.line(axis, pool[int(place * len(pool))].k) + offset, w))
    frame = [(np.vstack([face.outline, face.outline[:1]]) + offset, spec.frame_px)]
    if border is not None:
        x0, y0, x1, y1 = border
        frame.append((np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]]) + offset, spec.border_px))
    label_ticks = [(lab.tick + offset, max(1.0, spec.frame_px * 0.8)) for lab in labels if lab.tick is not None]
    return [(grid, spec.ink, True), (ticks, spec.ink, False), (frame, spec.frame_ink, False),
            (label_ticks, _band_text(spec) if spec.label_dark_band else spec.label_ink, False)]


def _crosses(spec, face: _Face, offset) -> list:
    """A cross at every crossing near the face, its arms along the lines (``cross_arm`` steps each way)."""
    (kx0, kx1), (ky0, ky1) = face.k_range
    arm = spec.cross_arm * spec.step
    t = np.linspace(-arm, arm, 2 if face.proj._t is None else 7)
    out = []
    for i in range(kx0, kx1 + 1):
        for j in range(ky0, ky1 + 1):
            node = np.array([i, j]) * spec.step
            for axis in (0, 1):
                pts = np.tile(node, (len(t), 1))
                pts[:, axis] += t
                px = face.to_face(pts)
                if np.all(np.isfinite(px)) and np.all(px > -50) and np.all(px < face.size + 50):
                    out.append((px + offset, spec.line_px))
    return out


def _ticks(spec, face: _Face, anchors: dict, offset) -> list:
    """A short tick along every line where it meets the neatline: inside, outside or across it."""
    length = _grid_tick_px(spec, face)
    reach = {"in": (0.0, 1.0), "out": (-1.0, 0.0), "across": (-0.5, 0.5)}[spec.tick_side]
    return [(np.array([a.at + a.inward * length * reach[0], a.at + a.inward * length * reach[1]]) + offset,
             spec.line_px) for edge in EDGES for a in anchors[edge]]


def _alpha(prims, r0: int, r1: int, width: int):
    """How much of each canvas px in rows ``r0``..``r1`` the primitives cover (float32, 0..1; None where
    none reach): drawn four times finer, anti-aliased, and reduced."""
    import cv2

    big = None
    for pts, w_px in prims:
        if pts[:, 1].max() < r0 - w_px - 2 or pts[:, 1].min() > r1 + w_px + 2:
            continue
        if big is None:
            big = np.zeros(((r1 - r0) * 4, width * 4), np.uint8)
        fine = np.round(((pts - [0.0, r0]) * 4 - 0.5) * 4).astype(np.int32)
        if w_px == 0:
            cv2.fillPoly(big, [fine], 255, cv2.LINE_8, shift=2)
        else:
            cv2.polylines(big, [fine], False, 255, max(1, int(round(w_px * 4))), cv2.LINE_AA, shift=2)
    if big is None:
        return None
    return cv2.resize(big, (width, r1 - r0), interpolation=cv2.INTER_AREA).astype(np.float32) / 255.0


def _composite(canvas, layers, outline, paper, bands) -> None:
    """Paint the paper outside the face (and the dark bands), then each ink layer, band of rows by band."""
    h, w = canvas.shape[:2]
    face = [(outline, 0)]
    dark = np.asarray(_band_colour(paper), np.float32)
    for r0 in range(0, h, BAND):
        r1 = min(h, r0 + BAND)
        inside = _alpha(face, r0, r1, w)
        back = np.empty((r1 - r0, w, 3), np.float32)
        back[:] = paper
        for x0, y0, x1, y1 in bands:
            ya, yb = int(round(max(y0, r0))) - r0, int(round(min(y1, r1))) - r0
            if yb > ya:
                back[ya:yb, int(round(np.clip(x0, 0, w))):int(round(np.clip(x1, 0, w)))] = dark
        out = back if inside is None else canvas[r0:r1] * inside[..., None] + back * (1 - inside[..., None])
        for prims, colour, clipped in layers:
            a = _alpha(prims, r0, r1, w)
            if a is None or (clipped and inside is None):
                continue
            a = a * inside if clipped else a
            out += (np.asarray(colour, np.float32) - out) * a[..., None]
        canvas[r0:r1] = np.clip(out + 0.5, 0, 255).astype(np.uint8)


def _band_colour(paper) -> tuple:
    return tuple(0.22 * np.asarray(paper, float))


def _band_text(spec) -> tuple:
    return tuple(0.98 * np.asarray(spec.paper, float))


# ---------------------------------------------------------------------------------------------------- text


def _text_mask(font: str, glyph_px: float, runs) -> np.ndarray:
    """The ink's alpha (uint8, cropped to it) of ``runs`` [(text, size relative to the capitals, raised)] in
    ``font`` with capitals ``glyph_px`` tall, side by side on one baseline; a raised run's capitals top the
    others'. Hershey faces draw the degree sign as a circle and primes as strokes."""
    pil = None if font.startswith("hershey") else _pil_font(font, 100)
    mask = _hershey_mask(font, glyph_px, runs) if pil is None else _pil_mask(font, glyph_px, runs)
    rows, cols = np.flatnonzero(mask.max(axis=1)), np.flatnonzero(mask.max(axis=0))
    if not len(rows):
        return np.zeros((1, 1), np.uint8)
    return np.ascontiguousarray(mask[rows[0]:rows[-1] + 1, cols[0]:cols[-1] + 1])


@lru_cache(maxsize=512)
def _pil_font(name: str, size: int):
    """A Pillow font of ``size`` px, from DejaVu; Pillow's own where the file is missing; None without one
    (Pillow before 10.1: a Hershey face then)."""
    from PIL import ImageFont

    try:
        return ImageFont.truetype(os.path.join(FONT_DIR, name + ".ttf"), size)
    except OSError:
        try:
            return ImageFont.load_default(size=size)
        except TypeError:
            return None


@lru_cache(maxsize=64)
def _cap_ratio(name: str) -> float:
    """Capitals' height per px of the font's size."""
    left, top, right, bottom = _pil_font(name, 200).getbbox("H", anchor="ls")
    return -top / 200.0


def _pil_mask(font: str, glyph_px: float, runs) -> np.ndarray:
    from PIL import Image, ImageDraw

    pad = int(glyph_px) + 6
    placed, x = [], float(pad)
    for text, rel, raised in runs:
        size = max(4, int(round(glyph_px * rel / _cap_ratio(font))))
        f = _pil_font(font, size)
        placed.append((x, text, f, size * _cap_ratio(font), raised))
        x += f.getlength(text)
    base = pad + int(math.ceil(glyph_px * 1.4))
    img = Image.new("L", (int(math.ceil(x)) + pad, base + int(glyph_px) + pad), 0)
    draw = ImageDraw.Draw(img)
    for x, text, f, cap, raised in placed:
        y = base - glyph_px + cap if raised else base
        draw.text((int(round(x)), int(round(y))), text, fill=255, font=f, anchor="ls")
    return np.asarray(img)


HERSHEY = {"hershey_simplex": ("FONT_HERSHEY_SIMPLEX", 0.09), "hershey_duplex": ("FONT_HERSHEY_DUPLEX", 0.11),
           "hershey_complex": ("FONT_HERSHEY_COMPLEX", 0.08), "hershey_triplex": ("FONT_HERSHEY_TRIPLEX", 0.09),
           "hershey_plain": ("FONT_HERSHEY_PLAIN", 0.1), "hershey_simplex_italic": ("FONT_HERSHEY_SIMPLEX", 0.09)}


@lru_cache(maxsize=16)
def _hershey_face(font: str):
    """(OpenCV's face, its capitals' height at scale 1, the stroke's width per px of capitals)."""
    import cv2

    name, thick = HERSHEY.get(font, HERSHEY["hershey_simplex"])
    face = getattr(cv2, name) | (cv2.FONT_ITALIC if font.endswith("italic") else 0)
    img = np.zeros((200, 200), np.uint8)
    cv2.putText(img, "H", (20, 150), face, 4.0, 255, 1, cv2.LINE_8)
    rows = np.flatnonzero(img.max(axis=1))
    return face, (rows[-1] - rows[0] + 1) / 4.0, thick


def _hershey_mask(font: str, glyph_px: float, runs) -> np.ndarray:
    face, unit, thick_frac = _hershey_face(font)
    pad = int(glyph_px) + 6
    pieces, x = [], float(pad)
    for text, rel, raised in runs:
        cap = glyph_px * rel
        scale, thick = cap / unit, max(1, int(round(cap * thick_frac)))
        for chunk in _split_symbols(text):
            pieces.append((x, chunk, cap, scale, thick, raised))
            x += _hershey_advance(chunk, face, cap, scale, thick)
    base = pad + int(math.ceil(glyph_px * 1.4))
    img = np.zeros((base + int(glyph_px) + pad, int(math.ceil(x)) + pad), np.uint8)
    for x, chunk, cap, scale, thick, raised in pieces:
        y = base - glyph_px + cap if raised else base
        _hershey_draw(img, chunk, x, y, face, cap, scale, thick)
    return img


def _split_symbols(text: str) -> list:
    out = []
    for ch in text:
        if ch in "°'\"′″\u2009" or not out or out[-1] in ("°", "'", '"', "′", "″", "\u2009"):
            out.append(ch)
        else:
            out[-1] += ch
    return out


def _hershey_advance(chunk, face, cap, scale, thick) -> float:
    import cv2

    symbols = {"°": 0.55, "'": 0.35, "′": 0.35, '"': 0.55, "″": 0.55, "\u2009": 0.25}
    if chunk in symbols:
        return symbols[chunk] * cap
    return cv2.getTextSize(chunk, face, scale, thick)[0][0]


def _hershey_draw(img, chunk, x, y, face, cap, scale, thick) -> None:
    """One chunk at (x, baseline y), image px: text through OpenCV, a degree sign as a circle, primes as
    strokes."""
    import cv2

    t = max(1, int(round(thick * 0.8)))
    if chunk == "°":
        r = 0.16 * cap
        cv2.circle(img, _q(x + r + 0.1 * cap, y - cap + r), int(round(r * 4)), 255, t, cv2.LINE_AA, 2)
    elif chunk in ("'", "′", '"', "″"):
        for dx in ((0.12,) if chunk in ("'", "′") else (0.12, 0.34)):
            top, bottom = (x + (dx + 0.1) * cap, y - cap), (x + dx * cap, y - 0.62 * cap)
            cv2.line(img, _q(*top), _q(*bottom), 255, t, cv2.LINE_AA, 2)
    elif chunk != "\u2009":
        cv2.putText(img, chunk, (int(round(x)), int(round(y))), face, scale, 255, thick, cv2.LINE_AA)


def _q(x, y):
    """Image px (corner convention) -> OpenCV's quarter-pixel points (``shift=2``)."""
    return int(round((x - 0.5) * 4)), int(round((y - 0.5) * 4))


def _stamp(canvas, mask, x: int, y: int, colour) -> None:
    """Paint ``colour`` through ``mask`` with its top-left at canvas px (x, y), cut at the canvas's edges."""
    h, w = canvas.shape[:2]
    mh, mw = mask.shape
    x0, y0, x1, y1 = max(x, 0), max(y, 0), min(x + mw, w), min(y + mh, h)
    if x1 <= x0 or y1 <= y0:
        return
    a = mask[y0 - y:y1 - y, x0 - x:x1 - x, None].astype(np.float32) / 255.0
    region = canvas[y0:y1, x0:x1].astype(np.float32)
    canvas[y0:y1, x0:x1] = np.clip(region + (np.asarray(colour, np.float32) - region) * a + 0.5, 0, 255).astype(
        np.uint8)


def _print_labels(canvas, spec: RandomSpec, labels: list, offset) -> list:
    """Paint the labels (with their boxes) and say what was printed where (canvas px, the ink's centre)."""
    import cv2

    colour = _band_text(spec) if spec.label_dark_band else spec.label_ink
    out = []
    for lab in labels:
        mh, mw = lab.mask.shape
        x, y = (int(round(v)) for v in lab.centre + offset - [mw / 2, mh / 2])
        _stamp(canvas, lab.mask, x, y, colour)
        if spec.label_boxed:
            p = max(2, int(round(0.25 * spec.glyph_px)))
            cv2.rectangle(canvas, (x - p, y - p), (x + mw + p - 1, y + mh + p - 1), colour,
                          max(1, int(round(spec.glyph_px / 12))), cv2.LINE_AA)
        out.append({"text": lab.text, "value": lab.value, "axis": lab.axis, "canvas_xy": [x + mw / 2, y + mh / 2],
                    "glyph_px": float(spec.glyph_px), "edge": lab.edge, "size": [int(mw), int(mh)],
                    "full": lab.full, "turn": int(spec.label_turn) if lab.axis == 1 else 0})
    return out


# ------------------------------------------------------------------------------------------------- content


def _content(spec: RandomSpec, rng, canvas_wh, face: _Face, offset, data_dir) -> np.ndarray:
    """The map's content over the whole canvas (RGB uint8): tints or a faded image, areas, contours, roads,
    rivers, straight boundaries, names and numbers (some close inside the neatline)."""
    w, h = canvas_wh
    small = _background(spec, rng, (max(8, h // 4), max(8, w // 4)), data_dir)
    canvas = _base(spec, rng, small, (h, w))
    density = spec.content * w * h / 1e6
    _areas(canvas, rng, int(3 * density) + 1)
    if spec.contours:
        _contours(canvas, rng, small)
    _features(canvas, rng, density)
    _names(canvas, spec, rng, int(15 * density) + 3)
    _numbers(canvas, spec, rng, int(20 * density) + 3, face, offset)
    return canvas


def _background(spec: RandomSpec, rng, shape, data_dir) -> np.ndarray:
    """A small RGB image (float32, 0..1) behind the map: a window of a real image, or a generated texture."""
    import cv2

    path = None if data_dir is None or spec.background_file == "texture" else os.path.join(
        data_dir, spec.background_file)
    if path is not None and os.path.exists(path):
        return _read_window(path, spec.background_window, shape)
    h, w = shape
    grey = np.zeros((h, w), np.float32)
    for scale, weight in ((24, 1.0), (6, 0.4)):
        noise = rng.normal(0, 1, (h // scale + 2, w // scale + 2)).astype(np.float32)
        grey += weight * cv2.resize(noise, (w, h), interpolation=cv2.INTER_CUBIC)
    grey = (grey - grey.min()) / (np.ptp(grey) + 1e-6)
    return np.repeat(grey[..., None], 3, axis=2)


def _read_window(path, window, shape) -> np.ndarray:
    """A window (fractions x, y, width, height) of the image at ``path``, read decimated to at most ``shape``."""
    import rasterio
    from rasterio.enums import Resampling
    from rasterio.windows import Window

    with rasterio.open(path) as ds:
        ww, wh = max(16, int(ds.width * window[2])), max(16, int(ds.height * window[3]))
        x0, y0 = int((ds.width - ww) * window[0]), int((ds.height - wh) * window[1])
        out = (min(shape[0], wh), min(shape[1], ww))
        bands = [1, 2, 3] if ds.count >= 3 else [1, 1, 1]
        data = ds.read(bands, window=Window(x0, y0, ww, wh), out_shape=(3,) + out, resampling=Resampling.average)
    img = np.moveaxis(data, 0, -1).astype(np.float32)
    return (img - img.min()) / (np.ptp(img) + 1e-6)


def _base(spec: RandomSpec, rng, small, shape) -> np.ndarray:
    """The canvas's ground (RGB uint8): flat tints from the image's levels, the image faded, or the paper."""
    import cv2

    h, w = shape
    paper = np.asarray(spec.paper, np.float32)
    if spec.background == "plain":
        return np.broadcast_to(np.round(paper).astype(np.uint8), (h, w, 3)).copy()
    level = np.arange(256, dtype=np.float32)[:, None]
    if spec.background == "faded":
        img = cv2.resize(np.round(small * 255).astype(np.uint8), (w, h), interpolation=cv2.INTER_LINEAR)
        lut = paper * (1 - 0.45 * spec.fade) + level * 0.45 * spec.fade  # each channel's grey -> its colour
        return cv2.LUT(img, np.round(lut).astype(np.uint8).reshape(256, 1, 3))
    grey = np.round(small.mean(axis=2) * 255).astype(np.uint8)
    n = int(rng.integers(3, 6))
    cls = np.searchsorted(np.quantile(grey, np.linspace(0, 1, n + 1)[1:-1]), level[:, 0], side="left")
    palette = np.array([paper] + [TINTS[int(i)] for i in rng.choice(len(TINTS), n - 1)], np.float32)
    lut = np.round(paper + (palette[cls] - paper) * spec.fade).astype(np.uint8).reshape(256, 1, 3)
    grey = cv2.resize(grey, (w, h), interpolation=cv2.INTER_CUBIC)
    return cv2.LUT(cv2.merge([grey, grey, grey]), lut)


def _blob(rng, centre, radius, n=24) -> np.ndarray:
    angles = np.linspace(0, 2 * math.pi, n, endpoint=False)
    r = radius * (1 + 0.35 * np.convolve(rng.normal(0, 1, n + 4), np.ones(5) / 5, "valid"))
    return np.column_stack([centre[0] + r * np.cos(angles), centre[1] + r * np.sin(angles)])


def _areas(canvas, rng, n: int) -> None:
    """Woods, water and built-up areas: blobs of flat tint, some outlined."""
    import cv2

    h, w = canvas.shape[:2]
    for _ in range(n):
        poly = _blob(rng, rng.uniform([0, 0], [w, h]), rng.uniform(20, 0.2 * min(w, h)))
        tint = TINTS[int(rng.integers(len(TINTS)))]
        pts = [_fine_px(poly)]
        cv2.fillPoly(canvas, pts, tint, cv2.LINE_AA, shift=2)
        if rng.random() < 0.4:
            cv2.polylines(canvas, pts, True, tuple(0.6 * np.asarray(tint)), 1, cv2.LINE_AA, shift=2)


def _fine_px(px) -> np.ndarray:
    """Canvas px (corner convention) -> OpenCV quarter-pixel points (``shift=2``)."""
    return np.round((np.asarray(px, float) - 0.5) * 4).astype(np.int32)


def _pt(xy) -> tuple:
    """One canvas point as OpenCV's quarter-pixel point (``shift=2``)."""
    return tuple(int(v) for v in _fine_px(xy))


def _contours(canvas, rng, small) -> None:
    """Brown contour lines: the background's levels traced at a quarter of the canvas's size."""
    import cv2

    grey = cv2.GaussianBlur(small.mean(axis=2), (0, 0), 2.0)
    scale = canvas.shape[1] / grey.shape[1]
    for lev in np.quantile(grey, np.linspace(0.1, 0.9, int(rng.integers(3, 9)))):
        found = cv2.findContours((grey > lev).astype(np.uint8), cv2.RETR_LIST, cv2.CHAIN_APPROX_SIMPLE)[-2]
        paths = [_fine_px((c[:, 0, :] + 0.5) * scale) for c in found if len(c) > 6]
        if paths:
            cv2.polylines(canvas, paths, True, (170, 110, 60), 1, cv2.LINE_AA, shift=2)


def _walk(rng, w, h, n, step, wiggle) -> np.ndarray:
    turns = np.cumsum(rng.normal(0, wiggle, n))
    heading = rng.uniform(0, 2 * math.pi)
    moves = np.column_stack([np.cos(heading + turns), np.sin(heading + turns)]) * step
    return rng.uniform([0, 0], [w, h]) + np.cumsum(moves, axis=0)


def _features(canvas, rng, density: float) -> None:
    """Roads (cased), rivers, railways and straight dashed boundaries: lines that are not the grid."""
    import cv2

    h, w = canvas.shape[:2]
    fills = ((230, 80, 50), (245, 170, 60), (250, 230, 120), (255, 255, 255))
    for _ in range(int(6 * density) + 2):
        path = [_fine_px(_walk(rng, w, h, 60, rng.uniform(10, 40), rng.uniform(0.02, 0.3)))]
        width = int(rng.integers(1, 6))
        cv2.polylines(canvas, path, False, (60, 50, 40), width + 2, cv2.LINE_AA, shift=2)
        cv2.polylines(canvas, path, False, fills[int(rng.integers(len(fills)))], width, cv2.LINE_AA, shift=2)
    for _ in range(int(2 * density) + 1):
        path = [_fine_px(_walk(rng, w, h, 80, 15, 0.25))]
        cv2.polylines(canvas, path, False, (60, 120, 200), int(rng.integers(1, 4)), cv2.LINE_AA, shift=2)
    for _ in range(int(rng.integers(0, 4))):  # straight: railways and boundaries
        a, b = rng.uniform([0, 0], [w, h], (2, 2))
        if rng.random() < 0.5:
            cv2.line(canvas, _pt(a), _pt(b), (40, 40, 40), 2, cv2.LINE_AA, 2)
        else:
            n = int(np.hypot(*(b - a)) // 18)
            for i in range(0, n, 2):
                p, q = a + (b - a) * i / max(n, 1), a + (b - a) * (i + 1) / max(n, 1)
                cv2.line(canvas, _pt(p), _pt(q), (120, 60, 140), 2, cv2.LINE_AA, 2)


SYLLABLES = ("ka", "ro", "mel", "ber", "sto", "vik", "an", "ter", "lu", "dor", "ham", "wick", "ville", "burg", "sen",
             "ta", "mi", "no", "ra", "el", "ost", "berg", "dal", "fjord", "loch", "port", "san", "ca", "mont")


def _names(canvas, spec: RandomSpec, rng, n: int) -> None:
    """Place names in the labels' font or another, dark or (water) blue."""
    h, w = canvas.shape[:2]
    for _ in range(n):
        name = "".join(SYLLABLES[int(i)] for i in rng.integers(0, len(SYLLABLES), int(rng.integers(2, 4))))
        name = name.upper() if rng.random() < 0.25 else name.capitalize()
        font = spec.label_font if rng.random() < 0.5 else _choice(rng, TRUETYPE_FONTS + HERSHEY_FONTS)
        mask = _text_mask(font, float(rng.uniform(5, 28)), [(name, 1.0, False)])
        colour = (40, 80, 170) if rng.random() < 0.25 else (30, 30, 30)
        _stamp(canvas, mask, int(rng.integers(-20, w)), int(rng.integers(-10, h)), colour)


def _number_text(rng) -> str:
    kind = int(rng.integers(0, 5))
    if kind == 0:
        return str(int(rng.integers(1, 4000)))  # spot heights
    if kind == 1:
        return f"{rng.uniform(0, 60):.1f}"  # soundings
    if kind == 2:
        return f"{int(rng.integers(0, 100)):02d}"  # like an abbreviated label
    if kind == 3:
        return f"{int(rng.integers(1, 90))}°{int(rng.integers(0, 60)):02d}'"  # a bearing, a declination
    return str(int(rng.integers(100, 99999)))


def _numbers(canvas, spec: RandomSpec, rng, n: int, face: _Face, offset) -> None:
    """Spot heights, soundings and other numbers in the labels' font and size, a third of them close inside
    the neatline, where labels are printed (canvas px)."""
    h, w = canvas.shape[:2]
    fw, fh = face.size
    for i in range(n):
        mask = _text_mask(spec.label_font, float(np.clip(spec.glyph_px * rng.uniform(0.5, 1.2), 5, 45)),
                          [(_number_text(rng), 1.0, False)])
        if i % 3 == 0:  # close inside an edge
            d = rng.uniform(2, 3 * spec.glyph_px + 4)
            x, y = rng.uniform(0, fw), rng.uniform(0, fh)
            x, y = [(x, d), (x, fh - d), (d, y), (fw - d, y)][int(rng.integers(0, 4))]
            x, y = np.array([x, y]) + offset - np.array(mask.shape[::-1]) / 2
        else:
            x, y = rng.uniform(-10, w), rng.uniform(-10, h)
        _stamp(canvas, mask, int(round(x)), int(round(y)), (40, 80, 170) if rng.random() < 0.3 else (35, 35, 35))


def _margin_notes(canvas, spec: RandomSpec, rng) -> None:
    """A title, a scale, a sheet number and the neighbouring sheets' numbers in the paper margins (canvas px)."""
    if not spec.margin_notes:
        return
    h, w = canvas.shape[:2]
    left, top, right, bottom = spec.paper_margin
    font = spec.label_font if rng.random() < 0.6 else _choice(rng, TRUETYPE_FONTS)
    title = "".join(SYLLABLES[int(i)] for i in rng.integers(0, len(SYLLABLES), 3)).upper()
    scale = f"1:{int(_choice(rng, (10, 20, 25, 50, 100, 250)) * 1000):,}".replace(",", " ")
    sheet = f"{int(rng.integers(1000, 9999))}-{_choice(rng, ('I', 'II', 'III', 'IV'))}"
    neighbours = [str(int(n)) for n in rng.integers(10, 9999, 2)]
    notes = ((title, w / 2, top / 2, 0.5 * top, w), (scale, w / 2, h - bottom / 2, 0.4 * bottom, w),
             (sheet, 0.85 * w, top / 2, 0.35 * top, w / 4), (neighbours[0], left / 2, h / 2, 0.35 * left, left),
             (neighbours[1], w - right / 2, h / 2, 0.35 * right, right))
    for text, x, y, size, room in notes:
        size = min(size, 36.0, 0.8 * room / len(text))
        if size >= 6:
            mask = _text_mask(font, size, [(text, 1.0, False)])
            _stamp(canvas, mask, int(x - mask.shape[1] / 2), int(y - mask.shape[0] / 2), (30, 30, 30))


# ---------------------------------------------------------------------------------------------------- the scan


def _age(canvas, spec: RandomSpec):
    """Yellow and darken the paper across the sheet, fold it, tear a corner off (canvas px, in place); the
    corner's triangle (right angle first) or None."""
    import cv2

    h, w = canvas.shape[:2]
    d = np.array([math.cos(math.radians(spec.yellow_dir)), math.sin(math.radians(spec.yellow_dir))])
    cast = np.array([1.0, 0.97, 0.85], np.float32)
    for r0 in range(0, h if spec.yellow or spec.fold is not None else 0, BAND):
        r1 = min(h, r0 + BAND)
        yy, xx = np.mgrid[r0:r1, 0:w].astype(np.float32) + 0.5
        band = canvas[r0:r1].astype(np.float32)
        if spec.yellow:
            ramp = ((xx - w / 2) * d[0] + (yy - h / 2) * d[1]) / max(w, h) + 0.5
            band *= 1 - spec.yellow * ramp[..., None] * (2 - cast)
        if spec.fold is not None:
            place, angle, depth, width = spec.fold
            a = math.radians(angle)
            across = (xx - place * w) * math.cos(a) + (yy - h / 2) * math.sin(a) if w >= h else \
                (yy - place * h) * math.cos(a) + (xx - w / 2) * math.sin(a)
            band -= (depth * np.exp(-0.5 * (across / width) ** 2)
                     - 0.3 * depth * np.exp(-0.5 * ((across - 2 * width) / width) ** 2))[..., None]
        canvas[r0:r1] = np.clip(band + 0.5, 0, 255).astype(np.uint8)
    if spec.corner is None:
        return None
    which, frac = spec.corner
    leg = frac * min(w, h)
    c = np.array([[0, 0], [w, 0], [w, h], [0, h]][which], float)
    sx, sy = (1 if c[0] == 0 else -1), (1 if c[1] == 0 else -1)
    tri = np.array([c, c + [sx * leg, 0], c + [0, sy * leg]])
    cv2.fillPoly(canvas, [_fine_px(tri)], (spec.scanner_tone,) * 3, cv2.LINE_AA, shift=2)
    return tri


def _scan(canvas, spec: RandomSpec, turn: _Turn, rng) -> np.ndarray:
    """The scanned image (RGB uint8): the canvas turned and warped onto the scanner's bed, blurred, noisy."""
    import cv2

    sw, sh = turn.scan_wh
    out = np.empty((sh, sw, 3), np.uint8)
    tone = (float(spec.scanner_tone),) * 3
    for r0 in range(0, sh, BAND * 2):
        r1 = min(sh, r0 + BAND * 2)
        mx, my = turn.source_maps(r0, r1)
        out[r0:r1] = cv2.remap(canvas, mx, my, cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT, borderValue=tone)
    if spec.blur >= 0.25:
        out = cv2.GaussianBlur(out, (0, 0), spec.blur)
    if spec.noise >= 0.5:
        for r0 in range(0, sh, BAND * 2):
            r1 = min(sh, r0 + BAND * 2)
            noisy = out[r0:r1] + rng.standard_normal((r1 - r0, sw, 3), dtype=np.float32) * spec.noise
            out[r0:r1] = np.clip(noisy + 0.5, 0, 255).astype(np.uint8)
    return out
