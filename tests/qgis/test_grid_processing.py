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
    for name in ("TARGET", "SHEET_CRS", "HINTS", "STEP", "GRID_CRS", "TOLERANCE", "KEEP_UNVERIFIED", "OUTPUT",
                 "GCP_LAYER", "GCP_POINTS", "REPORT"):
        assert name in names
    assert "REFERENCE" not in names and "EXTENT" not in names


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
