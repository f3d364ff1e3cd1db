"""Scanned sheets georeferenced by their own printed grid (issue 56): ``hamta bench --methods auto --families
scanned``.

Four kinds of units, each run as a user runs it (:func:`hamta.core.run`, method 'grid', no reference):

- no hints: the labels printed in the margins read (Tesseract), on the real sheets and the labelled
  synthetic ones;
- real sheets of ``../shared/data/scanned`` (:data:`REAL`: a 1907 map with a faint 1-degree graticule, NOAA
  charts in Mercator, conic and polyconic projections, one turned, a radiofax chart), read as pixels only: 2
  hints drawn from the sheet's own truth (crossings of the printed grid), placed within ``REAL_NOISE_PX`` of
  them, as a person would click. The truth's border points lie 1-8 px off the drawn frame, so a result is
  scored against a smooth model of all the truth points (:func:`_smooth_truth`): right within the check's
  tolerance, 3 scan px (:data:`REAL_RIGHT_PX`).
  Each sheet is marked 'tune' (looked at while the grid reader was built) or 'held-out';
- the synthetic family (:mod:`hamta.bench.sheets`: grids and graticules in several CRSs and styles, turned,
  warped, yellowed, folded, a corner missing, JPEG; one sheet without a grid), exact truth, right within 2 px,
  and the same sheets with one hint typed a step off (must be refused or right);
- sizes: a 5000 x 3500 px and a 20000 x 14000 px scan (tiled GeoTIFFs written tile by tile), every output
  written, timed, with the process's peak memory (goals: 15 s for the first, 1.5 GB for the second), and a
  30000 x 20000 px one (the issue's largest: read within bounded memory);
- onto a reference: a map drawn from a NAIP image's water (:mod:`hamta.bench.water_map`), 4 or 8 times finer
  than the reference and turned, registered by 'auto' onto NAIP imagery or its water as a layer, of the same
  date or another (:data:`ONTO`); right within 2 reference px over the sheet; onto the layer mirrored, any
  verified result is wrong.

A verified result beyond its threshold is a confident wrong answer.
"""
from __future__ import annotations

import csv
import os
import time

import numpy as np

from ..study import Study

FOLDER = "scanned"
REAL = {  # sheet: (file, the chart's projection, the printed coordinates' CRS, step in degrees, split)
    "nsw1907": ("nsw1907/nsw1907.jpg", "EPSG:4326", "EPSG:4326", 1.0, "tune"),
    "noaa16004": ("noaa16004/16004_1.KAP", "EPSG:3395", "EPSG:4269", 1.0, "tune"),
    "noaa14771": ("noaa14771/14771_1.KAP", "EPSG:3395", "EPSG:4269", 1 / 60, "tune"),
    "noaa14988": ("noaa14988_basswood/noaa14988.png",
                  "+proj=lcc +lat_1=47.033 +lat_2=48.05 +lon_0=-91.7 +ellps=GRS80", "EPSG:4269", 2 / 60, "tune"),
    "noaa19351": ("noaa19351_kaumalapau/noaa19351_2.png", "+proj=merc +lat_ts=20.8 +datum=WGS84", "EPSG:4326",
                  0.25 / 60, "tune"),
    "noaa14926": ("noaa14926_chicago/noaa14926_31.png", "+proj=poly +lon_0=-87.532 +ellps=GRS80", "EPSG:4269",
                  5 / 60, "held-out"),
    "noaa11361": ("noaa11361_swpass/noaa11361_2.png", "+proj=merc +lat_ts=29.133 +ellps=GRS80", "EPSG:4269",
                  1 / 60, "held-out"),
    "noaa19350": ("noaa19350_maalaea/noaa19350.png", "+proj=merc +lat_ts=20.8 +datum=WGS84", "EPSG:4326", 1 / 60,
                  "held-out"),
    "noaa19347": ("noaa19347_manele/noaa19347_2.png", "+proj=merc +lat_ts=20.8 +datum=WGS84", "EPSG:4326",
                  0.5 / 60, "held-out"),
    "fax": ("noaa_opc_windwave_fax/PWAE10.png", "+proj=merc +R=6371000", "EPSG:4326", 5.0, "held-out"),
}
REAL_NOISE_PX = 3.0
REAL_RIGHT_PX = 3.0  # the check's tolerance: the truth's own points are 0.5-5 px off the printed lines (its README)
SIZES = ((5000, 3500), (20000, 14000), (30000, 20000))
ONTO = {  # case: (the map's date, the reference's date, the reference: 'imagery', 'water' or 'water-mirrored'
    # (the layer flipped left to right: lakes of the same kind where none of the map's lie; must be refused),
    # zoom, turn degrees)
    "water-same-date-4x": ("20090818", "20090818", "water", 4.0, 7.0),
    "water-same-date-8x": ("20160816", "20160816", "water", 8.0, -35.0),
    "water-mirrored-4x": ("20160816", "20160816", "water-mirrored", 4.0, 12.0),
    "imagery-same-date-4x": ("20090818", "20090818", "imagery", 4.0, 7.0),
    "water-7-years-4x": ("20090818", "20160816", "water", 4.0, -20.0),
    "imagery-7-years-4x": ("20090818", "20160816", "imagery", 4.0, -20.0),
    "water-2-years-8x": ("20160816", "20140720", "water", 8.0, 3.0),
    "imagery-2-years-8x": ("20160816", "20140720", "imagery", 8.0, 3.0),
}
SEEDS = 5
REAL_SEEDS = 3


def available(data_dir: str) -> bool:
    return all(os.path.exists(os.path.join(data_dir, FOLDER, v[0])) for v in REAL.values())


def units(config):
    from ..sheets import SPECS

    seeds = range(SEEDS if not config.quick else 1)
    out = [("real", name, 2, s) for name in REAL for s in range(min(len(seeds), REAL_SEEDS))]
    out += [("synthetic", spec.name, k, s) for spec in SPECS for k in (2, 3) for s in seeds]
    out += [("one-step-off", spec.name, 3, s) for spec in SPECS if spec.grid for s in seeds]
    out += [("labels", name, 0, 0) for name in REAL] + [("labels", spec.name, 0, 0) for spec in SPECS if spec.labels]
    out += [("onto-reference", name, 0, 0) for name in ONTO]
    return out + [("size", f"{w}x{h}", 2, 0) for w, h in (SIZES if not config.quick else SIZES[:1])]


def run_unit(unit, config) -> list:
    from ..memory import PeakRss

    kind, name, k, seed = unit
    folder = os.path.join(config.out_dir, "cases", "scanned", f"{kind}-{name}-{k}-{seed}")  # one per unit: the
    os.makedirs(folder, exist_ok=True)  # pool runs units side by side
    row = {"kind": kind, "sheet": name, "hints": k, "seed": seed}
    if kind == "onto-reference":
        with PeakRss() as peak:
            row.update(_onto_reference(name, config.data_dir, folder))
        row["peak_mb"] = peak.peak
        row["confident_wrong"] = row["verdict"] == "verified" and (row["rms_px"] is None or row["rms_px"] > 2.0)
        return [row]
    if name in REAL:
        path, projection, grid_crs, step, split = REAL[name]
        path, crs, right_px = os.path.join(config.data_dir, FOLDER, path), None, REAL_RIGHT_PX
        truth = _smooth_truth(_truth(os.path.join(os.path.dirname(path), "truth.csv")), projection, grid_crs)
        hints = _hints(truth, step, k, seed) if k else None
        if k and hints is None:
            return [dict(row, split=split, verdict="skipped", why=f"the truth has fewer than {k} crossings",
                         rms_px=None, time_s=0.0, peak_mb=0.0, confident_wrong=False, right_px=right_px)]
        to_px = _synthetic_error(truth[:, 2:], truth[:, :2], grid_crs)
        row["split"] = split
    elif kind == "size":
        from ..sheets import large_sheet

        w, h = (int(v) for v in name.split("x"))
        sheet = large_sheet(os.path.join(folder, f"large_{name}.tif"), w, h)
        path, crs, grid_crs, hints, right_px = sheet.path, sheet.crs, sheet.crs, sheet.hints(k), 2.0
        nodes = _nodes_of(sheet, w, h)
        to_px = _synthetic_error(nodes, sheet.to_scan(nodes), grid_crs)
    else:
        from ..sheets import SPECS, render

        spec = next(s for s in SPECS if s.name == name)
        sheet = render(spec, folder)
        path, crs, grid_crs, right_px = sheet.path, spec.crs, spec.grid_crs, 2.0
        hints = sheet.hints(k, seed) if spec.grid else np.array([[300.0, 300.0, 500000.0, 5540000.0],
                                                                   [500.0, 310.0, 501000.0, 5540000.0]])
        hints = hints if k else None
        if kind == "one-step-off":
            hints[-1, 2] += spec.step
        nodes = sheet.nodes()
        to_px = _synthetic_error(nodes, sheet.to_scan(nodes), grid_crs) if spec.grid else None
    row["right_px"] = right_px
    with PeakRss() as peak:
        row.update(_run(path, crs, grid_crs, hints, to_px, folder if kind == "size" else None))
    row["peak_mb"] = peak.peak
    row["confident_wrong"] = row["verdict"] == "verified" and (row["rms_px"] is None or row["rms_px"] > right_px)
    return [row]


def _run(path, crs, grid_crs, hints, to_px, out) -> dict:
    import shutil

    from ...core import run
    from ...core.errors import HamtaError, UnverifiedResult
    from ...core.options import OutputOptions
    from ...core.outputs import OutputPaths

    paths = None
    if out is not None:
        out = os.path.join(out, "outputs")
        shutil.rmtree(out, ignore_errors=True)
        paths = OutputPaths.in_folder(out)
    t0 = time.perf_counter()
    try:
        result, _ = run(path, None, paths, method="grid", params={"hints": hints, "sheet_crs": grid_crs},
                        output=OutputOptions(crs=crs))
    except UnverifiedResult as exc:
        result = exc.result
    except HamtaError as exc:
        return {"verdict": "refused", "why": str(exc)[:160], "rms_px": None, "time_s": time.perf_counter() - t0,
                "crossings": 0, "model": None, "step": None}
    elapsed = time.perf_counter() - t0
    rms = None if to_px is None else to_px(result)
    return {"verdict": result.verification.verdict, "why": "; ".join(result.verification.reasons)[:160],
            "rms_px": rms, "time_s": elapsed, "crossings": len(result.gcps), "model": result.model.kind,
            "step": result.params["step"]}


def _onto_reference(name, data_dir, folder) -> dict:
    """Draw case ``name`` of :data:`ONTO`, register it with 'auto' onto its reference; the RMS (reference px)
    of the model over a 9 x 9 grid of the turned map face (its middle 80 %)."""
    from ...core import run
    from ...core.errors import HamtaError, UnverifiedResult
    from ..water_map import AREA, draw, write_reference

    date, ref_date, ref_kind, zoom, angle = ONTO[name]
    sheet = draw(data_dir, date, os.path.join(folder, "map.jpg"), zoom, angle)
    reference = write_reference(data_dir, ref_date, os.path.join(folder, "reference.tif"), ref_kind)
    face = np.array(AREA[2:], float) * zoom
    u, v = np.meshgrid(np.linspace(0.1, 0.9, 9), np.linspace(0.1, 0.9, 9))
    canvas = np.column_stack([u.ravel(), v.ravel()]) * face
    full = np.vstack([sheet.matrix, [0, 0, 1]])
    scan = (canvas - full[:2, 2]) @ np.linalg.inv(full[:2, :2]).T
    truth = sheet.to_reference(scan)
    t0 = time.perf_counter()
    try:
        result, _ = run(sheet.path, reference, None, method="auto")
    except UnverifiedResult as exc:
        result = exc.result
    except HamtaError as exc:
        return {"verdict": "refused", "why": str(exc)[:160], "rms_px": None, "time_s": time.perf_counter() - t0,
                "crossings": 0, "model": None, "step": None, "right_px": 2.0}
    rms = None
    if result.model is not None and ref_kind != "water-mirrored":
        rms = float(np.sqrt(np.mean(np.sum((result.model.apply(scan) - truth) ** 2, axis=1))))
    return {"verdict": result.verification.verdict, "why": "; ".join(result.verification.reasons)[:160],
            "rms_px": rms, "time_s": time.perf_counter() - t0, "crossings": len(result.gcps),
            "model": result.method, "step": None, "right_px": 2.0}


def _truth(path) -> np.ndarray:
    """Rows of scan x, y, lon, lat (columns pixel_x, pixel_y, lon, lat; or the BSB charts' X, Y with pixel
    indices, whose centres are half a pixel on)."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if "lon" in rows[0]:
        return np.array([[float(r["pixel_x"]), float(r["pixel_y"]), float(r["lon"]), float(r["lat"])] for r in rows])
    return np.array([[float(r["pixel_x"]) + 0.5, float(r["pixel_y"]) + 0.5, float(r["X"]), float(r["Y"])]
                     for r in rows])


def _smooth_truth(truth, projection, grid_crs) -> np.ndarray:
    """``truth`` with its scan px replaced by a smooth model's of all its points (a 2nd-order polynomial from the
    chart's projection, an affine under 12 points): the publishers' border points lie 1-8 px off the drawn frame
    (the data's README), the model of them all within 0.6 px of the printed crossings."""
    from pyproj import Transformer

    xy = np.column_stack(Transformer.from_crs(grid_crs, projection, always_xy=True).transform(*truth[:, 2:].T))
    u = (xy - xy.mean(axis=0)) / xy.std(axis=0).max()
    terms = [np.ones(len(u)), u[:, 0], u[:, 1]]
    if len(u) >= 12:
        terms += [u[:, 0] ** 2, u[:, 0] * u[:, 1], u[:, 1] ** 2]
    design = np.column_stack(terms)
    coef, *_ = np.linalg.lstsq(design, truth[:, :2], rcond=None)
    return np.column_stack([design @ coef, truth[:, 2:]])


def _hints(truth, step, k, seed) -> np.ndarray:
    """``k`` truth points on crossings of the printed grid, placed within :data:`REAL_NOISE_PX`."""
    on = np.all(np.abs(truth[:, 2:] / step - np.round(truth[:, 2:] / step)) < 0.01, axis=1)
    crossings = truth[on].copy()
    if len(crossings) < k:
        return None
    crossings[:, 2:] = np.round(crossings[:, 2:] / step) * step
    rng = np.random.default_rng(seed)
    pick = crossings[rng.choice(len(crossings), k, replace=False)].copy()
    pick[:, :2] += rng.uniform(-REAL_NOISE_PX, REAL_NOISE_PX, (k, 2))
    return pick


def _synthetic_error(grid_xy, scan_px, grid_crs):
    """result -> RMS (scan px) of every point from where the model puts its printed coordinates ``grid_xy``."""
    def error(result) -> float:
        from pyproj import CRS, Transformer

        from ...core.estimation.inverse import invert_model

        to_map = Transformer.from_crs(grid_crs, CRS.from_user_input(result.reference.crs.to_wkt()), always_xy=True)
        xy = np.column_stack(to_map.transform(*np.asarray(grid_xy).T))
        frame_px = np.column_stack((~result.reference.transform) * (xy[:, 0], xy[:, 1]))
        got, _ = invert_model(result.model, frame_px, (result.target.width, result.target.height))
        return float(np.sqrt(np.mean(np.sum((got - scan_px) ** 2, axis=1))))

    return error


def _nodes_of(sheet, width, height) -> np.ndarray:
    inverse = np.linalg.inv(np.vstack([sheet.matrix, [0, 0, 1]]))
    corners = np.array([[0, 0, 1], [width, 0, 1], [0, height, 1], [width, height, 1]]) @ inverse[:2].T
    lo, hi = np.ceil(corners.min(axis=0) / 1000), np.floor(corners.max(axis=0) / 1000)
    gx, gy = np.meshgrid(np.arange(lo[0], hi[0] + 1) * 1000, np.arange(lo[1], hi[1] + 1) * 1000)
    nodes = np.column_stack([gx.ravel(), gy.ravel()])
    px = sheet.to_scan(nodes)
    inside = (px[:, 0] > 50) & (px[:, 1] > 50) & (px[:, 0] < width - 50) & (px[:, 1] < height - 50)
    return nodes[inside]


def tables(rows) -> list:
    out = []
    for kind, title in (("labels", "no hints: the labels printed in the margins read (Tesseract)"),
                        ("real", "real sheets, 2 hints from the truth placed within 3 px"),
                        ("synthetic", "synthetic sheets (hamta.bench.sheets), 2 or 3 hints within 3 px"),
                        ("one-step-off", "synthetic sheets, 3 hints, one typed a step off: refused or right")):
        body = []
        for sheet in sorted({r["sheet"] for r in rows if r["kind"] == kind}):
            for k in sorted({r["hints"] for r in rows if r["kind"] == kind and r["sheet"] == sheet}):
                mine = [r for r in rows if r["kind"] == kind and r["sheet"] == sheet and r["hints"] == k and
                        r["verdict"] != "skipped"]
                if not mine:
                    continue
                right = [r for r in mine if r["verdict"] == "verified" and not r["confident_wrong"]]
                rms = [r["rms_px"] for r in right]
                split = mine[0].get("split", "")
                body.append([sheet + (f" ({split})" if split else ""), k, len(mine), len(right),
                             sum(r["confident_wrong"] for r in mine),
                             sum(r["verdict"] == "refused" for r in mine),
                             "–" if not rms else f"{np.median(rms):.2f}", "–" if not rms else f"{max(rms):.2f}",
                             f"{np.median([r['time_s'] for r in mine]):.1f}",
                             f"{max(r['peak_mb'] for r in mine):.0f}"])
        if body:
            out.append({"title": f"scanned: {title}", "rows": body,
                        "columns": ["sheet", "hints", "runs", "verified right", "confident wrong", "refused",
                                    "median RMS px", "max RMS px", "median s", "max peak MB"],
                        "note": "RMS: every truth point (real) or crossing (synthetic) from where the model puts "
                                "its coordinates, scan px (real: the smooth model of the truth's points). Right within "
                                "2 px (real: 3 px, the check's tolerance)."})
    onto = [r for r in rows if r["kind"] == "onto-reference"]
    if onto:
        out.append({"title": "scanned: onto a reference (a map drawn from NAIP water, 'auto')",
                    "columns": ["case", "verdict", "method", "RMS ref px", "time s", "peak MB"],
                    "rows": [[r["sheet"], r["verdict"], r["model"] or "–", "–" if r["rms_px"] is None else
                              f"{r['rms_px']:.1f}", f"{r['time_s']:.1f}", f"{r['peak_mb']:.0f}"] for r in onto],
                    "note": "Right within 2 reference px (NAIP 5 m) over the map face; the scan 4 or 8 times finer."})
    sizes = [r for r in rows if r["kind"] == "size"]
    if sizes:
        out.append({"title": "scanned: size (a 1 km grid on a tiled GeoTIFF, every output written)",
                    "columns": ["scan px", "verdict", "crossings", "RMS px", "time s", "peak MB"],
                    "rows": [[r["sheet"], r["verdict"], r["crossings"], "–" if r["rms_px"] is None else
                              f"{r['rms_px']:.2f}", f"{r['time_s']:.1f}", f"{r['peak_mb']:.0f}"] for r in sizes],
                    "note": "Goals: 15 s for 5000 x 3500 px, 1.5 GB for 20000 px; 30000 px within bounded memory."})
    return out


STUDY = Study("scanned", ("auto",), ("scanned",), units, run_unit, tables)
