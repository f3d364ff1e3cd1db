"""Local (non-rigid) correction: shifts measured on a dense grid of windows, then a thin plate spline.

After the global model, scenes still disagree locally (terrain relief the orthorectification missed,
sensor distortion, a mosaic's seams). Like AROSICS's local co-registration (Scheffler et al. 2017,
Remote Sensing 9(7):676, :DOI:`10.3390/rs9070676`), a regular grid of windows over the whole overlap
is matched at full resolution against the target resampled through the global model; each window
gives a local shift. Shifts are filtered (correlation peak, then spatial consistency: a shift far
from the median of its neighbours is an outlier), smoothed by a local linear fit over each point's
neighbours (noise averages out, smooth fields and their gradients survive), and the final model is
a thin plate spline through the grid (the warped raster is resampled through its exact inverse,
:mod:`hamta.core.outputs.spline_warp`; the GCP VRT hands it to GDAL as ``GCP_TPS``). The
independent check then judges the final model like any other.

Coordinates: grid points and shifts are full-resolution reference pixels; the model maps target px
to reference px (corner convention). A shift is ``global(target position) - reference position``:
how far the global model puts that window from where it is.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Callable, Optional

import numpy as np

from .errors import InsufficientMatchesError, UsageError
from .estimation.models import ThinPlateSplineModel
from .estimation.robust import Estimate, FinalFit
from .progress import Monitor
from .refine import RefineParams, grid_points, refine_points
from .types import Correspondences


@dataclass(frozen=True)
class LocalParams:
    """Settings of the local correction (full-resolution reference pixels).

    Attributes
    ----------
    window_px : int
        Side of each window. Larger is more robust on weak texture, smaller follows sharper
        distortions (the pipeline picks 64 px for intensity correlation, 96 px for structural
        descriptors, see :class:`hamta.core.options.RegisterOptions`).
    spacing_px : float
        Grid spacing; 0 picks it so that about ``max_points`` windows cover the overlap, never
        closer than half a window.
    max_points : int
        Most windows (bounds time and the spline's size).
    search_px : int
        Largest local shift measured, in each direction.
    min_ncc : float
        Lowest correlation peak kept (0.1 for structural descriptors, which peak lower).
    neighbours : int
        Neighbours of each point for the spatial consistency test and the smoothing fit.
    max_deviation_px : float
        A shift farther than this (or three robust standard deviations of the differences, when
        larger) from its neighbours' median is an outlier.
    """

    window_px: int = 96
    spacing_px: float = 0.0
    max_points: int = 2000
    search_px: int = 8
    min_ncc: float = 0.3
    neighbours: int = 8
    max_deviation_px: float = 1.0

    def __post_init__(self):
        if self.window_px < 16:
            raise UsageError(f"local window_px must be at least 16, got {self.window_px}")
        if not (math.isfinite(self.spacing_px) and self.spacing_px >= 0):
            raise UsageError(f"local spacing_px must be 0 (automatic) or positive, got {self.spacing_px}")
        if self.max_points < 10 or self.search_px < 1 or self.neighbours < 3:
            raise UsageError("local max_points must be >= 10, search_px >= 1 and neighbours >= 3")


@dataclass(frozen=True, eq=False)
class LocalGrid:
    """The measured grid: ``reference_px`` window centres, ``target_px`` where each was found,
    ``shift_xy`` (reference px) as measured, ``smoothed_xy`` as used, ``score`` (peak correlation),
    ``kept`` (passed the filters), ``window_px`` and ``spacing_px``."""

    reference_px: np.ndarray
    target_px: np.ndarray
    shift_xy: np.ndarray
    smoothed_xy: np.ndarray
    score: np.ndarray
    kept: np.ndarray
    window_px: int
    spacing_px: float

    def summary(self) -> dict:
        """The ``local`` section of the report (numbers only; the grid itself goes to the GCP layer)."""
        kept = self.kept
        mag = np.linalg.norm(self.shift_xy[kept], axis=1) if kept.any() else np.zeros(0)
        return {"window_px": self.window_px, "spacing_px": round(self.spacing_px, 2), "n_windows": int(len(kept)),
                "n_kept": int(kept.sum()), "shift_median_px": float(np.median(mag)) if len(mag) else None,
                "shift_max_px": float(mag.max()) if len(mag) else None}


def local_correction(estimate: Estimate, target, target_bands, reference, reference_bands,
                     params: LocalParams = LocalParams(), similarity: str = "ncc", monitor: Optional[Monitor] = None,
                     map_chunks: Optional[Callable] = None) -> tuple:
    """(FinalFit with a thin plate spline through the grid, LocalGrid) from a linear ``estimate``.

    ``map_chunks(fn, chunks)``, when given, evaluates ``fn`` on every chunk of grid points elsewhere
    (a Dask client's workers) and returns the results in order; by default they run here.

    Raises
    ------
    InsufficientMatchesError
        Fewer than 10 windows passed the filters.
    """
    monitor = monitor or Monitor()
    model = estimate.model
    refine = RefineParams(template_px=params.window_px, search_px=params.search_px,
                          min_ncc=params.min_ncc if similarity == "ncc" else min(params.min_ncc, 0.1),
                          max_points=params.max_points, points="grid", similarity=similarity)
    sites = _thin(grid_points(model, target, reference, refine), max(params.spacing_px, params.window_px / 2.0))
    spacing = _spacing(sites)

    def measure(chunk, mon=None):
        return refine_points(model, chunk, target, target_bands, reference, reference_bands, refine, mon)

    if map_chunks is None:  # the windows are measured here
        points = measure(sites, monitor.span(0.0, 0.9))
    else:
        monitor.report(0.05, "local shifts")
        points = _concat(map_chunks(measure, [sites[i:i + 256] for i in range(0, len(sites), 256)]))
    monitor.report(0.9, "local shifts")
    if len(points) < 10:
        raise InsufficientMatchesError(f"Local correction of '{target.path}': only {len(points)} of {len(sites)} "
                                       "windows could be matched (at least 10 are needed).", len(points), 10)
    shift = model.apply(points.target_px) - points.reference_px
    kept = consistent(points.reference_px, shift, points.score > 0, params)
    if kept.sum() < 10:
        raise InsufficientMatchesError(f"Local correction of '{target.path}': only {int(kept.sum())} windows "
                                       "agree with their neighbours (at least 10 are needed).", int(kept.sum()), 10)
    smoothed = shift.copy()
    smoothed[kept] = smooth(points.reference_px[kept], shift[kept], params.neighbours)
    control = points.target_px[kept]
    tps = ThinPlateSplineModel.fit(control, model.apply(control) - smoothed[kept], smoothing=0.0)
    grid = LocalGrid(points.reference_px, points.target_px, shift, smoothed, points.score, kept, params.window_px,
                     spacing)
    fitted = replace(points, inlier=kept)
    monitor.report(1.0, "local shifts")
    return FinalFit(tps, fitted, np.flatnonzero(kept), True), grid


def consistent(xy: np.ndarray, shift: np.ndarray, valid: np.ndarray, params: LocalParams, rounds: int = 2
               ) -> np.ndarray:
    """Points whose shift is close to the median of their ``params.neighbours`` nearest valid points'."""
    kept = valid.copy()
    for _ in range(rounds):
        idx = np.flatnonzero(kept)
        if len(idx) <= params.neighbours:
            break
        near = _nearest(xy[idx], xy[idx], params.neighbours + 1)[:, 1:]
        median = np.median(shift[idx][near], axis=1)
        dev = np.linalg.norm(shift[idx] - median, axis=1)
        mad = 1.4826 * np.median(dev)
        limit = max(params.max_deviation_px, 3.0 * mad)
        new = kept.copy()
        new[idx[dev > limit]] = False
        if np.array_equal(new, kept):
            break
        kept = new
    return kept


def smooth(xy: np.ndarray, shift: np.ndarray, neighbours: int) -> np.ndarray:
    """Each shift replaced by a linear fit (offset and gradient) over itself and its neighbours,
    evaluated at its own position."""
    k = min(neighbours + 1, len(xy))
    if k < 4:
        return shift.copy()
    near = _nearest(xy, xy, k)  # (n, k), itself first
    d = xy[near] - xy[:, None, :]
    scale = max(float(np.abs(d).max()), 1.0)
    design = np.concatenate([np.ones(d.shape[:2] + (1,)), d / scale], axis=2)  # (n, k, 3)
    normal = np.einsum("nki,nkj->nij", design, design) + 1e-9 * np.eye(3)
    rhs = np.einsum("nki,nkc->nic", design, shift[near])  # (n, 3, 2)
    return np.linalg.solve(normal, rhs)[:, 0, :]  # the fit's offset: its value at the point itself


def _nearest(points: np.ndarray, queries: np.ndarray, k: int) -> np.ndarray:
    from scipy.spatial import cKDTree

    return cKDTree(points).query(queries, k=min(k, len(points)))[1].reshape(len(queries), -1)


def _thin(sites: np.ndarray, spacing: float) -> np.ndarray:
    """The grid's points at least about ``spacing`` apart (a coarser regular subset)."""
    if len(sites) < 2:
        return sites
    step = _spacing(sites)
    every = max(1, int(math.ceil(spacing / max(step, 1e-9) - 1e-6)))
    cells = np.round((sites - sites.min(axis=0)) / step).astype(int)
    return sites[(cells[:, 0] % every == 0) & (cells[:, 1] % every == 0)]


def _spacing(sites: np.ndarray) -> float:
    if len(sites) < 2:
        return 0.0
    xs = np.unique(np.round(sites[:, 0], 6))
    return float(np.median(np.diff(xs))) if len(xs) > 1 else 0.0


def _concat(parts) -> Correspondences:
    parts = [p for p in parts if len(p)]
    if not parts:
        return Correspondences.unfitted(np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0))
    return Correspondences.unfitted(np.concatenate([p.target_px for p in parts]),
                                    np.concatenate([p.reference_px for p in parts]),
                                    np.concatenate([p.score for p in parts]))
