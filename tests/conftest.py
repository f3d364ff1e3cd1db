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
    if REQUIRE_DATA and not (SHARED / "data").is_dir():
        raise pytest.UsageError(f"{MISSING_DATA}; HAMTA_REQUIRE_DATA=1 forbids skipping the tests that need it")


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
