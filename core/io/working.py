"""Overlap planning and the working images every matching method sees.

A registration never matches full files: each raster is read once at a *working* resolution
bounded by a pixel budget. When both rasters are georeferenced, the target's georeferencing is a
prior: only the overlap is read and the target is resampled onto the reference's working grid, so
methods see both images in a common orientation and scale. Otherwise each raster is read whole
within the budget and the method searches the full images.

Every working image carries a ``to_source`` map from working pixels to full-resolution pixels of
its raster (both in the corner convention of :mod:`hamta.core.coords`), so correspondences found
in working pixels become target/reference pixel pairs exactly.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Optional, Tuple

import numpy as np
from affine import Affine
from rasterio.crs import CRS
from rasterio.warp import Resampling, reproject
from rasterio.windows import Window
from shapely.geometry import Polygon, box

from ..coords import as_xy, compose, continue_longitudes, map_to_pixel, pixel_to_map, raster_outline, transformer
from ..errors import GeoreferencingError, InputError, NoOverlapError
from ..options import TARGET_GEOREF
from ..parallel import threaded
from .raster import RasterInfo, budget_shape, placeholder_crs, read_image

# Up to this many source px per destination px GDAL's bilinear kernel keeps its plain 2 x 2 support.
_PLAIN_BILINEAR_SCALE = 1.01
_STRIP_ROWS = 256


@dataclass(frozen=True)
class ScaledWindow:
    """Working pixels -> source pixels of a decimated window read: ``src = off + xy * scale``."""

    col_off: float
    row_off: float
    sx: float
    sy: float

    def forward(self, xy) -> np.ndarray:
        xy = as_xy(xy)
        return np.column_stack([self.col_off + xy[:, 0] * self.sx, self.row_off + xy[:, 1] * self.sy])

    def inverse(self, xy) -> np.ndarray:
        xy = as_xy(xy)
        return np.column_stack([(xy[:, 0] - self.col_off) / self.sx, (xy[:, 1] - self.row_off) / self.sy])


@dataclass(frozen=True, eq=False)
class MapLink:
    """Map coordinates of one CRS -> another; longitudes of a geographic destination are continued next
    to the destination raster's centre (``centre``, see :func:`hamta.core.coords.continue_longitudes`)."""

    transformer: object  # a pyproj Transformer
    centre: Optional[float] = None

    def __call__(self, xy: np.ndarray) -> np.ndarray:
        x, y = self.transformer.transform(xy[:, 0], xy[:, 1])
        return continue_longitudes(np.column_stack([x, y]), self.centre)


@dataclass(frozen=True, eq=False)
class ReprojectedGrid:
    """Working pixels of a grid in one CRS -> source pixels of a raster in another CRS."""

    grid_transform: Affine
    src_transform: Affine
    to_src_crs: Optional[MapLink]
    to_grid_crs: Optional[MapLink]

    def forward(self, xy) -> np.ndarray:
        return map_to_pixel(self.src_transform, _reproject_xy(self.to_src_crs, pixel_to_map(self.grid_transform, xy)))

    def inverse(self, xy) -> np.ndarray:
        return map_to_pixel(self.grid_transform, _reproject_xy(self.to_grid_crs, pixel_to_map(self.src_transform, xy)))


def _reproject_xy(link: Optional[MapLink], xy: np.ndarray) -> np.ndarray:
    return xy if link is None else link(xy)


@dataclass(frozen=True, eq=False)
class WorkingImage:
    """A grey image at working resolution with its validity mask and its way back to the file.

    ``data`` is float32 in the raster's own units (complex already as amplitude); invalid pixels
    hold 0. ``source_px_per_working_px`` is the approximate linear decimation factor.
    """

    data: np.ndarray
    valid: np.ndarray
    to_source: object
    info: RasterInfo
    bands: Tuple[int, ...]
    source_px_per_working_px: float

    @property
    def shape(self) -> Tuple[int, int]:
        return self.data.shape


@dataclass(frozen=True)
class Plan:
    """How the working images were chosen.

    ``mode`` is 'georeferenced' (the target's georeferencing is used as a prior and only the
    overlap is read), 'search' (the target is placed by matching alone) or 'pixel' (the reference
    has no georeferencing: map coordinates are reference pixels).
    """

    mode: str
    reference_window: Window
    target_window: Window
    notes: Tuple[str, ...] = field(default=())


def prepare_working_images(target: RasterInfo, reference: RasterInfo, *, target_bands, reference_bands,
                           max_pixels: int, target_georef: str = "auto", extent: Optional[str] = None,
                           target_pixels: Optional[int] = None):
    """Plan the overlap and read both working images; without the target's georeferencing, only the
    reference's part inside ``extent`` (a search area, see :mod:`hamta.core.extent`) is read, and the
    target within ``target_pixels`` when given (a scale guess when searching a large area).

    Returns
    -------
    (WorkingImage, WorkingImage, Plan)
        Target and reference working images (pixels: working space) and the plan.
    """
    TARGET_GEOREF.check(target_georef)
    prior, notes = _prior_usable(target, reference, target_georef)
    notes += [f"the {role} raster '{info.path}' has a collar of {info.collar:g} around its footprint "
              f"({100 * info.collar_share:.1f} % of the pixels, no nodata declared); it is read as nodata"
              for role, info in (("target", target), ("reference", reference)) if info.collar is not None]
    if prior:
        return _prepare_with_prior(target, reference, target_bands, reference_bands, max_pixels, notes)
    mode = "search" if reference.georeferenced else "pixel"
    window = reference.window() if extent is None else _search_window(reference, extent)
    tgt, ref = threaded(lambda job: _read_whole(*job), [
        (target, target_bands, min(max_pixels, target_pixels or max_pixels), "target"),
        (reference, reference_bands, max_pixels, "reference", window)])
    return tgt, ref, Plan(mode, window, target.window(), tuple(notes))


def _prior_usable(target: RasterInfo, reference: RasterInfo, choice: str):
    notes = []
    if choice == "ignore":
        return False, ["target georeferencing ignored on request"]
    problem = None
    if not target.georeferenced:
        problem = f"the target raster '{target.path}' has no georeferencing"
    elif not reference.georeferenced:
        problem = f"the reference raster '{reference.path}' has no georeferencing"
    elif (target.crs is None) != (reference.crs is None):
        problem = "only one of the two rasters has a CRS, so their coordinates cannot be related"
    elif not _relatable(target.crs, reference.crs):
        problem = (f"the target's CRS ({target.crs.to_string() or 'a local one'}) cannot be transformed to the "
                   f"reference's ({reference.crs.to_string() or 'a local one'}), e.g. a local engineering CRS")
    if problem is None:
        return True, notes
    if choice == "use":
        raise GeoreferencingError(f"Cannot use the target's georeferencing as a starting point: {problem}.")
    notes.append(f"searching the reference (or its search area) without a starting point: {problem}")
    return False, notes


def _relatable(a: Optional[CRS], b: Optional[CRS]) -> bool:
    """Whether PROJ can transform coordinates between two CRSs (a local engineering CRS cannot)."""
    if a is None or b is None or a == b:
        return True
    from pyproj.exceptions import CRSError, ProjError

    try:
        transformer(a, b)  # kept: the run transforms between them next
    except (ProjError, CRSError):
        return False
    return True


def _read_whole(info: RasterInfo, bands, max_pixels: int, role: str, window: Optional[Window] = None) -> WorkingImage:
    window = window or info.window()
    shape, factor = budget_shape(window.width, window.height, max_pixels)
    data, valid = read_image(info, bands, window, shape)
    _check_content(data, valid, info, role, "" if window == info.window() else " in the search area")
    to_source = ScaledWindow(window.col_off, window.row_off, window.width / shape[1], window.height / shape[0])
    return WorkingImage(data, valid, to_source, info, bands, factor)


def _search_window(reference: RasterInfo, extent: str) -> Window:
    """The reference's pixels inside the search area ``extent`` (whole pixels, clipped to the raster)."""
    from ..extent import bounds_in, parse_extent

    area = parse_extent(extent)
    if reference.crs is None and area.crs is not None:
        raise InputError(f"The search area {area.text()} names a CRS, but the reference raster '{reference.path}' has "
                         "none: give the area in its map units (or pixels) without a CRS.")
    crs = reference.crs.to_wkt() if reference.crs else None
    x0, y0, x1, y1 = bounds_in(area, crs, crs)
    window = _window_of(box(x0, y0, x1, y1), reference, None, 0)
    px = map_to_pixel(reference.transform, [(x0, y0), (x1, y1)])
    if px[:, 0].max() <= 0 or px[:, 1].max() <= 0 or px[:, 0].min() >= reference.width or \
            px[:, 1].min() >= reference.height:
        raise NoOverlapError(f"The search area {area.text()} does not overlap the reference raster '{reference.path}'.")
    return window


MIN_SIDE_PX = 16  # smaller than a matching window of any method


def _check_content(data, valid, info: RasterInfo, role: str, where: str) -> None:
    if min(data.shape) < MIN_SIDE_PX:
        raise InputError(f"The {role} raster '{info.path}' is too small to register{where}: {data.shape[1]} x "
                         f"{data.shape[0]} px at working resolution (at least {MIN_SIDE_PX} px per side).")
    n_valid = int(valid.sum())
    if n_valid < 64:
        raise InputError(f"The {role} raster '{info.path}' has no valid pixels{where} "
                         f"(all nodata or masked; {n_valid} valid at working resolution).")
    values = data[valid]
    if float(values.max()) == float(values.min()):
        raise InputError(f"The {role} raster '{info.path}' is constant{where} (every valid pixel is "
                         f"{float(values[0]):g}); there is nothing to match.")


def footprint(info: RasterInfo, crs: Optional[CRS], points_per_side: int = 21,
              centre: Optional[float] = None) -> Polygon:
    """Outline of a raster in map coordinates of ``crs`` (its own CRS when equal or None); longitudes of
    a geographic ``crs`` are continued next to ``centre`` (see :class:`MapLink`)."""
    edge = raster_outline(info.width, info.height, points_per_side)
    xy = pixel_to_map(info.transform, edge)
    link = _link(info.crs, crs, centre)
    xy = _reproject_xy(link, xy) if link is not None else continue_longitudes(xy, centre)
    poly = Polygon(xy[np.all(np.isfinite(xy), axis=1)])
    return poly if poly.is_valid else poly.buffer(0)


def _link(src: Optional[CRS], dst: Optional[CRS], centre: Optional[float] = None) -> Optional[MapLink]:
    if src is None or dst is None or src == dst:
        return None
    return MapLink(transformer(src, dst), centre)


def central_longitude(info: RasterInfo) -> Optional[float]:
    """The longitude of a geographic raster's centre (None for a projected or unknown CRS)."""
    if info.crs is None or not info.crs.is_geographic:
        return None
    return float(pixel_to_map(info.transform, [(info.width / 2.0, info.height / 2.0)])[0, 0])


def _window_of(polygon: Polygon, info: RasterInfo, crs: Optional[CRS], margin_px: float) -> Window:
    """Whole-pixel window of ``info`` covering ``polygon`` (map coordinates in ``crs``) plus a margin."""
    ring = _reproject_xy(_link(crs, info.crs, central_longitude(info)), np.asarray(polygon.exterior.coords))
    px = map_to_pixel(info.transform, ring)
    c0, r0 = np.floor(px.min(axis=0) - margin_px)
    c1, r1 = np.ceil(px.max(axis=0) + margin_px)
    c0, r0 = max(0, int(c0)), max(0, int(r0))
    c1, r1 = min(info.width, int(c1)), min(info.height, int(r1))
    return Window(c0, r0, max(1, c1 - c0), max(1, r1 - r0))


def _prepare_with_prior(target, reference, target_bands, reference_bands, max_pixels, notes):
    centre = central_longitude(reference)
    ref_poly = footprint(reference, reference.crs)
    tgt_poly = footprint(target, reference.crs, centre=centre)
    overlap = ref_poly.intersection(tgt_poly)
    if overlap.is_empty or overlap.area <= 0:
        raise NoOverlapError(
            f"The target raster '{target.path}' and the reference raster '{reference.path}' do not "
            "overlap according to their georeferencing. If the target's georeferencing is wrong, "
            "ignore it (CLI: --target-georef ignore) to search the whole reference.")
    overlap_box = box(*overlap.bounds)
    ref_window = _window_of(overlap_box, reference, reference.crs, 64 + 0.05 * max(reference.width, reference.height))
    tgt_window = _window_of(overlap_box, target, reference.crs, 64 + 0.05 * max(target.width, target.height))

    gsd_ref = reference.pixel_size
    gsd_tgt = math.sqrt(tgt_poly.area / (target.width * target.height))
    gsd = max(gsd_ref, gsd_tgt)
    n_px = ref_window.width * ref_window.height * (gsd_ref / gsd) ** 2
    gsd *= max(1.0, math.sqrt(n_px / max_pixels))
    factor = gsd / gsd_ref
    rows = max(1, int(round(ref_window.height / factor)))
    cols = max(1, int(round(ref_window.width / factor)))
    grid = ScaledWindow(ref_window.col_off, ref_window.row_off, ref_window.width / cols, ref_window.height / rows)
    grid_transform = compose(reference.transform, Affine.translation(grid.col_off, grid.row_off),
                             Affine.scale(grid.sx, grid.sy))

    tgt_factor = max(1.0, gsd / gsd_tgt)
    t_shape = (max(1, int(round(tgt_window.height / tgt_factor))), max(1, int(round(tgt_window.width / tgt_factor))))
    (ref_data, ref_valid), (t_data, t_valid) = threaded(lambda job: read_image(*job), [
        (reference, reference_bands, ref_window, (rows, cols)), (target, target_bands, tgt_window, t_shape)])
    _check_content(ref_data, ref_valid, reference, "reference", " where it overlaps the target")
    ref_img = WorkingImage(ref_data, ref_valid, grid, reference, reference_bands, factor)
    _check_content(t_data, t_valid, target, "target", " where it overlaps the reference")
    t_transform = compose(target.transform, Affine.translation(tgt_window.col_off, tgt_window.row_off),
                          Affine.scale(tgt_window.width / t_shape[1], tgt_window.height / t_shape[0]))
    data, valid = _resample_onto(t_data, t_valid, t_transform, target.crs, grid_transform, reference.crs, (rows, cols))
    _check_content(data, valid, target, "target", " where it overlaps the reference")
    to_source = ReprojectedGrid(grid_transform, target.transform, _link(reference.crs, target.crs,
                                                                        central_longitude(target)),
                                _link(target.crs, reference.crs, centre))
    tgt_img = WorkingImage(data, valid, to_source, target, target_bands, tgt_factor)
    plan = Plan("georeferenced", ref_window, tgt_window, tuple(notes))
    return tgt_img, ref_img, plan


def _resample_onto(data, valid, src_transform, src_crs, dst_transform, dst_crs, shape):
    """Resample a float image and its mask from one grid onto another (bilinear / nearest)."""
    if src_crs == dst_crs:
        to_src = ~src_transform * dst_transform  # destination px -> source px, corner convention
        if to_src.b == to_src.d == 0 and max(abs(to_src.a), abs(to_src.e)) <= _PLAIN_BILINEAR_SCALE:
            return _resample_axes(data, valid, to_src, shape)
    return _gdal_resample(data, valid, src_transform, src_crs, dst_transform, dst_crs, shape)


def _gdal_resample(data, valid, src_transform, src_crs, dst_transform, dst_crs, shape):
    src_crs = src_crs or placeholder_crs()
    dst_crs = dst_crs or placeholder_crs()
    src = np.where(valid, data, np.nan).astype(np.float32)
    out = np.full(shape, np.nan, np.float32)
    reproject(src, out, src_transform=src_transform, src_crs=src_crs, dst_transform=dst_transform,
              dst_crs=dst_crs, src_nodata=np.nan, dst_nodata=np.nan, resampling=Resampling.bilinear)
    mask = np.zeros(shape, np.uint8)
    reproject(valid.astype(np.uint8), mask, src_transform=src_transform, src_crs=src_crs,
              dst_transform=dst_transform, dst_crs=dst_crs, src_nodata=None, dst_nodata=0,
              resampling=Resampling.nearest)
    ok = np.isfinite(out) & (mask > 0)
    return np.where(ok, out, 0).astype(np.float32), ok


def _resample_axes(data, valid, to_src: Affine, shape):
    """:func:`_resample_onto` between two north-up grids of one CRS, at most ``_PLAIN_BILINEAR_SCALE`` source
    px per destination px: GDAL's bilinear weights renormalised over valid pixels and its nearest-neighbour
    mask, one axis at a time (the same on every library stack; OpenCV 4 rounds positions to 1/32 px), in a
    fraction of GDAL's time. Rows are done in strips, so that no large array is allocated per step."""
    rows = _Axis(shape[0], to_src.e, to_src.f, data.shape[0])
    cols = _Axis(shape[1], to_src.a, to_src.c, data.shape[1])
    values = np.where(valid, data, 0).astype(np.float32, copy=False)
    weights = valid.astype(np.float32)
    out, ok = np.zeros(shape, np.float32), np.zeros(shape, bool)
    for r0 in range(0, shape[0], _STRIP_ROWS):
        strip = slice(r0, r0 + _STRIP_ROWS)
        cover = _bilinear(weights, rows, cols, strip)
        ok[strip] = (valid[np.ix_(rows.nearest[strip], cols.nearest)] & rows.inside[strip, None] & cols.inside
                     & (cover > 1e-3))
        np.divide(_bilinear(values, rows, cols, strip), cover, out=out[strip], where=ok[strip])
    return out, ok


class _Axis:
    """Along one axis of the destination, each pixel centre's two source neighbours (``low``, ``high``) and
    their bilinear weights, zero for a neighbour outside the source; its nearest source pixel and whether
    that pixel is inside the source."""

    def __init__(self, n: int, scale: float, offset: float, size: int):
        centre = offset + scale * (np.arange(n) + 0.5) - 0.5  # source px, pixel-centre indices
        low = np.floor(centre)
        upper = (centre - low).astype(np.float32)
        self.low, self.w_low = self._inside(low, 1 - upper, size)
        self.high, self.w_high = self._inside(low + 1, upper, size)
        nearest = np.floor(centre + 0.5)
        self.inside = (nearest >= 0) & (nearest < size)
        self.nearest = np.clip(nearest, 0, size - 1).astype(np.intp)

    @staticmethod
    def _inside(index: np.ndarray, weight: np.ndarray, size: int):
        inside = (index >= 0) & (index < size)
        return np.clip(index, 0, size - 1).astype(np.intp), np.where(inside, weight, 0).astype(np.float32)


def _bilinear(a: np.ndarray, rows: _Axis, cols: _Axis, strip: slice) -> np.ndarray:
    """``a`` (float32) resampled at ``rows[strip]`` and every column."""
    along = a[rows.low[strip]] * rows.w_low[strip, None]
    along += a[rows.high[strip]] * rows.w_high[strip, None]
    out = np.take(along, cols.low, axis=1) * cols.w_low
    out += np.take(along, cols.high, axis=1) * cols.w_high
    return out
