"""Search areas: ``xmin,ymin,xmax,ymax[,CRS]`` as typed by a user or passed by QGIS, and their
bounds in another CRS."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Tuple

from .errors import InputError, UsageError


@dataclass(frozen=True)
class Extent:
    """A rectangle in map coordinates of ``crs`` (None: the reference's CRS)."""

    xmin: float
    ymin: float
    xmax: float
    ymax: float
    crs: Optional[str] = None

    @property
    def bounds(self) -> Tuple[float, float, float, float]:
        return self.xmin, self.ymin, self.xmax, self.ymax

    def text(self) -> str:
        return ",".join(f"{v:.10g}" for v in self.bounds) + (f",{self.crs}" if self.crs else "")


MAX_COORDINATE = 1e10  # map units: every projected CRS fits (the Earth is 4e7 m round), so larger is a typo


def parse_extent(text: str) -> Extent:
    """``xmin,ymin,xmax,ymax`` optionally followed by ``,CRS`` (an authority code such as EPSG:4326)."""
    parts = [p.strip() for p in str(text).replace(";", ",").split(",")]
    usage = (f"the search area '{text}' must be xmin,ymin,xmax,ymax with an optional CRS after a comma, "
             "e.g. 10.70,59.90,10.80,59.95,EPSG:4326")
    if len(parts) not in (4, 5):
        raise UsageError(usage)
    try:
        xmin, ymin, xmax, ymax = (float(p) for p in parts[:4])
    except ValueError:
        raise UsageError(usage) from None
    if not all(abs(v) <= MAX_COORDINATE for v in (xmin, ymin, xmax, ymax)):  # nan and inf too
        raise UsageError(f"the search area '{text}' has a coordinate beyond any map (above {MAX_COORDINATE:g} map "
                         "units)")
    if not (xmin < xmax and ymin < ymax):
        raise UsageError(f"the search area '{text}' is empty: xmin must be below xmax and ymin below ymax")
    crs = parts[4] if len(parts) == 5 and parts[4] else None
    if crs is not None:
        _crs(crs, text)
    return Extent(xmin, ymin, xmax, ymax, crs)


def _crs(crs: str, text: str):
    from pyproj import CRS
    from pyproj.exceptions import CRSError

    try:
        return CRS.from_user_input(crs)
    except CRSError:
        raise UsageError(f"the search area '{text}' names a CRS PROJ does not know: {crs!r}") from None


def bounds_in(extent: Extent, crs, default_crs) -> Tuple[float, float, float, float]:
    """``extent``'s bounding box in ``crs`` (the extent without a CRS of its own is in ``default_crs``)."""
    from pyproj import CRS
    from pyproj.transformer import Transformer

    source = extent.crs or default_crs
    if source is None or crs is None or CRS.from_user_input(source) == CRS.from_user_input(crs):
        return extent.bounds
    transformer = Transformer.from_crs(CRS.from_user_input(source), CRS.from_user_input(crs), always_xy=True)
    bounds = transformer.transform_bounds(*extent.bounds, densify_pts=21)
    if not all(abs(v) < 1e300 for v in bounds):
        raise InputError(f"The search area {extent.text()} cannot be expressed in {crs}.")
    return bounds
