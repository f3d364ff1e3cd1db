"""QGIS test session: an offscreen QgsApplication with an isolated profile and Processing loaded."""
import os
import pathlib
import sys
import tempfile
from urllib.parse import quote

import numpy as np
import pytest

pytest.importorskip("qgis.core", reason="QGIS Python bindings are not available")

_HOME = pathlib.Path(tempfile.mkdtemp(prefix="hamta-qgis-"))
for key, sub in (("XDG_RUNTIME_DIR", "xdg"), ("QGIS_CUSTOM_CONFIG_PATH", "profile"), ("XDG_CONFIG_HOME", "config"),
                 ("XDG_CACHE_HOME", "cache")):
    (_HOME / sub).mkdir(mode=0o700, exist_ok=True)
    os.environ[key] = str(_HOME / sub)
os.environ["QT_QPA_PLATFORM"] = "offscreen"

from qgis.core import QgsApplication  # noqa: E402
from qgis.PyQt.QtCore import QCoreApplication  # noqa: E402

REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def qgis_app():
    QCoreApplication.setOrganizationName(QgsApplication.QGIS_ORGANIZATION_NAME)
    QCoreApplication.setOrganizationDomain(QgsApplication.QGIS_ORGANIZATION_DOMAIN)
    QCoreApplication.setApplicationName(QgsApplication.QGIS_APPLICATION_NAME)
    app = QgsApplication([], False)
    app.initQgis()
    sys.path.append("/usr/share/qgis/python/plugins")
    from processing.core.Processing import Processing

    Processing.initialize()
    yield app


@pytest.fixture(scope="session")
def provider(qgis_app):
    from hamta.processing.provider import HamtaProvider

    registry = QgsApplication.processingRegistry()
    existing = registry.providerById("hamta")
    if existing is not None:
        yield existing
        return
    p = HamtaProvider()
    assert registry.addProvider(p)
    yield p
    registry.removeProvider(p)


@pytest.fixture(scope="session")
def qgis_home():
    return _HOME


SOURCE = str(REPO.parent / "shared" / "data" / "landsat" / "RGB.byte.tif")
WINDOW = (250, 220, 300, 240)  # col, row, width, height of the crop, source pixels


@pytest.fixture(scope="session")
def landsat():
    """The real raster the tile server cuts its tiles from, and the window of the crop below."""
    return SOURCE, WINDOW


@pytest.fixture(scope="session")
def server():
    from hamta.bench.tileserver import TileServer

    with TileServer(SOURCE, zmax=12) as s:
        yield s


@pytest.fixture(scope="session")
def crop(tmp_path_factory):
    """An un-georeferenced PNG crop of the source (WINDOW, upsampled x2) and its footprint in EPSG:3857
    (xmin, ymin, xmax, ymax)."""
    import cv2
    import rasterio
    from pyproj import Transformer
    from rasterio.windows import Window

    c, r, w, h = WINDOW
    with rasterio.open(SOURCE) as ds:
        rgb = ds.read([1, 2, 3], window=Window(c, r, w, h))
        corners = [ds.transform * xy for xy in ((c, r), (c + w, r), (c, r + h), (c + w, r + h))]
        crs = ds.crs
    path = str(tmp_path_factory.mktemp("crop") / "scan.png")
    cv2.imwrite(path, cv2.resize(np.moveaxis(rgb, 0, 2)[:, :, ::-1], (2 * w, 2 * h), interpolation=cv2.INTER_CUBIC))
    x, y = Transformer.from_crs(crs, "EPSG:3857", always_xy=True).transform(*zip(*corners))
    return path, (min(x), min(y), max(x), max(y))


@pytest.fixture(scope="session")
def search_area(crop):
    """A search area 2.5 times the crop's footprint each way, as QGIS writes extents: 'xmin,xmax,ymin,ymax [CRS]'."""
    x0, y0, x1, y1 = crop[1]
    cx, cy, half_w, half_h = (x0 + x1) / 2, (y0 + y1) / 2, 1.25 * (x1 - x0), 1.25 * (y1 - y0)
    return f"{cx - half_w},{cx + half_w},{cy - half_h},{cy + half_h} [EPSG:3857]"


@pytest.fixture(scope="session")
def xyz_source(server) -> str:
    """The QGIS source of an XYZ layer of ``server``'s photo tiles."""
    return f"type=xyz&url={quote(server.xyz(), safe=':/')}&zmax=12&zmin=0"
