"""The plugin zip: what it holds, that it installs into a fresh QGIS profile and runs under
``qgis_process`` exactly as a user would, and that a missing Python package is reported, not raised.

Every QGIS process here gets a bare environment (``env -i`` style: PATH, the offscreen platform and
private XDG/profile folders only), so nothing from the test's virtual environment leaks into QGIS.
"""
import configparser
import importlib.util
import json
import os
import pathlib
import shutil
import subprocess
import sys
import zipfile

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
QGIS_PROCESS = shutil.which("qgis_process.bin", path="/usr/bin:/bin")  # /usr/bin/qgis_process passes a bad option
QGIS_PYTHON = "/usr/bin/python3"  # the interpreter QGIS embeds on Debian
UNZIP = pathlib.Path("/usr/share/qgis/python/pyplugin_installer/unzip.py")  # what "Install from ZIP" runs

slow = pytest.mark.slow  # make test runs these too

BLOCK_CV2 = '''\
import sys


class BlockCv2:
    """Makes 'import cv2' fail as it does where OpenCV is not installed."""

    def find_spec(self, name, path=None, target=None):
        if name == "cv2" or name.startswith("cv2."):
            raise ImportError("No module named 'cv2'", name=name)
        return None


sys.meta_path.insert(0, BlockCv2())
'''

LOAD_PLUGIN = '''\
import json
import sys

from qgis.core import Qgis, QgsApplication
from qgis.PyQt.QtCore import QCoreApplication

QCoreApplication.setOrganizationName(QgsApplication.QGIS_ORGANIZATION_NAME)
QCoreApplication.setApplicationName(QgsApplication.QGIS_APPLICATION_NAME)
app = QgsApplication([], False)
app.initQgis()
log = []
QgsApplication.messageLog().messageReceived.connect(lambda msg, tag, level: log.append([tag, int(level), msg]))
sys.path.insert(0, sys.argv[1])  # the profile's plugins folder, where "Install from ZIP" put the plugin


class MessageBar:
    def __init__(self):
        self.messages = []

    def pushMessage(self, title, text, show_more, level, duration):
        self.messages.append([title, text, show_more, int(level), duration])


class Iface:
    def __init__(self):
        self.bar = MessageBar()

    def messageBar(self):
        return self.bar

    def mainWindow(self):
        return None

    def __getattr__(self, name):  # addToolBarIcon, addPluginToRasterMenu, ... and their removal: no-ops
        return lambda *args: None


import hamta  # noqa: E402

out = {}
registry = QgsApplication.processingRegistry()
plugin = hamta.classFactory(None)  # as qgis_process does: no iface
plugin.initProcessing()
provider = registry.providerById("hamta")
out["provider"] = provider is not None
out["warning"] = provider.warningMessage()
out["algorithms"] = {a.id(): [a.displayName(), *a.canExecute()] for a in provider.algorithms()}
out["engine_imported"] = "hamta.core" in sys.modules
plugin.unload()
out["removed"] = registry.providerById("hamta") is None
QgsApplication.processEvents()
out["log_without_iface"] = list(log)

iface = Iface()
plugin = hamta.classFactory(iface)  # as the QGIS window does
plugin.initGui()
QgsApplication.processEvents()
out["log"] = log
out["message_bar"] = iface.bar.messages
out["warning_level"] = int(Qgis.Warning)
plugin.unload()
print("RESULT " + json.dumps(out))
'''


def bare_env(home, **extra):
    """The environment a user's QGIS would see: nothing from this test process (no venv, no PYTHONPATH)."""
    env = {"PATH": "/usr/bin:/bin", "QT_QPA_PLATFORM": "offscreen"}
    for key, sub in (("XDG_RUNTIME_DIR", "xdg"), ("XDG_CONFIG_HOME", "config"), ("XDG_CACHE_HOME", "cache")):
        (home / sub).mkdir(mode=0o700, exist_ok=True)
        env[key] = str(home / sub)
    env.update(extra)
    return env


def run(args, env, timeout=120):
    return subprocess.run([str(a) for a in args], env=env, capture_output=True, text=True, timeout=timeout)


@pytest.fixture(scope="module")
def plugin_zip(tmp_path_factory):
    out = tmp_path_factory.mktemp("dist")
    proc = run([sys.executable, REPO / "tools" / "package.py", "--out-dir", out], dict(os.environ))
    assert proc.returncode == 0, proc.stderr
    (path,) = out.glob("*.zip")
    return path


@pytest.fixture(scope="module")
def profile(plugin_zip, tmp_path_factory):
    """A fresh QGIS profile root with the zip installed the way Plugins > Install from ZIP does it."""
    home = tmp_path_factory.mktemp("qgis_home")
    plugins = home / "profile" / "profiles" / "default" / "python" / "plugins"
    if UNZIP.is_file():
        spec = importlib.util.spec_from_file_location("qgis_plugin_unzip", UNZIP)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        module.unzip(str(plugin_zip), str(plugins))
    else:
        plugins.mkdir(parents=True)
        with zipfile.ZipFile(plugin_zip) as zf:
            zf.extractall(plugins)
    return home


def test_zip_holds_the_plugin_and_nothing_else(plugin_zip):
    from hamta.core.version import __version__

    assert plugin_zip.name == f"hamta-{__version__}.zip"
    with zipfile.ZipFile(plugin_zip) as zf:
        names = zf.namelist()
        assert zf.testzip() is None
    assert all(n.startswith("hamta/") for n in names)
    tops = {n.split("/")[1] for n in names}
    assert tops <= {"metadata.txt", "__init__.py", "icon.svg", "plugin", "processing", "core", "i18n", "LICENSE"}
    for required in ("metadata.txt", "__init__.py", "icon.svg", "plugin/plugin.py", "processing/provider.py",
                     "processing/register_algorithm.py", "core/version.py", "core/descriptors/data/pca_sift_basis.npz",
                     "i18n/hamta_fa.qm", "i18n/hamta_en.qm"):
        assert f"hamta/{required}" in names
    for name in names:
        parts = name.split("/")
        assert not {"tests", "bench", "cli", "tools", "docs", ".venv", ".venv-qgis", "__pycache__", ".git"} & set(parts)
        assert not name.endswith((".pyc", ".ts")) and parts[-1] != "core_strings.py", name
    tracked = subprocess.run(["git", "-C", str(REPO), "ls-files"], capture_output=True, text=True, check=True).stdout
    assert {n[len("hamta/"):] for n in names} <= set(tracked.split("\n")), "only git-tracked files are packaged"


def test_metadata_declares_its_range_and_no_placeholder():
    meta = configparser.ConfigParser()  # QGIS reads metadata.txt with the default (interpolating) parser
    meta.read(REPO / "metadata.txt", encoding="utf-8")
    general = meta["general"]
    assert (general["qgisMinimumVersion"], general["qgisMaximumVersion"]) == ("3.22", "3.99")
    assert general["hasProcessingProvider"] == "yes"
    for key in ("homepage", "tracker", "repository", "email"):
        assert "example." not in general.get(key, ""), key
    assert "independent check" in general["about"] and "python3-opencv" in general["about"]
    assert general["changelog"].startswith(general["version"])


def test_message_for_missing_packages_names_them_and_how_to_install():
    from hamta.processing.provider import DEBIAN_COMMAND, REQUIREMENTS, missing_message

    message = missing_message([(req, "ImportError: No module named x") for req in REQUIREMENTS])
    assert "numpy, scipy, opencv, rasterio, pyproj, shapely" in message
    assert DEBIAN_COMMAND in message
    assert "select python3-numpy, python3-scipy, python3-rasterio, python3-pyproj, python3-shapely" in message
    assert 'OSGeo4W Shell and run: python -m pip install "opencv-python-headless<4.11"' in message
    assert ('/Applications/QGIS.app/Contents/MacOS/bin/python3 -m pip install numpy scipy '
            '"opencv-python-headless<4.11" rasterio pyproj shapely') in message
    only_rasterio = missing_message([(REQUIREMENTS[3], "ImportError: x")])
    assert "lacks rasterio." in only_rasterio and "opencv-python" not in only_rasterio


def test_unavailable_stand_ins_match_the_real_algorithms(provider):
    from hamta.processing.catalogue import algorithm_entries

    listed = sorted((e.id, e.title) for e in algorithm_entries())
    assert listed == sorted((a.name(), a.displayName()) for a in provider.algorithms())
    assert provider.unavailable is None and provider.warningMessage() == ""


@slow
@pytest.mark.skipif(QGIS_PROCESS is None, reason="qgis_process is not installed")
def test_installed_zip_runs_under_qgis_process(profile, small_pair, tmp_path):
    env = bare_env(profile, QGIS_CUSTOM_CONFIG_PATH=str(profile / "profile"))
    enable = run([QGIS_PROCESS, "plugins", "enable", "hamta"], env)
    assert enable.returncode == 0, enable.stdout + enable.stderr
    assert "* hamta" in enable.stdout
    output, report = tmp_path / "o.tif", tmp_path / "r.json"
    proc = run([QGIS_PROCESS, "run", "hamta:registersift", "--", f"TARGET={small_pair['target']}",
                f"REFERENCE={small_pair['reference']}", f"OUTPUT={output}", f"REPORT={report}"], env)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "Traceback" not in proc.stderr
    assert output.is_file() and output.stat().st_size > 0
    assert json.loads(report.read_text())["method"] == "sift"


@slow
def test_plugin_loads_without_opencv(profile, tmp_path):
    block = tmp_path / "block"
    block.mkdir()
    (block / "sitecustomize.py").write_text(BLOCK_CV2)
    script = tmp_path / "script" / "load_plugin.py"
    script.parent.mkdir()
    script.write_text(LOAD_PLUGIN)
    plugins = profile / "profile" / "profiles" / "default" / "python" / "plugins"
    env = bare_env(tmp_path, PYTHONPATH=str(block), QGIS_CUSTOM_CONFIG_PATH=str(tmp_path / "profile"))
    proc = run([QGIS_PYTHON, script, plugins], env)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "Traceback" not in proc.stderr, proc.stderr
    out = json.loads(proc.stdout.split("RESULT ", 1)[1])
    assert out["provider"] and out["removed"] and not out["engine_imported"]
    assert "missing opencv" in out["warning"]
    assert "hamta:registerauto" in out["algorithms"] and "hamta:registersift" in out["algorithms"]
    for name, (display, ok, message) in out["algorithms"].items():
        assert not ok and "(unavailable: missing opencv)" in display
        assert "lacks opencv" in message and "sudo apt install python3-opencv python3-rasterio" in message
        assert "opencv-python-headless&lt;4.11" in message and "/Applications/QGIS.app" in message
    hamta_log = [entry for entry in out["log"] if entry[0] == "Hamta"]
    assert len([e for e in out["log_without_iface"] if e[0] == "Hamta"]) == 1
    assert len(hamta_log) == 2 and hamta_log[0][1] == out["warning_level"]  # once per load, without and with iface
    assert "sudo apt install python3-opencv" in hamta_log[0][2]
    (bar,) = out["message_bar"]
    assert bar[0] == "Hamta" and "cannot run" in bar[1] and "python3-opencv" in bar[2]
    assert bar[3] == out["warning_level"] and bar[4] == 0  # a warning that stays until dismissed


@slow
@pytest.mark.skipif(QGIS_PROCESS is None, reason="qgis_process is not installed")
def test_qgis_process_without_opencv_lists_the_provider_and_explains(profile, small_pair, tmp_path):
    block = tmp_path / "block"
    block.mkdir()
    (block / "sitecustomize.py").write_text(BLOCK_CV2)
    config = tmp_path / "profile"
    shutil.copytree(profile / "profile", config)
    (config / "profiles" / "default" / "QGIS").mkdir(parents=True, exist_ok=True)
    (config / "profiles" / "default" / "QGIS" / "QGIS3.ini").write_text("[PythonPlugins]\nhamta=true\n")
    env = bare_env(tmp_path, PYTHONPATH=str(block), QGIS_CUSTOM_CONFIG_PATH=str(config))
    listing = run([QGIS_PROCESS, "list"], env)
    assert listing.returncode == 0, listing.stderr
    assert "Traceback" not in listing.stderr and "error starting plugin" not in listing.stdout + listing.stderr
    assert "hamta:registersift\tRegister raster (SIFT baseline) (unavailable: missing opencv)" in listing.stdout
    proc = run([QGIS_PROCESS, "run", "hamta:registersift", "--", f"TARGET={small_pair['target']}",
                f"REFERENCE={small_pair['reference']}", f"OUTPUT={tmp_path / 'o.tif'}"], env)
    assert proc.returncode == 1 and "Traceback" not in proc.stderr
    assert "ERROR:\tHamta cannot run: QGIS's Python lacks opencv." in proc.stderr
    assert "sudo apt install python3-opencv" in proc.stderr and not (tmp_path / "o.tif").exists()
