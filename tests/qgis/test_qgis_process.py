"""Headless batch use: the plugin as QGIS installs it, run by ``qgis_process``.

Debian's /usr/bin/qgis_process wrapper passes --noversioncheck, which QGIS 3.22 rejects, so the
binary ``qgis_process.bin`` is called (see QGIS_NOTES.md).
"""
import json
import os
import shutil
import subprocess

import pytest

REPO = __import__("pathlib").Path(__file__).resolve().parents[2]

QGIS_PROCESS = shutil.which("qgis_process.bin") or shutil.which("qgis_process")
pytestmark = pytest.mark.skipif(QGIS_PROCESS is None, reason="qgis_process is not installed")


@pytest.fixture(scope="module")
def qgis_env(tmp_path_factory):
    """An isolated QGIS profile with Hamta installed (as a folder named 'hamta') and enabled."""
    home = tmp_path_factory.mktemp("qgis_process")
    plugins = home / "plugins"
    plugins.mkdir()
    (plugins / "hamta").symlink_to(REPO, target_is_directory=True)
    profile = home / "profile"
    ini = profile / "profiles" / "default" / "QGIS"
    ini.mkdir(parents=True)
    (ini / "QGIS3.ini").write_text("[PythonPlugins]\nhamta=true\n")
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen", QGIS_CUSTOM_CONFIG_PATH=str(profile),
               QGIS_PLUGINPATH=str(plugins), XDG_RUNTIME_DIR=str(home), XDG_CONFIG_HOME=str(home / "config"),
               XDG_CACHE_HOME=str(home / "cache"))
    for key in ("PYTHONPATH", "VIRTUAL_ENV"):  # QGIS embeds Debian's python3 with Debian's packages only
        env.pop(key, None)
    os.chmod(home, 0o700)
    return env


def _qgis_process(env, *args, timeout=300):
    return subprocess.run([QGIS_PROCESS, *args], env=env, capture_output=True, text=True, timeout=timeout)


def test_qgis_process_lists_the_algorithm(qgis_env):
    proc = _qgis_process(qgis_env, "--json", "list")
    assert proc.returncode == 0, proc.stderr
    algs = json.loads(proc.stdout)["providers"]["hamta"]["algorithms"]
    assert "hamta:registersift" in algs


def test_qgis_process_run_writes_outputs(qgis_env, small_pair, tmp_path):
    out = {"OUTPUT": tmp_path / "reg.tif", "GCP_LAYER": tmp_path / "gcps.gpkg",
           "GCP_POINTS": tmp_path / "gcps.points", "REPORT": tmp_path / "report.json"}
    proc = _qgis_process(qgis_env, "--json", "run", "hamta:registersift", "--",
                         f"TARGET={small_pair['target']}", f"REFERENCE={small_pair['reference']}", "MODEL=1",
                         *[f"{k}={v}" for k, v in out.items()])
    assert proc.returncode == 0, proc.stderr
    results = json.loads(proc.stdout)["results"]
    for key, path in out.items():
        assert results[key] == str(path) and path.is_file()
    assert results["N_GCPS"] >= 50


def test_qgis_process_reports_bad_input(qgis_env, small_pair, tmp_path):
    proc = _qgis_process(qgis_env, "run", "hamta:registersift", "--", f"TARGET={small_pair['target']}",
                         f"REFERENCE={small_pair['target']}", "TARGET_GEOREF=1", f"OUTPUT={tmp_path / 'o.tif'}")
    assert proc.returncode == 1
    assert "has no georeferencing" in proc.stderr and not (tmp_path / "o.tif").exists()


def test_qgis_process_takes_an_xyz_layer_and_an_extent(qgis_env, xyz_source, crop, search_area, tmp_path):
    target, extent = crop[0], search_area
    env = dict(qgis_env, HAMTA_CACHE=str(tmp_path / "cache"))
    proc = subprocess.run([QGIS_PROCESS, "--json", "run", "hamta:registerauto", "--", f"TARGET={target}",
                           f"REFERENCE=wms://{xyz_source}", f"EXTENT={extent}",
                           f"OUTPUT={tmp_path / 'reg.tif'}"], env=env, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["results"]["VERDICT"] == "verified"
    assert (tmp_path / "reg.tif").is_file()


def test_qgis_process_georeferences_a_sheet_by_its_grid(qgis_env, tmp_path):
    from hamta.bench.sheets import SPECS, render

    spec = next(s for s in SPECS if s.name == "graticule-lambert-conic")
    sheet = render(spec, str(tmp_path))
    hints = tmp_path / "hints.points"
    hints.write_text("mapX,mapY,sourceX,sourceY,enable,dX,dY,residual\n" + "".join(
        f"{gx},{gy},{x},{-y},1,0,0,0\n" for x, y, gx, gy in sheet.hints(3, seed=0)))
    proc = _qgis_process(qgis_env, "--json", "run", "hamta:georeferencebygrid", "--", f"TARGET={sheet.path}",
                         "SHEET_CRS=EPSG:2154", f"HINTS={hints}", f"OUTPUT={tmp_path / 'sheet.tif'}",
                         f"REPORT={tmp_path / 'report.json'}")
    assert proc.returncode == 0, proc.stderr
    results = json.loads(proc.stdout)["results"]
    assert results["VERDICT"] == "verified" and (tmp_path / "sheet.tif").is_file()
