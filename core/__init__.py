"""Hamta's engine: raster IO, matching, estimation, verification and outputs. Never imports QGIS or
anything outside ``core``.

The names below are imported on first use, so that importing one light module (``core.errors``,
``core.version``) does not load the whole engine and its scientific libraries.
"""
from importlib import import_module

_WHERE = {"register": "pipeline", "run": "runner", "RegisterOptions": "options", "OutputOptions": "options",
          "RegistrationResult": "result", "__version__": "version", "HamtaError": "errors", "InputError": "errors",
          "NoOverlapError": "errors", "GeoreferencingError": "errors", "InsufficientMatchesError": "errors",
          "OutputError": "errors", "RegistrationCanceled": "errors", "UnverifiedResult": "errors",
          "MethodCrashed": "errors"}

__all__ = list(_WHERE)


def __getattr__(name):
    if name not in _WHERE:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(import_module(f".{_WHERE[name]}", __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
