"""Every choice a user makes about a registration and its outputs, declared once.

Each option is a field of :class:`RegisterOptions` or :class:`OutputOptions` made with
:func:`option`: its default, a short label, a help sentence, its bounds, and whether a dialog
shows it as basic or advanced. The front ends generate their parameters from these fields (the
CLI's arguments in :mod:`hamta.cli.options`, the Processing parameters in
:mod:`hamta.processing.options`) and map values back generically, so adding an option is adding
a field. A field whose values are listed is a :class:`Choice`: its allowed values with an English
label each, keyed by value, and its default. The order of a choice's values is part of the
``qgis_process`` interface (Processing enums are passed as indexes), so new values are appended,
never inserted.

:func:`resolve_options` fills what a user left open with the chosen method's defaults; it is
the only place method defaults are resolved.
"""
from __future__ import annotations

import math
import typing
from dataclasses import dataclass, field, fields, replace
from functools import lru_cache
from typing import Mapping, Optional, Tuple

from .errors import UsageError


@dataclass(frozen=True)
class Choice:
    """The allowed values of one option (in interface order) with their labels and default."""

    name: str
    labels: Mapping[str, str]
    default: Optional[str]
    aliases: Mapping[str, str] = None
    open_value: Optional[str] = None  # the value that leaves the option open (stored as None)

    @property
    def values(self) -> Tuple[str, ...]:
        return tuple(self.labels)

    def check(self, value: str) -> str:
        """``value`` in canonical spelling (aliases and case accepted); ``ValueError`` otherwise."""
        key = str(value).lower()
        key = (self.aliases or {}).get(key, key)
        if key not in self.labels:
            raise UsageError(f"unknown {self.name} {value!r}; choose one of {', '.join(self.values)}")
        return key

    def index(self, value: str) -> int:
        return self.values.index(self.check(value))

    def at(self, index: int) -> str:
        """The value at an enum ``index`` (as Processing passes it)."""
        if not 0 <= int(index) < len(self.values):
            raise UsageError(f"{self.name} index {index} is out of range 0..{len(self.values) - 1}")
        return self.values[int(index)]


MODEL = Choice("model", {
    "similarity": "Similarity (Helmert)",
    "affine": "Affine (polynomial 1)",
    "projective": "Projective",
    "polynomial-2": "Polynomial 2",
    "polynomial-3": "Polynomial 3",
    "tps": "Thin plate spline",
    "linear": "Linear (scale and shift per axis)",
    "auto": "Automatic (chosen by the check)",
}, "auto", open_value="auto", aliases={"helmert": "similarity", "polynomial-1": "affine", "poly1": "affine",
                                      "poly2": "polynomial-2", "poly3": "polynomial-3", "homography": "projective",
                                      "thin-plate-spline": "tps"})

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

PIXEL_GRID = Choice("pixel_grid", {
    "auto": "Automatic",
    "reference": "Reference pixel grid",
    "native": "Target's native resolution",
    "target": "Target's own pixels (not resampled)",
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

MODEL_CHOICES = tuple(v for v in MODEL.values if v != MODEL.open_value)  # the models a fit can take
RESAMPLING_CHOICES = RESAMPLING.values


def canonical_model(name: str) -> str:
    """Validate a model name (QGIS-style aliases accepted) and return its canonical spelling."""
    kind = MODEL.check(name)
    if kind == MODEL.open_value:
        raise UsageError(f"{name!r} leaves the model to the method and the check; a fit needs one of "
                         f"{', '.join(MODEL_CHOICES)}")
    return kind


LABEL_CHARS = 44  # longer labels make the parameters panel of an 800 px QGIS dialog scroll sideways


@dataclass(frozen=True)
class Option:
    """How one option is shown and checked (the metadata of its field).

    Attributes
    ----------
    label : str
        A few words for a dialog (at most :data:`LABEL_CHARS`).
    help : str
        One sentence: the CLI's help and the dialog's tooltip.
    advanced : bool
        Shown under Advanced in dialogs (the few a user is expected to set are not).
    choice : Choice, optional
        The allowed values, for a field that takes one of a list.
    minimum : float, optional
        Smallest value of a number (exclusive with ``above``).
    above : bool
        The number must be above ``minimum``, not equal to it.
    unset : str
        What leaving a field with default None means, for the help ("the method's").
    flag, key : str
        The CLI flag (without '--') and the Processing parameter name, when not derived from the
        field name (kebab case; the flag in upper case): kept as they were first published.
    kind : str
        'band:TARGET' or 'band:REFERENCE' (a band of that raster), 'crs' or 'list' (KEY=VALUE
        items), for the widgets a type alone does not say; '' otherwise.
    """

    label: str
    help: str
    advanced: bool = True
    choice: Optional[Choice] = None
    minimum: Optional[float] = None
    above: bool = False
    unset: str = ""
    flag: str = ""
    key: str = ""
    kind: str = ""


def option(default, label: str, help: str, **spec):
    """A field of an options dataclass, with its :class:`Option` metadata."""
    return field(default=default, metadata={"option": Option(label, help, **spec)})


def option_fields(cls):
    """``(field, Option)`` of every option of ``cls`` (:class:`RegisterOptions` or :class:`OutputOptions`)."""
    return [(f, f.metadata["option"]) for f in fields(cls)]


@lru_cache(maxsize=None)
def _hints(cls) -> dict:
    return typing.get_type_hints(cls)


def option_type(cls, name: str) -> type:
    """The type of an option's values, ``Optional`` unwrapped: bool, int, float, str or tuple."""
    hint = _hints(cls)[name]
    if typing.get_origin(hint) is typing.Union:
        hint = next(a for a in typing.get_args(hint) if a is not type(None))
    kind = typing.get_origin(hint) or hint
    if kind not in (bool, int, float, str, tuple):
        raise TypeError(f"option {name}: values of type {hint} have no front-end mapping")
    return kind


FLAG_WORDS = {"1": True, "true": True, "yes": True, "on": True, "0": False, "false": False, "no": False, "off": False}


def _flag(name: str, value) -> bool:
    """A flag given as a bool (numpy's too), 0/1 or a word (bench variants write ``local=1``)."""
    if not isinstance(value, (str, float)) and value in (0, 1):
        return bool(value)
    if isinstance(value, str) and value.lower() in FLAG_WORDS:
        return FLAG_WORDS[value.lower()]
    raise UsageError(f"{name} must be true or false, got {value!r}")


def cli_flag(f, spec: Option) -> str:
    return "--" + (spec.flag or f.name.replace("_", "-"))


def processing_key(f, spec: Option) -> str:
    return spec.key or (spec.flag or f.name).replace("-", "_").upper()


def check_options(options) -> None:
    """Check every field of ``options`` against its metadata; choices are stored in canonical spelling."""
    for f, spec in option_fields(type(options)):
        value, kind = getattr(options, f.name), option_type(type(options), f.name)
        if value is None and f.default is None:
            continue
        if spec.choice is not None:
            value = spec.choice.check(value)
            object.__setattr__(options, f.name, None if value == spec.choice.open_value else value)
        elif kind is bool:
            object.__setattr__(options, f.name, _flag(f.name, value))
        elif kind is int:
            _whole(f.name, value, int(spec.minimum or 0))
        elif kind is float and spec.minimum is None:
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise UsageError(f"{f.name} must be a number, got {value!r}")
        elif kind is float:
            _number(f.name, value, positive=spec.above)


@dataclass(frozen=True)
class RegisterOptions:
    """Settings shared by every method (see each field's ``help``; ``hamta register --help`` lists them).

    Pixel sizes are reference pixels unless a field says working pixels.
    """

    model: Optional[str] = option(
        None, "Transformation", "transform model: " + ", ".join(MODEL.values) + " (the method's, affine for most, or "
        "polynomial-2 where the points bend away from it and the check bounds its error more tightly)",
        advanced=False, choice=MODEL, unset="automatic")
    max_working_pixels: int = option(
        4_000_000, "Working image size (pixels)", "pixel budget of the images matched (larger rasters are read "
        "decimated, then refined at full resolution)", minimum=4096)
    ransac_threshold_px: Optional[float] = option(
        None, "RANSAC tolerance (working px)", "outlier threshold, working pixels", minimum=0, above=True,
        unset="the method's, 3 for most", flag="ransac-threshold")
    seed: int = option(0, "Random seed", "seed of every random choice (RANSAC, sampling, inside methods), for "
                       "reproducible runs", minimum=0)
    refine: str = option(
        REFINE.default, "Full-resolution refinement", "full-resolution refinement of the matches: auto refines "
        "when an image was decimated or the method asks for it", choice=REFINE)
    max_gcps: int = option(500, "Maximum number of GCPs", "most GCPs kept (well spread) for the fit and the outputs",
                           minimum=3)
    min_inliers: Optional[int] = option(
        None, "Fewest agreeing matches", "fewest agreeing correspondences accepted as a registration (at least "
        "the model's minimum + 2)", minimum=3, unset="the method's")
    robust: Optional[str] = option(
        None, "Outlier rejection", "outlier rejection before the fit: ransac, none (fit every correspondence, as "
        "some papers do) or triplets (cluster the transforms of match triplets)", choice=ROBUST,
        unset="the method's")
    target_georef: str = option(
        TARGET_GEOREF.default, "Target's own georeferencing", "use the target's own georeferencing as a starting "
        "point (auto: when it overlaps the reference), or ignore it when it is wrong", choice=TARGET_GEOREF)
    target_band: Optional[int] = option(
        None, "Target band to match", "band of the target to match", minimum=1,
        unset="luminance of RGB, else band 1", kind="band:TARGET")
    reference_band: Optional[int] = option(
        None, "Reference band to match", "band of the reference to match", minimum=1,
        unset="luminance of RGB, else band 1", kind="band:REFERENCE")
    tolerance_px: float = option(
        3.0, "Accuracy asked for (reference px)", "accuracy asked for, reference px: a result is verified only "
        "when the independent check bounds its error within this", minimum=0, above=True, flag="tolerance")
    auto_budget_s: Optional[float] = option(
        None, "Time cap of 'auto' (s)", "a cap on the seconds 'auto' and a basemap search may spend: then the "
        "method running is stopped (the first, the fast path, always completes) and no further method or place "
        "starts. Without it what they try is bounded by counts (methods, places, requests), so the verdict is the "
        "same on any machine and under any load; with it, a slower or busier machine may try less",
        minimum=0, flag="auto-budget", unset="no cap")
    local: bool = option(
        False, "Local (non-rigid) correction", "after the global model, correct local (non-rigid) misalignment "
        "from shifts measured on a dense grid of windows; the model becomes a thin plate spline through the grid",
        advanced=False)
    # Window 0: 64 px where intensities are correlated, 96 px for structural descriptors (weaker
    # evidence per pixel); on the nonrigid family 64 px follows a 4 px field about twice as closely as 96 px.
    local_window_px: int = option(
        0, "Local window (reference px; 0: automatic)", "local correction window side, reference px (0: "
        "automatic, 64 px, or 96 px for methods that correlate structure across modalities; otherwise at least "
        "16)", minimum=0, flag="local-window")
    local_spacing_px: float = option(
        0.0, "Local grid spacing (reference px; 0: auto)", "local correction grid spacing, reference px (0: "
        "automatic, about 2000 windows over the overlap)", minimum=0, flag="local-spacing")
    pixel_mode: bool = option(
        False, "Pixel-to-pixel (reference not georeferenced)", "pixel-to-pixel registration onto a reference "
        "without georeferencing: its pixel grid stands in for the map and the outputs carry no CRS (without "
        "this, such a reference is refused)")
    extent: Optional[str] = option(
        None, "Search area", "where to look for a target without usable georeferencing: xmin,ymin,xmax,ymax with an "
        "optional CRS after a comma (default CRS: the reference's, longitude and latitude for a map service)",
        advanced=False, unset="the whole reference; required with a map service", kind="extent")

    def __post_init__(self):
        if self.extent is not None:
            from .extent import parse_extent

            parse_extent(self.extent)
        if self.local_window_px != 0:  # 0 (automatic) or a window of at least 16 px
            _whole("local_window_px", self.local_window_px, 16)
        check_options(self)


def _whole(name: str, value, minimum: int) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise UsageError(f"{name} must be a whole number of at least {minimum}, got {value!r}")


def _number(name: str, value, positive: bool) -> None:
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
    if not ok or value < 0 or (positive and value == 0):
        raise UsageError(f"{name} must be a finite number {'above' if positive else 'of at least'} 0, got {value!r}")


def resolve_options(options: RegisterOptions, method) -> RegisterOptions:
    """``options`` with every setting left open (None) taken from ``method``'s defaults."""
    return replace(options, model=options.model or method.default_model,
                   ransac_threshold_px=options.ransac_threshold_px or method.ransac_threshold_px,
                   min_inliers=options.min_inliers or method.min_inliers, robust=options.robust or method.robust)


@dataclass(frozen=True)
class OutputOptions:
    """How the georeferenced raster is written (see each field's ``help``)."""

    resampling: str = option(RESAMPLING.default, "Resampling", "resampling of the warped output", advanced=False,
                             choice=RESAMPLING)
    pixel_grid: str = option(
        PIXEL_GRID.default, "Output pixel grid", "output pixel grid: the reference's, the target's own resolution, "
        "auto (the reference's when the resolutions are within 10 %), or target: the target's pixels unchanged under "
        "a corrected geotransform (where the model is a shift and scale, in the reference CRS)", choice=PIXEL_GRID)
    resolution: Optional[float] = option(
        None, "Output pixel size (output CRS units)", "output pixel size in output CRS units (overrides the grid's)",
        minimum=0, above=True, unset="from the pixel grid")
    crs: Optional[str] = option(
        None, "Output CRS (empty: the reference's)", "output CRS: EPSG:code, WKT or PROJ string",
        unset="the reference's CRS", key="OUTPUT_CRS", kind="crs")
    format: str = option(
        FORMAT.default, "Output format", "warped raster: gtiff (tiled, DEFLATE), cog (cloud-optimised, with "
        "overviews) or vrt (a warped VRT reading the target, written as registered.vrt)", choice=FORMAT)
    creation_options: Tuple[str, ...] = option(
        (), "GDAL creation options", "GDAL creation options of the warped raster, KEY=VALUE (e.g. COMPRESS=ZSTD, "
        "PREDICTOR=2), added to and overriding Hamta's defaults for the format", flag="co", key="CREATION_OPTIONS",
        kind="list")
    fill: str = option(
        FILL.default, "Pixels outside the target", "how pixels outside the target are marked: auto (the target's "
        "nodata or collar value, NaN for floats, else an alpha band, so valid zeros stay valid), alpha, or nodata",
        choice=FILL)
    nodata: Optional[float] = option(None, "Nodata value", "nodata value with fill 'nodata'",
                                     unset="the target's, else 0")

    def __post_init__(self):
        check_options(self)
        object.__setattr__(self, "creation_options", tuple(self.creation_options))
        for item in self.creation_options:
            if "=" not in item or not item.split("=", 1)[0].strip():
                raise UsageError(f"creation options are KEY=VALUE, got {item!r}")
        if self.crs is not None:
            from rasterio.crs import CRS
            from rasterio.errors import CRSError

            try:
                CRS.from_user_input(self.crs)
            except CRSError as exc:
                raise UsageError(f"crs: {self.crs!r} is not a coordinate reference system GDAL knows ({exc})") from None
