"""Hamta: automatic georeferencing and co-registration of rasters.

The repository root is both the QGIS plugin folder and the Python package ``hamta``. Importing
the package never imports QGIS (only :func:`classFactory`, which QGIS calls, does) nor the engine.
"""


def __getattr__(name):
    if name == "__version__":
        from .core.version import __version__

        return __version__
    raise AttributeError(f"module 'hamta' has no attribute {name!r}")


def classFactory(iface):  # noqa: N802 (QGIS's name)
    """QGIS plugin entry point."""
    from .plugin.plugin import HamtaPlugin

    return HamtaPlugin(iface)
