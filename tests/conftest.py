"""Shared fixtures: where the development data lives, and small synthetic rasters."""
import os
import pathlib
import warnings

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[1]
SHARED = pathlib.Path(os.environ.get("HAMTA_SHARED", REPO.parent / "shared"))


MISSING_DATA = f"development data not found at {SHARED}/data (set HAMTA_SHARED)"
# CI sets this: there a missing data folder is a broken set-up, not a reason to skip.
REQUIRE_DATA = os.environ.get("HAMTA_REQUIRE_DATA") == "1"


def pytest_configure(config):
    import signal

    # A shell starts background jobs with Ctrl-C ignored, and Python then installs no KeyboardInterrupt
    # handler, in this process or in the runs it starts: the tests of interrupts need the usual one.
    if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    if REQUIRE_DATA and not (SHARED / "data").is_dir():
        raise pytest.UsageError(f"{MISSING_DATA}; HAMTA_REQUIRE_DATA=1 forbids skipping the tests that need it")


@pytest.hookimpl(trylast=True)  # after -k and -m: the cases asked for are shared out, none lost
def pytest_collection_modifyitems(config, items):
    """``make test`` runs two halves, one per stack (HAMTA_TEST_HALF 0 and 1). A test marked ``split`` has
    cases that share one code path: each half runs every other case, so both stacks run the test and each
    case runs once. The marker's arguments name the parameters that are shared out (all by default): the cases
    that differ only in those form a group and alternate, so every value of the others runs on both stacks;
    successive groups start on alternate halves, so every shared value does too. A group of one (as ``-k``
    may leave) runs on both halves."""
    half = os.environ.get("HAMTA_TEST_HALF")
    if half not in ("0", "1"):
        return
    groups = {}
    for item in items:
        mark = item.get_closest_marker("split")
        if mark is None or not hasattr(item, "callspec"):
            continue
        params = item.callspec.params
        if not set(mark.args) <= set(params):
            raise pytest.UsageError(f"{item.nodeid}: split{mark.args} names parameters the test does not have "
                                    f"({', '.join(sorted(params))})")
        shared = set(mark.args) or set(params)
        key = (item.nodeid.split("[")[0],) + tuple(sorted((k, repr(v)) for k, v in params.items() if k not in shared))
        groups.setdefault(key, []).append(item)
    dropped = {id(m) for g, members in enumerate(groups.values()) if len(members) > 1
               for i, m in enumerate(members) if (i + g) % 2 != int(half)}
    if dropped:
        config.hook.pytest_deselected(items=[i for i in items if id(i) in dropped])
        items[:] = [i for i in items if id(i) not in dropped]


def pytest_terminal_summary(terminalreporter):
    if not (SHARED / "data").is_dir():
        skipped = len(terminalreporter.stats.get("skipped", []))
        terminalreporter.write_line(f"hamta: {MISSING_DATA}; {skipped} tests skipped", yellow=True, bold=True)


@pytest.fixture(scope="session")
def shared() -> pathlib.Path:
    if not (SHARED / "data").is_dir():
        pytest.skip(MISSING_DATA)
    return SHARED


@pytest.fixture(scope="session")
def landsat(shared) -> str:
    return str(shared / "data" / "landsat" / "RGB.byte.tif")


def write_raster(path, data, **profile):
    """Write ``data`` ((H, W) or (bands, H, W)) as a GeoTIFF; returns the path as str."""
    import rasterio
    from rasterio.errors import NotGeoreferencedWarning

    data = np.asarray(data)
    if data.ndim == 2:
        data = data[None]
    prof = dict(driver="GTiff", width=data.shape[2], height=data.shape[1], count=data.shape[0],
                dtype=data.dtype.name)
    prof.update(profile)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NotGeoreferencedWarning)
        with rasterio.open(path, "w", **prof) as dst:
            dst.write(data)
    return str(path)


@pytest.fixture
def raster_writer(tmp_path):
    def make(name, data, **profile):
        return write_raster(tmp_path / name, data, **profile)
    return make


@pytest.fixture(scope="session")
def demo_pair(tmp_path_factory):
    """The bundled demo pair (self-generated), written once per session."""
    from hamta.bench.sample import make_demo_pair

    return make_demo_pair(str(tmp_path_factory.mktemp("demo") / "sample"))


@pytest.fixture(scope="session")
def small_pair(tmp_path_factory):
    """The demo pair's make at 400 px (target 280 x 304 px): for tests of what happens around a registration
    (batches, publishing, exit codes), where the pair's size only costs time."""
    from hamta.bench.sample import make_demo_pair

    return make_demo_pair(str(tmp_path_factory.mktemp("small") / "sample"), side=400)


def grey(bands):
    """A (3, H, W) scene as grey float32."""
    import cv2

    return cv2.cvtColor(np.ascontiguousarray(np.moveaxis(bands, 0, 2)), cv2.COLOR_RGB2GRAY).astype(np.float32)


def turned_window(area, centre, side, scale, angle_deg):
    """A ``side`` px square target showing ``area`` around ``centre`` turned by ``angle_deg`` and magnified
    ``scale`` times; the 2 x 3 matrix mapping target px to area px (corner convention)."""
    import math

    import cv2

    a = math.radians(angle_deg)
    lin = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]) / scale
    off = np.asarray(centre, float) - lin @ np.array([side / 2.0, side / 2.0])
    cv = np.column_stack([lin, off + lin @ np.array([0.5, 0.5]) - 0.5])
    image = cv2.warpAffine(area, cv, (side, side), flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP)
    return image, np.column_stack([lin, off])


def option_samples():
    """``(field, Option, value)`` for every registration and output option, ``value`` valid and not its
    default: what the tests that reach every option from each front end set."""
    from hamta.core.options import OutputOptions, RegisterOptions, option_fields, option_type

    samples = []
    for cls in (RegisterOptions, OutputOptions):
        for f, spec in option_fields(cls):
            if spec.choice is not None:
                values = [v for v in spec.choice.values if v != spec.choice.open_value]
                value = values[-1] if values[-1] != f.default else values[0]
            elif spec.kind == "crs":
                value = "EPSG:4326"
            elif spec.kind == "list":
                value = ("COMPRESS=LZW",)
            elif spec.kind == "extent":
                value = "10.5,59.5,11,60,EPSG:4326"
            elif option_type(cls, f.name) is bool:
                value = not f.default
            elif spec.kind.startswith("band:"):
                value = 2
            elif option_type(cls, f.name) is int:
                value = max(f.default or 0, int(spec.minimum or 0)) + 17
            else:
                value = (f.default or 0.0) + 1.5
            samples.append((f, spec, value))
    return samples


NEW_METHOD = '''
"""A method defined by a test: one module, nothing else edited."""
from hamta.core.methods.registry import Method, Toolbox, match_with, register_method
from hamta.core.methods.sift import SiftParams, sift_image_features

METHOD = register_method(Method(
    name="testmethod", title="A method added by a test", summary="SIFT under another name.", citation="a test",
    params_type=SiftParams, match=match_with(sift_image_features), use_when="never (a test)",
    toolbox=Toolbox("registertestmethod", "Test method")))
'''


@pytest.fixture
def new_method_module(tmp_path, monkeypatch):
    """A method module written by the test into a folder added to the method package's path; removed after."""
    import sys

    import hamta.core.methods as package
    from hamta.core.methods import registry

    (tmp_path / "testmethod.py").write_text(NEW_METHOD)
    monkeypatch.setattr(package, "__path__", [*package.__path__, str(tmp_path)])
    yield "testmethod"
    registry._REGISTRY.pop("testmethod", None)
    sys.modules.pop("hamta.core.methods.testmethod", None)


@pytest.fixture
def raising_method():
    """``make(exc)`` registers a method whose matching raises ``exc`` under a name of its own and
    returns the name; the methods are unregistered after the test."""
    from hamta.core.methods import register_method
    from hamta.core.methods.registry import _REGISTRY, Method
    from hamta.core.methods.sift import SiftParams

    names = []

    def make(exc):
        def match(target, reference, params, monitor, seed=0):
            raise exc

        names.append(f"test-raises-{type(exc).__name__.lower()}-{len(names)}")
        register_method(Method(name=names[-1], title="Raises", summary="A method that raises (a test).",
                               citation="a test", params_type=SiftParams, match=match))
        return names[-1]

    yield make
    for name in names:
        _REGISTRY.pop(name, None)


@pytest.fixture(scope="session")
def landsat_crop(landsat, tmp_path_factory):
    """A 160 x 120 px window of the Landsat sample, georeferenced 100 m off (a case onto map services)."""
    from hamta.bench.goals.basemap import georeferenced_target

    path = str(tmp_path_factory.mktemp("georeferenced") / "target.tif")
    return georeferenced_target(landsat, path, (230, 250, 160, 120), 1.0, offset_m=(80.0, -60.0))
