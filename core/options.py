"""Every choice a user makes about a registration and its outputs, in one place.

Each choice is a :class:`Choice`: its allowed values with an English label each, keyed by value,
and its default. Front ends (CLI, Processing, benchmark) build their menus from these and map
back by value. The order of a choice's values is part of the ``qgis_process`` interface
(Processing enums are passed as indexes), so new values are appended, never inserted.

:func:`resolve_options` fills what a user left open with the chosen method's defaults; it is
the only place method defaults are resolved.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Mapping, Optional, Tuple


@dataclass(frozen=True)
class Choice:
    """The allowed values of one option (in interface order) with their labels and default."""

    name: str
    labels: Mapping[str, str]
    default: Optional[str]
    aliases: Mapping[str, str] = None

    @property
    def values(self) -> Tuple[str, ...]:
        return tuple(self.labels)

    def check(self, value: str) -> str:
        """``value`` in canonical spelling (aliases and case accepted); ``ValueError`` otherwise."""
        key = str(value).lower()
        key = (self.aliases or {}).get(key, key)
        if key not in self.labels:
            raise ValueError(f"unknown {self.name} {value!r}; choose one of {', '.join(self.values)}")
        return key

    def index(self, value: str) -> int:
        return self.values.index(self.check(value))

    def at(self, index: int) -> str:
        """The value at an enum ``index`` (as Processing passes it)."""
        if not 0 <= int(index) < len(self.values):
            raise ValueError(f"{self.name} index {index} is out of range 0..{len(self.values) - 1}")
        return self.values[int(index)]


MODEL = Choice("model", {
    "similarity": "Similarity (Helmert)",
    "affine": "Affine (polynomial 1)",
    "projective": "Projective",
    "polynomial-2": "Polynomial 2",
    "polynomial-3": "Polynomial 3",
    "tps": "Thin plate spline",
    "linear": "Linear (scale and shift per axis)",
}, "affine", aliases={"helmert": "similarity", "polynomial-1": "affine", "poly1": "affine", "poly2": "polynomial-2",
                      "poly3": "polynomial-3", "homography": "projective", "thin-plate-spline": "tps"})

RESAMPLING = Choice("resampling", {
    "nearest": "Nearest neighbour",
    "bilinear": "Bilinear",
    "cubic": "Cubic",
    "cubicspline": "Cubic B-spline",
    "lanczos": "Lanczos",
    "average": "Average",
    "mode": "Mode (most frequent: classes)",
    "max": "Maximum",
    "min": "Minimum",
    "med": "Median",
    "q1": "First quartile",
    "q3": "Third quartile",
}, "bilinear", aliases={"near": "nearest", "cubic_spline": "cubicspline"})

GRID = Choice("grid", {
    "auto": "Automatic",
    "reference": "Reference pixel grid",
    "native": "Target's native resolution",
}, "auto")

REFINE = Choice("refine", {
    "auto": "Automatic (when images were decimated)",
    "on": "Always",
    "off": "Never",
}, "auto")

TARGET_GEOREF = Choice("target_georef", {
    "auto": "Use when it overlaps the reference",
    "use": "Always use (fail otherwise)",
    "ignore": "Ignore",
}, "auto")

FORMAT = Choice("format", {
    "auto": "From the file name (.vrt or GeoTIFF)",
    "gtiff": "GeoTIFF (tiled, compressed)",
    "cog": "Cloud-optimised GeoTIFF",
    "vrt": "Warped VRT (no pixels copied)",
}, "auto", aliases={"geotiff": "gtiff", "tif": "gtiff", "tiff": "gtiff"})

FILL = Choice("fill", {
    "auto": "Automatic (nodata, NaN or an alpha band)",
    "alpha": "Alpha band",
    "nodata": "Nodata value",
}, "auto")

ROBUST = Choice("robust", {
    "ransac": "Seeded LO-RANSAC",
    "none": "None: fit every correspondence",
    "triplets": "Cluster the transforms of match triplets",
}, None)

MODEL_CHOICES = MODEL.values
RESAMPLING_CHOICES = RESAMPLING.values
GRID_CHOICES = GRID.values
REFINE_CHOICES = REFINE.values
TARGET_GEOREF_CHOICES = TARGET_GEOREF.values
ROBUST_CHOICES = ROBUST.values


def canonical_model(name: str) -> str:
    """Validate a model name (QGIS-style aliases accepted) and return its canonical spelling."""
    return MODEL.check(name)


@dataclass(frozen=True)
class RegisterOptions:
    """Settings shared by every method.

    Attributes
    ----------
    model : str, optional
        Transform model (see :data:`MODEL`); None = the method's default.
    max_working_pixels : int
        Pixel budget of each working image; bounds memory and matching time.
    ransac_threshold_px : float, optional
        Inlier tolerance in working reference pixels; None = the method's default.
    seed : int
        Seed of every random choice (RANSAC, in the pipeline and inside methods), for reproducible runs.
    refine : {'auto', 'on', 'off'}
        Full-resolution refinement; 'auto' refines when a working image was decimated or the method
        always refines (see :class:`hamta.core.methods.Method`).
    max_gcps : int
        Well-spread inliers kept as GCPs; the model is fitted on exactly these.
    min_inliers : int, optional
        Fewest agreeing correspondences accepted as a registration (at least the model minimum + 2);
        None = the method's default.
    robust : {'ransac', 'none', 'triplets'}, optional
        Outlier rejection before the fit; 'none' fits every correspondence (as some papers do);
        'triplets' clusters the affine transforms of all match triples (spec 003's future work);
        None = the method's default.
    target_georef : {'auto', 'use', 'ignore'}
        Whether the target's own georeferencing is used as a starting point.
    target_band, reference_band : int, optional
        1-based band to match; None = luminance of RGB images, else band 1.
    tolerance_px : float
        The accuracy asked for, in reference pixels: a result is verified only when the independent
        check bounds its error within this (see :mod:`hamta.core.verify`).
    auto_budget_s : float
        With method 'auto', a deadline: once this many seconds are spent, the method running is
        stopped at its next progress report (the first step always completes) and no further one starts.
    local : bool
        After the global model, correct local (non-rigid) misalignment from shifts measured on a
        dense grid of windows (:mod:`hamta.core.local`); the model becomes a thin plate spline.
    pixel_mode : bool
        Pixel-to-pixel registration: accept a reference without georeferencing, whose pixel grid
        then stands in for the map (outputs carry no CRS). Off by default, so a reference that lost
        its georeferencing is reported instead of silently giving outputs no GIS can place.
    local_window_px, local_spacing_px : int, float
        The local correction's window side and grid spacing (reference px). Window 0 = automatic:
        64 px where intensities are correlated, 96 px for structural descriptors (other modalities,
        weaker evidence per pixel); measured on the nonrigid family, 64 px follows a 4 px field
        about twice as closely as 96 px. Spacing 0 = automatic: about 2000 windows over the overlap,
        never closer than half a window.
    """

    model: Optional[str] = None
    max_working_pixels: int = 4_000_000
    ransac_threshold_px: Optional[float] = None
    seed: int = 0
    refine: str = REFINE.default
    max_gcps: int = 500
    min_inliers: Optional[int] = None
    robust: Optional[str] = None
    target_georef: str = TARGET_GEOREF.default
    target_band: Optional[int] = None
    reference_band: Optional[int] = None
    tolerance_px: float = 3.0
    auto_budget_s: float = 120.0
    local: bool = False
    local_window_px: int = 0
    local_spacing_px: float = 0.0
    pixel_mode: bool = False

    def __post_init__(self):
        if self.model is not None:
            object.__setattr__(self, "model", MODEL.check(self.model))
        REFINE.check(self.refine)
        TARGET_GEOREF.check(self.target_georef)
        if self.robust is not None:
            ROBUST.check(self.robust)
        _whole("max_working_pixels", self.max_working_pixels, 4096)
        _whole("seed", self.seed, 0)
        _whole("max_gcps", self.max_gcps, 3)
        for name in ("min_inliers", "target_band", "reference_band"):
            if getattr(self, name) is not None:
                _whole(name, getattr(self, name), 3 if name == "min_inliers" else 1)
        if self.ransac_threshold_px is not None:
            _number("ransac_threshold_px", self.ransac_threshold_px, positive=True)
        _number("tolerance_px", self.tolerance_px, positive=True)
        _number("auto_budget_s", self.auto_budget_s, positive=False)
        if self.local_window_px != 0:
            _whole("local_window_px", self.local_window_px, 16)
        _number("local_spacing_px", self.local_spacing_px, positive=False)


def _whole(name: str, value, minimum: int) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise ValueError(f"{name} must be a whole number of at least {minimum}, got {value!r}")


def _number(name: str, value, positive: bool) -> None:
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
    if not ok or value < 0 or (positive and value == 0):
        raise ValueError(f"{name} must be a finite number {'above' if positive else 'of at least'} 0, got {value!r}")


def resolve_options(options: RegisterOptions, method) -> RegisterOptions:
    """``options`` with every setting left open (None) taken from ``method``'s defaults."""
    return replace(options, model=options.model or method.default_model,
                   ransac_threshold_px=options.ransac_threshold_px or method.ransac_threshold_px,
                   min_inliers=options.min_inliers or method.min_inliers, robust=options.robust or method.robust)


@dataclass(frozen=True)
class OutputOptions:
    """How the georeferenced raster is written.

    Attributes
    ----------
    resampling : str
        See :data:`RESAMPLING`.
    grid : str
        Output pixel grid, see :data:`GRID` and :func:`hamta.core.outputs.warp.output_grid`.
    resolution : float, optional
        Output pixel size in output CRS units (overrides ``grid``'s).
    crs : str, optional
        Output CRS (EPSG code, WKT or PROJ string); the reference CRS when None.
    format : str
        See :data:`FORMAT`.
    creation_options : tuple of str
        GDAL creation options ``KEY=VALUE``, added to (and overriding) Hamta's defaults for the format.
    fill : str
        How pixels outside the target are marked, see :data:`FILL`; 'auto' never turns valid pixels
        (zeros included) into nodata.
    nodata : float, optional
        The nodata value with ``fill='nodata'`` (default: the target's, else 0).
    """

    resampling: str = RESAMPLING.default
    grid: str = GRID.default
    resolution: Optional[float] = None
    crs: Optional[str] = None
    format: str = FORMAT.default
    creation_options: Tuple[str, ...] = ()
    fill: str = FILL.default
    nodata: Optional[float] = None

    def __post_init__(self):
        RESAMPLING.check(self.resampling)
        GRID.check(self.grid)
        object.__setattr__(self, "format", FORMAT.check(self.format))
        FILL.check(self.fill)
        if self.resolution is not None:
            _number("resolution", self.resolution, positive=True)
        if self.nodata is not None and (isinstance(self.nodata, bool) or not isinstance(self.nodata, (int, float))):
            raise ValueError(f"nodata must be a number, got {self.nodata!r}")
        object.__setattr__(self, "creation_options", tuple(self.creation_options))
        for item in self.creation_options:
            if "=" not in item or not item.split("=", 1)[0].strip():
                raise ValueError(f"creation options are KEY=VALUE, got {item!r}")
        if self.crs is not None:
            from rasterio.crs import CRS
            from rasterio.errors import CRSError

            try:
                CRS.from_user_input(self.crs)
            except CRSError as exc:
                raise ValueError(f"crs: {self.crs!r} is not a coordinate reference system GDAL knows ({exc})") from None
