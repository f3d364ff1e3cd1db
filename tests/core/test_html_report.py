"""The visual report (``report.html``): self-contained, every image decodes, verdict and reasons
shown, the target warped correctly onto the reference for any model type, previews bounded."""
import base64
import dataclasses
import datetime
import html
import re
from xml.etree import ElementTree

import cv2
import numpy as np
import pytest
from affine import Affine
from rasterio.crs import CRS

from hamta.core import RegisterOptions, register
from hamta.core.errors import RegistrationCanceled
from hamta.core.estimation.models import LinearModel, PolynomialModel
from hamta.core.io.raster import open_raster
from hamta.core.outcome import Attempt, AutoRun
from hamta.core.outputs import html as report_html
from hamta.core.outputs import html_sections as report_sections
from hamta.core.outputs import preview as report_preview
from hamta.core.outputs import scale as report_scale
from hamta.core.outputs.html import write_html_report
from hamta.core.outputs.preview import Preview, read_preview, stretch, warp_to_reference
from hamta.core.progress import Monitor

IMG = re.compile(r'<img[^>]*?src="data:image/(?:png|jpeg);base64,([A-Za-z0-9+/=]+)"[^>]*?alt="([^"]*)"')


@pytest.fixture(scope="module")
def sift_result(small_pair):
    return register(small_pair["target"], small_pair["reference"], method="sift")


def _write(result, tmp_path, name="report.html") -> str:
    path = tmp_path / name
    write_html_report(str(path), result)
    assert path.is_file()
    return path.read_text(encoding="utf-8")


def _images(text: str) -> dict:
    """{alt: decoded image} of every embedded PNG."""
    out = {}
    for data, alt in IMG.findall(text):
        img = cv2.imdecode(np.frombuffer(base64.b64decode(data), np.uint8), cv2.IMREAD_UNCHANGED)
        assert img is not None, f"image '{alt}' does not decode"
        out[alt] = img
    return out


def test_report_is_self_contained_and_every_image_is_real(sift_result, tmp_path):
    text = _write(sift_result, tmp_path)
    assert re.search(r"class=word[^>]*>verified<", text)
    assert "not how accurate" in text
    assert not re.search(r'(src|href)="(?!data:)', text), "only embedded resources"
    assert "http://" not in text and "https://" not in text and "@import" not in text
    assert text.count("<script") == 0 and text.count("oninput=") == 1
    images = _images(text)
    assert text.count("data:image/png;base64,") + text.count("data:image/jpeg;base64,") == len(images) >= 7
    for alt, img in images.items():
        assert min(img.shape[:2]) >= 100 and max(img.shape[:2]) <= 1000, alt
        assert float(img[..., :3].std()) > 5.0, f"image '{alt}' is (nearly) constant"
    for alt in ("checkerboard", "residual vectors", "check sites", "target with GCPs", "reference with GCPs",
                "warped target"):
        assert alt in images
    # The histogram is a drawing: bars, axes, and the RMSE marked.
    (svg,) = re.findall(r'<img[^>]*?src="data:image/svg\+xml;base64,([A-Za-z0-9+/=]+)"[^>]*?alt="residual histogram"',
                        text)
    chart = ElementTree.fromstring(base64.b64decode(svg))
    ns = "{http://www.w3.org/2000/svg}"
    bars = [r for r in chart.iter(ns + "rect") if r.get("fill") != "#fff"]
    assert len(bars) >= 5 and sum(float(r.get("height")) > 0 for r in bars) >= 2
    assert f"RMSE {sift_result.stats.rmse_px:.2f}" in [t.text for t in chart.iter(ns + "text")]
    assert max(images["reference with GCPs"].shape[:2]) == 800
    # The checkerboard holds tinted target tiles and grey reference tiles.
    board = images["checkerboard"].astype(int)
    tinted = np.abs(board[..., 2] - board[..., 0]) > 8
    assert 0.2 < tinted.mean() < 0.6
    # Residual arrows are coloured; the rest of the image is grey.
    arrows = images["residual vectors"].astype(int)
    assert (np.abs(arrows[..., 2] - arrows[..., 0]) > 60).sum() > 500


def test_gcp_table_is_capped(sift_result, tmp_path):
    text = _write(sift_result, tmp_path)
    omitted = len(sift_result.gcps) - report_sections.MAX_TABLE_ROWS
    assert omitted > 0
    assert f"{omitted} more rows not shown" in text
    assert f"<td class=n>{report_sections.MAX_TABLE_ROWS}</td>" in text
    assert f"<td class=n>{report_sections.MAX_TABLE_ROWS + 1}</td>" not in text


def test_auto_attempts_notes_and_escaping(sift_result, tmp_path):
    auto = AutoRun.of([Attempt("orb", {}, "test", "failed", "<b>no</b> support", 0.5),
                       Attempt("sift", {}, "test", "verified", "verified", 1.25)], 1)
    result = dataclasses.replace(sift_result, auto=auto, notes=["a <script>alert(1)</script> note"])
    text = _write(result, tmp_path)
    assert "Attempts of" in text and "sift <b>(chosen)</b>" in text and "1.25 s" in text
    assert html.escape("<b>no</b> support") in text
    assert "<script>alert" not in text and html.escape("<script>alert(1)</script>") in text


@pytest.fixture(scope="module")
def unverified_result(small_pair):
    """The small pair asked for an accuracy of 0.01 px, which the check cannot confirm."""
    return register(small_pair["target"], small_pair["reference"], method="sift",
                    options=RegisterOptions(tolerance_px=0.01))


def test_unverified_result_shows_its_reasons(unverified_result, tmp_path):
    result = unverified_result
    v = result.verification
    assert not v.verified and v.reasons
    text = _write(result, tmp_path)
    assert re.search(rf"class=word[^>]*>{v.verdict}<", text)
    for reason in v.reasons:
        assert html.escape(reason) in text
    assert "0.01 px" in text


def test_tps_model(small_pair, tmp_path):
    result = register(small_pair["target"], small_pair["reference"], method="sift",
                      options=RegisterOptions(model="tps"))
    assert result.model.kind == "tps" and not hasattr(result.model, "inverse")
    text = _write(result, tmp_path)
    assert "<b>tps</b>" in text and "values (in report.json)" in text
    assert "checkerboard" in _images(text)
    ref = read_preview(result.reference, None)
    warped, ok = warp_to_reference(result.model, read_preview(result.target, None), ref)
    assert ok.mean() > 0.4
    assert np.corrcoef(warped[ok].astype(float), ref.image[ok].astype(float))[0, 1] > 0.8


def test_warp_follows_the_model_to_the_pixel():
    """A translation by (+3, -2) px, as a matrix (exact inverse) and as a polynomial (Newton inverse):
    reference pixel (x, y) shows target pixel (x - 3, y + 2)."""
    rng = np.random.default_rng(0)
    tgt_img = cv2.GaussianBlur(rng.uniform(0, 255, (120, 160)), (0, 0), 2).astype(np.float32)
    tgt = Preview(stretch(tgt_img, np.ones(tgt_img.shape, bool)), np.ones(tgt_img.shape, bool), (1.0, 1.0))
    ref = Preview(np.zeros((100, 140), np.uint8), np.ones((100, 140), bool), (1.0, 1.0))
    src = rng.uniform(0, 160, (20, 2))
    models = [LinearModel("affine", np.array([[1.0, 0, 3], [0, 1, -2], [0, 0, 1]])),
              PolynomialModel.fit(2, src, src + [3.0, -2.0])]
    for model in models:
        warped, ok = warp_to_reference(model, tgt, ref)
        expected = tgt.image[2:102, 0:137]
        assert ok[:, 3:].all() and not ok[:, :3].any()
        assert np.abs(warped[:, 3:].astype(int) - expected.astype(int)).max() <= 1


def test_preview_coordinates_put_pixel_centres_at_integers():
    p = Preview(np.zeros((10, 10), np.uint8), np.ones((10, 10), bool), (2.0, 4.0))
    assert np.allclose(p.to_opencv([[1.0, 2.0], [3.0, 6.0]]), [[0.0, 0.0], [1.0, 1.0]])
    assert np.allclose(p.to_full([[0.5, 0.5]]), [[1.0, 2.0]])


def test_previews_are_read_decimated(raster_writer, monkeypatch):
    import hamta.core.io.windows as windows

    shapes = []
    real = report_preview.read_image

    def spy(info, bands, window=None, out_shape=None, dataset=None):
        shapes.append(out_shape)
        return real(info, bands, window, out_shape, dataset)

    monkeypatch.setattr(report_preview, "read_image", spy)
    monkeypatch.setattr(windows, "read_image", spy)
    rng = np.random.default_rng(1)
    big = open_raster(raster_writer("big.tif", rng.integers(0, 255, (1500, 2400), dtype=np.uint8)))
    p = read_preview(big, None)
    assert shapes[-1] == (500, 800) and p.image.shape == (500, 800) and p.scale == (3.0, 3.0)
    small = open_raster(raster_writer("small.tif", rng.integers(0, 255, (50, 100), dtype=np.uint8)))
    p = read_preview(small, None)
    assert shapes[-1] is None and p.image.shape == (400, 800) and p.scale == (0.125, 0.125)  # read whole


def test_cancel_writes_nothing(sift_result, tmp_path):
    path = tmp_path / "report.html"
    with pytest.raises(RegistrationCanceled):
        write_html_report(str(path), sift_result, Monitor(is_canceled=lambda: True))
    assert not path.exists()


# ---------------------------------------------------------------------------------------------- for the analyst


def _section(text: str, number: int) -> str:
    start = text.index(f"<h2>{number}.")
    end = text.find("<h2>", start + 4)
    return text[start:end if end >= 0 else len(text)]


def _visible(text: str) -> str:
    """The text a reader sees without opening a <details> element: tags, folded parts and images removed."""
    text = re.sub(r"<details.*?</details>", " ", text, flags=re.S)
    text = re.sub(r"<(style|title)>.*?</\1>", " ", text, flags=re.S)
    text = re.sub(r"</?(b|code|span|time)\b[^>]*>", "", text)  # inline: no word break
    return " ".join(html.unescape(re.sub(r"<[^>]+>", " ", text)).split())


def test_crs_map_units_pixel_sizes_and_date(sift_result, tmp_path):
    before = datetime.datetime.now(datetime.timezone.utc).replace(microsecond=0)
    text = _write(sift_result, tmp_path)
    ref, v, rmse = sift_result.reference, sift_result.verification, sift_result.stats.rmse_px
    assert ref.crs.to_epsg() == 32639 and ref.pixel_size == 10.0
    assert "WGS 84 / UTM zone 39N (EPSG:32639)" in text and "unit: metre" in text
    assert "10.00 m per px" in text  # the reference's pixel size
    assert "not georeferenced" in text  # the small pair's target has no georeferencing of its own
    # The target's pixel size as registered: the affine model's scale times the reference's.
    k = np.sqrt(abs(np.linalg.det(np.asarray(sift_result.model.matrix)[:2, :2])))
    assert f"{k * 10:.2f} m per px" in text
    # Residuals in reference px (named), in metres and in target px, side by side.
    assert f"{rmse:.3f} reference px ({rmse * 10:.2f} m, {rmse / k:.3f} target px)" in text
    b, t = v.error_bound_px, v.tolerance_px
    assert f"{b:.2f} reference px ({b * 10:.2f} m, {b / k:.2f} target px)" in text
    assert f"{t:.2f} reference px ({t * 10:.2f} m, {t / k:.2f} target px)" in text
    assert f"{k:.4g} reference px per target px" in text and "on the ground" not in text  # UTM metres are the ground's
    assert "map X (reference CRS, m)" in text and "residual (m)" in text
    assert "Pixel-to-pixel" not in text and "pixel mode" not in text
    stamp = re.search(r'<time datetime="(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)">\1</time>', text)
    assert stamp, "an ISO 8601 UTC date"
    when = datetime.datetime.strptime(stamp.group(1), "%Y-%m-%dT%H:%M:%SZ").replace(tzinfo=datetime.timezone.utc)
    assert before <= when <= datetime.datetime.now(datetime.timezone.utc)


def test_outputs_are_listed_and_file_names_escaped(sift_result, tmp_path, small_pair):
    hostile = '<img src=x onerror="alert(1)"> & co'
    target = tmp_path / f"{hostile}.tif"
    target.symlink_to(small_pair["target"])
    result = dataclasses.replace(sift_result, target=dataclasses.replace(sift_result.target, path=str(target)))
    outputs = {"raster": str(tmp_path / f"{hostile}-registered.tif"), "report": "/out/report.json",
               "html": "/out/report.html"}
    path = tmp_path / "report.html"
    write_html_report(str(path), result, outputs=outputs)
    text = path.read_text(encoding="utf-8")
    assert hostile not in text and "onerror=\"alert" not in text
    assert html.escape(f"{hostile}.tif") in text
    assert f"registered raster: <code>{html.escape(outputs['raster'])}</code>" in text
    assert "report (JSON): <code>/out/report.json</code>" in text
    assert "this report: <code>/out/report.html</code>" in text
    assert "files written" not in _write(sift_result, tmp_path, "plain.html")  # no list without outputs


def test_verification_is_told_in_plain_words(sift_result, tmp_path):
    text = _write(sift_result, tmp_path)
    v = sift_result.verification
    section = _section(text, 4)
    seen = _visible(section)
    assert f"At {v.n_agree} of {v.n_sites} sites checked, the two images line up where the model puts them" in seen
    assert "the agreement is real" in seen
    for jargon in ("lift", "mann", "chance", "zero-offset", "p-value"):
        assert jargon not in _visible(text).lower(), jargon
    # The technical numbers stay available, folded.
    details = re.search(r"<details.*?</details>", section, flags=re.S).group(0)
    assert "Mann–Whitney p" in details and "chance rate per site" in details
    assert f"{v.z_hits} / " in details


def test_unverified_result_is_told_in_plain_words(unverified_result, tmp_path):
    seen = _visible(_write(unverified_result, tmp_path))
    assert "the accuracy asked for was 0.01 reference px (0.10 m, " in seen
    for jargon in ("lift", "mann", "chance"):
        assert jargon not in seen.lower(), jargon


def test_pixel_mode_has_a_banner_and_no_map_units(sift_result, tmp_path):
    reference = dataclasses.replace(sift_result.reference, crs=None, transform=Affine.identity(), georef_source="none")
    result = dataclasses.replace(sift_result, reference=reference)
    assert result.pixel_mode
    text = _write(result, tmp_path)
    banner = re.search(r"<div class=banner>([^<]*)</div>", text)
    assert banner and banner.group(1) == report_html.PIXEL_MODE_BANNER
    assert text.index("class=banner") < text.index("class=verdict")  # near the top
    assert "Pixel-to-pixel registration: the reference has no georeferencing" in banner.group(1)
    assert "reference CRS</th><td>none (pixel mode)" in text
    assert "EPSG" not in text and " m)" not in text and " m per px" not in text and "metre" not in text
    assert "map X (reference px)" in text and "residual (m)" not in text
    rmse = result.stats.rmse_px
    assert f"{rmse:.3f} px</td>" in text


def test_describe_crs_names_code_and_unit():
    assert report_scale.describe_crs(CRS.from_epsg(32632)) == ("WGS 84 / UTM zone 32N (EPSG:32632)", "metre")
    assert report_scale.describe_crs(CRS.from_epsg(4326)) == ("WGS 84 (EPSG:4326)", "degree")
    name, unit = report_scale.describe_crs(CRS.from_proj4("+proj=tmerc +lon_0=13.3 +ellps=GRS80 +units=us-ft"))
    assert name.endswith("(no EPSG code)") and unit == "US survey foot"
    scale = report_scale.MapScale("WGS 84 (EPSG:4326)", "degree", 1e-4)
    assert scale.px(0.5) == "0.000050°"
    assert report_scale.MapScale("x", "US survey foot", 2.0).px(1.25) == "2.50 US ft"


def test_the_swipes_top_layer_shows_the_reference_where_the_target_does_not_reach():
    """A JPEG has no transparency: where the warped target is missing, its layer holds the reference itself,
    not black."""
    from hamta.core.outputs.figures import swipe_top

    rng = np.random.default_rng(2)
    ref = Preview(rng.integers(0, 256, (60, 80)).astype(np.uint8), np.ones((60, 80), bool), (1.0, 1.0))
    warped = rng.integers(0, 256, (60, 80)).astype(np.uint8)
    valid = np.zeros((60, 80), bool)
    valid[10:50, 20:70] = True
    top = swipe_top(ref, warped, valid)
    assert np.array_equal(top[valid], warped[valid]) and np.array_equal(top[~valid], ref.image[~valid])


def _on_web_mercator(result, latitude: float, zoom=None):
    """``result`` with its reference moved into Web Mercator (10 m pixels) so that the target's centre, as
    registered, lies at ``latitude``; read from a basemap at ``zoom`` when given."""
    import math

    cx, cy = result.model.apply(np.array([[result.target.width / 2, result.target.height / 2]]))[0]
    y = 6378137.0 * math.asinh(math.tan(math.radians(latitude)))
    reference = dataclasses.replace(result.reference, crs=CRS.from_epsg(3857),
                                    transform=Affine(10.0, 0.0, 1.0e6, 0.0, -10.0, y + 10.0 * cy))
    service = None if zoom is None else {"service": "XYZ tiles", "zoom": zoom, "fetch": {"requests": 12}}
    return dataclasses.replace(result, reference=reference, reference_service=service)


def test_web_mercator_lengths_are_told_on_the_ground_and_in_target_pixels(sift_result, tmp_path):
    """Web Mercator's metres are cos(latitude) ground metres: at 53° N, 10 of them are 6.02 m."""
    result = _on_web_mercator(sift_result, 53.0, zoom=14)
    cos = np.cos(np.radians(53.0))
    assert report_scale.centre_latitude(result) == pytest.approx(53.0, abs=1e-9)
    assert report_scale.ground_factor(result) == pytest.approx(cos)
    k = report_scale.registered_scale(result)
    assert report_scale.ground_metres(result, 1.0) == pytest.approx(10.0 * cos)
    assert report_scale.target_px(result, 1.0) == pytest.approx(1.0 / k)
    text = _write(result, tmp_path)
    v, rmse = result.verification, result.stats.rmse_px
    assert "WGS 84 / Pseudo-Mercator (EPSG:3857)" in text
    assert f"{10 * cos:.2f} m per px on the ground at 53.0° N (10.00 Web Mercator m)" in text  # the reference
    assert (f"{10 * k * cos:.2f} m per px on the ground ({10 * k:.2f} Web Mercator m; {k:.4g} px of the basemap at "
            "zoom 14 per target px" in text)
    b = v.error_bound_px
    assert f"{b:.2f} px of the basemap at zoom 14 ({b * 10 * cos:.2f} m on the ground, {b / k:.2f} target px)" in text
    assert f"{rmse:.3f} px of the basemap at zoom 14 ({rmse * 10 * cos:.2f} m on the ground, " in text
    assert "residual (m on the ground)" in text and "residual (m)</th>" not in text
    g = result.gcps[0]
    assert f"<td class=n>{g.residual_px * 10 * cos:.2f}</td>" in text
    assert f"{b * 10:.2f} m" not in text.replace(f"{b * 10:.2f} m on", "")  # no Web Mercator metres as lengths


def test_a_length_names_its_pixels_and_the_ground_where_the_crs_is_not_web_mercator(sift_result):
    south = _on_web_mercator(sift_result, -33.9)
    assert report_scale.map_scale(south).px_name == "reference px"
    assert report_html._latitude(report_scale.centre_latitude(south)) == "33.9° S"
    utm = report_scale.map_scale(sift_result)
    assert utm.ground is None and report_scale.ground_metres(sift_result, 2.0) == pytest.approx(20.0)
    assert report_scale.is_web_mercator(CRS.from_epsg(3857))
    assert report_scale.is_web_mercator(CRS.from_proj4("+proj=merc +a=6378137 +b=6378137 +lat_ts=0 +lon_0=0 +x_0=0 "
                                                       "+y_0=0 +k=1 +units=m +nadgrids=@null +wktext +no_defs"))
    assert not any(report_scale.is_web_mercator(CRS.from_epsg(code)) for code in (3395, 32632))
    degrees = dataclasses.replace(sift_result, reference=dataclasses.replace(sift_result.reference,
                                                                             crs=CRS.from_epsg(4326)))
    assert report_scale.ground_metres(degrees, 1.0) is None  # a degree is no one length


def test_a_kept_unverified_result_says_so_and_no_longer_advises_keeping_it(unverified_result, tmp_path):
    path = tmp_path / "report.html"
    write_html_report(str(path), unverified_result, outputs={"raster": "/out/registered.tif", "html": str(path)})
    seen = _visible(path.read_text(encoding="utf-8"))
    assert "Kept anyway ('Keep unverified results')" in seen and "--accept-unverified" not in seen
    seen = _visible(_write(unverified_result, tmp_path, "not-kept.html"))
    assert "Kept anyway" not in seen and "--accept-unverified (QGIS: 'Keep unverified results')" in seen
