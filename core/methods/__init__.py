"""The method registry: every matching method Hamta offers, by stable name.

A method is a name, a frozen parameter dataclass with documented defaults, and a function
``match(target, reference, params, monitor, seed=0) -> Matches`` from two working images
(:class:`hamta.core.io.working.WorkingImage`) to correspondences in working pixels; ``seed``
seeds every random choice the method makes. Front ends (CLI, Processing, benchmark) list and
build methods only through this registry. A renamed method keeps its old name as an alias.
"""
from __future__ import annotations

from typing import Dict

from .registry import _ALIASES, _REGISTRY, Method, match_with, param, register_method, validate

__all__ = ["Method", "param", "validate", "match_with", "register_method", "get_method", "all_methods",
           "method_aliases"]


def get_method(name: str) -> Method:
    """The method called ``name`` (or formerly called so); a ``ValueError`` lists the valid names otherwise."""
    _load_builtin()
    try:
        return _REGISTRY[_ALIASES.get(name, name)]
    except KeyError:
        raise ValueError(f"unknown method {name!r}; available: {', '.join(_REGISTRY)}") from None


def method_aliases() -> Dict[str, str]:
    """Former method names -> current names."""
    _load_builtin()
    return dict(_ALIASES)


def all_methods() -> Dict[str, Method]:
    _load_builtin()
    return dict(_REGISTRY)


def _load_builtin() -> None:
    """Import the built-in method modules once (each registers itself on import)."""
    from . import (  # noqa: F401
        cfog,
        lines_spectral,
        ndsift_pc,
        orb,
        pca_sift,
        phasecorr,
        rift,
        rilbp,
        rilbp_baselines,
        sibrif,
        sift,
        xmodal,
    )
