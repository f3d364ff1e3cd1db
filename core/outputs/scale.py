"""Map units of the report: how lengths in reference pixels read in the reference CRS's unit
(metres, degrees...), the CRS's name, pixel sizes in map units per pixel, and the registered scale
(reference px per target px). In pixel mode (no georeferencing) there is no map scale and lengths
stay in reference px.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np

from ..estimation.models import local_jacobian
from ..io.raster import RasterInfo
from .html_text import _num

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
    """How reference pixels read in the reference CRS: its label, unit and pixel size."""

    crs: str
    unit_name: str
    pixel_size: float  # map units per reference pixel (geometric mean of the two axes)

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


def map_scale(result) -> Optional[MapScale]:
    """The reference's map scale; None in pixel mode (no georeferencing)."""
    if result.pixel_mode or result.reference.crs is None:
        return None
    name, unit = describe_crs(result.reference.crs)
    return MapScale(name, unit, result.reference.pixel_size)


def _both(value_px: Optional[float], scale: Optional[MapScale], fmt: str = ".2f") -> str:
    """``'0.41 px (4.10 m)'``: a length in reference px and, outside pixel mode, in map units."""
    text = _num(value_px, fmt, " px")
    if scale is None or text == "–":
        return text
    return f"{text} ({scale.px(value_px)})"


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
