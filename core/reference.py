"""The reference of a registration, resolved once from what a front end was given.

A reference is given as text or a path; :func:`resolve_reference` decides once what it is:

- :class:`ServiceReference`: a map service Hamta reads tile by tile itself (an XYZ template, a QGIS
  XYZ or WMS layer source; :mod:`hamta.core.basemap.services`), searched through :mod:`hamta.core.remote`;
- :class:`RasterReference`: anything GDAL opens (a file, a VRT, ``/vsicurl/…``, ``WMTS:…``).

A QGIS layer that neither covers (WMTS, WCS, a layer with QGIS's credentials) is rendered into a
GeoTIFF by the QGIS front end first (:class:`hamta.processing.reference.Rendering`) and is then a raster.
The runner, the batch and the Processing algorithms dispatch on the type, never on the text again.
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Union

from .basemap.services import TileService, parse_service, redact_source


@dataclass(frozen=True)
class RasterReference:
    """A raster GDAL opens: ``path`` (a file name or a GDAL string)."""

    path: str

    @property
    def text(self) -> str:
        return self.path

    @property
    def label(self) -> str:
        return redact_source(self.path)


@dataclass(frozen=True)
class ServiceReference:
    """A map service read by Hamta: ``service`` as parsed from ``text`` (the source as given)."""

    service: TileService
    text: str

    @property
    def label(self) -> str:
        return self.service.label


Reference = Union[RasterReference, ServiceReference]


def resolve_reference(value) -> Reference:
    """What ``value`` (text, a path, or a reference already resolved) is as a reference."""
    if isinstance(value, (RasterReference, ServiceReference)):
        return value
    service = parse_service(value)
    return ServiceReference(service, str(value).strip()) if service is not None else RasterReference(os.fspath(value))
