"""What a method is (:class:`Method`, its parameters' ``param`` fields) and the table they register in.

Method modules import this module; :mod:`hamta.core.methods` looks methods up in the table and
imports the built-in method modules on first use.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any, Callable, Dict, Mapping, Optional

from ..errors import UsageError
from ..matching.nearest import match_features
from ..progress import Monitor
from ..refine import RefineParams
from ..types import Matches


@dataclass(frozen=True)
class Toolbox:
    """A method's own algorithm in the QGIS Processing Toolbox: ``qgis_process run hamta:<id>``, shown
    as ``title``; its help is the method's summary and citation. Both stay as first published (the
    id is in users' scripts and models; the title in the Toolbox's search)."""

    id: str
    title: str


KINDS = ("method", "baseline", "faithful", "learned")


@dataclass(frozen=True)
class Method:
    """A registered matching method.

    Attributes
    ----------
    name : str
        Stable id used by the CLI, Processing and reports.
    title : str
        One-line human name.
    summary : str
        What it does and when to use it (``hamta methods --verbose``; the help of its Toolbox algorithm).
    citation : str
        The published source (or 'baseline').
    params_type : type
        Frozen dataclass of the method's parameters; every field has a default and a ``help``.
    match : callable
        ``match(target, reference, params, monitor, seed=0) -> Matches``.
    default_model : str
        Model used when the caller does not choose one.
    ransac_threshold_px : float
        Default RANSAC tolerance (working reference pixels) when the caller does not choose one.
    robust : str
        Default outlier rejection: 'ransac', or 'none' for methods whose paper fits all matches.
    min_inliers : int
        Default fewest agreeing correspondences accepted as a registration.
    refine : {'when-decimated', 'always'}
        When the caller leaves refinement on 'auto': refine only when a working image was
        decimated, or always (methods whose features are less precise than area correlation).
    refinement : RefineParams
        How this method's correspondences are refined at full resolution.
    kind : str
        'method' for the product version of a published method, 'faithful' for its as-published
        version, 'baseline' for the comparisons they are measured against, 'learned' for a learned
        matcher of the optional extra (listed last: without the extra it only says what to install).
    use_when : str
        When a user should choose it (one short line for ``hamta methods``); faithful versions and
        baselines say what they are for when left empty.
    toolbox : Toolbox, optional
        Its algorithm in the QGIS Processing Toolbox, for the methods users choose there (the others
        are reached through the CLI, the batch and ``auto``).
    """

    name: str
    title: str
    summary: str
    citation: str
    params_type: type
    match: Callable
    default_model: str = "affine"
    kind: str = "method"
    ransac_threshold_px: float = 3.0
    robust: str = "ransac"
    min_inliers: int = 8
    refine: str = "when-decimated"
    refinement: RefineParams = RefineParams()
    use_when: str = ""
    toolbox: Optional[Toolbox] = None

    @property
    def menu_key(self):
        """Its place in every list of methods: product methods, then baselines, then faithful versions,
        each kind by name, then the learned ones. The Processing batch's method enum follows it (qgis_process
        passes its index: a method added later may move the indexes after it; names are stable)."""
        return KINDS.index(self.kind), self.name

    @property
    def advice(self) -> str:
        """:attr:`use_when`, or what a faithful version or a baseline is for."""
        if self.use_when:
            return self.use_when
        return {"faithful": "reproducing the paper (the product version is better)",
                "baseline": "comparisons (a paper's baseline)"}.get(self.kind, "")

    def make_params(self, values: Optional[Mapping[str, Any]] = None):
        """Build the parameter dataclass from ``values`` (strings are converted; an instance of the
        dataclass is returned as it is); unknown keys fail."""
        if isinstance(values, self.params_type):
            return values
        values = dict(values or {})
        fields = {f.name: f for f in dataclasses.fields(self.params_type)}
        unknown = sorted(set(values) - set(fields))
        if unknown:
            raise UsageError(f"method {self.name!r} has no parameter(s) {', '.join(unknown)}; "
                             f"known: {', '.join(fields)}")
        converted = {k: _convert(fields[k], v) for k, v in values.items()}
        return self.params_type(**converted)


def _convert(field: dataclasses.Field, value):
    if not isinstance(value, str):
        return value
    kind = type(field.default)
    if kind is bool:
        if value.lower() in ("1", "true", "yes", "on"):
            return True
        if value.lower() in ("0", "false", "no", "off"):
            return False
        raise UsageError(f"parameter {field.name} expects true/false, got {value!r}")
    if kind in (int, float):
        try:
            number = float(value)
        except ValueError:
            raise UsageError(f"parameter {field.name} expects a number, got {value!r}") from None
        if kind is int:
            if not math.isfinite(number) or number != int(number):
                raise UsageError(f"parameter {field.name} expects a whole number, got {value!r}")
            return int(number)
        return number
    return value


def param(default, help: str, *, basic: bool = False, **limits):
    """A dataclass field with a documented default (``help``) and optional ``minimum``/``maximum``/``choices``.

    ``basic`` marks the few parameters a user is expected to tune; front ends show the others as
    advanced settings.
    """
    return dataclasses.field(default=default, metadata={"help": help, "basic": basic, **limits})


def validate(params) -> None:
    """Check every field of a parameter dataclass against its declared limits."""
    for f in dataclasses.fields(params):
        v = getattr(params, f.name)
        lo, hi, choices = f.metadata.get("minimum"), f.metadata.get("maximum"), f.metadata.get("choices")
        kind = type(f.default)
        if kind in (int, float) and (isinstance(v, bool) or not isinstance(v, (int, float))):
            raise UsageError(f"parameter {f.name} expects a number, got {v!r}")
        if kind is int and isinstance(v, float):
            raise UsageError(f"parameter {f.name} expects a whole number, got {v!r}")
        if kind in (int, float) and not math.isfinite(v):
            raise UsageError(f"parameter {f.name} must be a finite number, got {v}")
        if lo is not None and v < lo:
            raise UsageError(f"parameter {f.name} must be >= {lo}, got {v}")
        if hi is not None and v > hi:
            raise UsageError(f"parameter {f.name} must be <= {hi}, got {v}")
        if choices is not None and v not in choices:
            raise UsageError(f"parameter {f.name} must be one of {choices}, got {v!r}")


def match_with(features_fn: Callable, stage: str = "keypoints and descriptors") -> Callable:
    """A method's ``match`` from ``features_fn(working_image, params) -> Features``: features of the
    target, then of the reference, then the ratio test with ``params.ratio`` and ``params.cross_check``."""
    def match(target, reference, params, monitor: Monitor, seed: int = 0) -> Matches:
        ft = features_fn(target, params)
        monitor.report(0.45, stage)
        fr = features_fn(reference, params)
        monitor.report(0.9, stage)
        it, ir, score = match_features(ft, fr, ratio=params.ratio, cross_check=params.cross_check)
        monitor.report(1.0, "matching")
        return Matches(ft.keypoints.xy[it], fr.keypoints.xy[ir], score, len(ft), len(fr))
    return match


_REGISTRY: Dict[str, Method] = {}
_ALIASES: Dict[str, str] = {}


def register_method(method: Method, aliases=()) -> Method:
    """Add ``method`` to the registry; ``aliases`` are former names that keep working."""
    for name in (method.name,) + tuple(aliases):
        if name in _REGISTRY or name in _ALIASES:
            raise ValueError(f"method {name!r} is already registered")
    _REGISTRY[method.name] = method
    _ALIASES.update({a: method.name for a in aliases})
    return method
