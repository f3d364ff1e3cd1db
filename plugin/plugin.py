"""The QGIS plugin object: registers the Processing provider, loads translations and says once when
the provider's algorithms cannot run (missing Python packages) and how to fix it."""
from __future__ import annotations

import os

from qgis.core import Qgis, QgsApplication, QgsMessageLog, QgsSettings
from qgis.PyQt.QtCore import QCoreApplication, QTranslator

from ..processing.provider import HamtaProvider

I18N = os.path.join(os.path.dirname(os.path.dirname(__file__)), "i18n")


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

    def unload(self):
        if self.provider is not None:
            QgsApplication.processingRegistry().removeProvider(self.provider)
            self.provider = None
        if self.translator is not None:
            QCoreApplication.removeTranslator(self.translator)
            self.translator = None
