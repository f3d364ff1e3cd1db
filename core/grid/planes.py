"""The plane a sheet is drawn in: where its printed grid lines are straight and evenly spaced.

A grid printed in a projected CRS (a national grid, UTM) is drawn in that CRS. A graticule is drawn in a
projection the sheet rarely names; the user gives the CRS of its printed degrees. The projections a
graticule is drawn in on maps and charts are tried: Mercator (nautical charts), a conformal conic (charts
and topographic sheets of mid-latitudes), transverse Mercator (topographic series), polyconic (older
series of the United States) and the equirectangular plate carrée (old and small-scale maps), each centred
on the sheet (an affine map from the plane to the scan absorbs their false origins and scale factors, so
only their shape matters). :func:`hamta.core.grid.sheet.fit_sheet` keeps the one whose lattice the scan
holds best, and the check reports how well an affine in it fits the crossings.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import List

import numpy as np


@dataclass(frozen=True)
class Plane:
    """``name`` as the report says it; ``crs`` (pyproj CRS, projected) the plane; ``sheet_crs`` what the printed
    coordinates count in. :meth:`forward` maps printed coordinates to the plane, :meth:`backward` back."""

    name: str
    crs: object
    sheet_crs: object

    def __post_init__(self):
        from pyproj import Transformer

        object.__setattr__(self, "_to", Transformer.from_crs(self.sheet_crs, self.crs, always_xy=True))
        object.__setattr__(self, "_from", Transformer.from_crs(self.crs, self.sheet_crs, always_xy=True))

    def forward(self, grid_xy) -> np.ndarray:
        """(n, 2) printed coordinates -> (n, 2) plane coordinates (NaN where the plane has none)."""
        g = np.atleast_2d(np.asarray(grid_xy, float))
        x, y = self._to.transform(g[:, 0], g[:, 1], errcheck=False)
        out = np.column_stack([np.asarray(x, float), np.asarray(y, float)])
        out[~np.isfinite(out).all(axis=1)] = np.nan
        return out

    def backward(self, plane_xy) -> np.ndarray:
        p = np.atleast_2d(np.asarray(plane_xy, float))
        x, y = self._from.transform(p[:, 0], p[:, 1], errcheck=False)
        return np.column_stack([np.asarray(x, float), np.asarray(y, float)])

    @property
    def proj(self) -> str:
        return self.crs.to_proj4() if self.name != "the sheet's CRS" else self.crs.to_string()


def planes_for(sheet_crs, lon_lat_box) -> List[Plane]:
    """The planes to try for a sheet whose printed coordinates count in ``sheet_crs`` (a pyproj CRS), over
    ``lon_lat_box`` (west, south, east, north in its degrees, where it is geographic): the sheet's CRS itself
    where it is projected; else the projections of the module docstring, centred on the box, most usual
    first."""
    from pyproj import CRS

    if not sheet_crs.is_geographic:
        return [Plane("the sheet's CRS", sheet_crs, sheet_crs)]
    west, south, east, north = (float(v) for v in lon_lat_box)
    lon0 = _wrap((west + east) / 2)
    lat0 = float(np.clip((south + north) / 2, -85.0, 85.0))
    span = max(north - south, 1e-3)
    lat1, lat2 = south + span / 6, north - span / 6
    ellps = _ellipsoid(sheet_crs)
    conic = (f"+proj=lcc +lat_1={lat1:.6f} +lat_2={lat2:.6f} +lat_0={lat0:.6f} +lon_0={lon0:.6f}"
             if lat1 * lat2 > 0 and abs(lat0) < 85 else None)  # a cone needs both parallels in one hemisphere
    specs = [("Mercator", f"+proj=merc +lon_0={lon0:.6f} +lat_ts={min(abs(lat0), 80.0):.6f}"),
             ("Lambert conformal conic", conic),
             ("transverse Mercator", f"+proj=tmerc +lon_0={lon0:.6f} +lat_0={lat0:.6f}"),
             ("polyconic", f"+proj=poly +lon_0={lon0:.6f} +lat_0={lat0:.6f}"),
             ("equirectangular", f"+proj=eqc +lon_0={lon0:.6f} +lat_ts={min(abs(lat0), 85.0):.6f}")]
    return [Plane(name, CRS.from_user_input(f"{proj} {ellps} +units=m +no_defs"), sheet_crs)
            for name, proj in specs if proj is not None]


def _ellipsoid(crs) -> str:
    e = crs.ellipsoid
    if e is None:
        return "+ellps=WGS84"
    return f"+a={e.semi_major_metre:.4f} +rf={e.inverse_flattening:.9f}" if e.inverse_flattening else \
        f"+R={e.semi_major_metre:.4f}"


def _wrap(lon: float) -> float:
    return (lon + 180.0) % 360.0 - 180.0
