"""Map units of the report: how lengths in reference pixels read in the reference CRS's unit
(metres, degrees...), the CRS's name, pixel sizes in map units per pixel, and the registered scale
(reference px per target px). In pixel mode (no georeferencing) there is no map scale and lengths
stay in reference px.

A length is told in the pixels it was measured in, named ('px of the basemap at zoom 14', 'reference
px'), then on the ground and in the target's own pixels. Web Mercator (EPSG:3857, the CRS of XYZ
basemaps) stretches lengths by 1/cos(latitude): its "metres" are ground metres only at the equator
(11.81 of them are 7.1 m on the ground at 53° N), so its lengths are scaled by cos(latitude) at the
result's centre (:func:`ground_factor`) and said to be on the ground; so are those of any other projection
that stretches lengths there by more than 2 % (World Mercator of a nautical chart, by its scale factor).
"""
from __future__ import annotations

import html
import math
from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np

from ..basemap.services import HALF_WORLD
from ..estimation.models import local_jacobian
from ..io.raster import RasterInfo
from .html_text import _num

WEB_MERCATOR_RADIUS = HALF_WORLD / math.pi  # m: the sphere of EPSG:3857's formulas
METRE = ("metre", "meter")
UNIT_SYMBOLS = {"metre": "m", "meter": "m", "kilometre": "km", "degree": "°", "foot": "ft",
                "US survey foot": "US ft", "Clarke's foot": "Clarke's ft"}


def describe_crs(crs) -> Tuple[str, str]:
    """``('WGS 84 / UTM zone 32N (EPSG:32632)', 'metre')``: a CRS's name with its EPSG code (when it
    has one) and the unit of its first axis (``'unknown unit'`` without axes)."""
    from pyproj import CRS as ProjCRS

    pcrs = ProjCRS.from_user_input(crs.to_wkt())
    code = pcrs.to_epsg()
    name = f"{pcrs.name} (EPSG:{code})" if code else f"{pcrs.name} (no EPSG code)"
    unit = pcrs.axis_info[0].unit_name if pcrs.axis_info else "unknown unit"
    return name, unit


def _decimals(size: float) -> int:
    """Decimals that resolve about a hundredth of ``size`` (a pixel's size)."""
    return int(min(10, max(2, math.ceil(-math.log10(size)) + 2))) if size > 0 and math.isfinite(size) else 3


@dataclass(frozen=True)
class MapScale:
    """How reference pixels read in the reference CRS: its label, unit and pixel size; and, for a
    result, what a reference pixel is called, how map units read on the ground and in target pixels."""

    crs: str
    unit_name: str
    pixel_size: float  # map units per reference pixel (geometric mean of the two axes)
    ground: Optional[float] = None  # ground metres per map unit where they differ (Mercator), else None
    latitude: Optional[float] = None  # degrees, where ``ground`` was taken
    per_target_px: Optional[float] = None  # reference px per target px at the target's centre, when known
    px_name: str = "reference px"  # what a reference pixel is called: 'px of the basemap at zoom 14'

    @property
    def symbol(self) -> str:
        """The unit's symbol: ``'m'``, ``'°'``, ``'US ft'`` (the unit's name when it has none here)."""
        return UNIT_SYMBOLS.get(self.unit_name, self.unit_name)

    @property
    def unit(self) -> str:
        """The unit as printed after a number: ``' m'``, ``'°'``, ``' US ft'``."""
        return self.symbol if self.symbol == "°" else " " + self.symbol

    def length(self, size: Optional[float]) -> str:
        """A length in map units (escaped), to about a hundredth of a pixel."""
        return _num(size, f".{_decimals(self.pixel_size)}f", self.unit)

    def px(self, value_px: Optional[float]) -> str:
        """A length in reference px as map units (escaped); '–' when missing."""
        return self.length(None if value_px is None else value_px * self.pixel_size)

    def on_ground(self, value_px: Optional[float]) -> str:
        """A length in reference px as it reads on the ground: ``'2.91 m on the ground'`` where map units
        are not ground metres (Web Mercator), else in map units (``'4.10 m'``); escaped."""
        if self.ground is None:
            return self.px(value_px)
        size = None if value_px is None else value_px * self.pixel_size * self.ground
        return _num(size, f".{_decimals(self.pixel_size * self.ground)}f", " m on the ground")

    def in_target_px(self, value_px: Optional[float], fmt: str = ".2f") -> Optional[str]:
        """A length in reference px as target px (``'0.62 target px'``), or None when the registered
        scale is unknown."""
        if self.per_target_px is None or value_px is None:
            return None
        return _num(value_px / self.per_target_px, fmt, " target px")


def map_scale(result) -> Optional[MapScale]:
    """The reference's map scale, with how it reads on the ground and in target px at ``result``'s
    centre; None in pixel mode (no georeferencing)."""
    if result.pixel_mode or result.reference.crs is None:
        return None
    name, unit = describe_crs(result.reference.crs)
    latitude = centre_latitude(result) if is_web_mercator(result.reference.crs) else None
    ground = None if latitude is None else math.cos(math.radians(latitude))
    if latitude is None and unit in METRE:
        latitude, ground = _projection_scale(result)
    return MapScale(name, unit, result.reference.pixel_size, ground=ground, latitude=latitude,
                    per_target_px=registered_scale(result), px_name=reference_px_name(result))


def reference_px_name(result) -> str:
    """What one reference pixel is: ``'px of the basemap at zoom 14'`` for a map service read at zoom
    14, else ``'reference px'``."""
    service = result.reference_service
    if service and service.get("zoom") is not None:
        return f"px of the basemap at zoom {service['zoom']}"
    return "reference px"


def is_web_mercator(crs) -> bool:
    """Whether ``crs`` is Web Mercator (EPSG:3857 or the same projection under another name)."""
    from pyproj import CRS as ProjCRS

    pcrs = ProjCRS.from_user_input(crs.to_wkt())
    if pcrs.to_epsg() == 3857:
        return True
    operation = pcrs.coordinate_operation
    return operation is not None and "pseudo mercator" in operation.method_name.lower()


def centre_latitude(result) -> Optional[float]:
    """The latitude (degrees) of the target's centre as registered, for a Web Mercator reference; None
    where the model does not put it anywhere finite."""
    centre = [[result.target.width / 2.0, result.target.height / 2.0]]
    try:
        _, xy = result.map_points(centre)
    except (ValueError, np.linalg.LinAlgError):
        return None
    y = float(xy[0, 1])
    return math.degrees(math.atan(math.sinh(y / WEB_MERCATOR_RADIUS))) if math.isfinite(y) else None


STRETCH = 0.02  # a projection whose scale at the centre differs from 1 by more: its metres are not ground metres


def _projection_scale(result) -> Tuple[Optional[float], Optional[float]]:
    """(latitude, ground metres per map metre) at the target's centre as registered where the reference's
    projection stretches lengths there by more than :data:`STRETCH` (World Mercator at 70 degrees: 2.9
    times), else (None, None)."""
    from pyproj import CRS as ProjCRS
    from pyproj import Proj, Transformer

    try:
        _, xy = result.map_points([[result.target.width / 2.0, result.target.height / 2.0]])
        crs = ProjCRS.from_user_input(result.reference.crs.to_wkt())
        if not crs.is_projected:
            return None, None
        lon, lat = Transformer.from_crs(crs, crs.geodetic_crs, always_xy=True).transform(*xy[0])
        k = math.sqrt(Proj(crs).get_factors(lon, lat).areal_scale)
    except Exception:  # a centre the projection cannot take: its map units are read as they are
        return None, None
    return (float(lat), 1.0 / k) if math.isfinite(k) and k > 0 and abs(k - 1.0) > STRETCH else (None, None)


def ground_factor(result) -> Optional[float]:
    """Ground metres per map unit at ``result``'s centre where map units are not ground lengths: cos(latitude)
    for Web Mercator, the inverse of the scale factor for a projection that stretches lengths more than
    :data:`STRETCH`; None for other CRSs (their map units are read as they are) and in pixel mode."""
    scale = map_scale(result)
    return None if scale is None else scale.ground


def ground_metres(result, value_px: Optional[float]) -> Optional[float]:
    """A length in reference px as metres on the ground at ``result``'s centre; None in pixel mode, where
    the reference's unit is not the metre (degrees, feet) or the value is missing."""
    scale = map_scale(result)
    if scale is None or value_px is None or not math.isfinite(value_px) or (
            scale.ground is None and scale.unit_name not in METRE):
        return None
    return value_px * scale.pixel_size * (1.0 if scale.ground is None else scale.ground)


def target_px(result, value_px: Optional[float]) -> Optional[float]:
    """A length in reference px as target px (through the registered scale at the target's centre); None
    when that scale or the value is unknown."""
    k = registered_scale(result)
    if k is None or value_px is None or not math.isfinite(value_px):
        return None
    return value_px / k


def length_text(result, value_px: Optional[float], fmt: str = ".2f") -> str:
    """A length in reference px as plain text for messages, naming its pixels, on the ground and in target
    px when known (see :func:`_both`): ``'0.17 px of the basemap at zoom 14 (1.03 m on the ground, 0.14
    target px)'``."""
    return html.unescape(_both(value_px, map_scale(result), fmt))


def _both(value_px: Optional[float], scale: Optional[MapScale], fmt: str = ".2f") -> str:
    """A length in reference px, naming them, and on the ground and in target px when known:
    ``'0.41 reference px (4.10 m, 0.62 target px)'``, ``'0.50 px of the basemap at zoom 14 (2.91 m on the
    ground, 0.71 target px)'``; ``'0.41 px'`` in pixel mode."""
    text = _num(value_px, fmt, " px")
    if scale is None or text == "–":
        return text
    also = [scale.on_ground(value_px), scale.in_target_px(value_px, fmt)]
    return f"{_num(value_px, fmt, ' ' + scale.px_name)} ({', '.join(a for a in also if a and a != '–')})"


def axis_sizes(info: RasterInfo) -> Tuple[float, float]:
    """Map units per pixel along the raster's columns and rows."""
    t = info.transform
    return math.hypot(t.a, t.d), math.hypot(t.b, t.e)


def registered_scale(result) -> Optional[float]:
    """Reference px per target px at the target's centre, through the model (None if not finite)."""
    centre = [[result.target.width / 2.0, result.target.height / 2.0]]
    try:
        det = float(np.linalg.det(local_jacobian(result.model, centre)[0]))
    except (ValueError, np.linalg.LinAlgError):
        return None
    return math.sqrt(abs(det)) if math.isfinite(det) and det != 0 else None
