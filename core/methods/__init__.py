"""The method registry: every matching method Hamta offers, by stable name.

A method is a name, a frozen parameter dataclass with documented defaults, and a function
``match(target, reference, params, monitor, seed=0) -> Matches`` from two working images
(:class:`hamta.core.io.working.WorkingImage`) to correspondences in working pixels; ``seed``
seeds every random choice the method makes. Front ends (CLI, Processing, benchmark) list and
build methods only through this registry. A renamed method keeps its old name as an alias.
"""
from __future__ import annotations

from importlib import import_module
from typing import Dict

from .registry import _ALIASES, _REGISTRY, Method, match_with, param, register_method, validate

__all__ = ["Method", "param", "validate", "match_with", "register_method", "get_method", "all_methods",
           "method_aliases"]


# Where each built-in method lives (in the order methods are listed), so that running one method
# imports only its module: the others bring scipy's spatial, sparse and FFT modules in (a fifth of a
# second of start-up for a SIFT run).
BUILTIN = {"lines-spectral-faithful": "lines_spectral", "lines-eigen": "lines_spectral",
           "lines-vspm": "lines_spectral", "cfog": "cfog", "ndsift-pc": "ndsift_pc", "ndsift-pc-faithful": "ndsift_pc",
           "ndss-sift": "ndsift_pc", "gss-sift": "ndsift_pc", "bfsift": "ndsift_pc", "orb": "orb",
           "pca-sift": "pca_sift", "phasecorr": "phasecorr", "rift": "rift", "rilbp": "rilbp",
           "rilbp-faithful": "rilbp", "cslbp": "rilbp_baselines", "censure-sift": "rilbp_baselines", "sibrif": "sibrif",
           "sibrif-faithful": "sibrif", "sift": "sift", "xmodal": "xmodal", "lines-spectral": "cfog"}


def get_method(name: str) -> Method:
    """The method called ``name`` (or formerly called so); a ``ValueError`` lists the valid names otherwise."""
    if name in BUILTIN:
        import_module(f".{BUILTIN[name]}", __name__)
    else:
        _load_builtin()
    try:
        return _REGISTRY[_ALIASES.get(name, name)]
    except KeyError:
        _load_builtin()
        raise ValueError(f"unknown method {name!r}; available: {', '.join(all_methods())}") from None


def method_aliases() -> Dict[str, str]:
    """Former method names -> current names."""
    _load_builtin()
    return dict(_ALIASES)


def all_methods() -> Dict[str, Method]:
    """Every registered method, built-in ones in :data:`BUILTIN`'s order."""
    _load_builtin()
    ordered = {n: _REGISTRY[n] for n in BUILTIN if n in _REGISTRY}
    return dict(ordered, **{n: m for n, m in _REGISTRY.items() if n not in ordered})


def _load_builtin() -> None:
    """Import the built-in method modules once (each registers itself on import)."""
    for module in dict.fromkeys(BUILTIN.values()):
        import_module(f".{module}", __name__)
