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


def declared_distributions() -> dict:
    """The installed distributions hamta's declared dependencies need (transitively, extras left out)."""
    from importlib import metadata

    from packaging.requirements import Requirement
    from packaging.utils import canonicalize_name

    found, todo = {}, list(metadata.requires("hamta"))
    while todo:
        req = Requirement(todo.pop())
        if req.marker is not None and not req.marker.evaluate({"extra": ""}):
            continue
        if canonicalize_name(req.name) not in found:
            dist = metadata.distribution(req.name)
            found[canonicalize_name(req.name)] = dist
            todo += dist.requires or []
    return found


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """A fresh virtual environment with the wheel built from this repository (not editable) and, of this
    environment's packages, only those the wheel's declared dependencies need: links to their files in a
    folder the new environment reads (installing them again took 45 s of the suite)."""
    root = tmp_path_factory.mktemp("wheel")
    _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q", "-w", root / "dist",
          REPO])
    wheel = next((root / "dist").glob("hamta-*.whl"))
    venv = root / "venv"
    _run([sys.executable, "-m", "venv", "--without-pip", venv])
    deps = root / "deps"
    deps.mkdir()
    for dist in declared_distributions().values():
        for top in {f.parts[0] for f in dist.files or ()}:
            source = pathlib.Path(dist.locate_file(top))
            if source.exists() and not (deps / top).exists() and source.parent.name == "site-packages":
                (deps / top).symlink_to(source)
    site = next((venv / "lib").glob("python*/site-packages"))
    (site / "declared-dependencies.pth").write_text(f"{deps}\n")
    env = dict(os.environ, PIP_DISABLE_PIP_VERSION_CHECK="1")
    _run([sys.executable, "-m", "pip", "--python", venv / "bin" / "python", "install", "-q", "--no-deps", wheel],
         env=env)
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
