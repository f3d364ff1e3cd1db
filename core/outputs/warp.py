"""The warped target: every band resampled by GDAL (through rasterio) onto a north-up output grid.

GDAL warps from the model VRT (:mod:`hamta.core.outputs.model_vrt`), which carries the fitted model
exactly. Formats: a tiled, compressed GeoTIFF (written in strips of rows by a multithreaded warp, so
progress is reported, cancellation is honoured and memory stays bounded; a thin plate spline is
warped by :mod:`hamta.core.outputs.spline_warp` instead, where OpenCV has the kernel), a cloud-optimised GeoTIFF
(the same, then GDAL's COG driver adds the overviews), or a warped VRT (the transformation and the
target's path, no pixels copied). Pixels the target does not cover are marked so that no valid
pixel (a valid 0 included) becomes nodata: the target's own nodata value, its collar's value, NaN
for floating-point data, or else an alpha band (:func:`fill_plan`).

Coordinates: the output grid is in the output CRS (the reference CRS unless asked otherwise);
models map target pixels to reference pixels (corner convention).
"""
from __future__ import annotations

import contextlib
import math
import os
import warnings
import xml.etree.ElementTree as ET
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np
import rasterio
import rasterio.shutil
from affine import Affine
from rasterio.crs import CRS
from rasterio.enums import Resampling
from rasterio.vrt import WarpedVRT
from rasterio.warp import reproject
from rasterio.warp import transform as transform_points
from rasterio.windows import Window

from ..coords import as_xy, compose, raster_outline
from ..errors import OutputError, UsageError
from ..estimation.models import local_jacobian
from ..io.raster import numpy_dtype, placeholder_crs
from ..options import FORMAT, PIXEL_GRID, RESAMPLING, OutputOptions
from ..parallel import THREADS
from ..progress import Monitor
from .model_vrt import scratch_dir, write_model_vrt
from .moved import write_moved
from .spline_warp import spline_applies, spline_rows
from .tags import verdict_tags

STRIP_BYTES = 32 * 2 ** 20  # a strip of output rows (all bands); two are in memory at a time
WARP_MEMORY_MB = 256
# NUM_THREADS: DEFLATE compresses blocks on every core (a third of the writing time on two).
GTIFF_OPTIONS = {"TILED": "YES", "BLOCKXSIZE": "256", "BLOCKYSIZE": "256", "COMPRESS": "DEFLATE",
                 "BIGTIFF": "IF_SAFER", "INTERLEAVE": "BAND", "NUM_THREADS": str(THREADS)}
COG_OPTIONS = {"COMPRESS": "DEFLATE", "BIGTIFF": "IF_SAFER", "OVERVIEW_RESAMPLING": "AVERAGE",
               "NUM_THREADS": str(THREADS)}


def gdal_resampling(name: str) -> Resampling:
    """rasterio's enum member for a :data:`~hamta.core.options.RESAMPLING` value."""
    return Resampling[RESAMPLING.check(name).replace("cubicspline", "cubic_spline")]


def output_format(path: str, fmt: str = "auto") -> str:
    """'gtiff', 'cog' or 'vrt': ``fmt``, or with 'auto' from the file name (.vrt: a VRT)."""
    fmt = FORMAT.check(fmt)
    if fmt != "auto":
        return fmt
    return "vrt" if path.lower().endswith(".vrt") else "gtiff"


@dataclass(frozen=True)
class Fill:
    """How pixels outside the target are marked: a ``nodata`` value, or an ``alpha`` band; ``source``
    is the value of the target's own pixels that are not data (nodata or collar), if any."""

    nodata: Optional[float]
    alpha: bool
    source: Optional[float]


def check_output_options(output: OutputOptions, target, path: str) -> None:
    """Before any work: GDAL accepts the creation options for the format of the raster written at
    ``path``, and a nodata value fits its pixel type (the target's, ``target`` a
    :class:`~hamta.core.io.raster.RasterInfo`). Raises ``ValueError`` naming the option."""
    fmt = output_format(path, output.format)
    if output.pixel_grid == "target" and (fmt == "vrt" or output.crs is not None or output.resolution is not None):
        raise UsageError("the output grid 'target' keeps the target's pixels in the reference CRS: it takes no "
                         "output CRS or resolution, and is written as GeoTIFF or COG, not VRT")
    if output.creation_options and fmt == "vrt":
        raise UsageError("creation options (--co) apply to the gtiff and cog formats, not to a warped VRT")
    if output.creation_options:
        problems = _gdal_complaints(fmt, _creation(COG_OPTIONS if fmt == "cog" else GTIFF_OPTIONS, output))
        if problems:
            raise UsageError(f"creation options {', '.join(output.creation_options)}: GDAL's {fmt.upper()} driver "
                             f"says: {'; '.join(problems)}")
    if output.fill == "nodata" and output.nodata is not None:
        kind = numpy_dtype(target.dtype if not target.is_complex else "float32")
        if np.issubdtype(kind, np.integer):
            info = np.iinfo(kind)
            if not (float(output.nodata).is_integer() and info.min <= output.nodata <= info.max):
                raise UsageError(f"nodata {output.nodata:g} does not fit the pixel type of '{target.path}' "
                                 f"({kind.name}: whole numbers {info.min} to {info.max})")


def _gdal_complaints(fmt: str, creation: dict) -> list:
    """What GDAL warns about ``creation`` when it writes a 16 x 16 probe in memory (unknown options,
    values it ignores)."""
    import logging
    import uuid

    messages = []

    class Collect(logging.Handler):
        def emit(self, record):
            if record.levelno >= logging.WARNING:
                messages.append(record.getMessage().split(" in ", 1)[-1])

    handler, logger = Collect(), logging.getLogger("rasterio._env")
    logger.addHandler(handler)
    plain = f"/vsimem/hamta-probe-{uuid.uuid4().hex}.tif"
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            probe = dict(driver="GTiff", width=16, height=16, count=1, dtype="uint8")
            with rasterio.open(plain, "w", **(probe if fmt == "cog" else dict(probe, **creation))) as dst:
                dst.write(np.zeros((1, 16, 16), np.uint8))
            if fmt == "cog":
                rasterio.shutil.copy(plain, plain + ".cog.tif", driver="COG", **creation)
    except (rasterio.errors.RasterioError, ValueError) as exc:
        messages.append(str(exc))
    finally:
        logger.removeHandler(handler)
        for path in (plain, plain + ".cog.tif"):
            with contextlib.suppress(Exception):
                rasterio.shutil.delete(path)
    return messages


def fill_plan(target, dtype: str, output: OutputOptions) -> Fill:
    """The :class:`Fill` for ``target`` (a :class:`~hamta.core.io.raster.RasterInfo`) of pixel type ``dtype``."""
    source = target.nodata if target.nodata is not None else target.collar
    if output.fill == "alpha":
        return Fill(None, True, source)
    if output.fill == "nodata":
        value = output.nodata if output.nodata is not None else (source if source is not None else 0.0)
        return Fill(float(value), False, source)
    if source is not None:
        return Fill(float(source), False, source)
    if np.issubdtype(numpy_dtype(dtype), np.floating):
        return Fill(float("nan"), False, None)
    return Fill(None, True, None)


def output_grid(result, grid: str = "auto", resolution: Optional[float] = None, crs: Optional[str] = None
                ) -> Tuple[Affine, int, int, Optional[CRS]]:
    """(transform, width, height, crs) of the warped output, north-up.

    In the reference CRS: 'reference' uses the reference pixel size and grid; 'native' keeps the
    target's own resolution (snapped to the reference grid origin); 'auto' picks 'reference' when
    the two resolutions are within 10 %. ``resolution`` (output CRS units) overrides the pixel size.
    In another ``crs`` the same pixel size is carried over at the centre and the grid is aligned to
    multiples of it. In pixel mode the output is the reference pixel grid itself.
    """
    PIXEL_GRID.check(grid)
    ref = result.reference
    if result.pixel_mode:
        if crs is not None:
            raise OutputError("An output CRS needs a georeferenced reference; the reference "
                              f"'{ref.path}' has none, so the output is on its pixel grid.")
        return Affine.identity(), ref.width, ref.height, None
    t = result.target
    mp = result.reference_to_map(result.model.apply(raster_outline(t.width, t.height, 33, ends=True)))
    centre = as_xy([t.width / 2.0, t.height / 2.0])
    scale = math.sqrt(abs(np.linalg.det(local_jacobian(result.model, centre)[0])))  # ref px per target px
    target_px_size = ref.pixel_size * scale  # map units of one target pixel at the centre
    res_x, res_y = abs(ref.transform.a) or ref.pixel_size, abs(ref.transform.e) or ref.pixel_size
    if grid == "native" or (grid == "auto" and not 0.9 <= scale <= 1.1):
        res_x, res_y = res_x * scale, res_y * scale
    out_crs = ref.crs if crs is None else CRS.from_user_input(crs)
    x0, y0 = ref.transform.c, ref.transform.f
    if out_crs != ref.crs:
        if ref.crs is None:
            raise OutputError(f"An output CRS needs a reference with a CRS; '{ref.path}' has none.")
        mid = result.reference_to_map(result.model.apply(centre))[0]
        probe = np.array([mid, mid + [res_x, 0.0], mid + [0.0, res_y]])
        px, py = transform_points(ref.crs, out_crs, probe[:, 0], probe[:, 1])
        step = math.sqrt(math.hypot(px[1] - px[0], py[1] - py[0]) * math.hypot(px[2] - px[0], py[2] - py[0]))
        target_px_size *= step / math.sqrt(res_x * res_y)
        res_x = res_y = step
        xs, ys = transform_points(ref.crs, out_crs, mp[:, 0], mp[:, 1])
        mp = np.column_stack([xs, ys])
        x0 = y0 = 0.0
    if resolution is not None:
        res_x = res_y = float(resolution)
    if not np.isfinite(mp).all():
        raise OutputError(f"The fitted model does not map '{t.path}' to finite coordinates in the output CRS.")
    xmin = x0 + math.floor((mp[:, 0].min() - x0) / res_x) * res_x
    xmax = x0 + math.ceil((mp[:, 0].max() - x0) / res_x) * res_x
    ymax = y0 - math.floor((y0 - mp[:, 1].max()) / res_y) * res_y
    ymin = y0 - math.ceil((y0 - mp[:, 1].min()) / res_y) * res_y
    width, height = int(round((xmax - xmin) / res_x)), int(round((ymax - ymin) / res_y))
    out_px_per_target_px = target_px_size ** 2 / (res_x * res_y)  # from the model's scale, not the grid's
    limit = 16 * t.width * t.height * max(out_px_per_target_px, 1.0) + 1e6
    if width * height > limit or width <= 0 or height <= 0:
        raise OutputError(f"The fitted model maps '{t.path}' onto an implausible {width} x {height} pixel "
                          "grid; the registration is probably wrong, so no raster was written.")
    return Affine(res_x, 0, xmin, 0, -res_y, ymax), width, height, out_crs


def write_warped(path: str, result, output: OutputOptions = OutputOptions(), monitor: Optional[Monitor] = None,
                 scratch: Optional[str] = None) -> str:
    """Warp every band of the target onto the output grid and write it at ``path`` in the format
    :func:`output_format` picks; returns that format."""
    monitor = monitor or Monitor()
    fmt = output_format(path, output.format)
    if output.pixel_grid == "target":
        write_moved(path, result, _creation(COG_OPTIONS if fmt == "cog" else GTIFF_OPTIONS, output), fmt == "cog",
                    monitor)
        return fmt
    transform, width, height, crs = output_grid(result, output.pixel_grid, output.resolution, output.crs)
    warp_crs = crs or placeholder_crs()
    with scratch_dir(scratch) as tmp:
        vrt = os.path.join(tmp, f"model-{os.getpid()}.vrt")
        options = write_model_vrt(vrt, result, warp_crs.to_wkt(), scratch=tmp)
        with rasterio.open(vrt) as src:
            fill = fill_plan(result.target, src.dtypes[0], output)
            grid = (transform, width, height, crs, warp_crs)
            if fmt == "vrt":
                _write_warped_vrt(path, src, result, grid, fill, output, options)
            elif fmt == "cog":
                staged = os.path.join(tmp, f"cog-{os.getpid()}.tif")
                _write_gtiff(staged, src, result, grid, fill, output, options, monitor.span(0.0, 0.8), {})  # plain
                monitor.report(0.8, "writing overviews")
                rasterio.shutil.copy(staged, path, driver="COG", **_creation(COG_OPTIONS, output))
            else:
                _write_gtiff(path, src, result, grid, fill, output, options, monitor,
                             _creation(GTIFF_OPTIONS, output))
    monitor.report(1.0, "writing")
    return fmt


def _creation(defaults: dict, output: OutputOptions) -> dict:
    options = dict(defaults)
    for item in output.creation_options:
        key, value = item.split("=", 1)
        options[key.strip().upper()] = value.strip()
    return options


def _write_gtiff(path, src, result, grid, fill: Fill, output: OutputOptions, options, monitor: Monitor, creation):
    """The warped GeoTIFF at ``path`` with GDAL creation options ``creation`` (for a COG, the user's
    options apply to the final copy, not to this staged file)."""
    transform, width, height, crs, warp_crs = grid
    count = src.count + (1 if fill.alpha else 0)
    dtype = src.dtypes[0]
    profile = dict(driver="GTiff", width=width, height=height, count=count, dtype=dtype, nodata=fill.nodata,
                   **creation)
    if not result.pixel_mode:  # a reference with a geotransform but no CRS: its map units, CRS unknown
        profile.update(transform=transform)
    if crs is not None:
        profile.update(crs=crs)
    bands = list(range(1, src.count + 1))
    row_bytes = max(width * count * numpy_dtype(dtype).itemsize, 1)
    rows = max(256, int(STRIP_BYTES // row_bytes) // 256 * 256)
    resampling = gdal_resampling(output.resampling)
    own = spline_applies(result, dtype, output.resampling)

    def strip(r0: int) -> np.ndarray:
        n = min(rows, height - r0)
        if own:
            return spline_rows(src, bands, result, grid, fill, output.resampling, r0, n)
        block = np.zeros((count, n, width), dtype=numpy_dtype(dtype))
        if fill.nodata is not None:
            block[:] = fill.nodata
        reproject(rasterio.band(src, bands), block, src_nodata=fill.source,
                  dst_transform=compose(transform, Affine.translation(0, r0)), dst_crs=warp_crs,
                  dst_nodata=fill.nodata, dst_alpha=count if fill.alpha else 0, resampling=resampling,
                  num_threads=THREADS, warp_mem_limit=WARP_MEMORY_MB, **options)
        return block

    starts = list(range(0, height, rows))
    # The next strip is warped while this one is compressed and written (two strips in memory).
    with rasterio.open(path, "w", **profile) as dst, ThreadPoolExecutor(1) as ahead:
        pending = ahead.submit(strip, starts[0])
        for i, r0 in enumerate(starts):
            monitor.check()
            block = pending.result()
            if i + 1 < len(starts):
                pending = ahead.submit(strip, starts[i + 1])
            dst.write(block, window=Window(0, r0, width, block.shape[1]))
            monitor.report((r0 + block.shape[1]) / height, "writing raster")
        interp = list(src.colorinterp)
        if fill.alpha:
            from rasterio.enums import ColorInterp

            interp.append(ColorInterp.alpha)
        dst.colorinterp = interp
        dst.update_tags(**verdict_tags(result))


def _write_warped_vrt(path, src, result, grid, fill: Fill, output: OutputOptions, options):
    """A VRTWarpedDataset reading the target itself (absolute path) through the serialised transformer."""
    transform, width, height, crs, warp_crs = grid
    with WarpedVRT(src, crs=warp_crs, transform=transform, width=width, height=height,
                   resampling=gdal_resampling(output.resampling), src_nodata=fill.source, nodata=fill.nodata,
                   add_alpha=fill.alpha, warp_mem_limit=WARP_MEMORY_MB, NUM_THREADS=str(THREADS), **options) as vrt:
        staged = path + ".staged.vrt"
        rasterio.shutil.copy(vrt, staged, driver="VRT")
    tree = ET.parse(staged)
    os.remove(staged)
    root = tree.getroot()
    for el in root.iter("SourceDataset"):
        el.text = os.path.abspath(result.target.path)
        el.set("relativeToVRT", "0")
    metadata = ET.Element("Metadata")
    for key, value in verdict_tags(result).items():
        ET.SubElement(metadata, "MDI", key=key).text = value
    root.insert(0, metadata)
    if crs is None:
        for el in root.findall("SRS"):
            root.remove(el)
    tree.write(path, encoding="UTF-8")
