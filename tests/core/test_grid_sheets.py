"""Scanned sheets georeferenced by their own printed grid (issue 56), on the synthetic family of
:mod:`hamta.bench.sheets` (exact truth): every style found to a fraction of a pixel from two rough hints,
a sheet without a grid and contradictory hints refused, and the whole run from the command line."""
import json

import numpy as np
import pytest

from hamta.bench.sheets import SPECS, render
from hamta.cli.main import main
from hamta.core.errors import InputError, InsufficientMatchesError
from hamta.core.grid.sheet import fit_sheet
from hamta.core.mapping import map_points_from_report

BY_NAME = {s.name: s for s in SPECS}


@pytest.fixture(scope="module")
def sheets(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sheets")
    return {s.name: render(s, str(folder)) for s in SPECS}


def _grey(sheet):
    import cv2

    return cv2.imread(sheet.path, cv2.IMREAD_GRAYSCALE)


def _error_px(sheet, fit) -> np.ndarray:
    from pyproj import Transformer

    nodes = sheet.nodes()
    xy = np.column_stack(Transformer.from_crs(sheet.spec.grid_crs, sheet.spec.crs, always_xy=True).transform(*nodes.T))
    return np.hypot(*(fit.to_scan(xy) - sheet.to_scan(nodes)).T)


@pytest.mark.parametrize("name", [s.name for s in SPECS if s.grid])
def test_two_rough_hints_find_the_sheet_s_grid_in_every_style(sheets, name):
    sheet = sheets[name]
    fit = fit_sheet(_grey(sheet), sheet.hints(2, seed=0), sheet.spec.crs, sheet.spec.grid_crs)
    error = _error_px(sheet, fit)
    assert fit.verified, fit.notes
    assert fit.step == pytest.approx(sheet.spec.step)
    assert np.sqrt(np.mean(error ** 2)) < 1.0 and error.max() < 2.5, (error.max(), fit.notes)


def test_a_sheet_without_a_grid_is_refused_saying_so(sheets):
    sheet = sheets["no-grid"]
    hints = np.array([[300.0, 300.0, 500000.0, 5540000.0], [500.0, 310.0, 501000.0, 5540000.0]])
    with pytest.raises((InsufficientMatchesError, InputError), match="No printed grid was found|does not pass through"):
        fit_sheet(_grey(sheet), hints, sheet.spec.crs)


def test_a_hint_typed_one_step_off_is_never_a_verified_result(sheets):
    sheet = sheets["utm-km-lines"]
    hints = sheet.hints(3, seed=1)
    hints[2, 2] += sheet.spec.step
    try:
        fit = fit_sheet(_grey(sheet), hints, sheet.spec.crs)
    except (InputError, InsufficientMatchesError) as exc:
        assert "hint 3" in str(exc) or "No printed grid" in str(exc)
    else:
        assert not fit.verified or np.sqrt(np.mean(_error_px(sheet, fit) ** 2)) < 1.0


def _points(path, hints):
    with open(path, "w") as f:
        f.write("mapX,mapY,sourceX,sourceY,enable,dX,dY,residual\n")
        for x, y, gx, gy in hints:
            f.write(f"{gx},{gy},{x},{-y},1,0,0,0\n")


def test_the_command_line_georeferences_a_sheet_by_its_grid(sheets, tmp_path):
    import rasterio
    from pyproj import Transformer

    sheet = sheets["graticule-on-utm"]
    _points(tmp_path / "hints.points", sheet.hints(2, seed=3))
    out = tmp_path / "out"
    rc = main(["register", "--target", sheet.path, "--crs", "EPSG:32633", "--gcps", str(tmp_path / "hints.points"),
               "--out", str(out), "--quiet"])
    assert rc == 0
    report = json.loads((out / "report.json").read_text())
    assert report["method"] == "grid" and report["quality"]["verdict"] == "verified"
    assert report["quality"]["check"] == "grid-held-out-lines"
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
    rc = main(["register", "--target", sheet.path, "--crs", "EPSG:4326", "--gcps", str(tmp_path / "hints.points"),
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


needs_tesseract = pytest.mark.skipif(not __import__("shutil").which("tesseract"),
                                     reason="Tesseract is not installed (Debian: tesseract-ocr; make sysdeps)")


@needs_tesseract
@pytest.mark.parametrize("name", ["utm-km-labelled", "graticule-labelled"])
def test_a_labelled_sheet_is_georeferenced_with_no_hint(sheets, name, tmp_path):
    sheet = sheets[name]
    out = tmp_path / "out"
    assert main(["register", "--target", sheet.path, "--crs", sheet.spec.crs, "--out", str(out), "--quiet"]) == 0
    report = json.loads((out / "report.json").read_text())
    assert report["quality"]["verdict"] == "verified" and report["diagnostics"]["grid"]["labels"]["used"]
    from pyproj import Transformer

    nodes = sheet.nodes()
    truth = np.column_stack(Transformer.from_crs(sheet.spec.grid_crs, sheet.spec.crs, always_xy=True)
                            .transform(*nodes.T))
    got = np.array([r["map"] for r in map_points_from_report(str(out / "report.json"), sheet.to_scan(nodes))])
    assert np.hypot(*(got - truth).T).max() < 3.0 * sheet.spec.pixel_m  # a label misread would move it by a step


def test_labels_are_parsed_as_degrees_minutes_or_metres():
    from hamta.core.grid.labels import parse

    assert parse("44°27'") == pytest.approx((44.45, "degrees", ""))
    assert parse("146°") == (146.0, "degrees", "")
    assert parse("72°N") == (72.0, "degrees", "N")
    assert parse("30’") == (30.0, "minutes", "")
    assert parse("6785000") == (6785000.0, "metres", "")
    assert parse("Coast") is None and parse("61'") is None and parse("400°") is None


def test_labels_that_contradict_the_others_are_named_and_left_out_and_one_full_value_is_not_enough():
    from hamta.core.grid.labels import Label, hints_from_labels

    top = [Label(f"{500000 + v * 1000}", 500000.0 + v * 1000, "metres", "", (100.0 + 200 * v, 20.0), "top")
           for v in range(5)]
    left = [Label(f"{6000000 + v * 1000}", 6000000.0 + v * 1000, "metres", "", (20.0, 900.0 - 200 * v), "left")
            for v in range(5)]
    wrong = Label("509000", 509000.0, "metres", "", (300.0, 980.0), "bottom")
    hints, named = hints_from_labels(top + left + [wrong], 1000, 1000, geographic=False)
    assert named == ["'509000' at (300, 980)"]
    np.testing.assert_allclose(hints[0], [100.0, 900.0, 500000.0, 6000000.0], atol=1e-6)
    # kilometres abbreviated ('03') on one full value (a digit lost in reading it would move every line) are refused
    short = [Label(f"{v:02d}", float(v), "metres", "", (100.0 + 200 * v, 20.0), "top") for v in range(1, 5)]
    with pytest.raises(InsufficientMatchesError, match="top and bottom"):
        hints_from_labels(top[:1] + short + left, 1000, 1000, geographic=False)


def test_without_tesseract_and_hints_the_message_says_what_to_install(sheets, tmp_path, monkeypatch, capsys):
    monkeypatch.setattr("hamta.core.grid.labels.TESSERACT", "no-such-tesseract")
    sheet = sheets["utm-km-labelled"]
    rc = main(["register", "--target", sheet.path, "--crs", sheet.spec.crs, "--out", str(tmp_path / "o"), "--quiet"])
    assert rc != 0 and "tesseract-ocr" in capsys.readouterr().err


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
