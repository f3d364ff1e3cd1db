"""The method registry: names, aliases, parameters, and the run's seed reaching every method."""
import dataclasses
import inspect
import subprocess
import sys

import numpy as np
import pytest

from hamta.core import RegisterOptions, register
from hamta.core import methods as registry
from hamta.core.methods import all_methods, get_method, method_aliases


def test_every_method_takes_the_seed():
    for name, method in all_methods().items():
        assert "seed" in inspect.signature(method.match).parameters, name


def test_former_names_resolve_to_the_renamed_method():
    assert method_aliases() == {"lines-spectral": "cfog"}
    assert get_method("lines-spectral") is get_method("cfog")
    assert "lines-spectral" not in all_methods()
    with pytest.raises(ValueError, match="unknown method 'nope'; available: .*cfog"):
        get_method("nope")


def test_basic_parameters_are_few_and_documented():
    for name, method in all_methods().items():
        fields = dataclasses.fields(method.params_type)
        assert all(f.metadata.get("help") for f in fields), name
        assert sum(bool(f.metadata.get("basic")) for f in fields) <= 4, name


def test_the_run_seed_reaches_the_method(small_pair, monkeypatch):
    method, seen = get_method("sift"), []

    def spy(target, reference, params, monitor, seed=0):
        seen.append(seed)
        return method.match(target, reference, params, monitor, seed=seed)

    monkeypatch.setitem(registry._REGISTRY, "sift", dataclasses.replace(method, match=spy))
    register(small_pair["target"], small_pair["reference"], "sift", options=RegisterOptions(seed=17))
    assert seen == [17]


def test_cfog_dense_fit_uses_the_seed(monkeypatch):
    from hamta.core.methods import cfog

    seeds, real = [], cfog.ransac_or_none

    def spy(*args, rng=0, **kw):
        seeds.append(rng)
        return real(*args, rng=rng, **kw)

    monkeypatch.setattr(cfog, "ransac_or_none", spy)
    pts = np.random.default_rng(0).uniform(0, 500, (40, 2))
    model, n = cfog._fit((pts, pts + 3.0), seed=23)
    assert n == 40 and np.allclose(model[:, 2], 3.0)
    assert seeds and set(seeds) == {23}


def test_every_builtin_method_is_found_in_its_module():
    """Methods are found by listing the package; get_method of a method named after its module
    imports only that module (start-up time), and every name resolves to the module defining it."""
    import importlib
    import pkgutil

    import hamta.core.methods as package
    from hamta.core.methods import all_methods, method_aliases

    modules = [i.name for i in pkgutil.iter_modules(package.__path__) if i.name != "registry"]
    defined = {id(v): m for m in modules for v in vars(importlib.import_module(f"hamta.core.methods.{m}")).values()}
    for name in list(all_methods()) + list(method_aliases()):
        method = all_methods()[method_aliases().get(name, name)]
        assert id(method) in defined, name
    code = ("import sys; from hamta.core.methods import get_method; get_method('ndsift-pc-faithful'); "
            "print(sorted(m for m in sys.modules if m.startswith('hamta.core.methods.')))")
    out = subprocess.run([sys.executable, "-P", "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "['hamta.core.methods.ndsift_pc', 'hamta.core.methods.registry']"


def test_a_method_module_added_shows_in_every_front_end(new_method_module, capsys, small_pair, tmp_path):
    from hamta.bench.runner import default_methods
    from hamta.cli.main import main

    name = new_method_module
    order = list(all_methods())
    assert order.index(name) < order.index("orb")  # a product method, listed before the baselines
    assert main(["methods"]) == 0 and name in capsys.readouterr().out
    assert name in default_methods(quick=True)
    code = main(["register", "--target", small_pair["target"], "--reference", small_pair["reference"], "--out",
                 str(tmp_path / "o"), "--method", name, "--param", "ratio=0.75", "--quiet"])
    assert code == 0 and f"method {name}" in capsys.readouterr().out


def test_the_command_line_and_the_bench_list_the_methods_in_one_order(capsys):
    from hamta.bench.runner import default_methods
    from hamta.cli.main import main

    assert main(["methods"]) == 0
    rows = [line.split()[0] for line in capsys.readouterr().out.splitlines()[1:] if line.strip()][:-1]
    assert rows == default_methods(quick=False) == ["auto", *all_methods()]
    kinds = [all_methods()[name].kind for name in rows[1:]]
    assert kinds == sorted(kinds, key=["method", "baseline", "faithful", "learned"].index)
