"""The Hamta Processing provider."""
from __future__ import annotations

import os

from qgis.core import QgsProcessingProvider
from qgis.PyQt.QtCore import QCoreApplication
from qgis.PyQt.QtGui import QIcon

from .register_algorithm import (
    RegisterAutoAlgorithm,
    RegisterCrossModalAlgorithm,
    RegisterNdsiftAlgorithm,
    RegisterRilbpAlgorithm,
    RegisterSarOpticalAlgorithm,
    RegisterSibrifAlgorithm,
    RegisterSiftAlgorithm,
)

ICON = os.path.join(os.path.dirname(os.path.dirname(__file__)), "icon.svg")


class HamtaProvider(QgsProcessingProvider):
    def id(self):
        return "hamta"

    def name(self):
        return QCoreApplication.translate("HamtaProvider", "Hamta")

    def longName(self):
        return QCoreApplication.translate("HamtaProvider", "Hamta automatic georeferencing")

    def icon(self):
        return QIcon(ICON)

    def loadAlgorithms(self):
        for alg in (RegisterAutoAlgorithm(), RegisterSiftAlgorithm(), RegisterRilbpAlgorithm(),
                    RegisterSibrifAlgorithm(), RegisterNdsiftAlgorithm(), RegisterSarOpticalAlgorithm(),
                    RegisterCrossModalAlgorithm()):
            self.addAlgorithm(alg)

    def supportedOutputRasterLayerExtensions(self):
        return ["tif"]

    def supportedOutputVectorLayerExtensions(self):
        return ["gpkg"]

    def defaultVectorFileExtension(self, hasGeometry=True):
        return "gpkg"

    def defaultRasterFileExtension(self):
        return "tif"
