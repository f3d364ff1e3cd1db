"""The ``hamta`` command line, through its console script and its ``main`` function."""
import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

from hamta.cli.main import main
from hamta.core.estimation.models import model_from_dict


def test_register_writes_every_output_and_prints_them(tmp_path, small_pair, capsys):
    out = tmp_path / "out"
    rc = main(["register", "--reference", small_pair["reference"], "--target", small_pair["target"], "--method", "sift",
               "--model", "affine", "--out", str(out), "--vrt", "--quiet"])
    assert rc == 0
    printed = capsys.readouterr().out
    for name in ("registered.tif", "gcps.points", "gcps.gpkg", "gcps.vrt", "report.json"):
        assert (out / name).is_file() and name in printed
    report = json.loads((out / "report.json").read_text())
    assert report["method"] == "sift" and report["outputs"]["raster"].endswith("registered.tif")


def test_outputs_writes_only_what_is_asked_for(tmp_path, small_pair, capsys, monkeypatch):
    import hamta.core.outputs as outputs

    def not_asked(*args, **kwargs):
        raise AssertionError("an output nobody asked for was computed")

    monkeypatch.setattr(outputs, "write_html_report", not_asked)
    monkeypatch.setattr(outputs, "write_gcp_layer", not_asked)
    out = tmp_path / "out"
    rc = main(["register", "--reference", small_pair["reference"], "--target", small_pair["target"], "--method", "sift",
               "--out", str(out), "--outputs", "raster,report", "--quiet"])
    assert rc == 0
    assert sorted(p.name for p in out.iterdir() if not p.name.startswith(".")) == ["registered.tif", "report.json"]
    rc = main(["register", "--reference", small_pair["reference"], "--target", small_pair["target"], "--out", str(out),
               "--outputs", "raster,html5", "--quiet"])
    assert rc == 2 and "unknown output(s) html5" in capsys.readouterr().err


@pytest.mark.parametrize("model", ["affine", "tps"])
def test_map_points_uses_the_stored_model(tmp_path, small_pair, capsys, model):
    out = tmp_path / model
    main(["register", "--reference", small_pair["reference"], "--target", small_pair["target"], "--model", model,
          "--out", str(out), "--outputs", "report", "--quiet"])
    capsys.readouterr()
    assert main(["map-points", str(out / "report.json"), "10", "20", "250.5", "200.25", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    report = json.loads((out / "report.json").read_text())
    ref = model_from_dict(report["model"]).apply([[10, 20], [250.5, 200.25]])  # inside the 304 x 280 px target
    assert np.allclose([r["reference_px"] for r in rows], ref)
    gt = report["reference"]["transform"]  # GDAL order: c, a, b, f, d, e
    x, y = rows[1]["reference_px"]
    assert rows[1]["map"] == pytest.approx([gt[0] + gt[1] * x + gt[2] * y, gt[3] + gt[4] * x + gt[5] * y])


def test_errors_exit_nonzero_with_a_message(tmp_path, small_pair, capsys):
    rc = main(["register", "--reference", small_pair["reference"], "--target", str(tmp_path / "nope.tif"),
               "--out", str(tmp_path / "o"), "--quiet"])
    assert rc == 1 and "target raster" in capsys.readouterr().err
    rc = main(["register", "--reference", small_pair["reference"], "--target", small_pair["target"], "--model",
               "wobbly", "--out", str(tmp_path / "o"), "--quiet"])
    assert rc == 2 and "unknown model" in capsys.readouterr().err


def test_a_value_error_during_the_work_is_an_internal_error_not_a_usage_error(tmp_path, small_pair, monkeypatch,
                                                                            capsys):
    """Exit 2 says the command line was wrong, checked before any work; a ValueError from the work is a bug."""
    from hamta.core import runner

    def broken(*args, **kwargs):
        raise ValueError("math domain error")

    monkeypatch.setattr(runner, "register", broken)
    args = ["register", "--reference", small_pair["reference"], "--target", small_pair["target"], "--out",
            str(tmp_path / "o"), "--quiet"]
    assert main(args) == 1
    err = capsys.readouterr().err
    assert "internal error (ValueError: math domain error)" in err and "HAMTA_DEBUG=1" in err, err
    monkeypatch.setenv("HAMTA_DEBUG", "1")
    with pytest.raises(ValueError, match="math domain error"):  # the traceback, for a report
        main(args)
    monkeypatch.delenv("HAMTA_DEBUG")
    assert main(args + ["--param", "nonsense=1", "--method", "sift"]) == 2
    assert "no parameter" in capsys.readouterr().err


def test_former_method_name_still_works(tmp_path, demo_pair, capsys):
    out = tmp_path / "o"
    rc = main(["register", "--reference", demo_pair["reference"], "--target", demo_pair["target"], "--method",
               "lines-spectral", "--param", "max_rotation_deg=20", "--out", str(out), "--quiet"])
    assert rc == 0
    assert json.loads((out / "report.json").read_text())["method"] == "cfog"


def test_methods_is_a_short_table_and_verbose_lists_parameters(capsys):
    assert main(["methods"]) == 0
    out = capsys.readouterr().out.splitlines()
    rows = {line.split()[0]: line for line in out[1:] if line.strip() and not line.startswith("'")}
    assert out[0].split() == ["method", "kind", "when", "to", "use"] and "auto" in rows and "xmodal" in rows
    assert len(out) < 40 and "--param" not in rows["sift"]
    assert main(["methods", "--verbose"]) == 0
    assert "--param ratio=0.8" in capsys.readouterr().out


def test_version(capsys):
    from hamta.core.version import __version__

    assert main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == f"hamta {__version__}"


def test_console_script_is_installed_and_shows_progress(tmp_path, small_pair):
    exe = shutil.which("hamta", path=os.path.dirname(sys.executable))
    assert exe, "the 'hamta' console script is not installed next to this interpreter"
    proc = subprocess.run([exe, "register", "--reference", small_pair["reference"], "--target", small_pair["target"],
                           "--out", str(tmp_path / "o")], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    assert "100%" in proc.stderr and "registered.tif" in proc.stdout


def test_demo_reports_the_true_error(tmp_path, capsys):
    assert main(["demo", "--out", str(tmp_path / "demo"), "--quiet"]) == 0
    out = capsys.readouterr().out
    line = next(x for x in out.splitlines() if x.startswith("TRUE check-point error"))
    rmse = float(line.split("RMSE ")[1].split(" px")[0])
    assert rmse < 0.5
    assert (tmp_path / "demo" / "result" / "registered.tif").is_file()


def test_an_unverified_result_exits_3_and_writes_only_its_report(tmp_path, small_pair, capsys):
    out = tmp_path / "strict"
    rc = main(["register", "--reference", small_pair["reference"], "--target", small_pair["target"], "--method", "sift",
               "--tolerance", "0.01", "--out", str(out), "--quiet"])
    captured = capsys.readouterr()
    assert rc == 3 and "NOT VERIFIED" in captured.out and "No georeferenced output" in captured.err
    assert "(--accept-unverified)" in captured.err
    tips = captured.err.split("options that may help:")[1]
    assert "--model polynomial-2:" in tips and "--local:" in tips and "--accept-unverified:" in tips
    assert sorted(p.name for p in out.iterdir() if not p.name.startswith(".")) == ["report.html", "report.json"]
    assert "What may help:</div>" in (out / "report.html").read_text() and "--local (QGIS:" in (
        out / "report.html").read_text()
    report = json.loads((out / "report.json").read_text())
    assert report["quality"]["verdict"] != "verified" and report["quality"]["reasons"]


def test_accept_unverified_writes_the_outputs_with_the_verdict_in_them(tmp_path, small_pair, capsys):
    import rasterio

    out = tmp_path / "kept"
    rc = main(["register", "--reference", small_pair["reference"], "--target", small_pair["target"], "--method", "sift",
               "--tolerance", "0.01", "--accept-unverified", "--vrt", "--out", str(out), "--quiet"])
    assert rc == 3
    err = capsys.readouterr().err
    assert "--local:" in err and "--accept-unverified:" not in err  # it was given
    with rasterio.open(out / "registered.tif") as ds:
        assert ds.tags()["HAMTA_VERDICT"] in ("suspect", "failed") and "HAMTA_VERDICT_REASONS" in ds.tags()
    with rasterio.open(out / "gcps.vrt") as ds:
        assert ds.tags()["HAMTA_VERDICT"] in ("suspect", "failed")
    assert "NOT VERIFIED" in (out / "gcps.gpkg").read_bytes().decode("latin-1")


def test_auto_is_the_default_and_lists_what_it_tried(tmp_path, small_pair, capsys):
    rc = main(["register", "--reference", small_pair["reference"], "--target", small_pair["target"], "--out",
               str(tmp_path / "a"), "--quiet"])
    printed = capsys.readouterr().out
    assert rc == 0 and "* tried sift: verified" in printed and "result: verified" in printed


def test_a_reference_without_georeferencing_needs_pixel_mode(tmp_path, small_pair, capsys):
    import cv2
    import rasterio

    with rasterio.open(small_pair["reference"]) as ds:
        plain = str(tmp_path / "plain.png")
        cv2.imwrite(plain, ds.read().transpose(1, 2, 0)[:, :, ::-1])
    out = tmp_path / "o"
    rc = main(["register", "--reference", plain, "--target", small_pair["target"], "--method", "sift", "--out",
               str(out), "--quiet"])
    err = capsys.readouterr().err
    assert rc == 1 and "plain.png' has no georeferencing" in err and "--pixel-mode" in err and not out.exists()
    rc = main(["register", "--reference", plain, "--target", small_pair["target"], "--method", "sift", "--out",
               str(out), "--quiet", "--pixel-mode"])
    printed = capsys.readouterr().out
    assert rc == 0 and "pixel-to-pixel registration" in printed
    with rasterio.open(out / "registered.tif") as ds:
        assert ds.crs is None and "no CRS" in ds.tags()["HAMTA_PIXEL_MODE"]
    assert (out / "gcps.points").read_text().startswith("#CRS: \n")
    assert "Pixel-to-pixel" in (out / "report.html").read_text()
    assert json.loads((out / "report.json").read_text())["reference"]["pixel_mode"] is True


def test_the_counts_add_up(tmp_path, small_pair, capsys):
    rc = main(["register", "--reference", small_pair["reference"], "--target", small_pair["target"], "--method", "sift",
               "--out", str(tmp_path / "o"), "--quiet"])
    line = next(t for t in capsys.readouterr().out.splitlines() if "GCPs" in t)
    report = json.loads((tmp_path / "o" / "report.json").read_text())["stats"]
    words = line.split(": ", 1)[1].split()
    kept, pool = int(words[0]), int(words[4])
    assert rc == 0 and kept == report["n_gcps"] <= pool


def test_a_bug_in_a_method_is_an_internal_error_naming_it(tmp_path, small_pair, raising_method, monkeypatch, capsys):
    from hamta.core import auto
    from hamta.core.errors import MethodCrashed

    name = raising_method(ValueError("operands could not be broadcast"))
    args = ["register", "--reference", small_pair["reference"], "--target", small_pair["target"], "--out",
            str(tmp_path / "o"), "--quiet"]
    assert main(args + ["--method", name]) == 1
    assert f"hamta: internal error in method '{name}' (ValueError: operands could not" in capsys.readouterr().err
    monkeypatch.setattr(auto, "CHAIN", (auto.Step(name, {}, "test"), auto.Step("sift", {}, "test")))
    assert main(args) == 1  # 'auto' stops there: sift, which would verify, does not run
    err = capsys.readouterr().err
    assert f"internal error in method '{name}'" in err and "HAMTA_DEBUG=1" in err and not (tmp_path / "o").exists()
    monkeypatch.setenv("HAMTA_DEBUG", "1")
    with pytest.raises(MethodCrashed) as info:  # the original traceback is the cause
        main(args + ["--method", name])
    assert isinstance(info.value.__cause__, ValueError)
