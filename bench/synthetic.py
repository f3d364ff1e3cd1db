"""Synthetic registration cases with exact ground truth, and the self-generated demo landscape.

A case is a reference image, a known map ``g`` from target pixels to reference pixels, and the
target made by resampling the reference through ``g`` (every point of the target has a known
true position). Pixels follow :mod:`hamta.core.coords` (corner origin).
"""
from __future__ import annotations

import math

import cv2
import numpy as np

from ..core.coords import matrix_corner_to_opencv


def similarity_matrix(angle_deg: float, scale: float, target_shape, reference_shape, shift=(0.0, 0.0)) -> np.ndarray:
    """Target px -> reference px for a target rotated by ``angle_deg`` (clockwise as displayed,
    y down) and scaled by ``scale`` (target pixels per reference pixel) about the image centres,
    then shifted by ``shift`` reference pixels."""
    a = math.radians(angle_deg)
    rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]) / scale
    ct = np.array([target_shape[1] / 2.0, target_shape[0] / 2.0])
    cr = np.array([reference_shape[1] / 2.0, reference_shape[0] / 2.0]) + np.asarray(shift, float)
    g = np.eye(3)
    g[:2, :2] = rot
    g[:2, 2] = cr - rot @ ct
    return g


def warp_to_target(reference: np.ndarray, g: np.ndarray, target_shape, border_value=0) -> np.ndarray:
    """Resample ``reference`` ((H, W) or (bands, H, W)) into a target grid where target pixel p
    shows reference position ``g(p)``. The reference is low-pass filtered first when the target is
    coarser, so the target does not alias."""
    j = g[:2, :2]
    ref_px_per_tgt_px = math.sqrt(abs(np.linalg.det(j)))
    sigma = 0.5 * math.sqrt(max(ref_px_per_tgt_px ** 2 - 1.0, 0.0))
    cv_g = matrix_corner_to_opencv(g)
    size = (int(target_shape[1]), int(target_shape[0]))
    bands = reference[None] if reference.ndim == 2 else reference
    out = []
    for band in bands:
        src = band.astype(np.float32)
        if sigma > 0.05:
            src = cv2.GaussianBlur(src, (0, 0), sigma)
        out.append(cv2.warpPerspective(src, cv_g, size, flags=cv2.INTER_CUBIC | cv2.WARP_INVERSE_MAP,
                                       borderMode=cv2.BORDER_CONSTANT, borderValue=border_value))
    out = np.stack(out)
    return out[0] if reference.ndim == 2 else out


def make_landscape(shape=(1000, 1000), seed: int = 7) -> np.ndarray:
    """A deterministic, self-generated 3-band uint8 scene that looks like farmland from orbit:
    fractal terrain, Voronoi field parcels with furrow textures, roads, a river and villages."""
    rng = np.random.default_rng(seed)
    h, w = shape
    terrain = np.zeros(shape, np.float32)
    for octave in range(6):
        cell = max(2, int(min(h, w) / (2 ** (octave + 1))))
        small = rng.random((h // cell + 2, w // cell + 2)).astype(np.float32)
        terrain += cv2.resize(small, (w, h), interpolation=cv2.INTER_CUBIC)[:h, :w] / (1.6 ** octave)
    terrain = (terrain - terrain.min()) / (np.ptp(terrain) + 1e-9)

    n_fields = int(h * w / 6000)
    seeds = rng.random((n_fields, 2)) * [w, h]
    from scipy.spatial import cKDTree

    yy, xx = np.mgrid[0:h, 0:w]
    label = cKDTree(seeds).query(np.column_stack([xx.ravel(), yy.ravel()]))[1].reshape(shape)
    palette = np.array([[0.16, 0.30, 0.12], [0.32, 0.48, 0.20], [0.45, 0.36, 0.25], [0.62, 0.55, 0.40],
                        [0.55, 0.53, 0.50], [0.25, 0.22, 0.18], [0.50, 0.60, 0.30]], np.float32)
    tone = palette[rng.integers(0, len(palette), n_fields)] * rng.uniform(0.75, 1.25, (n_fields, 1))
    tone = tone.astype(np.float32)
    angle = rng.uniform(0, np.pi, n_fields)
    period = rng.uniform(4, 12, n_fields)
    phase = (xx * np.cos(angle[label]) + yy * np.sin(angle[label])) * (2 * np.pi / period[label])
    furrows = 0.06 * np.sin(phase).astype(np.float32)
    grain = cv2.GaussianBlur(rng.normal(0, 0.05, shape).astype(np.float32), (0, 0), 1.2)
    img = tone[label] * (0.55 + 0.6 * terrain[..., None]) + (furrows + grain)[..., None]
    edges = cv2.Laplacian(label.astype(np.float32), cv2.CV_32F) != 0
    img[edges] *= 0.8

    canvas = (np.clip(img, 0, 1) * 255).astype(np.uint8)
    for _ in range(max(3, (h + w) // 300)):
        pts = np.cumsum(rng.normal(0, 60, (8, 2)), axis=0) + rng.random(2) * [w, h]
        cv2.polylines(canvas, [pts.astype(np.int32)], False, (225, 220, 210), 3, cv2.LINE_AA)
    river = np.cumsum(np.column_stack([np.full(40, w / 39.0), rng.normal(0, 18, 40)]), axis=0)
    river[:, 1] += h * rng.uniform(0.3, 0.7)
    cv2.polylines(canvas, [river.astype(np.int32)], False, (40, 60, 70), 9, cv2.LINE_AA)
    for _ in range(max(2, h * w // 150000)):
        cx, cy = rng.random(2) * [w, h]
        for _ in range(40):
            x, y = int(cx + rng.normal(0, 25)), int(cy + rng.normal(0, 25))
            s = int(rng.integers(3, 8))
            cv2.rectangle(canvas, (x, y), (x + s, y + s), (245, 240, 235), -1)
    canvas = cv2.GaussianBlur(canvas, (0, 0), 0.7)
    noise = rng.normal(0, 2.0, canvas.shape)
    return np.clip(canvas + noise, 0, 255).astype(np.uint8).transpose(2, 0, 1)
