"""A wheel built from the repository installs whole: the CLI registers and the benchmark runs from it."""
import json
import os
import pathlib
import subprocess
import sys
import zipfile

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
pytestmark = pytest.mark.packaging


def _run(cmd, **kw):
    proc = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, timeout=1200, **kw)
    assert proc.returncode == 0, f"{cmd}\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
    return proc


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """A fresh virtual environment with the wheel built from this repository (not editable)."""
    root = tmp_path_factory.mktemp("wheel")
    _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q", "-w", root / "dist",
          REPO])
    wheel = next((root / "dist").glob("hamta-*.whl"))
    venv = root / "venv"
    _run([sys.executable, "-m", "venv", venv])
    env = dict(os.environ, PIP_DISABLE_PIP_VERSION_CHECK="1")
    _run([venv / "bin" / "python", "-m", "pip", "install", "-q", wheel], env=env)
    return wheel, venv


def test_the_wheel_carries_every_package_and_data_file(installed):
    wheel, _ = installed
    names = set(zipfile.ZipFile(wheel).namelist())
    for package in ("core", "core/methods", "core/estimation", "cli", "bench", "bench/reproductions", "processing",
                    "plugin"):
        assert f"hamta/{package}/__init__.py" in names, package
    for source in REPO.rglob("*.py"):
        rel = source.relative_to(REPO)
        if rel.parts[0] in ("core", "cli", "bench", "processing", "plugin"):
            assert f"hamta/{rel.as_posix()}" in names, rel
    assert {"hamta/metadata.txt", "hamta/core/descriptors/data/pca_sift_basis.npz"} <= names
    assert not any(n.startswith("hamta/tests/") for n in names)


def test_installed_cli_registers_and_benchmarks(installed, tmp_path, demo_pair, shared):
    _, venv = installed
    hamta = venv / "bin" / "hamta"
    cwd = tmp_path  # away from the repository, so nothing is imported from the checkout
    out = tmp_path / "out"
    _run([hamta, "register", "--reference", demo_pair["reference"], "--target", demo_pair["target"], "--out", out,
          "--quiet"], cwd=cwd)
    report = json.loads((out / "report.json").read_text())
    assert report["method"] == "sift" and report["stats"]["n_gcps"] >= 20
    assert str(venv) in _run([venv / "bin" / "python", "-c", "import hamta; print(hamta.__file__)"], cwd=cwd).stdout
    bench = tmp_path / "bench"
    _run([hamta, "bench", "--quick", "--families", "rotation", "--methods", "sift", "--jobs", "1", "--no-reproductions",
          "--out", bench, "--data", shared / "data", "--quiet"], cwd=cwd)
    summary = json.loads((bench / "bench.json").read_text())["summary"]
    assert summary["rotation"]["sift"]["success_rate"] == 1.0
