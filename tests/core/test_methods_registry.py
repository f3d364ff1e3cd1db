"""The method registry: names, aliases, parameters, and the run's seed reaching every method."""
import dataclasses
import inspect

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


def test_the_run_seed_reaches_the_method(demo_pair, monkeypatch):
    method, seen = get_method("sift"), []

    def spy(target, reference, params, monitor, seed=0):
        seen.append(seed)
        return method.match(target, reference, params, monitor, seed=seed)

    monkeypatch.setitem(registry._REGISTRY, "sift", dataclasses.replace(method, match=spy))
    register(demo_pair["target"], demo_pair["reference"], "sift", options=RegisterOptions(seed=17))
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
    """get_method imports only the module BUILTIN names; that module must define the method."""
    import importlib

    from hamta.core.methods import BUILTIN, all_methods, method_aliases

    assert sorted(all_methods()) == sorted(n for n in BUILTIN if n not in method_aliases())
    for name, module in BUILTIN.items():
        method = all_methods()[method_aliases().get(name, name)]
        defined = vars(importlib.import_module(f"hamta.core.methods.{module}")).values()
        assert any(v is method for v in defined), (name, module)
