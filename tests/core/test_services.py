"""Map-service references told apart from files, tile addresses, credentials kept out of messages, search
areas, and a search area over a local reference file."""
import os

import numpy as np
import pytest

from hamta.core.basemap.redact import redact
from hamta.core.basemap.services import HALF_WORLD, parse_service, redact_source
from hamta.core.basemap.tiles import tile_range
from hamta.core.errors import InputError, NoOverlapError
from hamta.core.extent import bounds_in, parse_extent

SOURCE = os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "data", "landsat", "RGB.byte.tif")


def test_a_tile_template_and_qgis_layer_sources_are_services():
    xyz = parse_service("https://tiles.example.org/{z}/{x}/{y}.png?key=SECRET")
    assert xyz.kind == "xyz" and xyz.tile_url(3, 2, 1) == "https://tiles.example.org/3/2/1.png?key=SECRET"
    assert "SECRET" not in xyz.label
    qgis = parse_service("type=xyz&url=https://t.example.org/%7Bz%7D/%7Bx%7D/%7B-y%7D.jpg&zmax=17&zmin=2")
    assert (qgis.zmin, qgis.zmax) == (2, 17) and qgis.tile_url(2, 1, 0) == "https://t.example.org/2/1/3.jpg"
    wms = parse_service("contextualWMSLegend=0&crs=EPSG:3857&dpiMode=7&format=image/jpeg&layers=ortho&styles="
                        "&url=https://wms.example.org/service")
    assert wms.kind == "wms" and wms.layers == "ortho" and wms.image_format == "image/jpeg"
    url = wms.tile_url(0, 0, 0)
    assert "REQUEST=GetMap" in url and "SRS=EPSG:3857" in url and f"BBOX={-HALF_WORLD:.10g}" in url


def test_layers_hamta_cannot_read_itself_are_left_to_qgis_or_gdal():
    wms = "crs=EPSG:3857&format=image/png&layers=roads&layers=buildings&styles=&styles=&url=https://w.example.org/wms"
    assert parse_service(wms).layers == "roads,buildings"
    assert parse_service(wms.replace("EPSG:3857", "EPSG:25832")) is None  # neither Web Mercator nor lon/lat
    for extra in ("authcfg=ab12cd", "username=me&password=pw", "http-header:referer=https://x.org", "referer=x"):
        assert parse_service(f"type=xyz&url=https://t.example.org/%7Bz%7D/%7Bx%7D/%7By%7D.png&{extra}") is None


@pytest.mark.parametrize("text", [SOURCE, "/vsicurl/https://example.org/cog.tif", "WMTS:https://example.org/wmts",
                                  "WCS:https://example.org/wcs?coverage=dem", "<GDAL_WMS><Service name='TMS'/>",
                                  "SERVICE=WMTS&url=https://example.org/wmts&layer=a&tileMatrixSet=g&layers=a"])
def test_files_and_gdal_strings_are_not_services(text):
    assert parse_service(text) is None


def test_a_template_without_a_row_placeholder_is_refused_clearly():
    with pytest.raises(InputError, match="placeholder"):
        parse_service("https://t.example.org/{z}/{x}.png")


def test_credentials_never_show():
    text = redact("https://me:pa55@t.example.org/{z}/{x}/{y}.png?token=abc&style=dark")
    assert "pa55" not in text and "abc" not in text and "me:" not in text
    assert "{z}/{x}/{y}" in text and "style=dark" in text
    for gdal in ("/vsicurl/https://me:pa55@s3.example.org/cog.tif?X-Amz-Signature=abc&x=1",
                 "WMTS:https://w.example.org/wmts?app_code=abc,layer=a"):
        text = redact_source(gdal)
        assert "pa55" not in text and "abc" not in text and text.startswith(gdal[:5]), text
    assert redact(SOURCE) == SOURCE


def test_search_areas_parse_or_say_how_to_write_them():
    area = parse_extent("10.7, 59.9, 10.8, 59.95, EPSG:4326")
    assert area.bounds == (10.7, 59.9, 10.8, 59.95) and area.crs == "EPSG:4326"
    assert parse_extent("0,0,1,1").crs is None
    for bad, words in (("1,2,3", "xmin,ymin,xmax,ymax"), ("a,b,c,d", "xmin,ymin,xmax,ymax"),
                       ("5,0,1,1", "empty"), ("0,0,1,1,EPSG:99999999", "CRS")):
        with pytest.raises(ValueError, match=words):
            parse_extent(bad)
    x0, y0, x1, y1 = bounds_in(area, "EPSG:3857", None)
    assert 1.19e6 < x0 < x1 < 1.21e6 and 8.3e6 < y0 < y1 < 8.4e6


def test_tiles_follow_the_grid():
    service = parse_service("https://t.example.org/{z}/{x}/{y}.png")
    assert abs(service.resolution(11) - 76.437) < 0.01
    tiles = tile_range(service, (-HALF_WORLD, -HALF_WORLD, HALF_WORLD, HALF_WORLD), 2)
    assert (tiles.x0, tiles.y0, tiles.x1, tiles.y1, tiles.count) == (0, 0, 3, 3, 16)
    with pytest.raises(InputError, match="outside"):
        tile_range(service, (3 * HALF_WORLD, 0, 4 * HALF_WORLD, 1), 2)


def test_a_search_area_limits_what_is_read_of_a_reference_file(tmp_path):
    """An un-georeferenced crop searched in a local file: only the area is read, and it still registers."""
    import cv2
    import rasterio
    from rasterio.windows import Window

    from hamta.core import RegisterOptions, register

    with rasterio.open(SOURCE) as ds:
        crop = ds.read([1, 2, 3], window=Window(300, 250, 200, 160))
        t = ds.transform
    target = str(tmp_path / "crop.png")
    cv2.imwrite(target, np.moveaxis(crop, 0, 2)[:, :, ::-1])
    x0, y1 = t * (200, 150)
    x1, y0 = t * (600, 500)
    result = register(target, SOURCE, options=RegisterOptions(extent=f"{x0},{y0},{x1},{y1}"))
    window = result.plan.reference_window
    assert result.verified and (window.col_off, window.row_off, window.width, window.height) == (200, 150, 400, 350)
    assert np.abs(result.model.apply(np.array([[0.0, 0.0]])) - [300, 250]).max() < 0.5
    with pytest.raises(NoOverlapError, match="search area"):
        register(target, SOURCE, options=RegisterOptions(extent="0,0,1000,1000"))


def test_a_search_area_in_metres_without_its_crs_is_explained(tmp_path):
    from hamta.core import RegisterOptions
    from hamta.core.basemap.fetch import Fetcher
    from hamta.core.progress import Monitor
    from hamta.core.remote import register_remote

    service = parse_service("http://127.0.0.1:9/{z}/{x}/{y}.png")
    options = RegisterOptions(extent="-8900000,2400000,-8500000,2800000", target_georef="ignore")
    with pytest.raises(InputError, match="EPSG:3857"):
        register_remote(SOURCE, service, options, Monitor(), Fetcher(cache=str(tmp_path)))


@pytest.mark.parametrize("key", ["api-key", "apiKey", "X-Api-Key", "access_token", "client_secret", "Signature",
                                 "X-Amz-Credential", "PASSWORD", "pwd", "auth", "authcfg", "sig", "subscription-key"])
def test_any_query_key_naming_a_secret_is_redacted_everywhere_in_a_text(key):
    text = f"failed: /vsicurl/https://u:pw@h.example.org/{{z}}/{{x}}/{{y}}.png?layers=a&{key}=S3CR3T then http://x/?{key}=S3CR3T"
    redacted = redact(text)
    assert "S3CR3T" not in redacted and "pw@" not in redacted and "layers=a" in redacted and "{z}" in redacted
    assert redacted.startswith("failed: /vsicurl/https://h.example.org/")


def test_outside_text_is_printed_escaped_and_cut():
    from hamta.core.text import printable, terminal_safe

    hostile = "\x1b]0;title\x07\x1b[2J\rFAKE\u202e" + "x" * 500
    shown = printable(hostile)
    assert shown.isprintable() and shown.startswith("\\x1b]0;title\\x07") and shown.endswith("x…") and len(shown) < 240
    assert terminal_safe("line\n\tnext\r\x1b[2J") == "line\n\tnext\r\\x1b[2J"


@pytest.mark.parametrize("text", ["-1e308,-1e308,1e308,1e308", "nan,0,1,1", "0,0,inf,1", "0,0,2e10,1,EPSG:3857"])
def test_a_search_area_beyond_any_map_is_refused_plainly(text):
    with pytest.raises(ValueError, match="beyond any map"):
        parse_extent(text)
