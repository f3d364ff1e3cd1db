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
import tempfile
import warnings

import cv2
import numpy as np
import pytest
import rasterio
from affine import Affine
from rasterio.control import GroundControlPoint

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from hamta.bench.synthetic import make_landscape  # noqa: E402
from hamta.cli.main import main  # noqa: E402
from hamta.core.coords import apply_matrix, matrix_corner_to_opencv  # noqa: E402

settings.register_profile("bounded", max_examples=12, deadline=None, derandomize=True,
                          suppress_health_check=list(HealthCheck))
settings.register_profile("long", max_examples=2000, deadline=None, suppress_health_check=list(HealthCheck))
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "bounded"))

EXIT_CODES = {0, 1, 2, 3}
TOLERANCE_PX = 3.0
SIZE = 400
FAMILIES = {"opencv": ["sift", "orb", "phasecorr"], "rilbp": ["rilbp", "cslbp"], "sibrif": ["sibrif", "pca-sift"],
            "sar": ["ndsift-pc", "gss-sift"], "structural": ["cfog", "lines-spectral-faithful"],
            "phase": ["xmodal", "rift"], "auto": ["auto"]}
FAMILY = os.environ.get("HAMTA_FUZZ_FAMILY")
METHODS = FAMILIES[FAMILY] if FAMILY else [m for ms in FAMILIES.values() for m in ms]
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


def _record(**row):
    log = os.environ.get("HAMTA_FUZZ_LOG")
    if log:
        with open(log, "a") as f:
            f.write(json.dumps(row) + "\n")


def _digest(path):
    return hashlib.sha256(open(path, "rb").read()).hexdigest()


@given(target=targets(), method=st.sampled_from(METHODS))
def test_any_raster_ends_with_a_documented_outcome(reference, target, method, capsys):
    stack, dtype, nodata, georef, truth = target
    with tempfile.TemporaryDirectory() as tmp:
        tpath = _write_target(os.path.join(tmp, "target.tif"), stack, dtype, nodata, georef, truth)
        before = (_digest(tpath), _digest(reference))
        out = os.path.join(tmp, "out")
        rc = main(["register", "--reference", reference, "--target", tpath, "--out", out, "--quiet", "--method",
                   method, "--auto-budget", "30",
                   "--tolerance", str(TOLERANCE_PX)])
        err = capsys.readouterr().err
        files = sorted(f for f in os.listdir(out) if not f.startswith(".")) if os.path.isdir(out) else []
        error = None
        if rc == 0 and truth is not None:
            from hamta.core.mapping import map_points_from_report

            h, w = stack.shape[1:]
            grid = np.array([(w * u, h * v) for u in (0.2, 0.5, 0.8) for v in (0.2, 0.5, 0.8)])
            truth_px = apply_matrix(truth, grid)
            inside = np.all((truth_px >= 0) & (truth_px <= SIZE), axis=1)
            if inside.any():
                report = os.path.join(out, "report.json")
                mapped = np.array([p["reference_px"] for p in map_points_from_report(report, grid[inside])])
                error = float(np.max(np.hypot(*(mapped - truth_px[inside]).T)))
        _record(method=method, rc=rc, kind="crop" if truth is not None else "other", dtype=dtype, shape=stack.shape,
                georef=georef, error=error, message=err.strip().splitlines()[-1][:200] if err.strip() else "")
        assert rc in EXIT_CODES and "Traceback" not in err, err
        assert (_digest(tpath), _digest(reference)) == before
        assert files in ([], ["report.json"], ["gcps.gpkg", "gcps.points", "registered.tif", "report.json"]), files
        assert rc != 0 or len(files) == 4
        assert truth is not None or rc != 0, "a target with nothing to find exited 0"
        assert error is None or error <= TOLERANCE_PX, f"exit 0 while {error:.1f} reference px off"


@given(values=st.dictionaries(st.sampled_from(["ratio", "n_features", "cross_check", "contrast_threshold",
                                               "edge_threshold", "bogus"]),
                              st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-10 ** 9, 10 ** 9),
                                        st.text(max_size=8)), max_size=3))
def test_any_method_parameter_value_is_checked(reference, values, capsys):
    with tempfile.TemporaryDirectory() as tmp:
        args = [a for k, v in values.items() for a in ("--param", f"{k}={v}")]
        rc = main(["register", "--reference", reference, "--target", reference, "--out", os.path.join(tmp, "o"),
                   "--quiet", "--method", "sift", *args])
        err = capsys.readouterr().err
    _record(method="params", rc=rc, kind="params", message=err.strip()[-200:])
    assert rc in EXIT_CODES and "Traceback" not in err, err


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
        rc = main(["map-points", path, *[repr(c) for c in coords[: len(coords) // 2 * 2]]])
        err = capsys.readouterr().err
    _record(method="map-points", rc=rc, kind="report", message=err.strip()[-200:])
    assert rc in {0, 1, 2} and "Traceback" not in err, err
