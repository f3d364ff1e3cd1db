"""Hamta's version: the one source the package, the QGIS ``metadata.txt`` and every report agree on."""

__version__ = "0.1.0"
