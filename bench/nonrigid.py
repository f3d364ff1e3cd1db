"""The ``nonrigid`` family: targets whose misalignment is not one transform.

A global affine (a few degrees, a slight scale, a shift) plus a displacement field in reference
pixels: smooth, terrain-like bumps of a few pixels (Gaussian hills of 150-300 px), and, in the
``patches`` cases, square patches displaced as a block by 3-4 px with sharp (8 px) edges, like a
mosaic seam or a misregistered tile. Target pixel q shows reference position
``g(q) + D(g(q))``; the check points are a dense grid over the whole target, so success measures
the mapping everywhere, not only at GCPs. ``info["smooth"]`` marks the check points farther than
two windows (192 px) from any patch edge: where the field is smooth at the window scale.
"""
from __future__ import annotations

import math
import os

import cv2
import numpy as np

from .cases import Canvas, Case, grid_inside, write_raster
from .synthetic import similarity_matrix

WINDOW_PX = 96  # the local correction's larger default window: 'smooth at the window scale' is judged against it


class Field:
    """A displacement field (reference px -> reference px offsets): Gaussian hills plus block patches."""

    def __init__(self, shape, rng, amplitude_px: float, patches: int, hills: int = 6):
        h, w = shape
        n = hills
        self.centres = rng.uniform([0, 0], [w, h], (n, 2))
        self.sigmas = rng.uniform(150, 300, n)
        angles = rng.uniform(0, 2 * math.pi, n)
        size = amplitude_px * rng.uniform(0.5, 1.0, n)
        self.vectors = np.column_stack([np.cos(angles), np.sin(angles)]) * size[:, None]
        self.patches = []
        for _ in range(patches):
            half = rng.uniform(90, 140)
            centre = rng.uniform([0.25 * w, 0.25 * h], [0.75 * w, 0.75 * h])
            a = rng.uniform(0, 2 * math.pi)
            self.patches.append((centre, half, rng.uniform(3, 4) * np.array([math.cos(a), math.sin(a)])))

    def __call__(self, xy: np.ndarray) -> np.ndarray:
        xy = np.asarray(xy, float).reshape(-1, 2)
        d2 = ((xy[:, None, :] - self.centres[None]) ** 2).sum(axis=2)
        out = np.exp(-d2 / (2 * self.sigmas[None] ** 2)) @ self.vectors
        for centre, half, shift in self.patches:
            inside = 1.0
            for c in range(2):
                inside = inside * _box(xy[:, c] - centre[c], half)
            out += inside[:, None] * shift[None]
        return out

    def dense(self, x0: float, y0: float, width: int, height: int, step: int = 16) -> np.ndarray:
        """(height, width, 2) field at the pixel centres of a window (col x0, row y0), evaluated every
        ``step`` px and interpolated (the hills are smooth over hundreds of pixels; no patches here)."""
        gx = x0 + 0.5 + np.arange(0, width + step, step)
        gy = y0 + 0.5 + np.arange(0, height + step, step)
        xx, yy = np.meshgrid(gx, gy)
        coarse = self(np.column_stack([xx.ravel(), yy.ravel()])).reshape(len(gy), len(gx), 2).astype(np.float32)
        fine = cv2.resize(coarse, ((len(gx) - 1) * step + 1, (len(gy) - 1) * step + 1), interpolation=cv2.INTER_LINEAR)
        return fine[:height, :width]

    def near_patch_edge(self, xy: np.ndarray, distance: float) -> np.ndarray:
        """Points within ``distance`` of any patch's edge."""
        xy = np.asarray(xy, float).reshape(-1, 2)
        near = np.zeros(len(xy), bool)
        for centre, half, _ in self.patches:
            d = np.abs(xy - centre)
            outside = np.linalg.norm(np.maximum(d - half, 0), axis=1)
            inside = np.minimum(half - d[:, 0], half - d[:, 1])
            edge = np.where((d <= half).all(axis=1), inside, outside)
            near |= edge < distance
        return near


def _box(u: np.ndarray, half: float, edge_px: float = 8.0) -> np.ndarray:
    """1 inside [-half, half], 0 outside, with logistic edges about ``edge_px`` wide."""
    k = 4.0 / edge_px
    return 1.0 / (1.0 + np.exp(k * (np.abs(u) - half)))


def nonrigid_case(folder: str, name: str, canvas: Canvas, rng, amplitude_px: float, patches: int) -> Case:
    """A target cut from ``canvas`` through a global similarity and a :class:`Field`."""
    os.makedirs(folder, exist_ok=True)
    ch, cw = canvas.shape
    shape = (int(0.8 * ch), int(0.8 * cw))
    g = similarity_matrix(float(rng.uniform(-6, 6)), float(rng.uniform(0.97, 1.03)), shape, (ch, cw),
                          tuple(rng.uniform(-15, 15, 2)))
    field = Field((ch, cw), rng, amplitude_px, patches)

    def truth(p):
        q = np.asarray(p, float).reshape(-1, 2)
        mapped = q @ g[:2, :2].T + g[:2, 2]
        return mapped + field(mapped)

    gx, gy = np.meshgrid(np.arange(shape[1]) + 0.5, np.arange(shape[0]) + 0.5)
    where = truth(np.column_stack([gx.ravel(), gy.ravel()])).reshape(shape[0], shape[1], 2) - 0.5
    mx, my = where[..., 0].astype(np.float32), where[..., 1].astype(np.float32)
    tgt = np.stack([cv2.remap(b, mx, my, cv2.INTER_CUBIC, borderMode=cv2.BORDER_CONSTANT) for b in canvas.data])
    tgt_valid = cv2.remap(canvas.valid.astype(np.float32), mx, my, cv2.INTER_LINEAR) > 0.999
    reference = write_raster(os.path.join(folder, f"{name}_reference.tif"), canvas.data, canvas.valid, canvas.dtype,
                             canvas.crs, canvas.transform)
    target = write_raster(os.path.join(folder, f"{name}_target.tif"), tgt, tgt_valid, canvas.dtype)
    points = grid_inside(shape, truth, canvas.valid, tgt_valid, n=40)
    smooth = ~field.near_patch_edge(truth(points), 2 * WINDOW_PX)
    return Case(name, target, reference, truth, points,
                info={"family": "nonrigid", "amplitude_px": amplitude_px, "patches": patches,
                      "smooth": smooth.tolist(), "global_px_to_reference_px": g.tolist()})
