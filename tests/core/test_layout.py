"""The package layout's rules: the engine imports nothing outside ``core`` (QGIS and Qt least of all),
and the version has one source."""
import ast
import pathlib
import re
import subprocess
import sys

from hamta.core.result import versions
from hamta.core.version import __version__

REPO = pathlib.Path(__file__).resolve().parents[2]


def _imports(path: pathlib.Path):
    """(absolute module name, line) of every import in ``path``, relative ones resolved."""
    package = ["hamta"] + list(path.relative_to(REPO).parent.parts)
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            yield from ((a.name, node.lineno) for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = package[: len(package) - node.level + 1] if node.level else []
            module = ".".join(base + ([node.module] if node.module else []))
            if node.module is None:  # from . import x
                yield from ((f"{module}.{a.name}", node.lineno) for a in node.names)
            else:
                yield module, node.lineno


def test_core_imports_nothing_outside_core():
    offenders = []
    for path in (REPO / "core").rglob("*.py"):
        for module, line in _imports(path):
            top = module.split(".")[0]
            outside = module.startswith("hamta.") and not module.startswith("hamta.core") or module == "hamta"
            if outside or top in ("qgis", "PyQt5", "PyQt6", "osgeo"):
                offenders.append(f"{path.relative_to(REPO)}:{line} imports {module}")
    assert not offenders, "\n".join(offenders)


BLOCK = """
import importlib.abc, pkgutil, sys

class Block(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in ("qgis", "PyQt5"):
            raise ImportError(f"{name} is blocked in this test")
        return None

sys.meta_path.insert(0, Block())
import hamta.core
for info in pkgutil.walk_packages(hamta.core.__path__, "hamta.core."):
    __import__(info.name)
from hamta.core.methods import all_methods
assert len(all_methods()) > 10
assert not [m for m in sys.modules if m.split(".")[0] in ("qgis", "PyQt5")]
print("ok")
"""


def test_core_imports_with_qgis_and_qt_unimportable():
    proc = subprocess.run([sys.executable, "-P", "-c", BLOCK], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0 and proc.stdout.strip() == "ok", proc.stderr


def test_the_version_has_one_source():
    metadata = (REPO / "metadata.txt").read_text(encoding="utf-8")
    assert re.search(r"^version=(.+)$", metadata, re.M).group(1).strip() == __version__
    assert versions()["hamta"] == __version__
    import hamta

    assert hamta.__version__ == __version__
    from importlib.metadata import version

    assert version("hamta") == __version__


def _module_name(path: pathlib.Path) -> str:
    parts = ["hamta"] + list(path.relative_to(REPO).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def test_no_import_cycles():
    """No cycle among the package's modules, counting imports inside functions too."""
    graph = {}
    for top in ("core", "cli", "bench", "processing", "plugin"):
        for path in (REPO / top).rglob("*.py"):
            tree = ast.parse(path.read_text(), str(path))
            path_imports = []
            for node in ast.walk(tree):
                path_imports.extend(_resolve(node, path))
            name = _module_name(path)
            graph[name] = {m for m in path_imports if m.startswith("hamta.")}
    known = set(graph)
    graph = {m: {_owner(d, known) for d in deps} - {None, m} for m, deps in graph.items()}
    state, cycles = {}, []

    def visit(m, stack):
        state[m] = "open"
        for d in graph.get(m, ()):
            if state.get(d) == "open":
                cycles.append(stack[stack.index(d):] + [d])
            elif d not in state:
                visit(d, stack + [d])
        state[m] = "done"

    for m in sorted(graph):
        if m not in state:
            visit(m, [m])
    assert not cycles, cycles


def _resolve(node, path):
    package = ["hamta"] + list(path.relative_to(REPO).parent.parts)
    if isinstance(node, ast.Import):
        return [a.name for a in node.names]
    if isinstance(node, ast.ImportFrom):
        base = package[: len(package) - node.level + 1] if node.level else []
        module = ".".join(base + ([node.module] if node.module else []))
        return [f"{module}.{a.name}" for a in node.names] + [module]
    return []


def _owner(name, known):
    """The longest known module that ``name`` is or lies in (``pkg.mod.attr`` -> ``pkg.mod``)."""
    while name and name not in known:
        name = name.rpartition(".")[0]
    return name or None


def test_lint_passes_in_a_clone_named_hamta(tmp_path):
    """The README installs from a clone named ``hamta``; ruff then reads the root as package ``hamta``."""
    import shutil

    ruff = shutil.which("ruff", path=str(pathlib.Path(sys.executable).parent))
    if ruff is None:
        import pytest

        pytest.skip("ruff is not installed in this interpreter's environment (the PyPI-wheels half lints)")
    files = subprocess.run(["git", "ls-files"], cwd=REPO, capture_output=True, text=True, check=True).stdout.split()
    clone = tmp_path / "hamta"
    for name in files:
        if name.endswith((".py", ".toml")):
            (clone / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(REPO / name, clone / name)
    run = subprocess.run([ruff, "check", "--no-cache", "."], cwd=clone, capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr


# Inside the package, each unit imports only from units listed before it (a lower layer): the
# engine's folders in data-flow order, then what stands on the engine. Units on one line never
# import each other.
LAYERS = (
    ("core.version", "core.errors", "core.coords", "core.types", "core.outcome", "core.text", "core.learned"),
    ("core.extent",),
    ("core.options", "core.progress", "core.memory", "core.blas", "core.fourier", "core.scratch"),
    ("core.parallel",),
    ("core.io", "core.preprocess", "core.detectors", "core.estimation", "core.basemap", "core.similarity"),
    ("core.descriptors",),
    ("core.matching",),
    ("core.refine", "core.verify"),
    ("core.local", "core.methods", "core.auto", "core.result", "core.advice", "core.order"),
    ("core.pipeline", "core.mapping", "core.outputs", "core.remote_places"),
    ("core.remote", "core.reference", "core.grid"),
    ("core.runner",),
    ("core.batch",),
    ("core",),
    ("bench", "processing"),
    ("cli", "plugin"),
)
RANK = {unit: i for i, layer in enumerate(LAYERS) for unit in layer}


def _unit(module: str):
    """The layer unit of a module: a folder (or top-level module) of ``core``, else a top-level folder."""
    parts = module.split(".")
    if parts[0] != "hamta" or len(parts) < 2:
        return None
    if parts[1] != "core":
        return parts[1]
    inside = len(parts) > 2 and ((REPO / "core" / parts[2]).is_dir() or (REPO / "core" / f"{parts[2]}.py").exists())
    return f"core.{parts[2]}" if inside else "core"


def test_imports_go_down_the_layers_only():
    """Function-level imports included: no unit imports a unit of its own layer or one above it."""
    offenders, unknown = [], set()
    for top in ("core", "cli", "bench", "processing", "plugin"):
        for path in (REPO / top).rglob("*.py"):
            me = _unit(_module_name(path))
            if me not in RANK:
                unknown.add(me)
                continue
            for node in ast.walk(ast.parse(path.read_text(), str(path))):
                for module in _resolve(node, path):
                    other = _unit(module)
                    if other is None or other == me:
                        continue
                    if other not in RANK:
                        unknown.add(other)
                    elif RANK[other] >= RANK[me]:
                        offenders.append(f"{path.relative_to(REPO)}:{node.lineno} ({me}) imports {module} ({other})")
    assert not unknown, f"units missing from LAYERS: {sorted(unknown)}"
    assert not offenders, "\n".join(offenders)


def test_the_check_imports_no_matcher():
    """The independent check shares its similarity measure with the matchers through ``core.similarity`` only:
    no module of ``core/verify`` imports the descriptors, the methods or the matching (function level too)."""
    matchers = ("hamta.core.descriptors", "hamta.core.methods", "hamta.core.matching")
    offenders = [f"{path.relative_to(REPO)}:{line} imports {module}"
                 for path in (REPO / "core" / "verify").rglob("*.py") for module, line in _imports(path)
                 if any(module == m or module.startswith(m + ".") for m in matchers)]
    assert not offenders, "\n".join(offenders)


def test_no_engine_module_is_longer_than_400_lines():
    long = [f"{p.relative_to(REPO)}: {n}" for p in (REPO / "core").rglob("*.py")
            if (n := len(p.read_text().splitlines())) > 400]
    assert not long, long


def test_only_core_reference_tells_kinds_of_reference_text_apart():
    """A map service is told from a raster in :func:`hamta.core.reference.resolve_reference` only."""
    allowed = {REPO / "core" / "reference.py", REPO / "core" / "basemap" / "services.py"}
    offenders = []
    for top in ("core", "cli", "bench", "processing", "plugin"):
        for path in set((REPO / top).rglob("*.py")) - allowed:
            for node in ast.walk(ast.parse(path.read_text(), str(path))):
                names = ([a.name for a in node.names] if isinstance(node, ast.ImportFrom)
                         else [getattr(node, "id", None), getattr(node, "attr", None)])
                if "parse_service" in names:
                    offenders.append(f"{path.relative_to(REPO)}:{node.lineno}")
    assert not offenders, offenders
