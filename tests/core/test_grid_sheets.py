"""Scanned sheets georeferenced by their own printed grid (issue 56), on the synthetic family of
:mod:`hamta.bench.sheets` (exact truth): every style found to a fraction of a pixel from two rough hints,
a sheet without a grid and contradictory hints refused, and the whole run from the command line."""
import json

import numpy as np
import pytest

from hamta.bench.sheets import SPECS, render
from hamta.cli.main import main
from hamta.core.mapping import map_points_from_report

BY_NAME = {s.name: s for s in SPECS}


@pytest.fixture(scope="module")
def sheets(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sheets")
    return {s.name: render(s, str(folder)) for s in SPECS}


def _run(sheet, hints, output_crs=None, paths=None, accept=False):
    """The sheet georeferenced by its grid as a user runs it (the printed coordinates' CRS given, the output in
    ``output_crs``)."""
    from hamta.core import run
    from hamta.core.options import OutputOptions

    return run(sheet.path, None, paths, method="grid", params={"hints": hints, "sheet_crs": sheet.spec.grid_crs},
               output=OutputOptions(crs=output_crs), accept_unverified=accept)


def _error_px(sheet, result) -> np.ndarray:
    """Scan px between where the result puts each crossing's printed coordinates and where it is printed."""
    from pyproj import CRS, Transformer

    from hamta.core.estimation.inverse import invert_model

    nodes = sheet.nodes()
    crs = CRS.from_user_input(result.reference.crs.to_wkt())
    xy = np.column_stack(Transformer.from_crs(sheet.spec.grid_crs, crs, always_xy=True).transform(*nodes.T))
    frame_px = np.column_stack((~result.reference.transform) * (xy[:, 0], xy[:, 1]))
    got, _ = invert_model(result.model, frame_px, (result.target.width, result.target.height))
    return np.hypot(*(got - sheet.to_scan(nodes)).T)


@pytest.mark.split
@pytest.mark.parametrize("name", [s.name for s in SPECS if s.grid])
def test_two_rough_hints_find_the_sheet_s_grid_in_every_style(sheets, name):
    sheet = sheets[name]
    result, _ = _run(sheet, sheet.hints(2, seed=0))
    error = _error_px(sheet, result)
    assert result.verified, result.verification.reasons
    ratios = np.array(sheet.spec.step) / np.array(result.params["step"])  # the printed step, or a faint grid's half
    assert np.allclose(ratios, np.round(ratios)) and set(np.round(ratios)) <= {1.0, 2.0}, result.params["step"]
    assert np.sqrt(np.mean(error ** 2)) < 1.0 and error.max() < 2.5, (error.max(), result.notes)


def test_a_sheet_without_a_grid_is_refused_and_its_report_says_what_was_tried(sheets, tmp_path):
    from hamta.core.errors import Refused
    from hamta.core.outputs import OutputPaths

    sheet = sheets["no-grid"]
    hints = np.array([[300.0, 300.0, 500000.0, 5540000.0], [500.0, 310.0, 501000.0, 5540000.0]])
    with pytest.raises(Refused, match="No printed grid was found|does not pass through") as caught:
        _run(sheet, hints, paths=OutputPaths.in_folder(str(tmp_path / "out")))
    report = json.loads((tmp_path / "out" / "report.json").read_text())
    assert report["outcome"] == "refused" and report["findings"]["lattices"] and report["findings"]["hints"]
    assert "Lattices tried" in (tmp_path / "out" / "report.html").read_text()
    assert caught.value.written["report"].endswith("report.json") and not (tmp_path / "out" / "registered.tif").exists()


def test_a_hint_typed_one_step_off_is_never_a_verified_result(sheets):
    from hamta.core.errors import HamtaError, UnverifiedResult

    sheet = sheets["utm-km-lines"]
    hints = sheet.hints(3, seed=1)
    hints[2, 2] += sheet.spec.step
    try:
        result, _ = _run(sheet, hints)
    except UnverifiedResult:
        return
    except HamtaError as exc:
        assert "hint 3" in str(exc) or "No printed grid" in str(exc) or "too few" in str(exc)
    else:
        assert np.sqrt(np.mean(_error_px(sheet, result) ** 2)) < 1.0


def _points(path, hints):
    with open(path, "w") as f:
        f.write("mapX,mapY,sourceX,sourceY,enable,dX,dY,residual\n")
        for x, y, gx, gy in hints:
            f.write(f"{gx},{gy},{x},{-y},1,0,0,0\n")


def test_the_command_line_georeferences_a_sheet_by_its_grid(sheets, tmp_path):
    """Degrees printed on a UTM sheet: --sheet-crs says what they count in, --crs the output's CRS."""
    import rasterio
    from pyproj import Transformer

    sheet = sheets["graticule-on-utm"]
    _points(tmp_path / "hints.points", sheet.hints(2, seed=3))
    out = tmp_path / "out"
    rc = main(["register", "--target", sheet.path, "--sheet-crs", "EPSG:4326", "--crs", "EPSG:32633", "--gcps",
               str(tmp_path / "hints.points"), "--out", str(out), "--quiet"])
    assert rc == 0
    report = json.loads((out / "report.json").read_text())
    assert report["method"] == "grid" and report["quality"]["verdict"] == "verified"
    assert report["quality"]["check"] == "grid-held-out-lines" and report["quality"]["lines_held_out"]["x"] >= 3
    assert "chance_probability" not in report["quality"] and "peak" not in str(report["quality"]["sites"][:1])
    nodes = sheet.nodes()
    truth = np.column_stack(Transformer.from_crs("EPSG:4326", "EPSG:32633", always_xy=True).transform(*nodes.T))
    with rasterio.open(out / "registered.tif") as ds:
        assert ds.crs.to_epsg() == 32633
        pixel_m = abs(ds.transform.a)
    x, y = sheet.to_scan(nodes)[0]
    assert main(["map-points", str(out / "report.json"), str(x), str(y), "--json"]) == 0
    got = np.array([r["map"] for r in map_points_from_report(str(out / "report.json"), sheet.to_scan(nodes))])
    assert np.hypot(*(got - truth).T).max() < 2.5 * pixel_m
    assert (out / "gcps.points").read_text().count("\n") > 8


def test_a_graticule_given_in_degrees_alone_is_written_in_the_projection_it_is_drawn_in(sheets, tmp_path):
    sheet = sheets["mercator-chart"]
    result, _ = _run(sheet, sheet.hints(2, seed=0))
    assert result.verified and result.reference.crs.is_projected  # a cylinder: Mercator, or plate carrée so near
    assert result.diagnostics["grid"]["plane"] in ("Mercator", "equirectangular")  # the equator that they are alike
    assert np.sqrt(np.mean(_error_px(sheet, result) ** 2)) < 1.0


def test_the_command_line_asks_for_the_sheet_s_crs_and_refuses_hints_beside_a_reference(sheets, tmp_path, capsys):
    sheet = sheets["utm-km-lines"]
    _points(tmp_path / "hints.points", sheet.hints(2, seed=0))
    rc = main(["register", "--target", sheet.path, "--gcps", str(tmp_path / "hints.points"), "--out",
               str(tmp_path / "a"), "--quiet"])
    assert rc != 0 and "needs the sheet's CRS" in capsys.readouterr().err
    rc = main(["register", "--target", sheet.path, "--reference", sheet.path, "--gcps", str(tmp_path / "hints.points"),
               "--out", str(tmp_path / "b"), "--quiet"])
    assert rc != 0 and "leave out --reference" in capsys.readouterr().err


def test_metres_typed_for_a_sheet_in_degrees_are_refused_saying_which_they_look_like(sheets, tmp_path, capsys):
    sheet = sheets["utm-km-lines"]
    _points(tmp_path / "hints.points", sheet.hints(2, seed=0))
    rc = main(["register", "--target", sheet.path, "--sheet-crs", "EPSG:4326", "--gcps", str(tmp_path / "hints.points"),
               "--out", str(tmp_path / "c"), "--quiet"])
    assert rc != 0 and "look like metres" in capsys.readouterr().err


def test_a_palette_raster_is_read_as_the_brightness_of_its_colours(tmp_path):
    import rasterio

    from hamta.core.io.raster import open_raster, read_image, resolve_bands

    index = np.array([[0, 1], [2, 1]], np.uint8)
    path = tmp_path / "palette.tif"
    with rasterio.open(path, "w", driver="GTiff", width=2, height=2, count=1, dtype="uint8") as ds:
        ds.write(index, 1)
        ds.write_colormap(1, {0: (255, 255, 255, 255), 1: (0, 0, 0, 255), 2: (255, 0, 0, 255)})
    info = open_raster(str(path))
    image, _ = read_image(info, resolve_bands(info, None))
    np.testing.assert_allclose(image, [[255.0, 0.0], [0.299 * 255, 0.0]], atol=0.01)


ENGINES = [name for name in ("tesseract", "rapidocr")]


def _engine_installed(name) -> bool:
    from hamta.core.grid import ocr

    return (ocr.tesseract() if name == "tesseract" else ocr._rapid()) is not None


@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("name", ["utm-km-labelled", "graticule-labelled"])
def test_a_labelled_sheet_is_georeferenced_with_no_hint(sheets, name, engine, tmp_path, monkeypatch):
    if not _engine_installed(engine):
        pytest.skip(f"the OCR engine {engine} is not installed here (make test installs Tesseract on both stacks, "
                    "RapidOCR on the PyPI-wheels one)")
    monkeypatch.setenv("HAMTA_OCR", engine)
    sheet = sheets[name]
    out = tmp_path / "out"
    rc = main(["register", "--target", sheet.path, "--sheet-crs", sheet.spec.grid_crs, "--crs", sheet.spec.crs,
               "--out", str(out), "--quiet"])
    assert rc == 0
    report = json.loads((out / "report.json").read_text())
    labels = report["quality"]["labels"]
    assert report["quality"]["verdict"] == "verified" and min(labels["x"]["lines_agreeing"],
                                                              labels["y"]["lines_agreeing"]) >= 2
    from pyproj import Transformer

    nodes = sheet.nodes()
    truth = np.column_stack(Transformer.from_crs(sheet.spec.grid_crs, sheet.spec.crs, always_xy=True)
                            .transform(*nodes.T))
    got = np.array([r["map"] for r in map_points_from_report(str(out / "report.json"), sheet.to_scan(nodes))])
    assert np.hypot(*(got - truth).T).max() < 3.0 * sheet.spec.pixel_m  # a label misread would move it by a step


def test_without_an_ocr_engine_and_hints_the_refusal_says_what_to_install(sheets, tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("HAMTA_TESSERACT", "no-such-tesseract")
    monkeypatch.setattr("hamta.core.grid.ocr.tesseract", lambda: None)
    monkeypatch.setattr("hamta.core.grid.ocr._rapid", lambda: None)
    sheet = sheets["utm-km-labelled"]
    rc = main(["register", "--target", sheet.path, "--sheet-crs", sheet.spec.crs, "--out", str(tmp_path / "o"),
               "--quiet"])
    err = capsys.readouterr().err
    assert rc == 1 and "tesseract-ocr" in err and "rapidocr_onnxruntime" in err
    report = json.loads((tmp_path / "o" / "report.json").read_text())
    assert report["outcome"] == "refused" and report["findings"]["labels"]["engine_available"] is False


def test_a_map_drawn_from_water_puts_its_lakes_on_the_water_it_was_drawn_from(shared, tmp_path):
    """The truth of the scanned maps 'onto a reference' (:mod:`hamta.bench.water_map`): the lake pixels of the
    scan, taken to NAIP px by the truth, land on open water; two NAIP px off, clearly fewer do."""
    import cv2

    from hamta.bench.water_map import draw, naip, water

    data = str(shared / "data")
    sheet = draw(data, "20160816", str(tmp_path / "map.jpg"), 4.0, -20.0)
    b, g, r = (cv2.imread(sheet.path)[..., i].astype(int) for i in range(3))
    ys, xs = np.nonzero((b > 200) & (r < 170) & (g > 180))
    pick = np.random.default_rng(0).choice(len(xs), 2000, replace=False)
    at = np.floor(sheet.to_reference(np.column_stack([xs[pick], ys[pick]]) + 0.5)).astype(int)
    wet = water(naip(data, "20160816")[0])
    assert wet[at[:, 1], at[:, 0]].mean() > 0.99
    assert wet[at[:, 1], at[:, 0] + 2].mean() < 0.97


def test_a_map_series_in_one_batch_one_verdict_per_sheet(sheets, tmp_path):
    """``hamta batch SHEETS/ --sheet-crs CRS`` with no reference: each sheet by its grid, its hints from the
    Georeferencer's ``.points`` beside it; a sheet with no grid is refused in its own folder, with its report."""
    import shutil
    import sqlite3

    folder = tmp_path / "series"
    folder.mkdir()
    for name, seed in (("utm-km-lines", 2), ("utm-km-crosses", 3)):
        sheet = sheets[name]
        shutil.copy(sheet.path, folder / f"{name}.tif")
        _points(folder / f"{name}.tif.points", sheet.hints(2, seed=seed))
    blank = folder / "blank.tif"
    import rasterio

    with rasterio.open(blank, "w", driver="GTiff", width=600, height=400, count=1, dtype="uint8") as dst:
        dst.write(np.full((1, 400, 600), 235, np.uint8))
    out = tmp_path / "out"
    rc = main(["batch", str(folder), "--sheet-crs", "EPSG:32633", "--out", str(out), "--workers", "1", "--quiet"])
    assert rc == 1  # one sheet refused
    with sqlite3.connect(out / "batch.gpkg") as con:
        rows = dict(con.execute("SELECT name, status FROM pairs").fetchall())
    assert rows == {"blank": "failed", "utm-km-crosses": "verified", "utm-km-lines": "verified"}
    assert json.loads((out / "blank" / "report.json").read_text())["outcome"] == "refused"
    for name in ("utm-km-lines", "utm-km-crosses"):
        report = json.loads((out / name / "report.json").read_text())
        assert report["method"] == "grid" and report["quality"]["verdict"] == "verified"
