"""Hamta against each peer on its own ground, whole process (issue 24): ``hamta bench --families speed``.

Every run is a fresh process, as a user runs it (start-up, reading, registration, every output), timed
wall-clock with its peak memory (:func:`hamta.bench.memory.measured`), with Python's compiled modules
kept as an installed package keeps them (``PYTHONDONTWRITEBYTECODE`` is dropped for Hamta and its peers
alike: otherwise every run compiles Hamta's modules again); each case runs ``REPEATS`` times,
Hamta and its peer one after the other, and medians are quoted. Run it with ``--jobs 1`` on a quiet
machine: the ratios are what counts, not the seconds.

- ``georeferenced``: a real Landsat-scene-sized pair built from the Landsat sample (upsampled 2.6x to
  2056 px, 3 bands, UTM): the reference is the scene's upper nine tenths, the target its lower nine
  tenths on another date (gamma and gain) with georeferencing off by (41, -33) px — AROSICS's ground.
  The peer is AROSICS's global co-registration writing its output, when ``HAMTA_AROSICS_PYTHON``
  names a Python that imports ``arosics`` (see docs/benchmarks.md); its error is measured from the
  shift it reports.
- ``inter1``: AROSICS's own test pair INTER1 (Sentinel-2A, T33UUU, 2016-05-29 onto 2016-06-08, 10 m; in the
  ``arosics`` 0.9.26 source package under ``tests/data/testcase_inter1_S2A_S2A/``), when ``HAMTA_INTER1``
  names that folder (``tools/fetch_inter1.sh`` fetches it): Hamta writing the raster only, resampled and
  with its pixels untouched (``--pixel-grid target --model linear``), and with ``--local``, against AROSICS
  COREG (and COREG_LOCAL, grid 50 px, one run). Neither tool's own figure is the score: each corrected
  raster is judged by phase correlation in 256 px windows against the reference (:func:`residual`).
- ``small-optical``: the first pairs of the multimodal set's Optical-Optical category (JPEGs of about
  600 x 500 px) against a bare OpenCV script: SIFT, ratio test, RANSAC affine, the warped image written.
- ``cross-modal``: the first pairs of each cross-modal category of the multimodal set, Hamta alone.
"""
from __future__ import annotations

import json
import os
import statistics
import sys

import numpy as np

from ..memory import measured
from ..study import Study

REPEATS = 3
PAIRS = {"small-optical": ("mm-optical",), "cross-modal": ("mm-infrared", "mm-map", "mm-depth", "mm-sar")}
PAIRS_PER_CATEGORY = 5
SHIFT_PX = (41.0, -33.0)
UPSAMPLE = 2.6

OPENCV_SCRIPT = """
import sys, cv2, numpy as np
a = cv2.imread(sys.argv[1], cv2.IMREAD_GRAYSCALE); b = cv2.imread(sys.argv[2], cv2.IMREAD_GRAYSCALE)
sift = cv2.SIFT_create()
ka, da = sift.detectAndCompute(a, None); kb, db = sift.detectAndCompute(b, None)
good = [m for m, n in cv2.BFMatcher().knnMatch(da, db, k=2) if m.distance < 0.8 * n.distance]
src = np.float32([ka[m.queryIdx].pt for m in good]); dst = np.float32([kb[m.trainIdx].pt for m in good])
m, _ = cv2.estimateAffine2D(src, dst, method=cv2.RANSAC, ransacReprojThreshold=3.0)
cv2.imwrite(sys.argv[3], cv2.warpAffine(cv2.imread(sys.argv[1]), m, (b.shape[1], b.shape[0])))
np.savetxt(sys.argv[4], m)
"""

# AROSICS's helpers use GDAL 3.7-3.8's Python API (``with`` on datasets, ``gdal.config_options``); on an
# older GDAL (Debian bookworm's 3.6) the script adds them in its own process. ``max_shift`` 100: AROSICS's
# default of 5 px rejects the case's offset as "too large to be valid".
GDAL_SHIM = """
import contextlib
from osgeo import gdal, ogr
if not hasattr(gdal, "config_options"):
    @contextlib.contextmanager
    def config_options(options, thread_local=True):
        old = {k: gdal.GetConfigOption(k) for k in options}
        for k, v in options.items():
            gdal.SetConfigOption(k, v)
        try:
            yield
        finally:
            for k, v in old.items():
                gdal.SetConfigOption(k, v)
    gdal.config_options = config_options
for cls, close in ((gdal.Dataset, "FlushCache"), (ogr.DataSource, "Release")):
    if not hasattr(cls, "__enter__"):
        cls.__enter__ = lambda self: self
        cls.__exit__ = lambda self, *exc, close=close: getattr(self, close)()
"""
AROSICS_SCRIPT = GDAL_SHIM + """
import json, sys
from arosics import COREG
cr = COREG(sys.argv[1], sys.argv[2], path_out=sys.argv[3], fmt_out="GTIFF", q=True, nodata=(0, 0), max_shift=100)
cr.calculate_spatial_shifts()
cr.correct_shifts()
print(json.dumps({"x_px": float(cr.x_shift_px), "y_px": float(cr.y_shift_px)}))
"""


AROSICS_LOCAL_SCRIPT = GDAL_SHIM + """
import sys
from arosics import COREG_LOCAL
COREG_LOCAL(sys.argv[1], sys.argv[2], grid_res=50, path_out=sys.argv[3], fmt_out="GTIFF", q=True).correct_shifts()
"""
INTER1 = ("ref_S2A_20160608T153121_T33UUU_sub.tif", "tgt_S2A_20160529T153631_T33UUU_sub.tif")
INTER1_OUTPUTS = ["--outputs", "raster,report"]  # the raster, and the JSON report the bench reads (a few kB)
INTER1_RUNS = {"global": INTER1_OUTPUTS, "untouched": INTER1_OUTPUTS + ["--pixel-grid", "target", "--model", "linear"],
               "local": INTER1_OUTPUTS + ["--local"]}


def units(config):
    """(kind, case) pairs: the georeferenced pair, INTER1's runs where ``HAMTA_INTER1`` is set, and the first
    pairs of each multimodal category."""
    out = [("georeferenced", "landsat-2056")]
    if os.environ.get("HAMTA_INTER1"):
        out += [("inter1", name) for name in INTER1_RUNS]
    for kind, categories in PAIRS.items():
        out += [(kind, f"{c}/{i}") for c in categories for i in range(1, PAIRS_PER_CATEGORY + 1)]
    return out


def run_unit(unit, config) -> list:
    """One row: Hamta, and the peer where the case has one, timed on the unit's case."""
    kind, name = unit
    folder = os.path.join(config.out_dir, "cases", "speed")
    os.makedirs(folder, exist_ok=True)
    if kind == "georeferenced":
        return [_georeferenced(folder, config.data_dir)]
    if kind == "inter1":
        return [_inter1(name, folder)]
    return [_pair(kind, name, folder, config.data_dir)]


def _hamta(args, out: str, repeats: int):
    """Median wall s, median peak MB and the last report of ``hamta register`` in a fresh process."""
    runs = []
    for _ in range(repeats):  # this interpreter's hamta (``python -m`` costs what the ``hamta`` script does)
        seconds, peak, code = measured([sys.executable, "-m", "hamta.cli.main", "register", *args, "--out", out,
                                        "--quiet"], env=_installed_env())
        runs.append((seconds, peak, code))
    with open(os.path.join(out, "report.json")) as f:
        report = json.load(f)
    return statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs), runs[-1][2], report


def _timed(commands, printed=None):
    """(median wall s, median peak MB) of ``commands`` (argument lists), each run in a fresh process; the lines
    they printed are added to ``printed`` when given."""
    runs = [measured(command, env=_installed_env(), printed=printed) for command in commands]
    return statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs)


def _installed_env() -> dict:
    """This environment without ``PYTHONDONTWRITEBYTECODE`` (see the module's docstring)."""
    return {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def _registration_s(report) -> float:
    """The seconds ``report`` gives to opening, reading and registering (the outputs left out)."""
    t = report["timings_s"]
    return t.get("open", 0) + t.get("read", 0) + t.get("auto_total", t.get("total", 0))


def _model(report):
    """The model of ``report`` (a dict as report.json holds it): target px -> reference px."""
    from ...core.estimation.models import LinearModel

    m = report["model"]
    return LinearModel(m["type"], np.asarray(m["target_px_to_reference_px"], float))


def _pair(kind: str, name: str, folder: str, data_dir: str) -> dict:
    """The row of the multimodal pair ``name`` ('category/n'): Hamta, and for 'small-optical' the OpenCV
    script; errors in reference px."""
    from ..multimodal_set import build

    family, pair = name.split("/")
    case = build(family, int(pair), data_dir)
    out = os.path.join(folder, f"{family}-{pair}")
    repeats = REPEATS if kind == "small-optical" else 1
    wall, peak, code, report = _hamta(["--reference", case.reference, "--target", case.target, "--pixel-mode",
                                       "--tolerance", str(case.tolerance_px)], out, repeats)
    row = {"kind": kind, "case": name, "hamta_s": wall, "hamta_mb": peak, "exit": code,
           "registration_s": _registration_s(report), "method": report["method"],
           "error_px": float(np.sqrt(np.mean(case.errors(_model(report)) ** 2))), "stages": report["timings_s"]}
    if kind == "small-optical":
        matrix = os.path.join(folder, f"{family}-{pair}-opencv.txt")
        seconds, mb = _timed([[sys.executable, "-c", OPENCV_SCRIPT, case.target, case.reference,
                               os.path.join(folder, f"{family}-{pair}-opencv.png"), matrix]] * REPEATS)
        m = np.vstack([np.loadtxt(matrix), [0, 0, 1]])
        peer = _model({"model": {"type": "affine", "target_px_to_reference_px": m}})
        row.update(peer="OpenCV script", peer_s=seconds, peer_mb=mb,
                   peer_error_px=float(np.sqrt(np.mean(case.errors(peer) ** 2))))
    return row


def georeferenced_pair(folder: str, data_dir: str):
    """The Landsat-sized shift pair (see the module's docstring): (target, reference, truth), truth the
    target px -> reference px map."""
    import cv2
    import rasterio
    from affine import Affine

    target, reference = os.path.join(folder, "landsat2056_target.tif"), os.path.join(folder, "landsat2056_ref.tif")
    with rasterio.open(os.path.join(data_dir, "landsat", "RGB.byte.tif")) as src:
        data, transform, crs = src.read(), src.transform, src.crs
    h, w = int(data.shape[1] * UPSAMPLE), int(data.shape[2] * UPSAMPLE)
    rows = int(h * 0.9)
    off = h - rows
    truth = np.array([[1.0, 0, 0], [0, 1.0, off], [0, 0, 1.0]])
    if not os.path.exists(target):
        up = np.stack([cv2.resize(b, (w, h), interpolation=cv2.INTER_CUBIC) for b in data])
        fine = transform * Affine.scale(1 / UPSAMPLE)
        later = np.clip(255 * (up[:, off:] / 255.0) ** 0.8 * 0.95 + 4, 0, 255).astype(np.uint8)
        later[:, up[:, off:].sum(axis=0) == 0] = 0
        profile = dict(driver="GTiff", count=3, dtype="uint8", crs=crs, nodata=0, tiled=True, compress="deflate",
                       width=w)
        with rasterio.open(reference, "w", height=rows, transform=fine, **profile) as dst:
            dst.write(up[:, :rows])
        wrong = fine * Affine.translation(SHIFT_PX[0], off + SHIFT_PX[1])
        with rasterio.open(target, "w", height=h - off, transform=wrong, **profile) as dst:
            dst.write(later)
    return target, reference, truth


def _georeferenced(folder: str, data_dir: str) -> dict:
    """The row of the Landsat-sized shift pair: Hamta, and AROSICS COREG where ``HAMTA_AROSICS_PYTHON`` is set;
    errors in px."""
    target, reference, truth = georeferenced_pair(folder, data_dir)
    wall, peak, code, report = _hamta(["--reference", reference, "--target", target], os.path.join(folder, "geo-out"),
                                      REPEATS)
    pts = np.array([[x, y] for x in np.linspace(50, 2000, 9) for y in np.linspace(50, 1600, 9)])
    err = _model(report).apply(pts) - (pts + truth[:2, 2])
    row = {"kind": "georeferenced", "case": "landsat-2056", "hamta_s": wall, "hamta_mb": peak, "exit": code,
           "registration_s": _registration_s(report), "method": report["method"],
           "error_px": float(np.sqrt(np.mean(np.sum(err ** 2, axis=1)))), "stages": report["timings_s"]}
    python = os.environ.get("HAMTA_AROSICS_PYTHON")
    if python:
        printed = []
        outputs = [os.path.join(folder, f"arosics-{i}.tif") for i in range(REPEATS)]
        seconds, mb = _timed([[python, "-c", AROSICS_SCRIPT, reference, target, out] for out in outputs], printed)
        shift = _arosics_shift(printed)
        # AROSICS moves the target by (x_px, y_px) of its pixels; the georeferencing was off by SHIFT_PX.
        error = None if shift is None else float(np.hypot(shift[0] + SHIFT_PX[0], shift[1] + SHIFT_PX[1]))
        row.update(peer="AROSICS", peer_s=seconds, peer_mb=mb,
                   peer_error_px=error)
    return row


def _inter1(name: str, folder: str) -> dict:
    """The row of INTER1 run ``name`` (a key of ``INTER1_RUNS``): Hamta, and AROSICS where it is installed;
    each corrected raster judged by :func:`residual`."""
    source = os.environ["HAMTA_INTER1"]
    reference, target = (os.path.join(source, f) for f in INTER1)
    out = os.path.join(folder, f"inter1-{name}")
    repeats = 1 if name == "local" else REPEATS
    wall, peak, code, report = _hamta(["--reference", reference, "--target", target] + INTER1_RUNS[name], out,
                                      repeats)
    row = {"kind": "inter1", "case": name, "hamta_s": wall, "hamta_mb": peak, "exit": code, "method": report["method"],
           "registration_s": _registration_s(report), "stages": report["timings_s"],
           "error_px": residual(reference, os.path.join(out, "registered.tif"))}
    python = os.environ.get("HAMTA_AROSICS_PYTHON")
    if python:  # the untouched run is timed against COREG too: both write the target's pixels under a moved transform
        script = AROSICS_LOCAL_SCRIPT if name == "local" else AROSICS_SCRIPT
        written = os.path.join(folder, f"arosics-{name}.tif")
        seconds, mb = _timed([[python, "-c", script, reference, target, written]] * repeats)
        row.update(peer="AROSICS " + ("COREG_LOCAL" if name == "local" else "COREG"), peer_s=seconds, peer_mb=mb,
                   peer_error_px=residual(reference, written))
    return row


def residual(reference: str, corrected: str, side: int = 256) -> float:
    """The misalignment a corrected raster leaves, judged by neither tool: OpenCV phase correlation between
    the reference and the corrected raster's first band (resampled bilinearly onto the reference grid) in
    ``side`` px windows tiling the reference where both have data, the median shift length (reference px)."""
    import cv2
    import rasterio
    from rasterio.warp import Resampling, reproject

    with rasterio.open(reference) as ref, rasterio.open(corrected) as cor:
        r = ref.read(1).astype(np.float32)
        c = np.full(r.shape, np.nan, np.float32)
        reproject(cor.read(1).astype(np.float32), c, src_transform=cor.transform, src_crs=cor.crs,
                  dst_transform=ref.transform, dst_crs=ref.crs, resampling=Resampling.bilinear, src_nodata=0,
                  dst_nodata=np.nan)
        valid = np.isfinite(c) & (r != (ref.nodata or 0))
    window = cv2.createHanningWindow((side, side), cv2.CV_32F)
    shifts = []
    for y in range(0, r.shape[0] - side + 1, side):
        for x in range(0, r.shape[1] - side + 1, side):
            if valid[y:y + side, x:x + side].mean() >= 0.99:
                pair = r[y:y + side, x:x + side].copy(), np.nan_to_num(c[y:y + side, x:x + side])
                shifts.append(np.hypot(*cv2.phaseCorrelate(*pair, window)[0]))
    return float(np.median(shifts)) if shifts else None


def _arosics_shift(printed):
    """AROSICS's (x, y) shift in target px from what the script printed (its last JSON line), or None."""
    for line in printed[::-1]:
        if line.startswith("{"):
            s = json.loads(line)
            return s["x_px"], s["y_px"]
    return None


def tables(rows) -> list:
    def f(v, d=2):
        return "–" if v is None else f"{v:.{d}f}"

    body = []
    for r in rows:
        ratio = None if not r.get("peer_s") else r["hamta_s"] / r["peer_s"]
        body.append([r["kind"], r["case"], r["method"], f(r["hamta_s"]), f(r["registration_s"]), f(r["hamta_mb"], 0),
                     f(r["error_px"]), r.get("peer", "–"), f(r.get("peer_s")), f(r.get("peer_mb"), 0),
                     f(r.get("peer_error_px")), f(ratio)])
    summary = []
    for kind in ("georeferenced", "inter1", "small-optical", "cross-modal"):
        some = [r for r in rows if r["kind"] == kind]
        if some:
            ratios = [r["hamta_s"] / r["peer_s"] for r in some if r.get("peer_s")]
            summary.append([kind, len(some), f(statistics.median(r["hamta_s"] for r in some)),
                            f(statistics.median(r["registration_s"] for r in some)),
                            f(statistics.median(ratios)) if ratios else "–"])
    return [{"title": "speed: Hamta (fresh process, every output) against each peer on its own ground",
             "columns": ["kind", "case", "method", "hamta wall s", "registration s", "hamta MB", "error px", "peer",
                         "peer wall s", "peer MB", "peer error px", "hamta / peer"], "rows": body,
             "note": "Medians of 3 runs (cross-modal and local: 1). Goals (issues 24, 37): georeferenced and INTER1 "
                     "<= 1.0x AROSICS with error <= its (INTER1: the residual judged by phase correlation, see "
                     "the module); INTER1 local <= 0.2x COREG_LOCAL; small optical <= 2x the OpenCV script end to end; "
                     "cross-modal median <= 2 s."},
            {"title": "speed: medians per kind", "columns": ["kind", "cases", "wall s", "registration s",
                                                             "hamta / peer"], "rows": summary, "note": ""}]


STUDY = Study("speed", ("auto",), ("speed",), units, run_unit, tables)
