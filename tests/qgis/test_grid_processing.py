"""'Georeference a scanned map by its grid' in Processing and qgis_process: a synthetic sheet with an exact
truth (:mod:`hamta.bench.sheets`), its hints as the Georeferencer saves them, the outputs loaded as layers."""
import json

import numpy as np
import pytest
from qgis.core import QgsProcessingException, QgsProcessingFeedback, QgsRasterLayer, QgsVectorLayer

from hamta.bench.sheets import SPECS, render
from hamta.core.mapping import map_points_from_report

SPEC = next(s for s in SPECS if s.name == "utm-km-lines")


@pytest.fixture(scope="module")
def sheet(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sheet")
    rendered = render(SPEC, str(folder))
    hints = folder / "hints.points"
    with open(hints, "w") as f:
        f.write("mapX,mapY,sourceX,sourceY,enable,dX,dY,residual\n")
        for x, y, gx, gy in rendered.hints(2, seed=2):
            f.write(f"{gx},{gy},{x},{-y},1,0,0,0\n")
    return rendered, str(hints)


def test_the_algorithm_asks_for_the_sheet_its_crs_and_its_hints_and_no_reference(provider):
    alg = provider.algorithm("georeferencebygrid")
    assert alg is not None and alg.displayName() == "Georeference a scanned map by its grid"
    names = [p.name() for p in alg.parameterDefinitions()]
    for name in ("TARGET", "SHEET_CRS", "HINTS", "STEP", "OUTPUT_CRS", "TOLERANCE", "KEEP_UNVERIFIED", "OUTPUT",
                 "GCP_LAYER", "GCP_POINTS", "REPORT"):
        assert name in names
    assert "REFERENCE" not in names and "EXTENT" not in names and "GRID_CRS" not in names


def test_processing_georeferences_a_sheet_by_its_grid_and_the_outputs_load(provider, sheet, tmp_path):
    import processing

    rendered, hints = sheet
    res = processing.run("hamta:georeferencebygrid", {
        "TARGET": rendered.path, "SHEET_CRS": "EPSG:32633", "HINTS": hints, "OUTPUT": str(tmp_path / "sheet.tif"),
        "GCP_LAYER": str(tmp_path / "gcps.gpkg"), "REPORT": str(tmp_path / "report.json")},
        feedback=QgsProcessingFeedback())
    assert res["VERDICT"] == "verified" and res["METHOD"] == "grid" and res["N_GCPS"] >= 9
    layer = QgsRasterLayer(res["OUTPUT"], "sheet")
    assert layer.isValid() and layer.crs().authid() == "EPSG:32633"
    gcps = QgsVectorLayer(res["GCP_LAYER"], "gcps")
    assert gcps.isValid() and gcps.featureCount() == res["N_GCPS"]
    nodes = rendered.nodes()
    got = np.array([r["map"] for r in map_points_from_report(res["REPORT"], rendered.to_scan(nodes))])
    assert np.hypot(*(got - nodes).T).max() < 2.5 * SPEC.pixel_m
    assert json.loads(open(res["REPORT"]).read())["quality"]["check"] == "grid-held-out-lines"


def test_a_hints_file_that_is_not_one_is_a_clear_processing_error(provider, sheet, tmp_path):
    import processing

    rendered, _ = sheet
    bad = tmp_path / "bad.points"
    bad.write_text("not a points file\n1,2\n")
    with pytest.raises(QgsProcessingException, match="cannot be read as a QGIS .points file"):
        processing.run("hamta:georeferencebygrid", {"TARGET": rendered.path, "SHEET_CRS": "EPSG:32633",
                                                    "HINTS": str(bad), "OUTPUT": str(tmp_path / "o.tif")},
                       feedback=QgsProcessingFeedback())


def test_a_refusal_is_a_processing_error_naming_its_report(provider, tmp_path):
    """No grid, no hints, no labels: Processing stops with what was looked for and where its report is."""
    import rasterio

    import processing

    blank = str(tmp_path / "blank.tif")
    paper = np.random.default_rng(1).normal(235, 4, (500, 700)).clip(0, 255).astype(np.uint8)
    with rasterio.open(blank, "w", driver="GTiff", width=700, height=500, count=1, dtype="uint8") as dst:
        dst.write(paper, 1)
    with pytest.raises(QgsProcessingException, match=r"What was read and tried: .*report\.(html|json)") as err:
        processing.run("hamta:georeferencebygrid", {"TARGET": blank, "SHEET_CRS": "EPSG:4326",
                                                    "OUTPUT": str(tmp_path / "o.tif"),
                                                    "REPORT": str(tmp_path / "report.json")},
                       feedback=QgsProcessingFeedback())
    message = str(err.value)
    assert "the hints" not in message and "Give two or three crossings" in message  # what would help, no hints
    report = json.loads((tmp_path / "report.json").read_text())
    assert report["outcome"] == "refused"
    assert not (tmp_path / "o.tif").exists()


def test_the_processing_batch_georeferences_sheets_by_their_grid_without_a_reference(provider, sheet, tmp_path):
    """'Batch register' with target rasters, no reference and the CRS of their printed coordinates: each sheet
    by its grid, its hints from the Georeferencer's '<raster>.points' beside it."""
    import shutil

    import processing

    rendered, hints = sheet
    folder = tmp_path / "series"
    folder.mkdir()
    targets = []
    for name in ("a", "b"):
        shutil.copy(rendered.path, folder / f"{name}.tif")
        shutil.copy(hints, folder / f"{name}.tif.points")
        targets.append(str(folder / f"{name}.tif"))
    with pytest.raises(QgsProcessingException, match="CRS of their printed coordinates"):
        processing.run("hamta:batchregister", {"TARGETS": targets, "OUTPUT_FOLDER": str(tmp_path / "none")},
                       feedback=QgsProcessingFeedback())
    res = processing.run("hamta:batchregister", {"TARGETS": targets, "SHEET_CRS": "EPSG:32633", "WORKERS": 1,
                                                 "OUTPUT_FOLDER": str(tmp_path / "out")},
                         feedback=QgsProcessingFeedback())
    assert res["VERIFIED"] == 2 and res["FAILED"] == 0
    for name in ("a", "b"):
        report = json.loads((tmp_path / "out" / name / "report.json").read_text())
        assert report["method"] == "grid" and report["quality"]["verdict"] == "verified"
