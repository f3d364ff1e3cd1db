"""The plugin loads in QGIS, registers its provider and unloads cleanly."""
from unittest import mock

from qgis.core import QgsApplication


def test_class_factory_registers_and_removes_the_provider(qgis_app):
    import hamta

    registry = QgsApplication.processingRegistry()
    registered_before = registry.providerById("hamta") is not None  # by the session fixture
    plugin = hamta.classFactory(mock.MagicMock())
    plugin.initGui()
    provider = registry.providerById("hamta")
    assert provider is not None and provider.name() == "Hamta"
    assert "hamta:registersift" in [a.id() for a in provider.algorithms()]
    plugin.initGui()  # a second call must not register a duplicate
    assert len([p for p in registry.providers() if p.id() == "hamta"]) == 1
    plugin.unload()
    assert (registry.providerById("hamta") is not None) == registered_before


def test_metadata_declares_a_processing_provider():
    import configparser
    import pathlib

    meta = configparser.ConfigParser()
    meta.read(pathlib.Path(__file__).resolve().parents[2] / "metadata.txt")
    general = meta["general"]
    assert general["hasProcessingProvider"] == "yes" and general["qgisMinimumVersion"] == "3.22"
    for key in ("name", "description", "about", "version", "author", "changelog", "tags"):
        assert general[key].strip()


def test_persian_translation_is_loaded_for_a_persian_locale(provider):
    import pathlib

    from qgis.core import QgsSettings
    from qgis.PyQt.QtCore import QCoreApplication

    from hamta.plugin.plugin import load_translator

    settings = QgsSettings()
    old = settings.value("locale/userLocale")
    settings.setValue("locale/userLocale", "fa_IR")
    translator = load_translator()
    try:
        assert translator is not None
        alg = provider.algorithm("registersift")
        assert alg.displayName() == "ثبت رستر (پایه SIFT)"
        assert alg.group() == "ثبت تصویر"
    finally:
        QCoreApplication.removeTranslator(translator)
        settings.setValue("locale/userLocale", old or "")
    assert alg.displayName() == "Register raster (SIFT baseline)"
    qm = pathlib.Path(__file__).resolve().parents[2] / "i18n" / "hamta_fa.qm"
    assert qm.stat().st_size > 1000


def test_compiled_translations_match_their_sources(tmp_path):
    import pathlib
    import shutil
    import subprocess

    import pytest

    lrelease = shutil.which("lrelease")
    if lrelease is None:
        pytest.skip("lrelease (qttools5-dev-tools) is not installed")
    i18n = pathlib.Path(__file__).resolve().parents[2] / "i18n"
    for ts in sorted(i18n.glob("*.ts")):
        out = tmp_path / (ts.stem + ".qm")
        subprocess.run([lrelease, "-silent", str(ts), "-qm", str(out)], check=True)
        assert out.read_bytes() == (i18n / out.name).read_bytes(), f"run 'make i18n': {out.name} is stale"
