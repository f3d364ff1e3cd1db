"""The QGIS plugin object: registers the Processing provider and the 'Auto-georeference…' action
(toolbar, Raster menu, raster layers' context menu), loads translations and says once when the
provider's algorithms cannot run (missing Python packages) and how to fix it."""
from __future__ import annotations

import os

from qgis.core import Qgis, QgsApplication, QgsMapLayerType, QgsMessageLog, QgsSettings
from qgis.PyQt.QtCore import QCoreApplication, QTranslator
from qgis.PyQt.QtGui import QIcon
from qgis.PyQt.QtWidgets import QAction

from ..processing.provider import HamtaProvider
from .action import AutoGeoreference

ROOT = os.path.dirname(os.path.dirname(__file__))
I18N = os.path.join(ROOT, "i18n")


def load_translator():
    """Install the translator for the user's QGIS locale, if Hamta has one; return it (or None)."""
    locale = (QgsSettings().value("locale/userLocale") or "")[0:2]
    path = os.path.join(I18N, f"hamta_{locale}.qm")
    if not locale or not os.path.exists(path):
        return None
    translator = QTranslator()
    if translator.load(path):
        QCoreApplication.installTranslator(translator)
        return translator
    return None


class HamtaPlugin:
    def __init__(self, iface):
        self.iface = iface
        self.provider = None
        self.translator = load_translator()
        self.autogeoref = AutoGeoreference(iface)
        self.action = None

    def initProcessing(self):  # noqa: N802 (QGIS's name)
        registry = QgsApplication.processingRegistry()
        if registry.providerById("hamta") is None:
            self.provider = HamtaProvider()
            registry.addProvider(self.provider)  # loads the algorithms, or their unavailable stand-ins
            if self.provider.unavailable:
                self.report_unavailable(self.provider.unavailable)

    def report_unavailable(self, message):
        """One warning in the message log and, in the QGIS window, one in its message bar."""
        QgsMessageLog.logMessage(message, "Hamta", Qgis.Warning)
        message_bar = getattr(self.iface, "messageBar", None)  # iface is None in qgis_process
        if callable(message_bar):
            summary = QCoreApplication.translate("HamtaPlugin", "its algorithms cannot run; press 'More' for why and "
                                                            "how to fix it.")
            message_bar().pushMessage("Hamta", summary, message, Qgis.Warning, 0)

    def initGui(self):  # noqa: N802
        self.initProcessing()
        if self.action is None:
            text = QCoreApplication.translate("AutoGeoreference", "Auto-georeference…")
            self.action = QAction(QIcon(os.path.join(ROOT, "icon.svg")), text)  # kept here, deleted in unload()
            self.action.setObjectName("mActionHamtaAutoGeoreference")
            self.action.setToolTip(QCoreApplication.translate(
                "AutoGeoreference", "Georeference the selected raster layer on the visible basemap (Hamta)"))
            self.action.triggered.connect(self.autogeoref.show_dialog)
            self.iface.addToolBarIcon(self.action)
            self.iface.addPluginToRasterMenu("Hamta", self.action)
            self.iface.addCustomActionForLayerType(self.action, "", QgsMapLayerType.RasterLayer, True)

    def unload(self):
        if self.action is not None:
            self.iface.removeCustomActionForLayerType(self.action)
            self.iface.removePluginRasterMenu("Hamta", self.action)
            self.iface.removeToolBarIcon(self.action)
            self.action.deleteLater()
            self.action = None
        self.autogeoref.cancel_all()
        if self.provider is not None:
            QgsApplication.processingRegistry().removeProvider(self.provider)
            self.provider = None
        if self.translator is not None:
            QCoreApplication.removeTranslator(self.translator)
            self.translator = None
