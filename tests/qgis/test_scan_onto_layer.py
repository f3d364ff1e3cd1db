"""A scanned map onto a vector layer of the areas it shows (issue 56, onto a reference): a map drawn from real
water (:mod:`hamta.bench.water_map`, exact truth) registered onto a layer of that water's polygons, in
Processing and from the dialog's reference list."""
import numpy as np
import pytest
from qgis.core import QgsFeature, QgsGeometry, QgsProcessingException, QgsProcessingFeedback, QgsVectorLayer

from hamta.core.mapping import map_points_from_report

DATE = "20160816"


@pytest.fixture(scope="module")
def scan_and_lakes(shared, tmp_path_factory):
    import rasterio.features
    from shapely.geometry import shape

    from hamta.bench.water_map import draw, naip, water

    folder = tmp_path_factory.mktemp("scan_onto_layer")
    data = str(shared / "data")
    sheet = draw(data, DATE, str(folder / "map.jpg"), 6.0, 25.0)
    bands, profile = naip(data, DATE)
    wet = water(bands)
    layer = QgsVectorLayer("Polygon?crs=EPSG:26914", "lakes", "memory")
    features = []
    for geometry, value in rasterio.features.shapes(wet, mask=wet > 0, transform=profile["transform"]):
        feature = QgsFeature()
        feature.setGeometry(QgsGeometry.fromWkt(shape(geometry).wkt))
        features.append(feature)
    layer.dataProvider().addFeatures(features)
    layer.updateExtents()
    return sheet, layer, profile["transform"]


def test_a_scanned_map_is_placed_on_a_layer_of_its_lakes(provider, scan_and_lakes, tmp_path):
    import processing
    from hamta.bench.water_map import AREA

    sheet, layer, transform = scan_and_lakes
    res = processing.run("hamta:registerregions", {
        "TARGET": sheet.path, "REFERENCE": layer, "OUTPUT": str(tmp_path / "map.tif"),
        "REPORT": str(tmp_path / "report.json")}, feedback=QgsProcessingFeedback())
    assert res["VERDICT"] == "verified" and res["METHOD"] == "regions"
    canvas = np.array([[0.2, 0.2], [0.8, 0.3], [0.5, 0.8], [0.3, 0.7]]) * np.array(AREA[2:]) * sheet.zoom
    full = np.vstack([sheet.matrix, [0, 0, 1]])
    scan = (canvas - full[:2, 2]) @ np.linalg.inv(full[:2, :2]).T
    naip_px = sheet.to_reference(scan)
    truth = np.column_stack([transform.c + naip_px[:, 0] * transform.a, transform.f + naip_px[:, 1] * transform.e])
    got = np.array([r["map"] for r in map_points_from_report(res["REPORT"], scan)])
    assert np.hypot(*(got - truth).T).max() < 2 * transform.a  # within two NAIP pixels (10 m)


def test_a_layer_with_nothing_where_the_map_is_asked_for_is_a_clear_error(provider, scan_and_lakes, tmp_path):
    import processing

    sheet, _, _ = scan_and_lakes
    empty = QgsVectorLayer("Polygon?crs=EPSG:26914", "no lakes", "memory")
    with pytest.raises(QgsProcessingException, match="no lakes.*no areas or lines"):
        processing.run("hamta:registerregions", {
            "TARGET": sheet.path, "REFERENCE": empty, "OUTPUT": str(tmp_path / "o.tif"),
            "EXTENT": "485900,490500,5205600,5209200 [EPSG:26914]"}, feedback=QgsProcessingFeedback())


class _Iface:
    def __init__(self):
        from qgis.gui import QgsMapCanvas

        self.canvas = QgsMapCanvas()

    def activeLayer(self):  # noqa: N802 (QGIS's names)
        return None

    def mapCanvas(self):  # noqa: N802
        return self.canvas


def test_the_dialog_offers_a_layer_of_areas_as_the_reference(qgis_app, scan_and_lakes, tmp_path):
    from qgis.core import QgsProject, QgsRasterLayer

    from hamta.plugin.autogeoref import AutoGeoreferenceDialog

    sheet, layer, _ = scan_and_lakes
    scan = QgsRasterLayer(sheet.path, "map")
    QgsProject.instance().addMapLayers([scan, layer], False)
    try:
        dialog = AutoGeoreferenceDialog(_Iface())
        dialog.folder.setFilePath(str(tmp_path / "out"))
        dialog.target.setLayer(scan)
        dialog.reference.setLayer(layer)
        assert dialog.reference.currentLayer() is layer
        assert dialog.problem() is None  # no search area needed: the layer's extent is where to look
    finally:
        QgsProject.instance().removeMapLayers([scan.id(), layer.id()])
