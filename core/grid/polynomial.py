"""Polynomials between scan px and map coordinates of any order, fitted on normalised coordinates (and a
similarity with a reflection, from two points), as the grid's modules use them: a model is a dict
(``centre``, ``scale``, ``m`` the coefficients, ``order``, and ``squeeze`` where it was fitted on longitudes
shrunk by that factor)."""
from __future__ import annotations

import numpy as np


def poly_terms(xy: np.ndarray, order: int) -> np.ndarray:
    x, y = xy[:, 0], xy[:, 1]
    return np.column_stack([x ** (i - j) * y ** j for i in range(order + 1) for j in range(i + 1)])


def fit_poly(src, dst, order, similarity=False) -> dict:
    """Polynomial ``src`` -> ``dst`` of ``order`` (on normalised coordinates); a similarity (two points)."""
    src, dst = np.asarray(src, float), np.asarray(dst, float)
    centre = src.mean(axis=0)
    scale = max(float(np.abs(src - centre).max()), 1e-9)
    u = (src - centre) / scale
    if similarity:  # with a reflection: scan rows run down, map northings up
        a = np.column_stack([u[:, 0], u[:, 1], np.ones(len(u)), np.zeros(len(u))])
        b = np.column_stack([-u[:, 1], u[:, 0], np.zeros(len(u)), np.ones(len(u))])
        p, q, tx, ty = np.linalg.lstsq(np.vstack([a, b]), np.concatenate([dst[:, 0], dst[:, 1]]), rcond=None)[0]
        m = np.array([[tx, ty], [p, q], [q, -p]])
    else:
        m = np.linalg.lstsq(poly_terms(u, order), dst, rcond=None)[0]
    return {"centre": centre, "scale": scale, "m": m, "order": order}


def apply_poly(coef: dict, xy) -> np.ndarray:
    xy = np.asarray(xy, float)
    if "squeeze" in coef:  # a model fitted on longitudes shrunk by this factor (see _first_model)
        xy = xy * np.array([coef["squeeze"], 1.0])
    u = (xy - coef["centre"]) / coef["scale"]
    return poly_terms(u, coef["order"]) @ coef["m"]
