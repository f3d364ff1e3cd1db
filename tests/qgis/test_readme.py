"""The README's headless block, run as printed: a checkout, a sample where ``make demo`` writes it (the demo's
make at 400 px), a fresh home with no QGIS profile yet, and a bare environment (no virtual environment, no
display)."""
import json
import pathlib
import re
import shutil
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
MARKER = "<!-- headless: tests/qgis/test_readme.py runs this block as printed -->"


BASEMAP_MARKER = "<!-- headless basemap: tests/qgis/test_readme.py runs this block as printed, after the one above -->"


def headless_block(marker: str = MARKER) -> str:
    text = (REPO / "README.md").read_text()
    return re.search(re.escape(marker) + r"\n```\n(.*?)```", text, re.S).group(1)


def checkout(folder: pathlib.Path) -> pathlib.Path:
    """A copy of this checkout's files (tracked and new) as a fresh git repository."""
    listed = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"], cwd=REPO,
                            capture_output=True, text=True, check=True).stdout.split("\n")
    for name in filter(None, listed):
        if (REPO / name).is_file():
            (folder / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(REPO / name, folder / name)
    for args in (["init", "-q"], ["add", "-A"]):
        subprocess.run(["git", *args], cwd=folder, check=True)
    return folder


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("qgis_process.bin", path="/usr/bin:/bin") is None, reason="qgis_process is not "
                    "installed")
def test_the_headless_block_runs_as_printed(tmp_path):
    from hamta.bench.sample import make_demo_pair

    repo = checkout(tmp_path / "hamta")
    make_demo_pair(str(repo / "demo-output" / "sample"), side=400)  # the README reads it; its size only costs time
    home = tmp_path / "home"
    (home / "xdg").mkdir(mode=0o700, parents=True)
    env = {"PATH": "/usr/bin:/bin", "HOME": str(home), "XDG_RUNTIME_DIR": str(home / "xdg")}
    proc = subprocess.run(["bash", "-e", "-c", headless_block()], cwd=repo, env=env, capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    assert "Traceback" not in proc.stderr
    for name in ("registered.tif", "gcps.gpkg", "report.json", "report.html"):
        assert (repo / "qgis-output" / name).is_file(), name
    assert (home / ".local/share/QGIS/QGIS3/profiles/default/python/plugins/hamta/metadata.txt").is_file()

    proc = subprocess.run(["bash", "-e", "-c", headless_block(BASEMAP_MARKER)], cwd=repo, env=env, capture_output=True,
                          text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    report = json.loads((repo / "qgis-output" / "on-tiles.json").read_text())
    assert report["quality"]["verdict"] == "verified" and (repo / "qgis-output" / "on-tiles.tif").is_file()
    assert report["reference"]["service"]["kind"] == "xyz"
