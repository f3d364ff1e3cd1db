"""Build the QGIS plugin zip: ``dist/hamta-<version>.zip`` with one top folder, ``hamta/``.

Usage: ``python3 tools/package.py [--out-dir DIR]`` (``make package``). Standard library only.

The files are the ones git tracks (``git ls-files``) that match ``INCLUDE``: the plugin's metadata,
icons and licence, the ``plugin``, ``processing`` and ``core`` packages with the engine's data, and
the compiled translations. Tests, tools, docs, the benchmark and the command line stay out. Files
under an included path that git does not track stop the build (``git add`` or remove them first).
The version comes from ``core/version.py`` and must match ``metadata.txt``.
"""
from __future__ import annotations

import argparse
import ast
import configparser
import fnmatch
import os
import subprocess
import sys
import time
import zipfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TOP = "hamta"  # the plugin's folder name in QGIS, which is also the package name its imports rely on

# (folder, file name pattern, recursive): a tracked file is packaged when one entry matches it.
INCLUDE = (
    ("", "metadata.txt", False),
    ("", "__init__.py", False),
    ("", "*.svg", False),
    ("", "*.png", False),
    ("", "LICENSE*", False),
    ("", "COPYING*", False),
    ("plugin", "*.py", True),
    ("processing", "*.py", True),
    ("core", "*.py", True),
    ("core/descriptors/data", "*.npz", False),
    ("i18n", "*.qm", False),
)


def included(path: str) -> bool:
    """Whether the repository path ``path`` (``/``-separated) belongs in the plugin."""
    folder, _, name = path.rpartition("/")
    if "__pycache__" in path.split("/"):
        return False
    for top, pattern, recursive in INCLUDE:
        in_folder = folder == top or (recursive and folder.startswith(top + "/"))
        if in_folder and fnmatch.fnmatchcase(name, pattern):
            return True
    return False


def git_files(*args: str) -> list:
    try:
        out = subprocess.run(["git", "-C", ROOT, "ls-files", "-z", *args], check=True, capture_output=True).stdout
    except (OSError, subprocess.CalledProcessError) as exc:
        raise SystemExit(f"package: needs git and a git checkout to list the tracked files ({exc})") from None
    return [p for p in out.decode("utf-8").split("\0") if p]


def version() -> str:
    """``__version__`` of core/version.py, read without importing the package."""
    with open(os.path.join(ROOT, "core", "version.py"), encoding="utf-8") as f:
        tree = ast.parse(f.read())
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == "__version__" for t in node.targets):
            return ast.literal_eval(node.value)
    raise SystemExit("package: core/version.py defines no __version__")


def metadata_version() -> str:
    meta = configparser.ConfigParser(interpolation=None)
    meta.read(os.path.join(ROOT, "metadata.txt"), encoding="utf-8")
    return meta.get("general", "version", fallback="")


def commit_time() -> tuple:
    """Timestamp of the files in the zip: the last commit's (the same zip for the same tree)."""
    out = subprocess.run(["git", "-C", ROOT, "log", "-1", "--format=%ct"], capture_output=True, text=True).stdout
    seconds = int(out.strip() or time.time())
    return time.gmtime(max(seconds, 315532800))[:6]  # zip dates start in 1980


def build(out_dir: str) -> str:
    """Write ``<out_dir>/hamta-<version>.zip`` and return its path."""
    v = version()
    if metadata_version() != v:
        raise SystemExit(f"package: metadata.txt says version {metadata_version()!r}, core/version.py {v!r}")
    files = sorted(p for p in git_files() if included(p))
    untracked = sorted(p for p in git_files("--others", "--exclude-standard") if included(p))
    if untracked:  # tracked files may import them: a zip without them could be broken
        raise SystemExit("package: plugin files not tracked by git (git add or remove them first): "
                         + ", ".join(untracked))
    absent = [p for p in files if not os.path.isfile(os.path.join(ROOT, p))]
    if absent:
        raise SystemExit("package: tracked but missing from the working tree: " + ", ".join(absent))
    os.makedirs(out_dir, exist_ok=True)
    target = os.path.join(out_dir, f"{TOP}-{v}.zip")
    partial = target + ".partial"
    stamp = commit_time()
    with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as zf:
        for path in files:
            info = zipfile.ZipInfo(f"{TOP}/{path}", date_time=stamp)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            with open(os.path.join(ROOT, path), "rb") as f:
                zf.writestr(info, f.read())
    os.replace(partial, target)
    return target


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="Build the QGIS plugin zip (Plugins > Install from ZIP).")
    parser.add_argument("--out-dir", default=os.path.join(ROOT, "dist"), help="folder for the zip (default: dist)")
    args = parser.parse_args(argv)
    target = build(args.out_dir)
    with zipfile.ZipFile(target) as zf:
        count = len(zf.namelist())
    print(f"{target}: {count} files, {os.path.getsize(target)} bytes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
