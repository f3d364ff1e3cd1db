"""Property-based fuzzing of the command line: rasters of every kind, method parameters, reports.

Whatever goes in, ``hamta`` ends with a documented exit code, no traceback, inputs unchanged, and
either a whole published set or no georeferenced output; a target cut from the reference must
not exit 0 while more than the tolerance off. The bounded profile runs in ``make test``;
``make fuzz`` runs the long one (``HYPOTHESIS_PROFILE=long``) and tallies outcomes into
``$HAMTA_FUZZ_LOG`` (one JSON line per run).
"""
import hashlib
import json
import math
import os
import signal
import tempfile
import time
import warnings

import cv2
import numpy as np
import pytest
import rasterio
from affine import Affine
from rasterio.control import GroundControlPoint

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, Phase, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from hamta.bench.synthetic import make_landscape  # noqa: E402
from hamta.cli.main import main  # noqa: E402
from hamta.core.coords import apply_matrix, matrix_corner_to_opencv  # noqa: E402

# The bounded profile (make test) does not shrink a failure: it reports the first failing example as drawn.
settings.register_profile("bounded", max_examples=12, deadline=None, derandomize=True,
                          suppress_health_check=list(HealthCheck), phases=(Phase.explicit, Phase.generate))
settings.register_profile("long", max_examples=int(os.environ.get("HAMTA_FUZZ_EXAMPLES", 2000)), deadline=None,
                          suppress_health_check=list(HealthCheck), phases=(Phase.explicit, Phase.generate))
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "bounded"))

EXIT_CODES = {0, 1, 2, 3}
TOLERANCE_PX = 3.0
SIZE = 400
FAMILIES = {"opencv": ["sift", "orb", "phasecorr", "shift"],
            "rilbp": ["rilbp", "rilbp-faithful", "cslbp", "censure-sift"],
            "sibrif": ["sibrif", "sibrif-faithful", "pca-sift"],
            "sar": ["ndsift-pc", "ndsift-pc-faithful", "ndss-sift", "gss-sift", "bfsift"],
            "structural": ["cfog", "lines-spectral-faithful", "lines-eigen", "lines-vspm", "regions"],
            "phase": ["xmodal", "rift", "xfeat"],
            "auto": ["auto"]}
FAMILY = os.environ.get("HAMTA_FUZZ_FAMILY")
METHODS = FAMILIES[FAMILY] if FAMILY in FAMILIES else [m for ms in FAMILIES.values() for m in ms]
REF_TRANSFORM = Affine(10.0, 0.0, 552000.0, 0.0, -10.0, 3620000.0)


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    path = str(tmp_path_factory.mktemp("fuzz-ref") / "reference.tif")
    with rasterio.open(path, "w", driver="GTiff", width=SIZE, height=SIZE, count=3, dtype="uint8", crs="EPSG:32639",
                       transform=REF_TRANSFORM, photometric="RGB") as dst:
        dst.write(make_landscape((SIZE, SIZE), seed=21))
    return path


@st.composite
def targets(draw):
    """(pixel stack, dtype, nodata, georeferencing, truth 3 x 3 target px -> reference px or None)."""
    kind = draw(st.sampled_from(["crop", "crop", "noise", "constant", "stripes"]))
    h, w = draw(st.integers(1, 600)), draw(st.integers(1, 600))
    dtype = draw(st.sampled_from(["uint8", "uint16", "int16", "float32", "float64", "complex64"]))
    bands = draw(st.integers(1, 4))
    truth = None
    if kind == "crop":
        angle, scale = draw(st.floats(0, 360)), draw(st.floats(0.5, 2.0))
        cx, cy = draw(st.floats(100, SIZE - 100)), draw(st.floats(100, SIZE - 100))
        a = math.radians(angle)
        lin = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]) / scale
        truth = np.eye(3)
        truth[:2, :2], truth[:2, 2] = lin, np.array([cx, cy]) - lin @ np.array([w / 2.0, h / 2.0])
        scene = make_landscape((SIZE, SIZE), seed=21).astype(np.float32)
        to_scene = matrix_corner_to_opencv(truth)[:2]
        stack = np.stack([cv2.warpAffine(b, to_scene, (w, h), flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP)
                          for b in scene[:min(bands, 3)]] + [np.ones((h, w), np.float32)] * max(bands - 3, 0))
    elif kind == "noise":
        stack = np.random.default_rng(draw(st.integers(0, 2 ** 16))).uniform(0, 255, (bands, h, w))
    elif kind == "constant":
        stack = np.full((bands, h, w), draw(st.floats(0, 255)))
    else:
        stack = (127 + 100 * np.sin(np.arange(w) / draw(st.floats(2, 50))))[None, None, :].repeat(h, 1).repeat(bands, 0)
    if dtype.startswith(("uint", "int")):
        info = np.iinfo(dtype)
        stack = np.clip(stack * draw(st.floats(0.5, 3.0)), info.min, info.max)
    if dtype.startswith("float") and draw(st.booleans()):
        mask = np.random.default_rng(1).random(stack.shape[1:]) < draw(st.floats(0, 0.5))
        stack[:, mask] = draw(st.sampled_from([np.nan, np.inf, -np.inf]))
    nodata = draw(st.sampled_from([None, 0, 255])) if not dtype.startswith("complex") else None
    georef = draw(st.sampled_from(["none", "geotransform", "rotated", "gcps"]))
    return stack.astype(dtype), dtype, nodata, georef, truth


def _write_target(path, stack, dtype, nodata, georef, truth):
    prof = dict(driver="GTiff", width=stack.shape[2], height=stack.shape[1], count=stack.shape[0], dtype=dtype)
    if nodata is not None:
        prof["nodata"] = nodata
    if georef in ("geotransform", "rotated"):
        shift = Affine.translation(3.0, -2.0) if georef == "geotransform" else Affine.rotation(0.5)
        prof.update(crs="EPSG:32639", transform=REF_TRANSFORM * (Affine(*truth[:2].ravel()) if truth is not None
                                                                   else Affine.identity()) * shift)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with rasterio.open(path, "w", **prof) as dst:
            dst.write(stack)
            if georef == "gcps":
                h, w = stack.shape[1:]
                corners = np.array([[0, 0], [w, 0], [w, h], [0, h]], float)
                mapped = apply_matrix(truth, corners) if truth is not None else corners
                dst.gcps = ([GroundControlPoint(row=c[1], col=c[0], x=REF_TRANSFORM.c + 10 * m[0],
                                                y=REF_TRANSFORM.f - 10 * m[1]) for c, m in zip(corners, mapped)],
                            rasterio.crs.CRS.from_epsg(32639))
    return path


class Hang(BaseException):
    """A run that outlived ``HANG_S`` (not an Exception, so the CLI's own handlers cannot absorb it)."""


HANG_S = 900


def _cli(args):
    """``main(args)`` with a watchdog: a run longer than ``HANG_S`` seconds is a hang."""
    def alarm(signum, frame):
        raise Hang(f"no answer after {HANG_S} s: {' '.join(args)}")

    previous = signal.signal(signal.SIGALRM, alarm)
    signal.alarm(HANG_S)
    try:
        return main(args)
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)


def _record(**row):
    log = os.environ.get("HAMTA_FUZZ_LOG")
    if log:
        with open(log, "a") as f:
            f.write(json.dumps(row) + "\n")


KEEP_GOING = os.environ.get("HYPOTHESIS_PROFILE") == "long"  # make fuzz: log every failure, stop at none


def _failures(checks):
    return [message[:500] for ok, message in checks if not ok]


def _settle(failures):
    """Fail the example, or, in the long profile, leave the failures in the log for the tally."""
    if failures and not KEEP_GOING:
        raise AssertionError("; ".join(failures))


def _digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def test_every_method_is_fuzzed():
    from hamta.core.methods import all_methods

    assert sorted(m for ms in FAMILIES.values() for m in ms if m != "auto") == sorted(all_methods())


@given(target=targets(), method=st.sampled_from(METHODS))
def test_any_raster_ends_with_a_documented_outcome(reference, target, method, capsys):
    stack, dtype, nodata, georef, truth = target
    with tempfile.TemporaryDirectory() as tmp:
        tpath = _write_target(os.path.join(tmp, "target.tif"), stack, dtype, nodata, georef, truth)
        before = (_digest(tpath), _digest(reference))
        out = os.path.join(tmp, "out")
        t0 = time.perf_counter()
        rc = _cli(["register", "--reference", reference, "--target", tpath, "--out", out, "--quiet", "--method",
                   method, "--auto-budget", "30",
                   "--tolerance", str(TOLERANCE_PX)])
        err = capsys.readouterr().err
        files = sorted(f for f in os.listdir(out) if not f.startswith(".")) if os.path.isdir(out) else []
        error = None
        if rc == 0 and truth is not None:
            from hamta.core.mapping import map_points_from_report

            h, w = stack.shape[1:]
            grid = np.array([(w * u, h * v) for u in np.linspace(0.05, 0.95, 10) for v in np.linspace(0.05, 0.95, 10)])
            truth_px = apply_matrix(truth, grid)
            inside = np.all((truth_px >= 0) & (truth_px <= SIZE), axis=1)
            if inside.any():
                report = os.path.join(out, "report.json")
                mapped = np.array([p["reference_px"] for p in map_points_from_report(report, grid[inside])])
                error = float(np.sqrt(np.mean(np.sum((mapped - truth_px[inside]) ** 2, axis=1))))  # RMSE_cp
        failures = _failures([
            (rc in EXIT_CODES and "Traceback" not in err, err),
            ((_digest(tpath), _digest(reference)) == before, "an input was modified"),
            (files in ([], ["report.html", "report.json"],
                       ["gcps.gpkg", "gcps.points", "registered.tif", "report.html", "report.json"]),
             f"partial output set {files}"),
            (rc != 0 or len(files) == 5, f"exit 0 with outputs {files}"),
            (truth is not None or rc != 0, "a target with nothing to find exited 0"),
            (error is None or error <= TOLERANCE_PX, f"exit 0 while {error} reference px off (RMS)")])
        _record(method=method, rc=rc, time_s=round(time.perf_counter() - t0, 2),
                kind="crop" if truth is not None else "other", dtype=dtype, shape=stack.shape,
                georef=georef, error=error, message=err.strip().splitlines()[-1][:200] if err.strip() else "",
                failures=failures)
        _settle(failures)


@given(values=st.dictionaries(st.sampled_from(["ratio", "n_features", "cross_check", "contrast_threshold",
                                               "edge_threshold", "bogus"]),
                              st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-10 ** 9, 10 ** 9),
                                        st.text(max_size=8)), max_size=3))
def test_any_method_parameter_value_is_checked(reference, values, capsys):
    with tempfile.TemporaryDirectory() as tmp:
        args = [a for k, v in values.items() for a in ("--param", f"{k}={v}")]
        rc = _cli(["register", "--reference", reference, "--target", reference, "--out", os.path.join(tmp, "o"),
                   "--quiet", "--method", "sift", *args])
        err = capsys.readouterr().err
    failures = _failures([(rc in EXIT_CODES and "Traceback" not in err, err)])
    _record(method="params", rc=rc, kind="params", message=err.strip()[-200:], failures=failures)
    _settle(failures)


JSON = st.recursive(st.none() | st.booleans() | st.floats() | st.integers() | st.text(max_size=6),
                    lambda children: st.lists(children, max_size=4) | st.dictionaries(st.text(max_size=6), children,
                                                                                      max_size=4), max_leaves=20)


@given(report=st.one_of(JSON, st.fixed_dictionaries({
    "reference": st.fixed_dictionaries({"transform": st.lists(st.floats(), min_size=6, max_size=6),
                                        "pixel_mode": st.booleans()}),
    "model": st.fixed_dictionaries({"type": st.sampled_from(["affine", "projective", "similarity", "tps", "x"]),
                                    "target_px_to_reference_px": st.lists(st.lists(st.floats(), min_size=3,
                                                                                   max_size=3), min_size=2,
                                                                          max_size=3)})})),
       coords=st.lists(st.floats(), min_size=2, max_size=6))
def test_map_points_never_breaks_on_any_report(report, coords, capsys):
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "report.json")
        with open(path, "w") as f:
            json.dump(report, f)
        rc = _cli(["map-points", path, *[repr(c) for c in coords[: len(coords) // 2 * 2]]])
        err = capsys.readouterr().err
    failures = _failures([(rc in {0, 1, 2} and "Traceback" not in err, err)])
    _record(method="map-points", rc=rc, kind="report", message=err.strip()[-200:], failures=failures)
    _settle(failures)


def _on_earth(crs, transform, size) -> bool:
    """The oracle: whether a ``size`` px square raster with ``transform`` has a place on the Earth in ``crs``."""
    from pyproj import CRS, Transformer

    corners = np.array([transform * (x, y) for x in (0, size) for y in (0, size)], float)
    pcrs = CRS.from_user_input(crs)
    if pcrs.is_geographic:
        return bool(np.abs(corners[:, 1]).max() <= 90.0 + 0.5 * abs(transform.e) + 1e-9)
    lon, lat = Transformer.from_crs(pcrs, pcrs.geodetic_crs, always_xy=True).transform(
        corners[:, 0], corners[:, 1], errcheck=False)
    return bool(np.isfinite(lon).all() and np.isfinite(lat).all() and np.abs(lat).max() <= 90.0)


@given(crs=st.sampled_from([None, "EPSG:4326", "EPSG:32639", "EPSG:3857", "EPSG:3031"]),
       origin=st.tuples(st.floats(-1e8, 1e8), st.floats(-1e8, 1e8)) | st.tuples(st.floats(-400, 400),
                                                                               st.floats(-200, 200)),
       pixel=st.floats(1e-6, 1e5), pixel_mode=st.booleans())
def test_any_reference_georeferencing_is_checked(crs, origin, pixel, pixel_mode, capsys):
    size = 240
    transform = Affine(pixel, 0.0, origin[0], 0.0, -pixel, origin[1])
    with tempfile.TemporaryDirectory() as tmp:
        ref, tgt = os.path.join(tmp, "reference.tif"), os.path.join(tmp, "target.tif")
        image = make_landscape((size, size), seed=5)
        georef = {} if crs is None else {"crs": crs, "transform": transform}
        with rasterio.open(ref, "w", driver="GTiff", width=size, height=size, count=3, dtype="uint8",
                           photometric="RGB", **georef) as dst:
            dst.write(image)
        with rasterio.open(tgt, "w", driver="GTiff", width=180, height=180, count=3, dtype="uint8",
                           photometric="RGB") as dst:
            dst.write(image[:, 30:210, 40:220])
        rc = _cli(["register", "--reference", ref, "--target", tgt, "--out", os.path.join(tmp, "o"), "--quiet",
                   "--method", "sift", *(["--pixel-mode"] if pixel_mode else [])])
        err = capsys.readouterr().err
    valid = crs is None or _on_earth(crs, transform, size)
    failures = _failures([
        (rc in EXIT_CODES and "Traceback" not in err and "internal error" not in err, err),
        (valid or (rc == 1 and "is georeferenced" in err), f"exit {rc} on georeferencing off the Earth: {err}"),
        (crs is not None or pixel_mode or (rc == 1 and "--pixel-mode" in err), f"exit {rc} without georeferencing")])
    _record(method="georef", rc=rc, kind="reference-georef", crs=crs, valid=valid, message=err.strip()[-200:],
            failures=failures)
    _settle(failures)
