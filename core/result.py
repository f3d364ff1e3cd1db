"""The result of one registration: model, GCPs, statistics and provenance."""
from __future__ import annotations

import dataclasses
import platform
from dataclasses import dataclass, field
from typing import List, Optional

import numpy as np

from .basemap.redact import redact
from .coords import as_xy, gdal_coefficients, pixel_to_map
from .estimation.robust import FinalFit
from .io.raster import RasterInfo
from .io.working import Plan
from .outcome import AutoRun, Stats, Timings
from .types import Correspondences, Matches
from .verify import Verification
from .version import __version__

REPORT_SCHEMA_VERSION = 3


@dataclass(frozen=True)
class Gcp:
    """One ground control point.

    ``target_px`` and ``reference_px`` are full-resolution pixels (corner convention), ``map_xy``
    the reference map coordinates of ``reference_px`` (reference pixels in pixel mode).
    ``residual_xy`` is model(target_px) - reference_px in reference pixels.
    """

    target_px: tuple
    reference_px: tuple
    map_xy: tuple
    residual_xy: tuple
    score: float
    enabled: bool

    @property
    def residual_px(self) -> float:
        return float(np.hypot(*self.residual_xy))


@dataclass(frozen=True, eq=False)
class RegistrationResult:
    """Everything a registration produced, before any file is written.

    ``model`` maps target pixels to reference pixels. ``gcps`` holds the points the model was
    fitted on (``enabled``) followed by rejected matches (``enabled=False``).
    """

    method: str
    params: dict
    options: dict
    model: object  # a model of hamta.core.estimation (apply, to_dict, kind): target px -> reference px
    target: RasterInfo
    reference: RasterInfo
    plan: Plan
    gcps: List[Gcp]
    stats: Stats
    timings: Timings
    notes: List[str] = field(default_factory=list)
    diagnostics: dict = field(default_factory=dict)
    correspondences: Optional[Correspondences] = None
    verification: Optional[Verification] = None
    auto: Optional[AutoRun] = None  # the methods 'auto' tried
    run_id: Optional[str] = None  # set when outputs are written: every file of one set carries it
    local: Optional[object] = None  # the local correction's grid (hamta.core.local.LocalGrid), when asked for
    reference_service: Optional[dict] = None  # the map service read as the reference (hamta.core.remote)

    @property
    def verified(self) -> bool:
        """True when the independent check confirmed the result (see :mod:`hamta.core.verify`)."""
        return self.verification is not None and self.verification.verified

    @property
    def pixel_mode(self) -> bool:
        """True when the reference has no georeferencing: map coordinates are reference pixels."""
        return not self.reference.georeferenced

    def reference_to_map(self, reference_px) -> np.ndarray:
        """Reference pixels -> reference map coordinates (identity in pixel mode)."""
        xy = as_xy(reference_px)
        return xy.copy() if self.pixel_mode else pixel_to_map(self.reference.transform, xy)

    def map_points(self, target_px):
        """Target pixels -> (reference pixels, map coordinates) through the fitted model."""
        ref = self.model.apply(as_xy(target_px))
        return ref, self.reference_to_map(ref)

    def enabled_gcps(self) -> List[Gcp]:
        return [g for g in self.gcps if g.enabled]

    def to_report(self) -> dict:
        """The ``report.json`` document (schema documented in docs/report.md)."""
        ref = self.reference
        return {
            "schema_version": REPORT_SCHEMA_VERSION,
            "method": self.method,
            "params": self.params,
            "options": self.options,
            "model": self.model.to_dict(),
            "target": _raster_dict(self.target),
            "reference": dict(_raster_dict(ref), pixel_mode=self.pixel_mode, service=self.reference_service),
            "plan": {"mode": self.plan.mode,
                     "reference_window": _window_list(self.plan.reference_window),
                     "target_window": _window_list(self.plan.target_window)},
            "gcps": [{"id": i + 1, "target_px": list(g.target_px), "reference_px": list(g.reference_px),
                      "map": list(g.map_xy), "residual_px": g.residual_px, "residual_xy_px": list(g.residual_xy),
                      "score": g.score, "enabled": g.enabled} for i, g in enumerate(self.gcps)],
            "stats": self.stats.to_dict(),
            "timings_s": self.timings.to_dict(),
            "notes": list(self.notes),
            "diagnostics": self.diagnostics,
            "quality": None if self.verification is None else self.verification.to_dict(),
            "auto": None if self.auto is None else self.auto.to_dict(),
            "local": None if self.local is None else self.local.summary(),
            "versions": versions(),
        }


def _raster_dict(info: RasterInfo) -> dict:
    return {"path": redact(info.path), "width": info.width, "height": info.height, "count": info.count,
            "dtype": info.dtype, "crs": info.crs.to_wkt() if info.crs else None,
            "collar": None if info.collar is None else {"value": info.collar, "share": round(info.collar_share, 4)},
            "transform": gdal_coefficients(info.transform), "georeferencing": info.georef_source}


def _window_list(w) -> list:
    return [int(w.col_off), int(w.row_off), int(w.width), int(w.height)]


def versions() -> dict:
    """Versions of Hamta and the libraries that shaped a result; scipy, pyproj and PROJ are None when this
    process never loaded them (a pixel-mode run needs no PROJ, and importing it costs a tenth of a second)."""
    import sys

    import cv2
    import rasterio
    import shapely

    scipy, pyproj = sys.modules.get("scipy"), sys.modules.get("pyproj")
    return {"hamta": __version__, "python": platform.python_version(), "numpy": np.__version__,
            "scipy": getattr(scipy, "__version__", None), "opencv": cv2.__version__, "rasterio": rasterio.__version__,
            "gdal": rasterio.__gdal_version__, "pyproj": getattr(pyproj, "__version__", None),
            "proj": getattr(pyproj, "proj_version_str", None), "shapely": shapely.__version__}


def params_dict(params) -> dict:
    return dataclasses.asdict(params) if dataclasses.is_dataclass(params) else dict(params or {})


def make_gcps(fit: FinalFit, to_map) -> List[Gcp]:
    """The GCPs of ``fit`` (enabled), followed by as many of its rejected correspondences, best
    score first (disabled). ``to_map`` maps reference px to map coordinates."""
    p, res = fit.points, _residuals(fit)
    outliers = np.flatnonzero(~p.inlier)
    outliers = _new_places(outliers[np.argsort(-p.score[outliers], kind="stable")], fit.used, p, len(fit.used))
    gcps = []
    for i, enabled in [(i, True) for i in fit.used] + [(i, False) for i in outliers]:
        gcps.append(Gcp(tuple(map(float, p.target_px[i])), tuple(map(float, p.reference_px[i])),
                        tuple(map(float, to_map(p.reference_px[i:i + 1])[0])), tuple(map(float, res[i])),
                        float(p.score[i]), enabled))
    return gcps


def _new_places(candidates: np.ndarray, taken: np.ndarray, p: Correspondences, limit: int) -> np.ndarray:
    """The first ``limit`` of ``candidates`` (in order) at a target and a reference pixel that no
    point of ``taken`` nor an earlier candidate holds, so no place is listed twice."""
    def places(i):
        return {(k,) + tuple(np.round(xy[i], 6)) for k, xy in enumerate((p.target_px, p.reference_px))}

    seen = set().union(*map(places, taken)) if len(taken) else set()
    kept = []
    for i in candidates:
        if len(kept) == limit:
            break
        here = places(i)
        if not here & seen:
            kept.append(i)
            seen |= here
    return np.asarray(kept, int)


def make_stats(matches: Matches, first: Correspondences, fit: FinalFit) -> Stats:
    """Counts and self-reported residual figures of a registration (never its accuracy)."""
    p, used = fit.points, fit.used
    used_res = np.linalg.norm(_residuals(fit)[used], axis=1)
    loo = fit.model.loo_residuals(p.target_px[used], p.reference_px[used])
    return Stats(
        n_keypoints_target=int(matches.n_target), n_keypoints_reference=int(matches.n_reference),
        n_matches=int(len(matches)), n_inliers=int(first.inlier.sum()), n_gcps=int(len(used)),
        n_refined=int(len(p)) if fit.refined else 0,
        rmse_px=float(np.sqrt(np.mean(used_res ** 2))),
        rms_loo_px=float(np.sqrt(np.nanmean(loo ** 2))) if np.isfinite(loo).any() else None,
        max_residual_px=float(used_res.max()),
        refined=bool(fit.refined),
        peak_rss_mb=peak_rss_mb(),
    )


def _residuals(fit: FinalFit) -> np.ndarray:
    p = fit.points
    return fit.model.apply(p.target_px) - p.reference_px if len(p) else np.zeros((0, 2))


def peak_rss_mb() -> Optional[float]:
    """Peak resident memory of this process so far (None where the OS does not say)."""
    try:
        import resource
    except ImportError:
        return None
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
