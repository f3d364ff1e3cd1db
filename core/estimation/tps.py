"""The thin plate spline model: target pixels to reference pixels through (or near) control points.

One of the models of :mod:`hamta.core.estimation.models` (fitted, applied, its leave-one-out
residuals and ``report.json`` form alike); the local correction's model (:mod:`hamta.core.local`).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from ..coords import as_xy


def _squared_distances(q: np.ndarray) -> np.ndarray:
    """(n, n) squared distances between the rows of ``q`` (n, 2), without an (n, n, 2) temporary."""
    dx = q[:, None, 0] - q[None, :, 0]
    dy = q[:, None, 1] - q[None, :, 1]
    dx *= dx
    dy *= dy
    dx += dy
    return dx


def _tps_kernel(r2: np.ndarray) -> np.ndarray:
    out = np.zeros_like(r2)
    np.log(r2, out=out, where=r2 > 1e-300)
    out *= r2
    return out


@dataclass(frozen=True, eq=False)
class ThinPlateSplineModel:
    """Thin plate spline through (or, with ``smoothing`` > 0, near) its control points.

    ``f(p) = a0 + a1 u + a2 v + sum_i w_i U(|q - q_i|^2)`` with ``U(r2) = r2 log r2`` and
    ``q = (p - center) / scale``; a TPS is unchanged by this normalisation, which only conditions
    the solve. ``smoothing`` = 0 interpolates the points exactly (GDAL's ``-tps``); a positive
    value is the penalty weight of a smoothing spline (Wahba 1990), which keeps match noise out of
    the surface. Any such spline is reproduced exactly by an interpolating TPS through its own
    values at the control points, which is how GDAL is handed the model.
    """

    control: np.ndarray  # (n, 2) target px
    center: np.ndarray
    scale: float
    weights: np.ndarray  # (n, 2)
    affine: np.ndarray  # (3, 2)
    smoothing: float = 0.0
    loo: Optional[np.ndarray] = field(default=None, repr=False)  # leave-one-out errors, when fitted here

    kind = "tps"
    matrix = None
    n_min = 3

    def _q(self, xy) -> np.ndarray:
        return (as_xy(xy) - self.center) / self.scale

    def _pieces(self, xy, max_cells: int):
        """(normalised ``xy``, normalised control points, points per piece): pieces whose kernel with
        the control points holds at most ``max_cells`` values."""
        c = self._q(self.control)
        return self._q(xy), c, max(1, max_cells // max(len(c), 1))

    def apply(self, xy, max_cells: int = 250_000) -> np.ndarray:
        """Evaluate in chunks of points so that the kernel matrix stays within ``max_cells`` values
        (memory bounded however many control points there are; temporaries of 2 MB each stay in the
        CPU's cache: a quarter faster than 32 MB ones). No BLAS: its threads would spin beside the threads
        that call this (the spline warp's lattice chunks), and its sums differ between library builds."""
        q, c, chunk = self._pieces(xy, max_cells)
        c2 = (c ** 2).sum(axis=1)
        out = np.empty_like(q)
        for i in range(0, len(q), chunk):
            part = q[i:i + chunk]
            cross = part[:, :1] * c[None, :, 0] + part[:, 1:] * c[None, :, 1]
            r2 = np.maximum((part ** 2).sum(axis=1)[:, None] + c2[None, :] - 2.0 * cross, 0.0)
            affine = self.affine[0] + part[:, :1] * self.affine[1] + part[:, 1:] * self.affine[2]
            out[i:i + chunk] = np.einsum("ij,jk->ik", _tps_kernel(r2), self.weights) + affine
        return out

    def jacobian(self, xy, max_cells: int = 250_000) -> np.ndarray:
        """(N, 2, 2) derivative of :meth:`apply` at ``xy`` (``[n, output, input]``), exact:
        ``dU/dq = 2 (q - q_i) (log r2 + 1)``, zero at a control point; the ``+ 1`` terms sum to zero
        (the weights are orthogonal to the affine part: ``sum w_i = sum w_i q_i = 0``). In chunks as
        :meth:`apply`."""
        q, c, chunk = self._pieces(xy, max_cells)
        out = np.empty((len(q), 2, 2))
        for i in range(0, len(q), chunk):
            part = q[i:i + chunk]
            dx = part[:, :1] - c[None, :, 0]
            dy = part[:, 1:] - c[None, :, 1]
            r2 = dx * dx + dy * dy
            g = np.zeros_like(r2)
            np.log(r2, out=g, where=r2 > 1e-300)
            g *= 2.0
            out[i:i + chunk, :, 0] = np.einsum("ij,jk->ik", g * dx, self.weights) + self.affine[1]
            out[i:i + chunk, :, 1] = np.einsum("ij,jk->ik", g * dy, self.weights) + self.affine[2]
        return out / self.scale

    def residuals(self, src, dst) -> np.ndarray:
        return np.linalg.norm(self.apply(src) - as_xy(dst), axis=1)

    @staticmethod
    def _system(q: np.ndarray, smoothing: float) -> np.ndarray:
        n = len(q)
        k = _tps_kernel(_squared_distances(q))
        k[np.diag_indices(n)] += smoothing
        p = np.column_stack([np.ones(n), q])
        return np.block([[k, p], [p.T, np.zeros((3, 3))]])

    @classmethod
    def fit(cls, src, dst, smoothing="auto", center=None, scale=None) -> "ThinPlateSplineModel":
        """Fit through ``src`` -> ``dst``; ``smoothing='auto'`` picks the penalty with the smallest
        leave-one-out error over a logarithmic grid (0 = exact interpolation is a candidate).
        ``center``/``scale`` fix the normalisation (the penalty is defined in normalised units)."""
        src, dst = as_xy(src), as_xy(dst)
        if len(src) < cls.n_min:
            raise ValueError(f"tps needs at least {cls.n_min} points, got {len(src)}")
        center = src.mean(axis=0) if center is None else np.asarray(center, float)
        scale = (float(np.abs(src - center).max()) or 1.0) if scale is None else float(scale)
        q = (src - center) / scale
        rhs = np.vstack([dst, np.zeros((3, 2))])
        if smoothing == "auto":
            candidates = [0.0] + list(10.0 ** np.arange(-7.0, 3.5, 0.5))
            fits = [cls._solve(q, rhs, lam) for lam in candidates]
            best = int(np.argmin([np.sqrt(np.nanmean(f[1] ** 2)) for f in fits]))
            (sol, loo), smoothing = fits[best], candidates[best]
        else:
            sol, loo = cls._solve(q, rhs, float(smoothing))
        return cls(src.copy(), center, scale, sol[:-3], sol[-3:], float(smoothing), loo)

    @classmethod
    def _solve(cls, q, rhs, smoothing):
        """Coefficients and leave-one-out residual norms for one penalty weight."""
        n = len(q)
        system = cls._system(q, smoothing)
        try:
            inv = np.linalg.inv(system)
        except np.linalg.LinAlgError:  # duplicated or collinear control points
            inv = np.linalg.pinv(system)
        sol = inv @ rhs
        if smoothing == 0:
            with np.errstate(divide="ignore", invalid="ignore"):  # a zero diagonal: duplicated points
                loo = sol[:n] / np.diag(inv)[:n, None]  # Rippa (1999)
            loo[~np.isfinite(loo)] = np.nan
        else:
            # Linear smoother S (fitted = S y); the leave-one-out lemma gives e_i / (1 - S_ii).
            basis = system[:n].copy()
            basis[np.diag_indices(n)] -= smoothing  # the kernel and the affine columns
            s_diag = np.einsum("ij,ji->i", basis, inv[:, :n])
            loo = (smoothing * sol[:n]) / (1 - s_diag)[:, None]
        return sol, np.linalg.norm(loo, axis=1)

    def loo_residuals(self, src=None, dst=None) -> np.ndarray:
        """Exact leave-one-out errors at the control points (Rippa 1999; Wahba's lemma when smoothing):
        those of the fit when it was fitted here (solving the system again costs as much as the fit)."""
        if self.loo is not None:
            return self.loo.copy()
        q = self._q(self.control)
        dst = self.apply(self.control) + (self.smoothing * self.weights if self.smoothing else 0.0)
        return self._solve(q, np.vstack([dst, np.zeros((3, 2))]), self.smoothing)[1]

    def to_dict(self) -> dict:
        return {"type": "tps", "target_px_to_reference_px": None,
                "tps": {"kernel": "U(r2) = r2*log(r2), q = (p - center)/scale", "smoothing": self.smoothing,
                        "center": self.center.tolist(), "scale": self.scale,
                        "control_points_target_px": self.control.tolist(),
                        "weights": self.weights.tolist(), "affine": self.affine.tolist()}}
