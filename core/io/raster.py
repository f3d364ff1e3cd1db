"""Raster access through rasterio: metadata, band choice, masks and bounded-memory reads.

This is the only module that opens input rasters. Reads are always of a window and, when a pixel
budget asks for it, decimated by GDAL (which uses overviews when the file has them), so memory is
bounded by the requested output size and not by the file size. Pixel coordinates follow
:mod:`hamta.core.coords` (corner origin, x = column, y = row).
"""
from __future__ import annotations

import contextlib
import math
import os
import threading
import warnings
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Optional, Tuple

import numpy as np
import rasterio
from affine import Affine
from rasterio.crs import CRS
from rasterio.enums import ColorInterp, MaskFlags, Resampling
from rasterio.errors import NodataShadowWarning, NotGeoreferencedWarning, RasterioError
from rasterio.windows import Window

from ..errors import InputError
from .collar import SAMPLE_PIXELS, Collar, find_collar
from .scope import current, dataset_for, file_key

# Plain images (pixel mode) and nodata shadowing an alpha band are expected here; rasterio's warnings about
# them tell a user nothing. Filtered for the process too: ``warnings.catch_warnings`` is not thread-safe
# (the refinement, the check and the writers read on threads), so a block's filter may be undone.
warnings.filterwarnings("ignore", category=NotGeoreferencedWarning)
warnings.filterwarnings("ignore", category=NodataShadowWarning)

SUPPORTED_DTYPES = ("uint8", "int8", "uint16", "int16", "uint32", "int32", "float32", "float64",
                    "complex64", "complex128", "complex_int16")
STRIP_PIXELS = 4_000_000  # full-resolution pixels held at once when complex data is decimated


@dataclass(frozen=True)
class RasterInfo:
    """What Hamta needs to know about an input raster, read once without loading pixels.

    ``transform`` maps pixel corner coordinates to map coordinates. ``georeferenced`` tells
    whether it is real (from a geotransform, or an affine fit of the file's GCPs when
    ``georef_source == 'gcps'``) or the identity GDAL reports for plain images.
    """

    path: str
    width: int
    height: int
    count: int
    dtype: str
    crs: Optional[rasterio.crs.CRS]
    transform: Affine
    georef_source: str  # 'geotransform', 'gcps' or 'none'
    nodata: Optional[float]
    colorinterp: Tuple[str, ...]
    overview_factors: Tuple[int, ...]
    collar_fill: Optional[Collar] = field(default=None, compare=False, repr=False)

    @property
    def collar(self) -> Optional[float]:
        """The value of an undeclared fill around the footprint, read as nodata (None without one)."""
        return None if self.collar_fill is None else self.collar_fill.value

    @property
    def collar_share(self) -> float:
        return 0.0 if self.collar_fill is None else self.collar_fill.share

    @property
    def georeferenced(self) -> bool:
        return self.georef_source != "none"

    @property
    def is_complex(self) -> bool:
        return self.dtype.startswith("complex")

    @property
    def pixel_size(self) -> float:
        """Map units per pixel (geometric mean of the two axes); 1 when not georeferenced."""
        return math.sqrt(abs(self.transform.determinant))

    def window(self) -> Window:
        return Window(0, 0, self.width, self.height)


def open_raster(path, role: str = "input") -> RasterInfo:
    """Read the metadata of ``path``; raise :class:`InputError` naming the file on any problem.

    Parameters
    ----------
    path : str or os.PathLike
        Anything GDAL opens (a file, a VRT, a ``/vsi...`` path).
    role : str
        'target' or 'reference', used in error messages.
    """
    path = os.fspath(path)
    if not path.startswith("/vsi") and not os.path.exists(path) and ":" not in os.path.basename(path):
        raise InputError(f"The {role} raster '{path}' does not exist.")
    if os.path.isdir(path):
        raise InputError(f"The {role} raster '{path}' is a folder, not a raster file.")
    if os.path.exists(path) and not os.path.isfile(path):  # reading a pipe or a device would wait forever
        raise InputError(f"The {role} raster '{path}' is not a regular file (a pipe, socket or device); save the "
                         "raster to a file first.")
    files = current()
    key = file_key(path) if files is not None else None
    if key is not None and key in files.described:
        return files.described[key]
    try:
        with dataset_for(path) as ds:
            info = _describe(ds, path, role)
    except (RasterioError, OSError, RecursionError) as exc:
        raise InputError(f"The {role} raster '{path}' is not a raster GDAL can read, or it is truncated or corrupt "
                         f"({str(exc).strip() or type(exc).__name__}).") from None
    if key is not None:
        files.described[key] = info
    return info


def _describe(ds, path: str, role: str) -> RasterInfo:
    if ds.count < 1 or ds.width < 1 or ds.height < 1:
        raise InputError(f"The {role} raster '{path}' has no pixels (bands={ds.count}, "
                         f"size={ds.width}x{ds.height}).")
    dtype = ds.dtypes[0]
    if dtype not in SUPPORTED_DTYPES:
        raise InputError(f"The {role} raster '{path}' has pixel type {dtype}, which Hamta does not "
                         f"support (supported: {', '.join(SUPPORTED_DTYPES)}).")
    transform, source = ds.transform, "geotransform"
    if transform == Affine.identity() and ds.crs is None:
        source = "none"
        gcps, gcp_crs = ds.gcps
        if len(gcps) >= 3:
            transform, source = rasterio.transform.from_gcps(gcps), "gcps"
            crs = gcp_crs
        else:
            crs = None
    else:
        crs = ds.crs
    if transform.determinant == 0:
        raise InputError(f"The {role} raster '{path}' has a degenerate geotransform {transform}.")
    return RasterInfo(
        path=path, width=ds.width, height=ds.height, count=ds.count, dtype=dtype,
        crs=crs if crs else None, transform=transform, georef_source=source, nodata=ds.nodata,
        colorinterp=tuple(ci.name for ci in ds.colorinterp),
        overview_factors=tuple(ds.overviews(1)),
        collar_fill=_collar(ds, dtype),
    )


def _collar(ds, dtype: str):
    """A collar (see :mod:`hamta.core.io.collar`) when the raster declares no valid-pixel mask."""
    if ds.nodata is not None or dtype.startswith("complex") or any(
            MaskFlags.all_valid not in flags for flags in ds.mask_flag_enums):
        return None
    shape, factor = budget_shape(ds.width, ds.height, SAMPLE_PIXELS)
    bands = list(range(1, min(ds.count, 4) + 1))
    sample = ds.read(bands, out_shape=(len(bands),) + shape, resampling=Resampling.nearest)
    return find_collar(sample, dtype, factor)


def check_on_earth(info: RasterInfo, role: str) -> None:
    """Refuse georeferencing that puts the raster where its CRS has no place: beyond a pole in a
    geographic CRS (more than half a pixel), or where the CRS cannot be turned into longitude and
    latitude. Rasters without a CRS (a map in local units) pass."""
    if info.crs is None or not info.georeferenced:
        return
    from pyproj import CRS, Transformer

    from ..coords import pixel_to_map, raster_outline

    xy = pixel_to_map(info.transform, raster_outline(info.width, info.height, 9, ends=True))
    crs = CRS.from_user_input(info.crs.to_wkt())
    if crs.is_geographic:
        lat = xy[:, 1]  # GDAL geotransforms are in longitude, latitude order whatever the CRS says
        slack = 0.5 * abs(info.transform.e) + 1e-9
        if np.abs(lat).max() > 90.0 + slack:
            raise InputError(f"The {role} raster '{info.path}' is georeferenced beyond the pole (latitude up to "
                             f"{np.abs(lat).max():.6g}°): its geotransform or CRS is wrong.")
        return
    geo = crs.geodetic_crs
    if geo is None:
        return
    lon, lat = Transformer.from_crs(crs, geo, always_xy=True).transform(xy[:, 0], xy[:, 1], errcheck=False)
    if not (np.isfinite(lon).all() and np.isfinite(lat).all() and np.abs(lat).max() <= 90.0):
        raise InputError(f"The {role} raster '{info.path}' is georeferenced outside what its CRS ({crs.name}) can "
                         "place on the Earth: its geotransform or CRS is wrong.")


@lru_cache(maxsize=1)
def placeholder_crs() -> CRS:
    """A projected CRS that lets GDAL resample between two grids of rasters without one (looked up
    once, when first needed: PROJ's database costs 10 ms)."""
    return CRS.from_epsg(3857)


def numpy_dtype(name: str) -> np.dtype:
    """The numpy type rasterio reads a GDAL pixel type into (GDAL's CInt16 has none of its own)."""
    return np.dtype("complex64" if name == "complex_int16" else name)


def resolve_bands(info: RasterInfo, band: Optional[int]) -> Tuple[int, ...]:
    """The 1-based band indexes to read for ``band``; ``None`` means luminance of RGB or band 1."""
    if band is None:
        rgb = (ColorInterp.red.name, ColorInterp.green.name, ColorInterp.blue.name)
        if info.count >= 3 and info.colorinterp[:3] == rgb:
            return (1, 2, 3)
        return (1,)
    if not 1 <= band <= info.count:
        raise InputError(f"Band {band} does not exist in '{info.path}', which has {info.count} "
                         f"band(s).")
    return (band,)


LUMINANCE = np.array([0.299, 0.587, 0.114], dtype=np.float32)


def read_image(info: RasterInfo, bands: Tuple[int, ...], window: Optional[Window] = None,
               out_shape: Optional[Tuple[int, int]] = None, dataset=None) -> Tuple[np.ndarray, np.ndarray]:
    """Read one grey image and its validity mask from a window, optionally decimated.

    Parameters
    ----------
    info : RasterInfo
    bands : tuple of int
        One band, or three RGB bands combined to luminance.
    window : Window, optional
        Window in whole full-resolution pixels; the whole raster by default. Parts outside the
        raster read as invalid (through GDAL's slower boundless path).
    dataset : open rasterio dataset of ``info.path``, optional
        Saves re-opening the file when many small windows are read (see :class:`hamta.core.io.windows.WindowReader`).
    out_shape : (rows, cols), optional
        Size of the returned arrays; pixel (x, y) of the output covers the full-resolution area
        ``window.col_off + x * window.width / cols`` (corner convention, so no half-pixel shift).

    Returns
    -------
    image : (rows, cols) float32
        Complex data is returned as amplitude; invalid pixels hold 0.
    valid : (rows, cols) bool
        False where the raster is nodata, masked, NaN or outside the window's raster.
    """
    window = window or info.window()
    shape = out_shape or (int(window.height), int(window.width))
    decimating = shape[0] < window.height or shape[1] < window.width
    inside = (window.col_off >= 0 and window.row_off >= 0 and window.col_off + window.width <= info.width
              and window.row_off + window.height <= info.height)
    full_shape = (len(bands),) + tuple(shape)
    shadow = info.nodata is not None and ColorInterp.alpha.name in info.colorinterp  # GDAL uses the nodata
    with _quiet(not info.georeferenced or shadow), _read_errors_named(info), dataset_for(info.path, dataset) as ds:
        if info.is_complex and decimating:
            data = _read_amplitude_by_strips(ds, bands, window, shape, not inside)
        else:
            palette = _palette_grey(info, bands, ds)
            resampling = Resampling.average if decimating and palette is None else Resampling.nearest
            data = ds.read(bands, window=window, out_shape=full_shape, resampling=resampling,
                           boundless=not inside, fill_value=0)
            data = np.abs(data) if info.is_complex else data if palette is None else palette[data]
        # GDAL would compute an all-valid mask block by block and keep those blocks in its cache
        # (120 MB for a 10980 px band read once); inside the raster such a mask is all true anyway.
        flags = ds.mask_flag_enums if inside else ()
        all_valid = inside and all(MaskFlags.all_valid in flags[b - 1] for b in bands)
        masks = None if all_valid else ds.read_masks(bands, window=window, out_shape=full_shape,
                                                     resampling=Resampling.nearest, boundless=not inside)
    data = data.astype(np.float32, copy=False)
    valid = np.all(np.isfinite(data), axis=0)
    if masks is not None:
        valid &= np.all(masks > 0, axis=0)
    if info.collar_fill is not None:
        valid &= ~info.collar_fill.window_mask(window.col_off, window.row_off, window.width, window.height, shape)
    image = np.tensordot(LUMINANCE, data, axes=1) if len(bands) == 3 else data[0]
    image = np.where(valid, image, 0).astype(np.float32, copy=False)
    return image, valid


def _palette_grey(info: RasterInfo, bands, ds) -> Optional[np.ndarray]:
    """The luminance of each entry of a palette band's colour table (a chart or a scanned map in 256
    colours: its indexes are not brightness), or None for a band without one."""
    if len(bands) != 1 or info.colorinterp[bands[0] - 1] != ColorInterp.palette.name or info.dtype not in ("uint8",
                                                                                                           "uint16"):
        return None
    try:
        table = ds.colormap(bands[0])
    except ValueError:
        return None
    size = 256 if info.dtype == "uint8" else 65536
    rgb = np.array([table.get(i, (0, 0, 0, 0))[:3] for i in range(size)], np.float32)
    return rgb @ LUMINANCE


_QUIET = threading.Lock()


@contextlib.contextmanager
def _quiet(needed: bool):
    """Rasterio's two warnings ignored in this block, also for callers that raise on warnings, when
    ``needed`` (a plain image, nodata beside an alpha band: the reads that warn), one block at a time:
    ``warnings.catch_warnings`` swaps the process's filters, which threads must not interleave."""
    if not needed:
        yield
        return
    with _QUIET, warnings.catch_warnings():
        warnings.simplefilter("ignore", NotGeoreferencedWarning)
        warnings.simplefilter("ignore", NodataShadowWarning)
        yield


@contextlib.contextmanager
def _read_errors_named(info: RasterInfo):
    """GDAL read failures (a truncated or corrupt file, a VRT whose source is gone) as
    :class:`InputError` naming the raster."""
    try:
        yield
    except (RasterioError, OSError) as exc:
        raise InputError(f"The raster '{info.path}' could not be read: it may be truncated or corrupt, or a file it "
                         f"refers to is missing ({str(exc).strip() or type(exc).__name__}).") from None


def _read_amplitude_by_strips(ds, bands, window, out_shape, boundless):
    """Area-average the amplitude (not the complex values) of each output cell, strip by strip."""
    rows, cols = out_shape
    height, width = int(window.height), int(window.width)
    w_rows = _area_weights(height, rows)
    w_cols = _area_weights(width, cols)
    out = np.zeros((len(bands), rows, cols), np.float64)
    step = max(1, STRIP_PIXELS // max(width, 1))
    for r0 in range(0, height, step):
        r1 = min(height, r0 + step)
        strip = Window(window.col_off, window.row_off + r0, width, r1 - r0)
        amp = np.abs(ds.read(bands, window=strip, boundless=boundless, fill_value=0))
        for i in range(len(bands)):
            out[i] += w_rows[:, r0:r1] @ (w_cols @ amp[i].astype(np.float64).T).T
    return out.astype(np.float32)


def _area_weights(n_src: int, n_out: int):
    """Sparse (n_out, n_src) matrix averaging source cells over each output cell's footprint."""
    from scipy import sparse

    edges = np.arange(n_out + 1) * (n_src / n_out)
    rows, cols, vals = [], [], []
    for i in range(n_out):
        lo, hi = edges[i], edges[i + 1]
        for j in range(int(np.floor(lo)), min(n_src, int(np.ceil(hi)))):
            overlap = min(hi, j + 1) - max(lo, j)
            if overlap > 0:
                rows.append(i)
                cols.append(j)
                vals.append(overlap / (hi - lo))
    return sparse.csr_matrix((vals, (rows, cols)), shape=(n_out, n_src))


def budget_shape(width: float, height: float, max_pixels: int) -> Tuple[Tuple[int, int], float]:
    """Output (rows, cols) of a ``width x height`` window within ``max_pixels``, and the factor."""
    factor = max(1.0, math.sqrt(width * height / float(max_pixels)))
    return (max(1, int(round(height / factor))), max(1, int(round(width / factor)))), factor


def input_files(info: RasterInfo) -> Tuple[str, ...]:
    """Every file reading ``info`` touches: the raster, its sidecars, a VRT's sources."""
    try:
        with rasterio.open(info.path) as ds:
            files = tuple(ds.files)
    except RasterioError:
        files = ()
    return (info.path,) + files
