"""``make test`` on a machine without the development data: CI fails at once, a user is told in one line."""
import os
import pathlib
import subprocess
import sys

REPO = pathlib.Path(__file__).resolve().parents[2]
NEEDS_DATA = "tests/core/test_working.py::test_pixel_mode_without_reference_georeferencing"


def _pytest(tmp_path, require: str):
    env = dict(os.environ, HAMTA_SHARED=str(tmp_path / "nowhere"), HAMTA_REQUIRE_DATA=require)
    return subprocess.run([sys.executable, "-P", "-m", "pytest", NEEDS_DATA, "-q", "-rs", "-p", "no:cacheprovider"],
                          cwd=REPO, env=env, capture_output=True, text=True, timeout=120)


def test_ci_fails_when_the_data_is_missing(tmp_path):
    run = _pytest(tmp_path, "1")
    assert run.returncode == 4, run.stdout + run.stderr
    assert f"development data not found at {tmp_path / 'nowhere'}/data" in run.stderr + run.stdout


def test_a_user_is_told_in_one_line_what_was_skipped(tmp_path):
    run = _pytest(tmp_path, "0")
    assert run.returncode == 0, run.stdout + run.stderr
    assert "SKIPPED" in run.stdout  # -rs lists each skip with its reason
    assert f"hamta: development data not found at {tmp_path / 'nowhere'}/data (set HAMTA_SHARED); 1 tests skipped" \
        in run.stdout
