"""A map service as the reference in Processing and ``qgis_process``: an XYZ layer served by a local
tile server cut from a real raster, a search area, and a layer QGIS reads through its own provider."""
import json
import os
from urllib.parse import quote

import pytest


def test_an_xyz_layer_is_a_reference_through_processing(provider, server, xyz_source, crop, search_area, tmp_path,
                                                        monkeypatch):
    from qgis.core import QgsRasterLayer

    import processing

    monkeypatch.setenv("HAMTA_CACHE", str(tmp_path / "cache"))
    layer = QgsRasterLayer(xyz_source, "basemap", "wms")
    assert layer.isValid()
    target, extent = crop[0], search_area
    res = processing.run("hamta:registerauto", dict(TARGET=target, REFERENCE=layer, EXTENT=extent,
                                                    OUTPUT=str(tmp_path / "reg.tif"),
                                                    REPORT=str(tmp_path / "report.json")))
    assert res["VERDICT"] == "verified"
    report = json.loads((tmp_path / "report.json").read_text())
    service = report["reference"]["service"]
    assert service["kind"] == "xyz" and service["service"].startswith(server.url) and service["fetch"]["requests"] > 0
    import rasterio

    with rasterio.open(tmp_path / "reg.tif") as ds:
        assert ds.crs.to_epsg() == 3857


def test_a_layer_without_a_gdal_equivalent_is_read_through_its_provider(provider, landsat, tmp_path):
    """A QGIS virtual raster (the raster calculator's provider) over a georeferenced crop: the area
    around the target is rendered into a file, which verifies like the file itself."""
    import rasterio
    from qgis.core import QgsRasterLayer
    from rasterio.windows import Window

    import processing

    source, (c, r, w, h) = landsat
    target = str(tmp_path / "target.tif")
    with rasterio.open(source) as ds:
        profile = dict(ds.profile, width=w, height=h, transform=ds.window_transform(Window(c, r, w, h)))
        with rasterio.open(target, "w", **profile) as out:
            out.write(ds.read(window=Window(c, r, w, h)))
        b = ds.bounds
        uri = (f"?crs=EPSG:{ds.crs.to_epsg()}&extent={b.left},{b.bottom},{b.right},{b.top}&width={ds.width}"
               f"&height={ds.height}&formula=%22s@1%22&s:uri={quote(os.path.abspath(source))}&s:provider=gdal")
    layer = QgsRasterLayer(uri, "calculated", "virtualraster")
    assert layer.isValid() and layer.providerType() == "virtualraster"
    res = processing.run("hamta:registerauto", dict(TARGET=target, REFERENCE=layer, OUTPUT=str(tmp_path / "o.tif"),
                                                    REPORT=str(tmp_path / "r.json")))
    assert res["VERDICT"] == "verified"
    report = json.loads((tmp_path / "r.json").read_text())
    assert report["reference"]["path"] != os.path.abspath(source) and report["plan"]["mode"] == "georeferenced"


def test_a_search_area_is_needed_for_a_target_without_georeferencing(provider, xyz_source, crop, tmp_path):
    from qgis.core import QgsProcessingException, QgsRasterLayer

    import processing

    layer = QgsRasterLayer(xyz_source, "basemap", "wms")
    with pytest.raises(QgsProcessingException, match="search area"):
        processing.run("hamta:registerauto", dict(TARGET=crop[0], REFERENCE=layer, OUTPUT=str(tmp_path / "o.tif"),
                                                  REPORT=str(tmp_path / "r.json")))
    assert not (tmp_path / "r.json").exists()
