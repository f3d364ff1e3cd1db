"""Geometric models from target pixels to reference pixels, fitted by least squares.

All models map target pixel coordinates to reference pixel coordinates (corner convention, see
:mod:`hamta.core.coords`). Each model knows its minimal point count, how to fit itself, apply
itself, report leave-one-out residuals (RMS_LOO, Goncalves et al. 2009, GRSL 6(2)) and serialise
itself for ``report.json``.

The names follow the QGIS Georeferencer: similarity = Helmert, affine = polynomial 1, projective,
polynomial 2 and 3, thin plate spline (exact interpolation, as GDAL's ``-tps``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..coords import apply_matrix, as_xy
from ..options import canonical_model
from .tps import ThinPlateSplineModel

MIN_POINTS = {"similarity": 2, "affine": 3, "projective": 4, "polynomial-1": 3, "polynomial-2": 6, "polynomial-3": 10,
              "tps": ThinPlateSplineModel.n_min, "linear": 2}  # polynomial-1: an affine among the orders a fit chooses
LINEAR_KINDS = ("linear", "similarity", "affine", "projective")


def _loo_from_blocks(design_blocks: np.ndarray, residuals: np.ndarray) -> np.ndarray:
    """Leave-one-out residual norms of a linear least-squares fit with 2-row blocks per point.

    ``design_blocks`` is (n, 2, p): the rows of the design matrix that predict point i's x and y.
    The LOO residual is ``(I - H_ii)^-1 e_i`` with ``H_ii`` the 2x2 hat-matrix block.
    """
    n, _, p = design_blocks.shape
    x = design_blocks.reshape(2 * n, p)
    gram_inv = np.linalg.pinv(x.T @ x)
    h = np.einsum("nip,pq,njq->nij", design_blocks, gram_inv, design_blocks)
    eye = np.eye(2)[None] - h
    out = np.full(n, np.nan)
    ok = np.abs(np.linalg.det(eye)) > 1e-10
    out[ok] = np.linalg.norm(np.linalg.solve(eye[ok], residuals[ok][..., None])[..., 0], axis=1)
    return out


@dataclass(frozen=True, eq=False)
class LinearModel:
    """Similarity, affine or projective map given by a 3x3 matrix (target px -> reference px)."""

    kind: str
    matrix: np.ndarray

    @property
    def n_min(self) -> int:
        return MIN_POINTS[self.kind]

    def apply(self, xy) -> np.ndarray:
        return apply_matrix(self.matrix, xy)

    def inverse(self) -> "LinearModel":
        return LinearModel(self.kind, np.linalg.inv(self.matrix))

    def residuals(self, src, dst) -> np.ndarray:
        return np.linalg.norm(self.apply(src) - as_xy(dst), axis=1)

    @classmethod
    def fit(cls, kind: str, src, dst) -> "LinearModel":
        src, dst = as_xy(src), as_xy(dst)
        if len(src) < MIN_POINTS[kind]:
            raise ValueError(f"{kind} needs at least {MIN_POINTS[kind]} points, got {len(src)}")
        if kind == "linear":  # QGIS's "Linear": a scale and a shift per axis, no rotation
            ax, cx = np.linalg.lstsq(np.column_stack([src[:, 0], np.ones(len(src))]), dst[:, 0], rcond=None)[0]
            ay, cy = np.linalg.lstsq(np.column_stack([src[:, 1], np.ones(len(src))]), dst[:, 1], rcond=None)[0]
            m = np.array([[ax, 0.0, cx], [0.0, ay, cy], [0, 0, 1.0]])
        elif kind == "similarity":
            a, b, tx, ty = np.linalg.lstsq(_similarity_design(src).reshape(-1, 4), dst.reshape(-1), rcond=None)[0]
            m = np.array([[a, -b, tx], [b, a, ty], [0, 0, 1.0]])
        elif kind == "affine":
            coef = np.linalg.lstsq(np.column_stack([src, np.ones(len(src))]), dst, rcond=None)[0]
            m = np.vstack([coef.T, [0, 0, 1.0]])
        elif kind == "projective":
            m = _fit_homography(src, dst)
        else:
            raise ValueError(f"{kind!r} is not a linear model")
        return cls(kind, m)

    def loo_residuals(self, src, dst) -> np.ndarray:
        """Leave-one-out residual norms (reference px); exact for similarity/affine,
        first-order (linearised at the fit) for projective."""
        src, dst = as_xy(src), as_xy(dst)
        e = dst - self.apply(src)
        if len(src) <= self.n_min:
            return np.full(len(src), np.nan)
        if self.kind == "linear":
            blocks = np.zeros((len(src), 2, 4))
            blocks[:, 0, 0], blocks[:, 0, 1] = src[:, 0], 1.0
            blocks[:, 1, 2], blocks[:, 1, 3] = src[:, 1], 1.0
        elif self.kind == "similarity":
            blocks = _similarity_design(src)
        elif self.kind == "affine":
            row = np.column_stack([src, np.ones(len(src))])
            blocks = np.zeros((len(src), 2, 6))
            blocks[:, 0, :3] = row
            blocks[:, 1, 3:] = row
        else:
            blocks = _homography_jacobian(self.matrix, src)
        return _loo_from_blocks(blocks, e)

    def to_dict(self) -> dict:
        return {"type": self.kind, "target_px_to_reference_px": self.matrix.tolist()}


def _similarity_design(src: np.ndarray) -> np.ndarray:
    """(n, 2, 4) design blocks for x' = a x - b y + tx, y' = b x + a y + ty."""
    n = len(src)
    d = np.zeros((n, 2, 4))
    d[:, 0, 0], d[:, 0, 1], d[:, 0, 2] = src[:, 0], -src[:, 1], 1
    d[:, 1, 0], d[:, 1, 1], d[:, 1, 3] = src[:, 1], src[:, 0], 1
    return d


def _normaliser(xy: np.ndarray) -> np.ndarray:
    """Hartley normalisation: centroid to the origin, mean distance sqrt(2)."""
    c = xy.mean(axis=0)
    d = np.sqrt(((xy - c) ** 2).sum(axis=1)).mean()
    s = np.sqrt(2) / d if d > 0 else 1.0
    return np.array([[s, 0, -s * c[0]], [0, s, -s * c[1]], [0, 0, 1.0]])


def _fit_homography(src: np.ndarray, dst: np.ndarray) -> np.ndarray:
    """Normalised DLT, then Gauss-Newton on the geometric (reference-pixel) error."""
    ts, td = _normaliser(src), _normaliser(dst)
    a, b = apply_matrix(ts, src), apply_matrix(td, dst)
    n = len(a)
    rows = np.zeros((2 * n, 9))
    rows[0::2, 0:2], rows[0::2, 2] = a, 1
    rows[0::2, 6:8], rows[0::2, 8] = -a * b[:, :1], -b[:, 0]
    rows[1::2, 3:5], rows[1::2, 5] = a, 1
    rows[1::2, 6:8], rows[1::2, 8] = -a * b[:, 1:], -b[:, 1]
    h = np.linalg.svd(rows, full_matrices=False)[2][-1].reshape(3, 3)
    m = np.linalg.inv(td) @ h @ ts
    m = m / m[2, 2]
    for _ in range(5):
        jac = _homography_jacobian(m, src).reshape(-1, 8)
        e = (dst - apply_matrix(m, src)).reshape(-1)
        step = np.linalg.lstsq(jac, e, rcond=None)[0]
        m = m + np.append(step, 0.0).reshape(3, 3)
        if np.abs(step).max() < 1e-12:
            break
    return m / m[2, 2]


def _homography_jacobian(m: np.ndarray, src: np.ndarray) -> np.ndarray:
    """(n, 2, 8) derivatives of the mapped points w.r.t. the 8 free entries (h33 = 1)."""
    x, y = src[:, 0], src[:, 1]
    w = m[2, 0] * x + m[2, 1] * y + m[2, 2]
    u = (m[0, 0] * x + m[0, 1] * y + m[0, 2]) / w
    v = (m[1, 0] * x + m[1, 1] * y + m[1, 2]) / w
    j = np.zeros((len(src), 2, 8))
    j[:, 0, 0], j[:, 0, 1], j[:, 0, 2] = x / w, y / w, 1 / w
    j[:, 1, 3], j[:, 1, 4], j[:, 1, 5] = x / w, y / w, 1 / w
    j[:, 0, 6], j[:, 0, 7] = -u * x / w, -u * y / w
    j[:, 1, 6], j[:, 1, 7] = -v * x / w, -v * y / w
    return j


POLY_TERMS = ("1", "u", "v", "u^2", "u*v", "v^2", "u^3", "u^2*v", "u*v^2", "v^3")


@dataclass(frozen=True, eq=False)
class PolynomialModel:
    """Polynomial of order 2 or 3 (1: an affine, where an order is chosen) in normalised target coordinates
    ``u = (x - cx) / s``, ``v = (y - cy) / s``; one coefficient vector per output axis (terms in ``POLY_TERMS``
    order)."""

    order: int
    center: np.ndarray
    scale: float
    coef: np.ndarray  # (n_terms, 2)

    kind = property(lambda self: f"polynomial-{self.order}")
    matrix = None

    @property
    def n_min(self) -> int:
        return MIN_POINTS[self.kind]

    def _design(self, xy) -> np.ndarray:
        return poly_design((as_xy(xy) - self.center) / self.scale, self.order)

    def apply(self, xy) -> np.ndarray:
        return self._design(xy) @ self.coef

    def residuals(self, src, dst) -> np.ndarray:
        return np.linalg.norm(self.apply(src) - as_xy(dst), axis=1)

    @classmethod
    def fit(cls, order: int, src, dst) -> "PolynomialModel":
        src, dst = as_xy(src), as_xy(dst)
        need = MIN_POINTS[f"polynomial-{order}"]
        if len(src) < need:
            raise ValueError(f"polynomial-{order} needs at least {need} points, got {len(src)}")
        center = src.mean(axis=0)
        scale = float(np.abs(src - center).max()) or 1.0
        coef = np.linalg.lstsq(poly_design((src - center) / scale, order), dst, rcond=None)[0]
        return cls(order, center, scale, coef)

    def loo_residuals(self, src, dst) -> np.ndarray:
        src, dst = as_xy(src), as_xy(dst)
        if len(src) <= self.n_min:
            return np.full(len(src), np.nan)
        a = self._design(src)
        h = np.einsum("ij,jk,ik->i", a, np.linalg.pinv(a.T @ a), a)
        e = dst - a @ self.coef
        with np.errstate(divide="ignore", invalid="ignore"):
            out = np.linalg.norm(e, axis=1) / (1 - h)
        return np.where(1 - h > 1e-10, out, np.nan)

    def to_dict(self) -> dict:
        return {"type": self.kind, "target_px_to_reference_px": None,
                "polynomial": {"order": self.order, "center": self.center.tolist(), "scale": self.scale,
                               "terms": list(POLY_TERMS[: self.coef.shape[0]]),
                               "coefficients_x": self.coef[:, 0].tolist(),
                               "coefficients_y": self.coef[:, 1].tolist()}}


def poly_design(uv: np.ndarray, order: int) -> np.ndarray:
    """The terms (:data:`POLY_TERMS` order) of ``order`` at normalised coordinates ``uv`` (n, 2)."""
    u, v = uv[:, 0], uv[:, 1]
    cols = [np.ones_like(u), u, v]
    if order >= 2:
        cols += [u * u, u * v, v * v]
    if order >= 3:
        cols += [u ** 3, u * u * v, u * v * v, v ** 3]
    return np.column_stack(cols)


def fit_model(kind: str, src, dst):
    """Least-squares fit of the model named ``kind`` (see :data:`hamta.core.options.MODEL`)."""
    kind = canonical_model(kind)
    if kind in LINEAR_KINDS:
        return LinearModel.fit(kind, src, dst)
    if kind == "tps":
        return ThinPlateSplineModel.fit(src, dst)
    return PolynomialModel.fit(int(kind[-1]), src, dst)


def model_from_dict(d: dict, reference_transform=None, reference_crs_wkt=None):
    """Rebuild a model from its ``report.json`` form.

    Models fitted in the target's CRS frame (``"frame": "target_crs"``) also need the reference's
    geotransform (rasterio ``Affine``) and CRS (WKT).
    """
    if d.get("frame") == "target_crs":
        from affine import Affine

        from .framed import CrsFrame, FramedModel

        inner = dict(d, target_px_to_reference_px=d["target_px_to_frame_px"])
        inner.pop("frame")
        frame = CrsFrame(Affine.from_gdal(*d["frame_transform"]), d["frame_crs"], reference_transform,
                         reference_crs_wkt, d.get("reference_centre_lon"), d.get("frame_centre_lon"))
        return FramedModel(model_from_dict(inner), frame)
    kind = canonical_model(d["type"])
    if kind in LINEAR_KINDS:
        return LinearModel(kind, np.asarray(d["target_px_to_reference_px"], float))
    if kind == "tps":
        t = d["tps"]
        return ThinPlateSplineModel(np.asarray(t["control_points_target_px"], float), np.asarray(t["center"], float),
                                    float(t["scale"]), np.asarray(t["weights"], float), np.asarray(t["affine"], float),
                                    float(t.get("smoothing", 0.0)))
    p = d["polynomial"]
    coef = np.column_stack([p["coefficients_x"], p["coefficients_y"]])
    return PolynomialModel(int(p["order"]), np.asarray(p["center"], float), float(p["scale"]), coef)


def local_jacobian(model, xy, step: float = 0.5) -> np.ndarray:
    """(N, 2, 2) derivative of ``model.apply`` at ``xy``: the model's own where it has one (a thin
    plate spline's, exact and in 40 % of the time), else by central differences."""
    if hasattr(model, "jacobian"):
        return model.jacobian(xy)
    xy = as_xy(xy)
    dx = np.array([step, 0.0])
    dy = np.array([0.0, step])
    jx = (model.apply(xy + dx) - model.apply(xy - dx)) / (2 * step)
    jy = (model.apply(xy + dy) - model.apply(xy - dy)) / (2 * step)
    return np.stack([jx, jy], axis=2)

