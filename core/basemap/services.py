"""Map services as references: XYZ tile templates and WMS layers, told apart from what GDAL opens.

A reference given as text is one of:

- a tile-URL template, ``https://host/{z}/{x}/{y}.png`` (``{-y}`` for TMS rows; ``{s}`` is not
  expanded, write one sub-domain);
- a QGIS XYZ layer source, ``type=xyz&url=…&zmin=0&zmax=19`` (what the layer's properties show);
- a QGIS WMS layer source, ``url=…&layers=…&crs=EPSG:3857&format=image/png&styles=`` (read as tiles
  of a GetMap request on the same grid as XYZ layers);
- anything else: a path or a GDAL string (``/vsicurl/…``, ``WMTS:…``, ``WCS:…``, a GDAL WMS XML),
  opened by GDAL like a file (:func:`parse_service` returns None).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Tuple
from urllib.parse import parse_qsl, urlencode

from ..errors import InputError
from .redact import redact

WEB_MERCATOR = "EPSG:3857"
HALF_WORLD = 20037508.342789244  # metres from the centre of EPSG:3857 to its edge
GRIDS = {  # CRS -> (origin x, origin y, resolution of zoom 0 for 256-px tiles)
    "EPSG:3857": (-HALF_WORLD, HALF_WORLD, 2 * HALF_WORLD / 256),
    "EPSG:4326": (-180.0, 90.0, 180.0 / 256),
}


@dataclass(frozen=True)
class TileService:
    """A tiled map service on a power-of-two grid: zoom ``z`` has pixels of ``resolution(z)`` map units.

    ``kind`` is 'xyz' (``url`` is a template) or 'wms' (``url`` is the service address, ``layers``
    and ``styles`` its layer). ``crs`` is the grid's CRS (EPSG:3857, or EPSG:4326 for a WMS in
    geographic coordinates).
    """

    kind: str
    url: str
    crs: str = WEB_MERCATOR
    zmin: int = 0
    zmax: int = 19
    tile_px: int = 256
    layers: str = ""
    styles: str = ""
    image_format: str = "image/png"

    @property
    def id(self) -> str:
        """A digest of the whole definition, credentials included (to recognise the same service again)."""
        import hashlib

        return hashlib.sha256(repr(self).encode()).hexdigest()[:16]

    @property
    def label(self) -> str:
        """The service as a user would recognise it, without credentials."""
        text = redact(self.url)
        return text + (f" (layers {self.layers})" if self.kind == "wms" else "")

    def resolution(self, z: int) -> float:
        return GRIDS[self.crs][2] * 256 / self.tile_px / 2 ** z

    def origin(self) -> Tuple[float, float]:
        return GRIDS[self.crs][:2]

    def tile_count(self, z: int) -> Tuple[int, int]:
        """Columns and rows of tiles at zoom ``z`` (EPSG:4326 grids are two tiles wide at zoom 0)."""
        n = 2 ** z
        return (2 * n if self.crs == "EPSG:4326" else n), n

    def tile_url(self, z: int, x: int, y: int) -> str:
        if self.kind == "xyz":
            flipped = self.tile_count(z)[1] - 1 - y
            return (self.url.replace("{z}", str(z)).replace("{x}", str(x)).replace("{-y}", str(flipped))
                    .replace("{y}", str(y)))
        res, (x0, y0) = self.resolution(z) * self.tile_px, self.origin()
        bbox = (x0 + x * res, y0 - (y + 1) * res, x0 + (x + 1) * res, y0 - y * res)
        query = {"SERVICE": "WMS", "VERSION": "1.1.1", "REQUEST": "GetMap", "LAYERS": self.layers,
                 "STYLES": self.styles, "SRS": self.crs, "BBOX": ",".join(f"{v:.10g}" for v in bbox),
                 "WIDTH": self.tile_px, "HEIGHT": self.tile_px, "FORMAT": self.image_format, "TRANSPARENT": "TRUE"}
        return self.url + ("&" if "?" in self.url else "?") + urlencode(query, safe=",:/")


AUTH_KEYS = ("authcfg", "username", "password", "http-header:", "referer")  # QGIS sends these; Hamta cannot


def parse_service(text) -> Optional[TileService]:
    """The :class:`TileService` ``text`` describes, or None when it is not one Hamta reads itself: a file
    or GDAL string, a WMTS or WCS layer, a WMS whose CRS is neither EPSG:3857 nor EPSG:4326, or a layer
    that needs QGIS's credentials or headers (in QGIS such layers are read through their provider)."""
    text = str(text).strip()
    if text.startswith(("http://", "https://")) and "{z}" in text and "{x}" in text:
        return _checked(TileService("xyz", _template(text)), text)
    if "url=" not in text or text.startswith(("/", "<")):
        return None
    pairs = parse_qsl(text, keep_blank_values=True)
    fields = {}
    for key, value in pairs:  # QGIS repeats 'layers' and 'styles' for a WMS of several layers
        fields[key] = f"{fields[key]},{value}" if key in ("layers", "styles") and key in fields else value
    url = fields.get("url", "")
    if not url.startswith(("http://", "https://")) or any(k.lower().startswith(AUTH_KEYS) for k, _ in pairs):
        return None
    if fields.get("type") == "xyz":
        service = TileService("xyz", _template(url), zmin=_zoom(fields, "zmin", 0, text),
                              zmax=_zoom(fields, "zmax", 19, text))
        return _checked(service, text)
    crs = fields.get("crs", WEB_MERCATOR).upper().replace("EPSG:900913", WEB_MERCATOR).replace("CRS:84", "EPSG:4326")
    if "layers" in fields and "tileMatrixSet" not in fields and crs in GRIDS:
        return TileService("wms", url, crs=crs, zmax=22, tile_px=512, layers=fields["layers"],
                           styles=fields.get("styles", ""), image_format=fields.get("format", "image/png"))
    return None


def _template(url: str) -> str:
    for name in ("z", "x", "y", "-y"):  # GDAL writes ${z}
        url = url.replace("${" + name + "}", "{" + name + "}")
    return url


def _zoom(fields, key: str, default: int, text: str) -> int:
    try:
        value = int(fields.get(key, default))
    except ValueError:
        raise InputError(f"The reference layer '{redact_source(text)}' has {key}={fields[key]!r}, not a zoom "
                         "level.") from None
    return min(max(value, 0), 24)


def _checked(service: TileService, text: str) -> TileService:
    if "{y}" not in service.url and "{-y}" not in service.url:
        raise InputError(f"The tile template '{redact_source(text)}' has no {{y}} (or {{-y}}) placeholder.")
    if service.zmin > service.zmax:
        raise InputError(f"The reference layer '{redact_source(text)}' has zmin above zmax.")
    return service


def redact_source(text: str) -> str:
    """A reference given as text, without credentials (for messages and reports)."""
    if "url=" in text and not text.startswith(("http://", "https://", "/")):
        return redact(dict(parse_qsl(text, keep_blank_values=True)).get("url", ""))
    return redact(text)
