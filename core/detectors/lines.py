"""Straight lines and their intersections, the features of spec 003 (SAR onto optical).

Edges: the Gaussian-Gamma-shaped (GGS) bi-window ratio detector (Shui & Cheng 2012, IEEE GRSL
9(6):1107-1111), non-maximum suppression across the edge and hysteresis; connected components under
``min_component_px`` removed, then thinning until nothing changes. Lines: the Radon transform of
the binary edge map (a (theta, rho) vote count over edge pixels), its strongest local maxima, and
greedy clustering of near-duplicate lines. Intersections of line pairs crossing at a large enough
angle keep the indices of their two lines and their crossing angle.

Every function takes and returns working pixels of one image (x = column, y = row, corner origin).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np
from scipy.special import gammaln


@dataclass(frozen=True)
class Lines:
    """Lines x cos(theta) + y sin(theta) = rho, in pixels about the image centre ``centre``."""

    theta: np.ndarray   # radians in [0, pi)
    rho: np.ndarray
    votes: np.ndarray
    centre: tuple

    def __len__(self) -> int:
        return len(self.theta)


@dataclass(frozen=True)
class Intersections:
    """Intersection points (working px) with their two lines and crossing angle (degrees, 0-90)."""

    xy: np.ndarray
    lines: np.ndarray   # (N, 2) line indices
    angle: np.ndarray

    def __len__(self) -> int:
        return len(self.xy)


def ggs_radius(alpha: float, beta: float, sigma_x: float) -> int:
    """Half-size of the GGS windows: 3 sigma_x along the edge, the Gamma profile's tail across it."""
    return int(math.ceil(max(3.0 * sigma_x, alpha * beta + 4.0 * math.sqrt(alpha) * beta)))


def ggs_kernels(alpha: float, beta: float, sigma_x: float, orientations: int):
    """Per orientation theta_p = p pi / P the pair (W_U, W_L) of eqs. 2-29 to 2-32, sampled on
    pixel offsets, truncated at :func:`ggs_radius` and renormalised to sum 1, plus the unit normal
    (dx, dy) of the edge that orientation detects."""
    r = ggs_radius(alpha, beta, sigma_x)
    dy, dx = np.mgrid[-r:r + 1, -r:r + 1].astype(np.float64)
    log_norm = -0.5 * math.log(2 * math.pi) - math.log(sigma_x) - gammaln(alpha) - alpha * math.log(beta)
    out = []
    for p in range(orientations):
        th = p * math.pi / orientations
        u = dx * math.cos(th) + dy * math.sin(th)      # along the edge
        v = -dx * math.sin(th) + dy * math.cos(th)     # across it
        av = np.abs(v)
        with np.errstate(divide="ignore"):
            w = np.exp(log_norm + (alpha - 1) * np.log(av) - u ** 2 / (2 * sigma_x ** 2) - av / beta)
        w[av == 0] = 0.0
        wu, wl = np.where(v > 0, w, 0.0), np.where(v < 0, w, 0.0)
        out.append((wu / wu.sum(), wl / wl.sum(), (-math.sin(th), math.cos(th))))
    return out


def ggs_strength(image: np.ndarray, alpha: float = 3.0, beta: float = 1.5, sigma_x: float = 6.5 / math.sqrt(math.pi),
                 orientations: int = 8, floor: float = 1e-3):
    """Edge strength map ESM = 1 - min_p min(m1/m2, m2/m1) (eq. 2-35) and the index of the
    minimising orientation (eq. 2-39). ``floor`` (a fraction of the image mean) keeps ratios finite
    where an optical image is black."""
    img = image.astype(np.float32)
    img = img + np.float32(floor * max(float(img.mean()), 1e-12))
    best = np.full(img.shape, np.inf, np.float32)
    arg = np.zeros(img.shape, np.uint8)
    normals = []
    for p, (wu, wl, normal) in enumerate(ggs_kernels(alpha, beta, sigma_x, orientations)):
        m1 = cv2.filter2D(img, cv2.CV_32F, wu[::-1, ::-1].astype(np.float32), borderType=cv2.BORDER_REFLECT)
        m2 = cv2.filter2D(img, cv2.CV_32F, wl[::-1, ::-1].astype(np.float32), borderType=cv2.BORDER_REFLECT)
        ratio = np.minimum(m1 / m2, m2 / m1)
        better = ratio < best
        best[better] = ratio[better]
        arg[better] = p
        normals.append(normal)
    return 1.0 - best, arg, np.array(normals)


def non_maximum_suppression(strength: np.ndarray, arg: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """``strength`` where it is a maximum along the edge normal (nearest 8-neighbour), else 0."""
    pad = np.pad(strength, 1, mode="constant")
    h, w = strength.shape
    step = np.round(normals).astype(int)
    keep = np.zeros(strength.shape, bool)
    for p, (sx, sy) in enumerate(step):
        sel = arg == p
        fwd = pad[1 + sy:1 + sy + h, 1 + sx:1 + sx + w]
        bwd = pad[1 - sy:1 - sy + h, 1 - sx:1 - sx + w]
        keep |= sel & (strength >= fwd) & (strength > bwd)
    return np.where(keep, strength, 0.0).astype(np.float32)


def hysteresis(strength: np.ndarray, low: float, high: float) -> np.ndarray:
    """Pixels above ``low`` 8-connected to a pixel above ``high``."""
    weak = (strength > low).astype(np.uint8)
    n, labels = cv2.connectedComponents(weak, connectivity=8)
    strong = np.zeros(n, bool)
    strong[np.unique(labels[strength > high])] = True
    strong[0] = False
    return strong[labels]


def remove_small(binary: np.ndarray, min_pixels: int) -> np.ndarray:
    """``binary`` without its 8-connected components of fewer than ``min_pixels`` (MATLAB's bwareaopen)."""
    n, labels, stats, _ = cv2.connectedComponentsWithStats(binary.astype(np.uint8), connectivity=8)
    big = stats[:, cv2.CC_STAT_AREA] >= min_pixels
    big[0] = False
    return big[labels]


def thin(binary: np.ndarray) -> np.ndarray:
    """Zhang-Suen thinning repeated until nothing changes (Zhang & Suen 1984, CACM 27(3):236-239): a
    one-pixel-wide skeleton like that of MATLAB's ``bwmorph(BW, 'thin', Inf)``, which uses the
    related Lam-Lee-Suen rules."""
    img = np.pad(binary.astype(np.uint8), 1)
    while True:
        changed = False
        for step in (0, 1):
            p = [np.roll(np.roll(img, -dy, 0), -dx, 1) for dy, dx in
                 ((-1, 0), (-1, 1), (0, 1), (1, 1), (1, 0), (1, -1), (0, -1), (-1, -1))]   # P2 .. P9
            b = sum(q.astype(np.int32) for q in p)
            a = sum(((p[i] == 0) & (p[(i + 1) % 8] == 1)).astype(np.int32) for i in range(8))
            if step == 0:
                c = (p[0] * p[2] * p[4] == 0) & (p[2] * p[4] * p[6] == 0)
            else:
                c = (p[0] * p[2] * p[6] == 0) & (p[0] * p[4] * p[6] == 0)
            remove = (img == 1) & (b >= 2) & (b <= 6) & (a == 1) & c
            if remove.any():
                img[remove] = 0
                changed = True
        if not changed:
            return img[1:-1, 1:-1].astype(bool)


def radon_lines(edges: np.ndarray, peaks: int = 40, theta_step_deg: float = 1.0, min_votes: int = 15) -> Lines:
    """The ``peaks`` strongest local maxima (3 x 3, with ``min_votes`` or more) of the Radon
    transform of a binary edge map: for theta in [0, 180) and rho in 1 px bins, the number of edge
    pixel centres on x cos(theta) + y sin(theta) = rho about the centre of the middle pixel (so that
    rows and columns of pixel centres fall exactly on bins; eq. 2-63)."""
    h, w = edges.shape
    centre = (w // 2 + 0.5, h // 2 + 0.5)
    ys, xs = np.nonzero(edges)
    theta = np.deg2rad(np.arange(0.0, 180.0, theta_step_deg))
    if len(xs) == 0:
        return Lines(np.zeros(0), np.zeros(0), np.zeros(0), centre)
    x, y = xs + 0.5 - centre[0], ys + 0.5 - centre[1]
    d = int(math.ceil(math.hypot(w, h) / 2.0)) + 1
    acc = np.zeros((len(theta), 2 * d + 1), np.float32)
    for k in range(0, len(theta), 16):
        th = theta[k:k + 16]
        rho = np.rint(np.outer(np.cos(th), x) + np.outer(np.sin(th), y)).astype(np.int64) + d
        rows = np.repeat(np.arange(len(th)), len(x))
        acc[k:k + len(th)] = np.bincount(rows * acc.shape[1] + rho.ravel(),
                                         minlength=len(th) * acc.shape[1]).reshape(len(th), -1)
    # theta wraps onto itself with rho mirrored: pad with the mirrored rows before the 3 x 3 maximum
    wrapped = np.vstack([acc[-1:, ::-1], acc, acc[:1, ::-1]])
    local = cv2.dilate(wrapped, np.ones((3, 3), np.uint8))[1:-1]
    cand = np.argwhere((acc >= local) & (acc >= max(min_votes, 1)))
    votes = acc[cand[:, 0], cand[:, 1]]
    order = np.argsort(-votes, kind="stable")[:peaks]
    cand, votes = cand[order], votes[order]
    return Lines(theta[cand[:, 0]], cand[:, 1].astype(float) - d, votes.astype(float), centre)


def cluster_lines(lines: Lines, max_dtheta_deg: float = 5.0, max_drho_px: float = 10.0) -> Lines:
    """Greedy clustering of near-duplicate lines: in decreasing votes, a line joins the first kept
    line within ``max_dtheta_deg`` and ``max_drho_px`` (theta circular, rho mirrored across the
    wrap); each cluster is represented by its strongest line."""
    kept = []
    for i in np.argsort(-lines.votes, kind="stable"):
        dup = False
        for j in kept:
            dth = abs(lines.theta[i] - lines.theta[j])
            same = dth if dth <= math.pi / 2 else math.pi - dth
            rho_j = lines.rho[j] if dth <= math.pi / 2 else -lines.rho[j]
            if math.degrees(same) <= max_dtheta_deg and abs(lines.rho[i] - rho_j) <= max_drho_px:
                dup = True
                break
        if not dup:
            kept.append(i)
    k = np.array(kept, int)
    return Lines(lines.theta[k], lines.rho[k], lines.votes[k], lines.centre)


def intersections(lines: Lines, shape, min_angle_deg: float = 10.0) -> Intersections:
    """Pairwise intersections inside the image of lines crossing at ``min_angle_deg`` or more
    (Sui et al. 2015's constraint; the thesis's eq. 3-1 solved in normal form)."""
    h, w = shape
    pts, pairs, angles = [], [], []
    for i in range(len(lines)):
        for j in range(i + 1, len(lines)):
            d = abs(lines.theta[i] - lines.theta[j]) % math.pi
            angle = math.degrees(min(d, math.pi - d))
            if angle < min_angle_deg:
                continue
            a = np.array([[math.cos(lines.theta[i]), math.sin(lines.theta[i])],
                          [math.cos(lines.theta[j]), math.sin(lines.theta[j])]])
            x, y = np.linalg.solve(a, [lines.rho[i], lines.rho[j]]) + np.asarray(lines.centre)
            if 0 <= x < w and 0 <= y < h:
                pts.append((x, y))
                pairs.append((i, j))
                angles.append(angle)
    if not pts:
        return Intersections(np.zeros((0, 2)), np.zeros((0, 2), int), np.zeros(0))
    return Intersections(np.array(pts), np.array(pairs, int), np.array(angles))
