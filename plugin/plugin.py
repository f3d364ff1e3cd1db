"""The QGIS plugin object: registers the Processing provider and loads translations."""
from __future__ import annotations

import os

from qgis.core import QgsApplication, QgsSettings
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
            registry.addProvider(self.provider)

    def initGui(self):  # noqa: N802
        self.initProcessing()

    def unload(self):
        if self.provider is not None:
            QgsApplication.processingRegistry().removeProvider(self.provider)
            self.provider = None
        if self.translator is not None:
            QCoreApplication.removeTranslator(self.translator)
            self.translator = None
