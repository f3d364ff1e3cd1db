"""Models fitted in the target's own map frame, for targets georeferenced in another CRS.

When a target is georeferenced in a CRS other than the reference's, its georeferencing error
is a simple (shift, affine) correction in its *own* map frame, while the map from its pixels to
reference pixels also contains the curvature of the change of projection (0.7 px across a
Landsat scene from UTM to WGS 84 coordinates). Fitting the chosen model between target pixels and
*frame pixels* (reference points expressed in the target's CRS and pixel grid) and composing it
with the exact CRS transformation keeps the model simple and the result exact.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np
from affine import Affine

from ..coords import as_xy, continue_longitudes, gdal_coefficients, map_to_pixel, pixel_to_map, transformer


@dataclass(frozen=True, eq=False)
class CrsFrame:
    """The target's pixel grid in its CRS (``frame``), related exactly to the reference pixels."""

    frame_transform: Affine
    frame_crs_wkt: str
    reference_transform: Affine
    reference_crs_wkt: str
    reference_centre: Optional[float] = None  # the central longitude of a geographic reference
    frame_centre: Optional[float] = None  # and of a geographic target frame

    def to_reference_px(self, frame_px) -> np.ndarray:
        mp = pixel_to_map(self.frame_transform, as_xy(frame_px))
        x, y = transformer(self.frame_crs_wkt, self.reference_crs_wkt).transform(mp[:, 0], mp[:, 1])
        return map_to_pixel(self.reference_transform, continue_longitudes(np.column_stack([x, y]),
                                                                          self.reference_centre))

    def from_reference_px(self, reference_px) -> np.ndarray:
        mp = pixel_to_map(self.reference_transform, as_xy(reference_px))
        x, y = transformer(self.reference_crs_wkt, self.frame_crs_wkt).transform(mp[:, 0], mp[:, 1])
        return map_to_pixel(self.frame_transform, continue_longitudes(np.column_stack([x, y]), self.frame_centre))

    def to_frame_map(self, frame_px) -> np.ndarray:
        return pixel_to_map(self.frame_transform, as_xy(frame_px))

    def to_dict(self) -> dict:
        return {"crs": self.frame_crs_wkt, "transform": gdal_coefficients(self.frame_transform)}


@dataclass(frozen=True, eq=False)
class FramedModel:
    """``inner`` (target px -> frame px) composed with the exact frame -> reference pixel map."""

    inner: object
    frame: CrsFrame

    @property
    def kind(self) -> str:
        return self.inner.kind

    matrix = None

    @property
    def n_min(self) -> int:
        return self.inner.n_min

    def apply(self, xy) -> np.ndarray:
        return self.frame.to_reference_px(self.inner.apply(xy))

    def residuals(self, src, dst) -> np.ndarray:
        return np.linalg.norm(self.apply(src) - as_xy(dst), axis=1)

    def loo_residuals(self, src, dst) -> np.ndarray:
        """Leave-one-out residuals of the inner fit, converted to reference pixels by the local scale."""
        frame_dst = self.frame.from_reference_px(dst)
        loo = self.inner.loo_residuals(src, frame_dst)
        ref = as_xy(dst)
        step = self.frame.from_reference_px(ref + [1.0, 0.0]) - frame_dst
        return loo / np.maximum(np.linalg.norm(step, axis=1), 1e-12)

    def to_dict(self) -> dict:
        inner = self.inner.to_dict()
        out = {"type": inner.pop("type"), "target_px_to_reference_px": None, "frame": "target_crs",
               "frame_crs": self.frame.frame_crs_wkt, "frame_transform": gdal_coefficients(self.frame.frame_transform),
               "target_px_to_frame_px": inner.pop("target_px_to_reference_px"),
               "reference_centre_lon": self.frame.reference_centre, "frame_centre_lon": self.frame.frame_centre}
        out.update(inner)
        return out


def fit_framed(fit, frame: CrsFrame, tgt_px, ref_px) -> FramedModel:
    """Fit with ``fit(src, dst)`` between target pixels and the frame pixels of ``ref_px``."""
    return FramedModel(fit(tgt_px, frame.from_reference_px(ref_px)), frame)
