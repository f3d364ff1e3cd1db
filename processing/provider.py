"""The Hamta Processing provider.

The algorithms import the engine (``core``), which needs numpy, scipy, OpenCV, rasterio, pyproj and
shapely in QGIS's Python. Those are checked first, without importing ``core``: when one is missing
or broken, the provider still loads and lists its algorithms as unavailable, each one saying which
packages are missing and how to install them (Hamta never installs anything itself).
"""
from __future__ import annotations

import configparser
import html
import importlib
import os
from typing import List, NamedTuple, Optional, Tuple

from qgis.core import QgsProcessingAlgorithm, QgsProcessingException, QgsProcessingProvider
from qgis.PyQt.QtCore import QCoreApplication
from qgis.PyQt.QtGui import QIcon

from .catalogue import algorithm_entries

ROOT = os.path.dirname(os.path.dirname(__file__))
ICON = os.path.join(ROOT, "icon.svg")


class Requirement(NamedTuple):
    module: str  # what the check imports (a compiled submodule where one breaks first)
    label: str  # the package's name for the user
    debian: str  # Debian/Ubuntu package
    pip: str  # PyPI distribution


REQUIREMENTS = (
    Requirement("numpy", "numpy", "python3-numpy", "numpy"),
    Requirement("scipy.ndimage", "scipy", "python3-scipy", "scipy"),
    Requirement("cv2", "opencv", "python3-opencv", "opencv-python-headless"),
    Requirement("rasterio", "rasterio", "python3-rasterio", "rasterio"),
    Requirement("pyproj", "pyproj", "python3-pyproj", "pyproj"),
    Requirement("shapely.geometry", "shapely", "python3-shapely", "shapely"),
)

DEBIAN_COMMAND = "sudo apt install python3-opencv python3-rasterio python3-scipy python3-pyproj python3-shapely"
OPENCV_PIP = '"opencv-python-headless<4.11"'  # 4.11+ pulls numpy 2 in, breaking modules built on numpy 1

def missing_requirements() -> List[Tuple[Requirement, str]]:
    """``(requirement, error)`` for every required package QGIS's Python cannot import."""
    missing = []
    for req in REQUIREMENTS:
        try:
            importlib.import_module(req.module)
        except Exception as exc:  # ImportError, or a broken build (e.g. compiled against another numpy)
            missing.append((req, f"{type(exc).__name__}: {exc}".splitlines()[0]))
    return missing


def missing_summary(missing: List[Tuple[Requirement, str]]) -> str:
    """``missing opencv, rasterio``: a few words for the algorithm list."""
    return "missing " + ", ".join(req.label for req, _ in missing)


def missing_message(missing: List[Tuple[Requirement, str]]) -> str:
    """What is missing and how to install it on each platform (plain text)."""
    reqs = [req for req, _ in missing]
    pip = " ".join(OPENCV_PIP if req.module == "cv2" else req.pip for req in reqs)
    windows = []
    osgeo4w = [req.debian for req in reqs if req.module != "cv2"]  # OSGeo4W names them as Debian does
    if osgeo4w:
        windows.append("run the OSGeo4W Setup (Advanced Install) and select " + ", ".join(osgeo4w))
    if any(req.module == "cv2" for req in reqs):
        windows.append("for OpenCV open the OSGeo4W Shell and run: python -m pip install " + OPENCV_PIP)
    lines = [
        "Hamta cannot run: QGIS's Python lacks {}. Install the missing packages, then restart QGIS (Hamta installs "
        "nothing itself).".format(", ".join(req.label for req in reqs)),
        "",
        "Debian/Ubuntu: " + DEBIAN_COMMAND,
        "Windows (OSGeo4W or the QGIS installer): " + "; ".join(windows),
        "macOS (official QGIS package): /Applications/QGIS.app/Contents/MacOS/bin/python3 -m pip install " + pip
        + " (use your QGIS app's name, e.g. QGIS-LTR.app)",
        "",
        "Details:",
    ]
    lines += [f"  {req.label} ({req.module}): {error}" for req, error in missing]
    return "\n".join(lines)


def engine_error_message(exc: BaseException) -> str:
    """The message when the engine itself fails to import although every requirement did."""
    return ("Hamta cannot run: its engine failed to load ({}: {}). Check that numpy, scipy, opencv, rasterio, "
            "pyproj and shapely in QGIS's Python work together, or report the problem."
            ).format(type(exc).__name__, exc)


def plugin_version() -> str:
    meta = configparser.ConfigParser(interpolation=None)
    meta.read(os.path.join(ROOT, "metadata.txt"), encoding="utf-8")
    return meta.get("general", "version", fallback="")


class UnavailableAlgorithm(QgsProcessingAlgorithm):
    """Stands in for an algorithm that cannot run: its help, ``canExecute()`` and running it give ``message``."""

    def __init__(self, name, display_name, reason, message):
        super().__init__()
        self._name, self._display_name, self._reason, self._message = name, display_name, reason, message

    def createInstance(self):
        return UnavailableAlgorithm(self._name, self._display_name, self._reason, self._message)

    def name(self):
        return self._name

    def displayName(self):
        title = QCoreApplication.translate("RegisterAlgorithm", self._display_name)
        return QCoreApplication.translate("HamtaProvider", "{} (unavailable: {})").format(title, self._reason)

    def group(self):
        return QCoreApplication.translate("RegisterAlgorithm", "Registration")

    def groupId(self):
        return "registration"

    def _html(self):
        return html.escape(self._message, quote=False).replace("\n", "<br>")

    def shortHelpString(self):
        return self._html()

    def initAlgorithm(self, config=None):
        pass

    def canExecute(self):  # the toolbox shows this message as HTML
        return False, self._html()

    def processAlgorithm(self, parameters, context, feedback):
        raise QgsProcessingException(self._message)


class HamtaProvider(QgsProcessingProvider):
    def __init__(self):
        super().__init__()
        self.unavailable: Optional[str] = None  # why the algorithms cannot run, with the fix (None: they can)
        self.unavailable_reason = ""  # the same in a few words

    def id(self):
        return "hamta"

    def name(self):
        return QCoreApplication.translate("HamtaProvider", "Hamta")

    def longName(self):
        return QCoreApplication.translate("HamtaProvider", "Hamta automatic georeferencing")

    def icon(self):
        return QIcon(ICON)

    def versionInfo(self):
        return plugin_version()

    def warningMessage(self):
        """Shown above an algorithm's dialog and by ``qgis_process help/run``: short, the help has the rest."""
        if self.unavailable is None:
            return ""
        return QCoreApplication.translate("HamtaProvider", "Hamta cannot run ({}): see the algorithm's help for how to "
                                          "fix it.").format(self.unavailable_reason)

    def loadAlgorithms(self):
        missing = missing_requirements()
        if missing:
            self.unavailable_reason, self.unavailable = missing_summary(missing), missing_message(missing)
        else:
            self.unavailable_reason, self.unavailable = "", None
            try:  # the engine is imported here, once its requirements are known to import
                from ..core.methods import all_methods
                from .batch_algorithm import BatchRegisterAlgorithm
                from .grid_algorithm import GridAlgorithm
                from .register_algorithm import AUTO, RegisterAlgorithm
            except Exception as exc:  # never a traceback at plugin load: the algorithms say what failed
                self.unavailable_reason, self.unavailable = "engine failed to load", engine_error_message(exc)
        if self.unavailable is not None:
            for entry in algorithm_entries():
                self.addAlgorithm(UnavailableAlgorithm(entry.id, entry.title, self.unavailable_reason,
                                                       self.unavailable))
            return
        methods = [name for name, method in all_methods().items() if method.toolbox is not None]
        for alg in [RegisterAlgorithm(AUTO), *map(RegisterAlgorithm, methods), GridAlgorithm(),
                    BatchRegisterAlgorithm()]:
            self.addAlgorithm(alg)

    def supportedOutputRasterLayerExtensions(self):
        return ["tif", "vrt"]

    def supportedOutputVectorLayerExtensions(self):
        return ["gpkg"]

    def defaultVectorFileExtension(self, hasGeometry=True):
        return "gpkg"

    def defaultRasterFileExtension(self):
        return "tif"
