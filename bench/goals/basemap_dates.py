"""Finding an old photo on a basemap of another date, held out: ``hamta bench --families basemap-dates``.

The held-out part of :mod:`hamta.bench.goals.basemap_real` (the tuning part, 'basemap-real'): the same
imagery (``timeseries/``), the same local XYZ tile server up to :func:`~.basemap_real.native_zoom`, the same
judging (right within 3 px of the zoom registered at, or 2 px of the target's source where coarser), but
cases the tuning part does not have. Nothing here is drawn at random; every parameter is fixed below.

What each case varies against 'basemap-real':

- the date pair: 8 ordered NAIP pairs not in ``basemap_real.PAIRS`` (June onto August and back, September
  onto June, July onto September, one to six years apart), plus the two Landsat pairs;
- the window: off the raster's centre (the tuning part cuts near it), its longer side 0.35-0.45 of the
  raster's shorter side (smaller footprints), aspect 0.65-1, still within the source's valid pixels;
- the turn (any angle) and the scale (0.8-2 target px per source px);
- the file: half the NAIP targets are 4-band GeoTIFFs without georeferencing holding the NAIP file's own
  bands (R, G, B, NIR; no colour interpretation, as a user cutting the scene gets), the rest RGB PNGs;
- the search area: 3, 5 and 10 times the footprint (XYZ only), the target at a fixed offset per case and side.
"""
from __future__ import annotations

import dataclasses
import os
import warnings

import numpy as np

from ..study import Study
from . import basemap_real
from .basemap import rotated_target, window_matrix

FOLDER = basemap_real.FOLDER
# target date, basemap date, window centre (share of width, height), window's longer side (share of the
# raster's shorter side), aspect (short / long), scale (target px per source px), angle (degrees), file
CASES = (
    ("naip_20100629.tif", "naip_20090818.tif", (0.30, 0.33), 0.40, 0.75, 1.6, -20.0, "tif"),  # Jun -> Aug, 1 y
    ("naip_20150926.tif", "naip_20100629.tif", (0.68, 0.62), 0.38, 0.80, 0.9, 65.0, "png"),  # Sep -> Jun, 5 y
    ("naip_20090818.tif", "naip_20140720.tif", (0.62, 0.36), 0.42, 1.00, 1.25, 170.0, "tif"),  # Aug -> Jul, 5 y
    ("naip_20160816.tif", "naip_20100629.tif", (0.35, 0.64), 0.36, 0.70, 1.8, -95.0, "png"),  # Aug -> Jun, 6 y
    ("naip_20140720.tif", "naip_20150926.tif", (0.70, 0.40), 0.44, 0.85, 1.1, 40.0, "tif"),  # Jul -> Sep, 1 y
    ("naip_20150926.tif", "naip_20160816.tif", (0.28, 0.60), 0.35, 0.75, 2.0, -150.0, "png"),  # Sep -> Aug, 1 y
    ("naip_20090818.tif", "naip_20100629.tif", (0.74, 0.30), 0.40, 0.90, 0.8, 110.0, "tif"),  # Aug -> Jun, 1 y
    ("naip_20140720.tif", "naip_20090818.tif", (0.33, 0.40), 0.45, 0.65, 1.4, -45.0, "png"),  # Jul -> Aug, 5 y
    ("landsat_1990.tif", "landsat_2005.tif", (0.30, 0.45), 0.42, 0.80, 1.7, -60.0, "png"),  # 15 y
    ("landsat_2005.tif", "landsat_1990.tif", (0.68, 0.55), 0.38, 0.90, 1.1, 135.0, "png"),  # 15 y
)
SIDES = (3.0, 5.0, 10.0)
OFFSETS = ((-0.4, 0.5), (0.6, -0.7), (-0.7, -0.5), (0.5, 0.3), (0.2, 0.8))  # the target's place in the area


def available(data_dir: str) -> bool:
    return all(os.path.exists(os.path.join(data_dir, FOLDER, c[k])) for c in CASES for k in (0, 1))


def units(config):
    """(case index, search area side factor, 'xyz', method) for each case to run."""
    methods = [m for m in config.methods if "[" not in m and m != "sift"] or ["auto"]
    cases = range(len(CASES)) if not config.quick else (0, 8)
    sides = SIDES if not config.quick else (5.0,)
    return [(i, side, "xyz", m) for i in cases for side in sides for m in methods]


def name_of(i: int) -> str:
    target, basemap, *_, kind = CASES[i]
    return f"{os.path.splitext(target)[0]}-onto-{os.path.splitext(basemap)[0].split('_')[-1]}-{kind}"


def build(i: int, side: float, data_dir: str, folder: str):
    """The target of case ``i``, its basemap raster and the search area for ``side``."""
    import rasterio

    target_date, basemap_date, (fx, fy), share, aspect, scale, angle, kind = CASES[i]
    target_date, basemap_date = (os.path.join(data_dir, FOLDER, f) for f in (target_date, basemap_date))
    with rasterio.open(target_date) as ds:
        width, height = ds.width, ds.height
    w = int(round(share * min(width, height) * scale))
    h = int(round(w * aspect))
    os.makedirs(folder, exist_ok=True)
    case = rotated_target(target_date, os.path.join(folder, f"target_{i}.png"), (fx * width, fy * height), (h, w),
                          scale, angle)
    if kind == "tif":
        case = dataclasses.replace(case, path=_four_band(target_date, os.path.join(folder, f"target_{i}.tif"), case))
    offset = OFFSETS[(i + SIDES.index(side)) % len(OFFSETS)] if side in SIDES else (0.0, 0.0)
    return case, basemap_date, case.search_area(side * side, offset=offset)


def _four_band(source: str, path: str, case) -> str:
    """``case``'s window of every band of ``source`` (the same warp as :func:`rotated_target`), written as a
    GeoTIFF with neither georeferencing nor colour interpretation, as the source stores its bands."""
    import cv2
    import rasterio
    from rasterio.errors import NotGeoreferencedWarning

    h, w = case.shape
    _, cv_matrix = window_matrix(case.info["centre"], case.shape, case.info["scale"], case.info["angle_deg"])
    with rasterio.open(source) as ds:
        bands = np.ascontiguousarray(np.moveaxis(ds.read(), 0, 2))
    image = cv2.warpAffine(bands, cv_matrix, (w, h), flags=cv2.INTER_CUBIC | cv2.WARP_INVERSE_MAP)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NotGeoreferencedWarning)
        with rasterio.open(path, "w", driver="GTiff", width=w, height=h, count=image.shape[2], dtype="uint8",
                           photometric="MINISBLACK") as dst:  # GDAL's default for 4 bytes: RGB, NIR as alpha
            dst.write(np.moveaxis(image, 2, 0))
    return path


def run_unit(unit, config) -> list:
    """One row, as :func:`basemap_real.run_unit`, with the check's evidence and the places tried."""
    i, side, kind, method = unit
    name = name_of(i)
    folder = os.path.join(config.out_dir, "cases", "basemap-dates", f"{name}-{side:g}x-{kind}")
    case, basemap, extent = build(i, side, config.data_dir, folder)
    row, result = basemap_real.searched(case, basemap, extent, kind, method)
    row.update(unit=f"{name}-{side:g}x-{kind}", case=name, side=side)
    if result is not None:
        row.update(evidence(result))
    return [row]


def evidence(result) -> dict:
    """The check's verdict and figures, the registration's inliers and the places the search tried."""
    v = result.verification
    quality = None if v is None else {k: x for k, x in v.to_dict().items() if k != "sites"}
    return {"quality": quality, "n_inliers": result.stats.n_inliers, "n_gcps": result.stats.n_gcps,
            "places": (result.reference_service or {}).get("places")}


def tables(rows) -> list:
    out = basemap_real.tables(rows)
    for t in out:
        t["title"] = t["title"].replace("basemap-real", "basemap-dates (held out)")
    checks = []
    for r in sorted(rows, key=lambda r: (r["side"], r["case"])):
        if r["outcome"] == "verified":
            continue
        q = r.get("quality") or {}
        checks.append([r["case"], f"{r['side']:g}x", r["outcome"], r.get("verdict") or "–",
                       "; ".join(q.get("reasons") or []) or (r.get("error") or "–")[:160],
                       f"{q.get('n_agree', '–')}/{q.get('n_sites', '–')}", _num(q.get("error_bound_px")),
                       r.get("n_inliers", "–"), _num(r.get("rms_px")), len(r.get("places") or [])])
    out.append({"title": "basemap-dates (held out): the cases not verified and right, and why",
                "columns": ["case", "area", "outcome", "verdict", "reasons or error", "agree/sites", "bound px",
                            "inliers", "err rms px", "places tried"],
                "rows": checks, "note": "reasons: the check's own; bound: its error bound (px of the zoom "
                                        "registered at); err rms: the true error against the window's truth."})
    return out


def _num(v) -> str:
    return "–" if v is None else f"{v:.2f}"


STUDY = Study("basemap-dates", ("auto",), ("basemap-dates",), units, run_unit, tables)
