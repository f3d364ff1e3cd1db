"""QGIS test session: an offscreen QgsApplication with an isolated profile and Processing loaded."""
import os
import pathlib
import sys
import tempfile

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
