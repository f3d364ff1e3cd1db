"""``hamta bench``: the quick run as a smoke test with real assertions, and the table logic."""
import json
import os

import numpy as np
import pytest

from hamta.bench.families import DEFAULT_FAMILIES, build_case, family_specs
from hamta.bench.runner import BenchConfig
from hamta.bench.tables import summarise
from hamta.cli.main import main


@pytest.mark.bench
def test_quick_bench_runs_every_family_and_the_baselines_succeed_on_easy_cases(tmp_path, shared, capsys, monkeypatch):
    monkeypatch.setenv("HAMTA_LEARNED", "0")  # the same bench in both halves; the extra's figures come from make bench
    out, sar = tmp_path / "bench", tmp_path / "speckle"
    # the methods this test asserts on, beside SIFT (ND-SIFT on the SAR-like family it is for); the others (auto,
    # cfog, xmodal, rilbp, sibrif, shift) have tests of their own, and make bench runs them all
    assert main(["bench", "--quick", "--methods", "orb,phasecorr", "--jobs", "2", "--out", str(out), "--data",
                 str(shared / "data"), "--quiet"]) == 0
    printed = capsys.readouterr().out
    assert main(["bench", "--quick", "--methods", "ndsift-pc", "--families", "speckle", "--no-reproductions", "--jobs",
                 "2", "--out", str(sar), "--data", str(shared / "data"), "--quiet"]) == 0
    report = json.loads((out / "bench.json").read_text())
    summary = report["summary"]
    speckle = json.loads((sar / "bench.json").read_text())["summary"]["speckle"]
    assert set(summary) == set(DEFAULT_FAMILIES)
    assert {"sift", "orb", "phasecorr"} <= set(summary["rotation"])
    for family in ("rotation", "scale", "affine", "overlap", "georeferenced"):
        s = summary[family]["sift"]
        assert s["success_rate"] == 1.0 and s["median_rmse_cp"] < 0.3, (family, s)
        assert s["median_precision"] > 0.9
    assert summary["rotation"]["orb"]["success_rate"] == 1.0
    assert speckle["ndsift-pc"]["median_rmse_cp"] < 0.5  # the 1-look SAR-like case
    assert "bfsift" not in speckle  # paper baselines belong to full runs
    assert summary["overlap"]["phasecorr"]["success_rate"] == 1.0  # a pure shift (plus < 10 degrees rotation)
    assert summary["rotation"]["phasecorr"]["success_rate"] == 0.0  # no rotation invariance, honestly reported
    mt = next(r for r in report["cases"] if r["case"] == "multitemporal" and r["method"] == "sift")
    assert mt["success"] and mt["rmse_cp"] < 1.0  # the real pair's ground truth is good to ~0.7 px
    assert all(r["time_s"] > 0 and r["peak_rss_mb"] > 0 for r in report["cases"])
    assert "time / SIFT" in printed and (out / "bench.md").read_text().startswith("# hamta bench")


def test_cases_are_deterministic(tmp_path, shared):
    spec = family_specs("speckle", quick=True)[0]
    a = build_case(spec, str(tmp_path / "a"), 256, str(shared / "data"))
    b = build_case(spec, str(tmp_path / "b"), 256, str(shared / "data"))
    assert open(a.target, "rb").read() == open(b.target, "rb").read()
    assert (a.check_points == b.check_points).all()


def test_summary_counts_failures_once_and_ratios_per_case():
    rows = [
        {"family": "f", "case": "a", "method": "sift", "success": True, "rmse_cp": 0.2, "ncm": 10, "precision": 1.0,
         "time_s": 2.0, "peak_rss_mb": 100},
        {"family": "f", "case": "b", "method": "sift", "success": True, "rmse_cp": 0.4, "ncm": 8, "precision": 0.8,
         "time_s": 4.0, "peak_rss_mb": 100},
        {"family": "f", "case": "a", "method": "x", "success": True, "rmse_cp": 0.1, "ncm": 5, "precision": 0.5,
         "time_s": 1.0, "peak_rss_mb": 50},
        {"family": "f", "case": "b", "method": "x", "success": False, "rmse_cp": 40.0, "ncm": 0, "precision": 0.0,
         "time_s": 1.0, "peak_rss_mb": 50},
    ]
    s = summarise(rows, ["sift", "x"])["f"]
    assert s["x"]["success_rate"] == 0.5 and s["x"]["median_rmse_cp"] == 0.1  # the failure is not averaged in
    assert s["x"]["time_ratio_to_sift"] == pytest.approx(0.375)  # median of 1/2 and 1/4
    assert s["sift"]["median_rmse_cp"] == pytest.approx(0.3)
    assert s["x"]["hardest_third_success"] == 0.0 and s["sift"]["hardest_third_success"] == 1.0  # case b


def test_bad_selection_is_rejected():
    with pytest.raises(ValueError, match="unknown family"):
        BenchConfig(families=("nope",)).resolved()
    with pytest.raises(ValueError, match="unknown method 'nope'"):
        BenchConfig(methods=("nope",)).resolved()


def test_default_data_folder_is_beside_the_repository(shared, monkeypatch):
    from hamta.bench.families import default_data_dir

    monkeypatch.delenv("HAMTA_SHARED_DATA", raising=False)
    assert os.path.samefile(default_data_dir(), shared / "data")


def test_a_bug_in_a_method_is_a_crash_not_a_failure():
    import re
    from types import SimpleNamespace

    from hamta.bench.metrics import judge
    from hamta.bench.tables import text_tables
    from hamta.core.errors import InsufficientMatchesError, MethodCrashed

    crash = MethodCrashed("x", ValueError("bad shapes"))
    no_model = InsufficientMatchesError("only 2 matches", 2, 8)
    should_fail = SimpleNamespace(truth=None)  # nothing to find: no model is a success, a crash never is
    assert judge(should_fail, error=no_model)["success"] and not judge(should_fail, error=no_model)["crashed"]
    row = judge(should_fail, error=crash)
    assert row["crashed"] and not row["success"] and row["error"].startswith("MethodCrashed: internal error in method")
    rows = [dict(row, family="f", case=c, method=m, rmse_cp=None, time_s=1.0, peak_rss_mb=10)
            for c in ("a", "b") for m in ("sift", "x")]
    rows[0].update(crashed=False, success=True)
    summary = summarise(rows, ["sift", "x"])
    assert summary["f"]["x"]["n_crashed"] == 2 and summary["f"]["sift"]["n_crashed"] == 1
    report = {"summary": summary, "cases": rows, "meta": {"duration_s": 1.0, "notes": []}}
    header, _, sift, x = [re.split(r"\s{2,}", line.strip()) for line in text_tables(report).splitlines()[2:6]]
    assert (sift[header.index("crashes")], x[header.index("crashes")]) == ("1", "2")


@pytest.mark.bench
def test_the_speed_study_times_hamta_and_the_opencv_script_on_a_small_pair(tmp_path, shared, monkeypatch):
    """One repeat of the speed family's small-optical case: both run in fresh processes, both models scored."""
    from types import SimpleNamespace

    from hamta.bench.goals import speed

    monkeypatch.setattr(speed, "REPEATS", 1)
    config = SimpleNamespace(out_dir=str(tmp_path), data_dir=str(shared / "data"))
    row, = speed.run_unit(("small-optical", "mm-optical/1"), config)
    assert row["exit"] == 0 and row["method"] == "sift" and row["error_px"] < 15
    assert row["peer"] == "OpenCV script" and row["peer_s"] > 0 and row["peer_error_px"] < 15
    assert row["hamta_s"] > row["registration_s"] > 0


def test_the_neutral_residual_measures_a_georeferencing_left_off(landsat, tmp_path):
    """INTER1's judge: the shift a corrected raster leaves against the reference, by neither tool's figures."""
    import rasterio
    from affine import Affine

    from hamta.bench.goals.speed import residual

    with rasterio.open(landsat) as ds:
        profile, data = ds.profile, ds.read()
    for shift, name in (((0.0, 0.0), "same.tif"), ((1.2, -0.9), "off.tif")):
        moved = dict(profile, transform=profile["transform"] * Affine.translation(*shift))
        with rasterio.open(tmp_path / name, "w", **moved) as out:
            out.write(data)
    assert residual(landsat, str(tmp_path / "same.tif"), side=128) < 0.05
    assert abs(residual(landsat, str(tmp_path / "off.tif"), side=128) - 1.5) < 0.15


def test_the_years_apart_study_scores_a_moved_georeferencing_against_the_files_own(shared, tmp_path, monkeypatch):
    """The years-apart family: the target file copied with only its geotransform moved by the pair's offset, the
    truth from the file's own georeferencing (the moved file's lies that offset away); a model off by a known
    offset scored as that offset, in reference px; a real pair (NAIP 2016 onto 2014) registered and scored."""
    from types import SimpleNamespace

    import rasterio

    import hamta.core
    from hamta.bench.goals import years_apart

    config = SimpleNamespace(out_dir=str(tmp_path), data_dir=str(shared / "data"), methods=["auto"], quick=False)
    i = 4
    name, reference_name, (dx, dy) = years_apart.PAIRS[i]
    source = str(shared / "data" / "timeseries" / name)
    reference = str(shared / "data" / "timeseries" / reference_name)
    moved = years_apart.moved_target(i, config.data_dir, str(tmp_path))
    with rasterio.open(source) as a, rasterio.open(moved) as b:
        assert (b.read() == a.read()).all() and b.colorinterp == a.colorinterp and b.crs == a.crs
        assert b.transform == a.transform * rasterio.Affine.translation(dx, dy)
    pts, truth = years_apart.truth_points(source, source)
    assert abs(truth - pts).max() < 1e-6
    pts, truth = years_apart.truth_points(moved, reference)
    assert abs(truth - years_apart.truth_points(source, reference)[1] - [dx, dy]).max() < 1e-6

    rows = []
    for off in ((0.5, -0.25), (0.3, 0.0)):
        model = SimpleNamespace(apply=lambda p, off=off: years_apart.truth_points(source, reference)[1] + off)
        found = SimpleNamespace(method="stand-in", model=model, verification=SimpleNamespace(verdict="verified",
                                                                                         error_bound_px=0.7))
        monkeypatch.setattr(hamta.core, "run", lambda *args, **kwargs: (found, {}), raising=False)
        row, = years_apart.run_unit((i, "auto"), config)
        assert row["offset_px"] == pytest.approx(off) and row["rms_px"] == pytest.approx(np.hypot(*off))
        rows.append(row)
    assert years_apart.tables(rows)[0]["title"].endswith("verified within 0.5 px: auto 1 of 2")
    monkeypatch.undo()

    row, = years_apart.run_unit((i, "auto"), config)
    assert row["case"] == "naip_20160816-onto-20140720" and row["method_used"] != "stand-in"
    assert row["verdict"] == "verified" and row["rms_px"] < 1.0
