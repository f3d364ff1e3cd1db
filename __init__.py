"""Hamta: automatic georeferencing and co-registration of rasters.

The repository root is both the QGIS plugin folder and the Python package ``hamta``. Importing
the package (or ``hamta.core``) never imports QGIS; only :func:`classFactory`, which QGIS calls,
does.
"""

__version__ = "0.1.0"


def classFactory(iface):  # noqa: N802 (QGIS's name)
    """QGIS plugin entry point."""
    from .plugin.plugin import HamtaPlugin

    return HamtaPlugin(iface)
