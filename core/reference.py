"""The reference of a registration, resolved once from what a front end was given.

A reference is given as text or a path; :func:`resolve_reference` decides once, where the text
enters (the CLI, a batch's job list or ``--reference``, a QGIS layer's source), what it is:

- :class:`ServiceReference`: a map service Hamta reads tile by tile itself (an XYZ template, a QGIS
  XYZ or WMS layer source; :mod:`hamta.core.basemap.services`), searched through :mod:`hamta.core.remote`;
- :class:`RasterReference`: anything GDAL opens (a file, a VRT, ``/vsicurl/…``, ``WMTS:…``).

A QGIS layer that neither covers (WMTS, WCS, a layer with QGIS's credentials) is rendered into a
GeoTIFF by the QGIS front end first (:class:`hamta.processing.reference.Rendering`) and is then a raster.
A batch's :class:`hamta.core.batch.jobs.Job` carries the resolved reference to its workers; the runner,
the batch and the Processing algorithms dispatch on the type, never on the text again, and no other
module tells kinds of reference text apart.
"""
from __future__ import annotations

import os
import re
from dataclasses import dataclass
from typing import Optional, Union

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


GDAL_STRING = re.compile(r"/vsi|[A-Za-z]\w+:")


def resolve_reference(value, base: Optional[str] = None) -> Reference:
    """What ``value`` (text, a path, or a reference already resolved, returned as it is) is as a reference.

    With ``base`` (a job list's folder), a raster path is taken relative to it; a map service or a
    GDAL string (``/vsicurl/…``, ``WMTS:…``, a URL) is kept as written.
    """
    if isinstance(value, (RasterReference, ServiceReference)):
        return value
    service = parse_service(value)
    if service is not None:
        return ServiceReference(service, str(value).strip())
    path = os.fspath(value)
    if base is None:
        return RasterReference(path)
    path = path.strip()
    return RasterReference(path if GDAL_STRING.match(path) else os.path.abspath(os.path.join(base, path)))
