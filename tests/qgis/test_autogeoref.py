"""'Auto-georeference…' end to end, offscreen: the plugin's action opens the dialog on the selected raster,
which proposes the basemap of the canvas (an XYZ layer served locally) and the canvas extent; the task
registers, and the results land in the project with the message bar saying so."""
import html
import json
import os
import pathlib
import re
import time

import numpy as np
import pytest
from qgis.core import Qgis, QgsApplication, QgsCoordinateReferenceSystem, QgsProject, QgsRasterLayer, QgsRectangle
from qgis.gui import QgsMapCanvas, QgsMessageBar
from qgis.PyQt import sip
from qgis.PyQt.QtWidgets import QAction, QApplication, QMainWindow, QProgressBar, QPushButton

AREA = 2.2  # the search area's half side, in target footprints (4.4 x 4.4 footprints, EPSG:3857)


class Iface:
    """The part of QgisInterface the plugin uses, with real widgets; other calls are recorded."""

    def __init__(self):
        self.window = QMainWindow()
        self.canvas = QgsMapCanvas(self.window)
        self.canvas.resize(800, 640)
        self.bar = QgsMessageBar(self.window)
        self.georeferencer = QAction("Georeferencer", self.window)
        self.georeferencer.setObjectName("mActionShowGeoreferencer")
        self.georeferencer_opened = 0
        self.georeferencer.triggered.connect(self._opened)
        self.active, self.calls = None, []

    def _opened(self):
        self.georeferencer_opened += 1

    def mainWindow(self):  # noqa: N802 (QGIS's names)
        return self.window

    def mapCanvas(self):  # noqa: N802
        return self.canvas

    def messageBar(self):  # noqa: N802
        return self.bar

    def activeLayer(self):  # noqa: N802
        return self.active

    def __getattr__(self, name):
        return lambda *args: self.calls.append(name)


@pytest.fixture
def session(qgis_app, xyz_source, crop, tmp_path, monkeypatch):
    """The plugin loaded on a fake iface; the project holds the basemap and the target (selected), the
    canvas (EPSG:3857) shows the search area around the target."""
    from hamta.plugin.plugin import HamtaPlugin

    monkeypatch.setenv("HAMTA_CACHE", str(tmp_path / "cache"))
    project = QgsProject.instance()
    project.clear()
    basemap = QgsRasterLayer(xyz_source, "basemap", "wms")
    scan = QgsRasterLayer(crop[0], "scan")
    assert basemap.isValid() and scan.isValid()
    project.addMapLayers([basemap, scan])
    iface = Iface()
    iface.active = scan
    x0, y0, x1, y1 = crop[1]
    cx, cy, half_w, half_h = (x0 + x1) / 2, (y0 + y1) / 2, AREA * (x1 - x0), AREA * (y1 - y0)
    iface.canvas.setDestinationCrs(QgsCoordinateReferenceSystem("EPSG:3857"))
    iface.canvas.setExtent(QgsRectangle(cx - half_w, cy - half_h, cx + half_w, cy + half_h))
    plugin = HamtaPlugin(iface)
    plugin.initGui()
    yield plugin, iface, basemap, scan
    plugin.unload()
    project.clear()
    sip.delete(iface.window)  # with the dialog, canvas and message bar, now rather than at exit


def wait_for_tasks(action, timeout=60.0, seen=None, bars=None):
    """Until ``action``'s tasks end; ``seen`` (a set or a list, in order) gets the message bar's texts
    meanwhile, ``bars`` (a list) every value its progress bars took."""
    end = time.monotonic() + timeout
    watched = set()
    while action.tasks:
        assert time.monotonic() < end, "the task did not end in time"
        items = action.iface.messageBar().items()
        for bar in (bar for item in items for bar in item.findChildren(QProgressBar)):
            if bars is not None and id(bar) not in watched:
                watched.add(id(bar))
                bar.valueChanged.connect(bars.append)
        QgsApplication.processEvents()
        if isinstance(seen, set):
            seen.update(item.text() for item in items)
        elif seen is not None:
            seen.extend(t for t in (item.text() for item in items) if not seen or t != seen[-1])
        time.sleep(0.01)
    QgsApplication.processEvents()


def files(folder):
    """The outputs in ``folder`` (not Hamta's hidden bookkeeping)."""
    return sorted(name for name in os.listdir(folder) if not name.startswith("."))


def messages(iface):
    return [(item.level(), item.text(), [b.text() for b in item.findChildren(QPushButton)])
            for item in iface.bar.items()]


def test_one_click_georeferences_the_selected_raster_on_the_basemap(session, monkeypatch):
    plugin, iface, basemap, scan = session
    assert {"addToolBarIcon", "addPluginToRasterMenu", "addCustomActionForLayerType"} <= set(iface.calls)
    plugin.action.trigger()
    dialog = plugin.autogeoref.dialog
    assert dialog.isVisible() and dialog.target.currentLayer() is scan
    assert dialog.reference.currentLayer() is basemap
    assert dialog.area.isChecked() and dialog.extent().endswith(",EPSG:3857")  # no georeferencing: search the canvas
    folder = dialog.folder.filePath()
    assert folder == os.path.join(os.path.dirname(scan.source()), "scan_georeferenced")

    dialog.run_button.click()
    assert not dialog.isVisible() and len(plugin.autogeoref.tasks) == 1
    [task] = plugin.autogeoref.tasks
    seen, bars = [], []
    wait_for_tasks(plugin.autogeoref, seen=seen, bars=bars)  # about 8 s here
    assert any(re.match(r"Auto-georeference 'scan': zoom \d+: fetching tiles ", t) for t in seen), seen
    assert any(t.startswith("Auto-georeference 'scan': place 1: ") for t in seen), seen  # each part named
    assert len({t for t in seen if t.startswith("Auto-georeference 'scan': ")}) >= 4, seen  # stages as they go
    # The bar only moves forward and ends full; each part's tile counter counts on, never restarting.
    assert bars and bars == sorted(bars) and bars[-1] == 100, bars
    counts = {}
    for t in seen:
        found = re.search(r": (.*)fetching tiles (\d+)/(\d+)$", t)
        if found:
            counts.setdefault(found.group(1), []).append((int(found.group(2)), int(found.group(3))))
    assert counts and any(c[-1][0] > 1 for c in counts.values()), counts
    for part in counts.values():
        assert [c[0] for c in part] == sorted(c[0] for c in part), counts
        assert all(done <= total for done, total in part), counts

    layers = {layer.source(): layer for layer in QgsProject.instance().mapLayers().values()}
    raster, gcps = layers[os.path.join(folder, "registered.tif")], layers[os.path.join(folder, "gcps.gpkg") +
                                                                          "|layername=gcps"]
    assert raster.crs().authid() == "EPSG:3857" and gcps.featureCount() >= 3
    report = json.loads(pathlib.Path(folder, "report.json").read_text())
    assert report["quality"]["verdict"] == "verified", report["quality"]["reasons"]
    import rasterio

    with rasterio.open(raster.source()) as ds:
        assert ds.crs.to_epsg() == 3857
    [(level, text, buttons)] = messages(iface)
    assert level == Qgis.Success and text.startswith("'scan' verified, within "), text
    assert len(text) <= 60 and re.search(r"within [0-9.]+ m \([0-9.]+ px\)\.$", text), text  # fits; ground and own px
    assert buttons == ["Details", "Open report", "Open the GCPs in the Georeferencer"]

    opened, shown = [], []
    monkeypatch.setattr("hamta.plugin.action.QDesktopServices.openUrl", lambda url: opened.append(url.toLocalFile()))
    monkeypatch.setattr("hamta.plugin.action.QMessageBox.information", lambda parent, title, text: shown.append(text))
    item = iface.bar.items()[0]
    [details_button, report_button, georef_button] = item.findChildren(QPushButton)
    details_button.click()
    [details] = shown
    assert "Independent check: verified" in details and "sites agree" in details, details
    result = task.result  # (QGIS has deleted the task; what Python kept of it is still readable)
    assert result.notes and all(note in details for note in result.notes), details  # where it was found
    # The whole run's time, not the last registration's.
    assert task.elapsed_s >= result.timings.total and f"Time: {task.elapsed_s:.1f} s" in details, details
    report_button.click()
    assert opened == [os.path.join(folder, "report.html")]
    georef_button.click()
    points = os.path.join(folder, "gcps.points")
    assert iface.georeferencer_opened == 1 and QApplication.clipboard().text() == points
    assert points in iface.bar.currentItem().text() and "Load GCP Points" in iface.bar.currentItem().text()


def test_the_reference_is_the_visible_basemap(session, landsat):
    plugin, iface, basemap, scan = session
    other = QgsRasterLayer(landsat[0], "landsat")  # a georeferenced raster above the basemap
    QgsProject.instance().addMapLayer(other)
    plugin.action.trigger()
    assert plugin.autogeoref.dialog.reference.currentLayer() is basemap
    plugin.autogeoref.dialog.close()
    QgsProject.instance().layerTreeRoot().findLayer(basemap.id()).setItemVisibilityChecked(False)
    plugin.action.trigger()
    assert plugin.autogeoref.dialog.reference.currentLayer() is other
    assert plugin.autogeoref.dialog.target.exceptedLayerList() == [basemap]  # a target is a file
    plugin.autogeoref.dialog.close()


def test_cancel_adds_nothing(session):
    plugin, iface, basemap, scan = session
    before = set(QgsProject.instance().mapLayers())
    plugin.action.trigger()
    folder = plugin.autogeoref.dialog.folder.filePath()
    plugin.autogeoref.dialog.run_button.click()
    [task] = plugin.autogeoref.tasks
    end = time.monotonic() + 20
    while task.progress() == 0 and time.monotonic() < end:  # the engine is at work: it must stop on its own
        QgsApplication.processEvents()
        time.sleep(0.005)
    assert task.status() == task.Running
    task.cancel()
    wait_for_tasks(plugin.autogeoref)
    assert task.outcome == "canceled"
    assert set(QgsProject.instance().mapLayers()) == before
    assert not os.path.exists(os.path.join(folder, "registered.tif"))
    [(level, text, _)] = messages(iface)
    assert level == Qgis.Info and "canceled" in text


def test_without_georeferencing_nor_search_area_it_says_what_to_do(session):
    plugin, iface, basemap, scan = session
    plugin.action.trigger()
    dialog = plugin.autogeoref.dialog
    dialog.area.setChecked(False)
    dialog.run_button.click()  # refused in the dialog, which stays open
    assert dialog.isVisible() and not plugin.autogeoref.tasks
    [item] = dialog.bar.items()
    assert "no georeferencing" in item.text() and "search area" in item.text()

    task = plugin.autogeoref.start(dialog.job())  # the engine says the same if asked anyway
    wait_for_tasks(plugin.autogeoref)
    assert task is not None
    [(level, text, _)] = messages(iface)
    assert level == Qgis.Critical and "search area" in text and "scan.png" in text, text
    dialog.close()


def test_a_georeferenced_target_is_searched_where_it_says_unless_told_otherwise(session, landsat):
    plugin, iface, basemap, scan = session
    source = QgsRasterLayer(landsat[0], "landsat")
    QgsProject.instance().addMapLayer(source)
    iface.active = source
    plugin.action.trigger()
    dialog = plugin.autogeoref.dialog
    assert dialog.target.currentLayer() is source and dialog.reference.currentLayer() is basemap
    assert not dialog.area.isChecked() and dialog.problem() is None
    job = dialog.job()
    assert job.extent is None and job.options.target_georef == "auto" and job.options.model is None
    dialog.area.setChecked(True)  # the user says where to look: the target's own georeferencing is set aside
    assert dialog.job().options.target_georef == "ignore"
    dialog.reference.setLayer(source)
    assert "other than the target" in dialog.problem()
    dialog.close()


def test_a_bug_is_said_plainly(session, tmp_path):
    from types import SimpleNamespace

    plugin, iface, basemap, scan = session
    job = SimpleNamespace(target_name="scan", folder=str(tmp_path))
    crashed = SimpleNamespace(outcome="crashed", job=job, written={}, result=None, error=KeyError("x"),
                              trace="Traceback ...")
    plugin.autogeoref.show_outcome(crashed)
    [(level, text, buttons)] = messages(iface)
    assert level == Qgis.Critical and "unexpected error (KeyError: 'x')" in text and not buttons


def test_an_unverified_result_is_said_in_one_short_line_and_kept_without_searching_again(session, monkeypatch):
    """The check cannot confirm an accuracy of 0.01 px: the message bar says so in a few plain words; Details
    has why; 'Keep anyway' writes that result's outputs (no second registration), marked NOT VERIFIED."""
    import dataclasses

    plugin, iface, basemap, scan = session
    plugin.action.trigger()
    dialog = plugin.autogeoref.dialog
    job = dialog.job()
    dialog.close()
    job = dataclasses.replace(job, options=dataclasses.replace(job.options, tolerance_px=0.01, auto_budget_s=5.0))
    task = plugin.autogeoref.start(job)
    bars = []
    wait_for_tasks(plugin.autogeoref, timeout=120, bars=bars)
    assert task.outcome == "unverified" and bars == sorted(bars) and bars[-1] == 100, (task.outcome, bars)
    assert files(job.folder) == ["report.html", "report.json"]
    [(level, text, buttons)] = messages(iface)
    assert level == Qgis.Warning and len(text) <= 60 and "chance" not in text, text  # fits the bar, plain words
    assert text == "'scan' not verified; nothing added."
    assert buttons == ["Details", "Keep anyway", "Open report"]
    assert not QgsProject.instance().mapLayersByName("scan (georeferenced)")

    shown = []
    monkeypatch.setattr("hamta.plugin.action.QMessageBox.information", lambda parent, title, text: shown.append(text))
    [details_button, keep_button, _] = iface.bar.items()[0].findChildren(QPushButton)
    details_button.click()
    [details] = shown
    v = task.result.verification
    assert f"Independent check: {v.verdict}" in details and all(reason in details for reason in v.reasons), details
    assert "What may help:" in details and "'Keep anyway' here, or 'Keep unverified results' in the dialog" in details
    assert f"Time: {task.elapsed_s:.1f} s" in details

    for module in ("pipeline", "remote", "runner"):  # keeping writes what was found: no registration again
        monkeypatch.setattr(f"hamta.core.{module}.register", lambda *a, **k: pytest.fail("registered again"))
    keep_button.click()
    [(_, text, buttons)] = messages(iface)  # the message goes; the outputs are written in a task, shown going
    assert text.startswith("Keeping 'scan': ") and buttons == ["Cancel"], text
    [keeping] = plugin.autogeoref.tasks
    bars = []
    wait_for_tasks(plugin.autogeoref, bars=bars)
    assert keeping.outcome == "written" and bars == sorted(bars) and bars[-1] == 100, bars
    assert files(job.folder) == ["gcps.gpkg", "gcps.points", "registered.tif", "report.html", "report.json"]
    [raster] = QgsProject.instance().mapLayersByName("NOT VERIFIED scan (georeferenced)")  # seen in a narrow panel
    assert raster.source() == os.path.join(job.folder, "registered.tif") and raster.isValid()
    report = json.loads(pathlib.Path(job.folder, "report.json").read_text())
    assert report["quality"]["verdict"] == v.verdict != "verified" and report["request"]["accept_unverified"] is True
    page = html.unescape(pathlib.Path(job.folder, "report.html").read_text())
    assert "Kept anyway ('Keep unverified results')" in page
    import rasterio

    with rasterio.open(raster.source()) as ds:
        assert ds.tags()["HAMTA_VERDICT"] == v.verdict
    [(level, text, buttons)] = messages(iface)
    assert level == Qgis.Warning and text == "'scan' NOT VERIFIED; check it before use."
    assert buttons == ["Details", "Open report", "Open the GCPs in the Georeferencer"]
    iface.bar.items()[0].findChildren(QPushButton)[0].click()
    assert f"Time: {task.elapsed_s:.1f} s" in shown[-1] and "Kept after the run: the outputs were written in " in \
        shown[-1]
    assert "What may help" not in shown[-1]  # kept: the advice is past


def test_one_name_for_keeping_unverified_results(session, provider):
    from hamta.core.advice import KEEP_UNVERIFIED, Advice, spelled

    plugin, iface, basemap, scan = session
    plugin.action.trigger()
    assert plugin.autogeoref.dialog.keep.text() == KEEP_UNVERIFIED == "Keep unverified results"
    plugin.autogeoref.dialog.close()
    for alg in ("hamta:registerauto", "hamta:batchregister"):
        found = QgsApplication.processingRegistry().createAlgorithmById(alg)
        assert found is not None, alg
        assert found.parameterDefinition("KEEP_UNVERIFIED").description() == KEEP_UNVERIFIED, alg
    assert f"(QGIS: '{KEEP_UNVERIFIED}')" in spelled(Advice("accept_unverified", True, "why"))


SHEET = "graticule-on-utm"  # a sheet of the synthetic family (hamta.bench.sheets)


@pytest.fixture
def sheet_session(qgis_app, tmp_path, monkeypatch):
    from hamta.plugin.plugin import HamtaPlugin

    monkeypatch.setenv("HAMTA_CACHE", str(tmp_path / "cache"))
    from hamta.bench.sheets import SPECS, render

    sheet = render(next(s for s in SPECS if s.name == SHEET), str(tmp_path))
    with open(sheet.path + ".points", "w") as f:  # where the Georeferencer saves a raster's GCPs
        f.write("mapX,mapY,sourceX,sourceY,enable,dX,dY,residual\n")
        for x, y, gx, gy in sheet.hints(2, seed=4):
            f.write(f"{gx},{gy},{x},{-y},1,0,0,0\n")
    project = QgsProject.instance()
    project.clear()
    layer = QgsRasterLayer(sheet.path, "sheet")
    assert layer.isValid()
    project.addMapLayer(layer)
    iface = Iface()
    iface.active = layer
    plugin = HamtaPlugin(iface)
    plugin.initGui()
    yield plugin, iface, sheet
    plugin.unload()
    project.clear()
    sip.delete(iface.window)


def test_one_click_georeferences_a_sheet_by_its_grid_when_no_reference_is_chosen(sheet_session):
    plugin, iface, sheet = sheet_session
    plugin.action.trigger()
    dialog = plugin.autogeoref.dialog
    assert dialog.reference.currentLayer() is None and dialog.sheet.isVisibleTo(dialog)
    assert not dialog.area.isVisibleTo(dialog)
    assert dialog.hints.filePath() == sheet.path + ".points"
    dialog.run_button.click()
    assert dialog.isVisible() and "CRS of the sheet" in dialog.bar.currentItem().text()
    dialog.sheet_crs.setCrs(QgsCoordinateReferenceSystem("EPSG:32633"))
    dialog.run_button.click()
    assert not dialog.isVisible()
    wait_for_tasks(plugin.autogeoref)
    folder = dialog.folder.filePath()
    [(level, text, buttons)] = messages(iface)
    assert level == Qgis.Success and text.startswith("'sheet' verified"), text
    assert "Open the GCPs in the Georeferencer" in buttons
    layers = {layer.source(): layer for layer in QgsProject.instance().mapLayers().values()}
    raster = layers[os.path.join(folder, "registered.tif")]
    assert raster.crs().authid() == "EPSG:32633"
    report = pathlib.Path(folder, "report.json")
    assert json.loads(report.read_text())["method"] == "grid"
    from pyproj import Transformer

    from hamta.core.mapping import map_points_from_report

    nodes = sheet.nodes()
    truth = np.column_stack(Transformer.from_crs("EPSG:4326", "EPSG:32633", always_xy=True).transform(*nodes.T))
    got = np.array([r["map"] for r in map_points_from_report(str(report), sheet.to_scan(nodes))])
    assert np.hypot(*(got - truth).T).max() < 2.5 * sheet.spec.pixel_m


def test_a_second_scan_is_never_proposed_as_the_reference_of_another(sheet_session, tmp_path):
    """A scan without georeferencing cannot be registered onto: the dialog proposes none (the sheet's own grid)
    and says why when one is chosen."""
    import rasterio

    plugin, iface, sheet = sheet_session
    with rasterio.open(sheet.path) as src:
        profile = {k: v for k, v in src.profile.items() if k not in ("crs", "transform")}
        pixels = src.read()
    other_path = str(tmp_path / "second_scan.tif")
    with rasterio.open(other_path, "w", **profile) as dst:
        dst.write(pixels)
    other = QgsRasterLayer(other_path, "second scan")
    assert other.isValid()
    QgsProject.instance().addMapLayer(other)
    first = QgsProject.instance().mapLayersByName("sheet")[0]
    iface.active = other
    plugin.action.trigger()
    dialog = plugin.autogeoref.dialog
    assert dialog.target.currentLayer() is other and dialog.reference.currentLayer() is None
    dialog.reference.setLayer(first)
    dialog.run_button.click()
    text = dialog.bar.currentItem().text()
    assert dialog.isVisible() and "'sheet' has no georeferencing" in text and "printed grid" in text
    dialog.close()


def test_a_refusal_says_so_in_one_line_with_its_details_and_report(qgis_app, tmp_path, monkeypatch):
    """A sheet with no printed grid, no hints and no labels to read: nothing is added; the report of what was
    looked for is one click away."""
    import rasterio

    from hamta.plugin.plugin import HamtaPlugin

    monkeypatch.setenv("HAMTA_CACHE", str(tmp_path / "cache"))
    blank = str(tmp_path / "blank.tif")
    paper = np.random.default_rng(0).normal(235, 4, (600, 800)).clip(0, 255).astype(np.uint8)
    with rasterio.open(blank, "w", driver="GTiff", width=800, height=600, count=1, dtype="uint8") as dst:
        dst.write(paper, 1)
    project = QgsProject.instance()
    project.clear()
    layer = QgsRasterLayer(blank, "blank")
    project.addMapLayer(layer)
    iface = Iface()
    iface.active = layer
    plugin = HamtaPlugin(iface)
    plugin.initGui()
    try:
        plugin.action.trigger()
        dialog = plugin.autogeoref.dialog
        assert dialog.reference.currentLayer() is None
        dialog.sheet_crs.setCrs(QgsCoordinateReferenceSystem("EPSG:4326"))
        dialog.run_button.click()
        wait_for_tasks(plugin.autogeoref, timeout=120)
        [(level, text, buttons)] = messages(iface)
        assert level == Qgis.Warning and text.startswith("'blank' not georeferenced; nothing added"), text
        assert buttons == ["Details", "Open report"]
        assert [layer.name() for layer in project.mapLayers().values()] == ["blank"]
        report = json.loads(pathlib.Path(dialog.folder.filePath(), "report.json").read_text())
        assert report["outcome"] == "refused" and report["findings"]["reason"]
        assert pathlib.Path(dialog.folder.filePath(), "report.html").is_file()
    finally:
        plugin.unload()
        project.clear()
        sip.delete(iface.window)
