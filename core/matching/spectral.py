"""Spectral point-pattern matching of line intersections (spec 003, sections 2.8-2.11).

- Eigenvector (modal) matching: Shapiro & Brady 1992, Feature-based correspondence: an
  eigenvector approach, Image and Vision Computing 10(5):283-288.
- VSPM, Voronoi-integrated spectral point matching: Sui, Xu, Liu & Hua 2015, IEEE TGRS
  53(11):6058-6072, as the thesis describes it (Hausdorff distances between Voronoi cells, a
  proximity matrix, its eigenvectors, a crossing-angle mask).
- Their fusion, which the thesis leaves unspecified: a score-level sum or a cascade (spec 2.10).

Points are working pixels of each image; every matcher returns index pairs (i into the first set,
j into the second) and a score per pair (higher is better).
"""
from __future__ import annotations

from typing import Tuple

import numpy as np
from scipy.spatial import Voronoi
from scipy.spatial.distance import cdist

FUSIONS = ("score", "cascade")
VSPM_PROXIMITIES = ("printed", "laplacian", "gaussian")


def modes(h: np.ndarray, k: int, largest: bool = True) -> np.ndarray:
    """The ``k`` eigenvectors of symmetric ``h`` with the largest (or smallest) eigenvalues, as columns."""
    w, v = np.linalg.eigh(h)
    order = np.argsort(-w if largest else w, kind="stable")
    return v[:, order[:k]]


def align_signs(u: np.ndarray, v: np.ndarray, quantiles: int = 21) -> np.ndarray:
    """``v`` with each column's sign chosen so that the distribution of its entries best matches the
    same column of ``u`` (compared by quantiles, which do not depend on point order or count)."""
    q = np.linspace(0.0, 1.0, quantiles)
    qu, qv = np.quantile(u, q, axis=0), np.quantile(v, q, axis=0)
    qn = np.quantile(-v, q, axis=0)
    flip = np.abs(qu - qn).sum(axis=0) < np.abs(qu - qv).sum(axis=0)
    return v * np.where(flip, -1.0, 1.0)


def gaussian_proximity(xy: np.ndarray, sigma: float) -> np.ndarray:
    """H_ij = exp(-r_ij / (2 sigma^2)), r_ij the squared distance (eq. 2-68)."""
    return np.exp(-cdist(xy, xy, "sqeuclidean") / (2.0 * sigma ** 2))


def rms_spread(xy: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.sum((xy - xy.mean(axis=0)) ** 2, axis=1)))) if len(xy) else 1.0


def mutual_best(score: np.ndarray, largest: bool) -> Tuple[np.ndarray, np.ndarray]:
    """Pairs (i, j) where score[i, j] is the best of its row and of its column (finite only)."""
    if score.size == 0:
        return np.zeros(0, int), np.zeros(0, int)
    s = score if largest else -score
    j = np.argmax(s, axis=1)
    i = np.arange(len(s))
    ok = (np.argmax(s, axis=0)[j] == i) & np.isfinite(s[i, j])
    return i[ok], j[ok]


def eigenvector_distances(xy1: np.ndarray, xy2: np.ndarray, h1: np.ndarray, h2: np.ndarray) -> np.ndarray:
    """Z_ij = ||F_i - F_j||^2 between the rows of both modal matrices truncated to min(m, n) modes,
    the second's signs aligned to the first's (eq. 2-72)."""
    k = min(len(xy1), len(xy2))
    u = modes(h1, k)
    return cdist(u, align_signs(u, modes(h2, k)), "sqeuclidean")


def modal_distances(xy1, xy2, sigma_factor: float = 0.5) -> np.ndarray:
    """Shapiro-Brady's Z with Gaussian proximity, sigma = ``sigma_factor`` x each set's RMS spread."""
    return eigenvector_distances(xy1, xy2, gaussian_proximity(xy1, sigma_factor * rms_spread(xy1)),
                                 gaussian_proximity(xy2, sigma_factor * rms_spread(xy2)))


def eigenvector_match(xy1, xy2, sigma_factor: float = 0.5):
    """Shapiro-Brady: the modal distances Z, mutual minima."""
    z = modal_distances(xy1, xy2, sigma_factor)
    i, j = mutual_best(z, largest=False)
    return i, j, -z[i, j]


def voronoi_cells(xy: np.ndarray, shape) -> list:
    """Each point's Voronoi cell clipped to the image rectangle, as an (K, 2) vertex array. The
    points are mirrored across the four image edges, which bounds every cell exactly by the rectangle."""
    h, w = shape
    pts = np.asarray(xy, float)
    mirrored = [pts, pts * [-1, 1], pts * [-1, 1] + [2 * w, 0], pts * [1, -1], pts * [1, -1] + [0, 2 * h]]
    vor = Voronoi(np.vstack(mirrored))
    cells = []
    for i in range(len(pts)):
        region = vor.regions[vor.point_region[i]]
        v = vor.vertices[[r for r in region if r >= 0]]
        centre = v.mean(axis=0)
        cells.append(v[np.argsort(np.arctan2(v[:, 1] - centre[1], v[:, 0] - centre[0]))])
    return cells


def cell_hausdorff(cells: list) -> np.ndarray:
    """Hausdorff distance between every two filled convex cells (eqs. 2-75, 2-76): the directed
    distance is attained at a vertex of the first cell, so vertex-to-polygon distances are exact."""
    n = len(cells)
    if n == 0:
        return np.zeros((0, 0))
    size = max(len(c) for c in cells)
    poly = np.stack([np.vstack([c, np.repeat(c[-1:], size - len(c), axis=0)]) for c in cells])  # (n, V, 2)
    a, ab = poly, np.roll(poly, -1, axis=1) - poly
    ab2 = np.maximum((ab ** 2).sum(-1), 1e-12)
    d = np.zeros((n, n))
    for i, pts in enumerate(cells):
        ap = pts[:, None, None, :] - a[None]                                  # (Vi, n, V, 2)
        t = np.clip((ap * ab[None]).sum(-1) / ab2[None], 0, 1)
        edge = np.sqrt(((ap - t[..., None] * ab[None]) ** 2).sum(-1)).min(axis=2)   # (Vi, n)
        cross = ab[None, ..., 0] * ap[..., 1] - ab[None, ..., 1] * ap[..., 0]
        inside = np.all(cross >= -1e-9, axis=2) | np.all(cross <= 1e-9, axis=2)
        d[i] = np.where(inside, 0.0, edge).max(axis=0)
    np.fill_diagonal(d, 0.0)
    return np.maximum(d, d.T)


def vspm_proximity(hd: np.ndarray, form: str) -> np.ndarray:
    """Proximity from within-image cell Hausdorff distances: r_ij = exp(-H_ij / (2 sigma^2)) (eq. 2-74)
    with 2 sigma^2 = the median distance (sigma is not given), then 'printed' (eq. 2-73 as printed:
    -r_ij^2 off the diagonal, -sum_k r_ik on it), 'laplacian' (-r_ij, +sum_k r_ik) or 'gaussian' (r)."""
    off = hd[~np.eye(len(hd), dtype=bool)]
    scale = float(np.median(off)) if off.size else 1.0
    r = np.exp(-hd / max(scale, 1e-9))
    np.fill_diagonal(r, 0.0)
    if form == "gaussian":
        return r + np.eye(len(r))
    if form == "laplacian":
        return np.diag(r.sum(axis=1)) - r
    if form == "printed":
        return np.diag(-r.sum(axis=1)) - r ** 2
    raise ValueError(f"VSPM proximity must be one of {VSPM_PROXIMITIES}, got {form!r}")


def angle_mask(angle1: np.ndarray, angle2: np.ndarray, tolerance_deg: float) -> np.ndarray:
    """A_ij = 1 when the crossing angles of intersection i and j differ by less than the tolerance (eq. 2-79)."""
    return np.abs(angle1[:, None] - angle2[None, :]) < tolerance_deg


def vspm_similarity(cells1, cells2, proximity: str) -> np.ndarray:
    """U_k V_k^T: inner products of the rows of both images' truncated eigenvector matrices (eq. 2-80).
    For the Laplacian form the informative modes are those of the smallest eigenvalues after the
    constant one; the other forms take the largest, as Shapiro and Brady do."""
    k = min(len(cells1), len(cells2))
    h1 = vspm_proximity(cell_hausdorff(cells1), proximity)
    h2 = vspm_proximity(cell_hausdorff(cells2), proximity)
    if proximity == "laplacian":
        u, v = modes(h1, k, largest=False)[:, 1:], modes(h2, k, largest=False)[:, 1:]
    else:
        u, v = modes(h1, k), modes(h2, k)
    return u @ align_signs(u, v).T


def vspm_match(cells1, cells2, angle1, angle2, tolerance_deg: float = 5.0, proximity: str = "printed"):
    """VSPM: Z = A o (U V^T) with masked pairs excluded (-inf, as a 0 would not exclude a negative
    score), mutual maxima."""
    z = np.where(angle_mask(angle1, angle2, tolerance_deg), vspm_similarity(cells1, cells2, proximity), -np.inf)
    i, j = mutual_best(z, largest=True)
    return i, j, z[i, j]


def _minmax(a: np.ndarray) -> np.ndarray:
    lo, hi = float(a.min()), float(a.max())
    return (a - lo) / (hi - lo) if hi > lo else np.zeros_like(a)


def fused_match(xy1, xy2, cells1, cells2, angle1, angle2, *, rule: str = "score", weight: float = 0.5,
                sigma_factor: float = 0.5, tolerance_deg: float = 5.0, proximity: str = "printed"):
    """The thesis's "resultant of the two methods" (its rule is not given, spec 2.10).

    'score': S = w (1 - Z_A / max Z_A) + (1 - w) minmax(U V^T), angle-masked, mutual maxima.
    'cascade': VSPM's Hausdorff proximity matrices as Shapiro-Brady's H, angle-masked, mutual minima.
    """
    mask = angle_mask(angle1, angle2, tolerance_deg)
    if rule == "cascade":
        h1 = vspm_proximity(cell_hausdorff(cells1), proximity)
        h2 = vspm_proximity(cell_hausdorff(cells2), proximity)
        z = np.where(mask, eigenvector_distances(xy1, xy2, h1, h2), np.inf)
        i, j = mutual_best(z, largest=False)
        return i, j, -z[i, j]
    if rule != "score":
        raise ValueError(f"fusion rule must be one of {FUSIONS}, got {rule!r}")
    za = modal_distances(xy1, xy2, sigma_factor)
    sa = 1.0 - za / max(float(za.max()), 1e-12)
    sb = _minmax(vspm_similarity(cells1, cells2, proximity))
    s = np.where(mask, weight * sa + (1.0 - weight) * sb, -np.inf)
    i, j = mutual_best(s, largest=True)
    return i, j, s[i, j]
