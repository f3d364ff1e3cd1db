"""The method registry: every matching method Hamta offers, by stable name.

A method is a name, a frozen parameter dataclass with documented defaults, and a function
``match(target, reference, params, monitor, seed=0) -> Matches`` from two working images
(:class:`hamta.core.io.working.WorkingImage`) to correspondences in working pixels; ``seed``
seeds every random choice the method makes. Each module of this package (other than
``registry``) registers its methods on import; they are found by listing the package, so adding a
method is adding a module. Front ends (CLI, Processing, benchmark) list and build methods only
through this registry, in :func:`all_methods`' order. A renamed method keeps its old name as an alias.
"""
from __future__ import annotations

import pkgutil
from importlib import import_module
from typing import Dict

from ..errors import UsageError
from .registry import _ALIASES, _REGISTRY, Method, Toolbox, match_with, param, register_method, validate

__all__ = ["Method", "Toolbox", "param", "validate", "match_with", "register_method", "get_method", "all_methods",
           "method_aliases"]


def get_method(name: str) -> Method:
    """The method called ``name`` (or formerly called so); a ``ValueError`` lists the valid names otherwise.

    Running one method imports only its module when the module is named after it (``ndsift-pc`` in
    ``ndsift_pc.py``, its ``-faithful`` version beside it): the others bring scipy's spatial, sparse
    and FFT modules in (a fifth of a second of start-up for a SIFT run). Other names import every module.
    """
    if name not in _REGISTRY and name not in _ALIASES:
        module = name.removesuffix("-faithful").replace("-", "_")
        if module in _module_names():
            import_module(f".{module}", __name__)
    if name not in _REGISTRY and name not in _ALIASES:
        _load_all()
    try:
        return _REGISTRY[_ALIASES.get(name, name)]
    except KeyError:
        raise UsageError(f"unknown method {name!r}; available: {', '.join(all_methods())}") from None


def method_aliases() -> Dict[str, str]:
    """Former method names -> current names."""
    _load_all()
    return dict(_ALIASES)


def all_methods() -> Dict[str, Method]:
    """Every registered method, in the order every front end lists them (:attr:`Method.menu_key`)."""
    _load_all()
    return {m.name: m for m in sorted(_REGISTRY.values(), key=lambda m: m.menu_key)}


def _module_names():
    return [info.name for info in pkgutil.iter_modules(__path__) if info.name != "registry"]


def _load_all() -> None:
    """Import every method module once (each registers its methods on import)."""
    for module in _module_names():
        import_module(f".{module}", __name__)
