"""The real multimodal set of ``../shared/data/multimodal``: six families, one per modality category.

600 pairs (100 per category) published with Li, Hu & Zhang (2023), ISPRS J. 204:77-88, with
arbitrary rotation and scale on top of the modality gap. Image 1 is the target, image 2 the
reference; ``gt_N.txt`` maps image-1 pixels to image-2 pixels with the pixel-centre origin
(OpenCV), here converted to the corner convention. The ground truth is good to a few pixels only,
so success is an RMS error of at most 15 px over a 20 x 20 grid of image-1 points that land inside
image 2 (the set's README). The files are read where they are, never copied.

Two defects of the published ground truth of Optical-SAR are corrected. Image 1 was resized from
image 2's size to its stored size after the ground truth was made, and ``gt_N.txt`` lacks that
rescaling, so the map is first GT o scale(w2 / w1, h2 / h1); its rotation is also wrong, and is
replaced by the one the SAR image's collar shows (:mod:`hamta.bench.sar_truth`, which gives the
evidence). ``published_truth=True`` scores against the files as published.
"""
from __future__ import annotations

import os
import warnings
from typing import List

import numpy as np

from ..core.coords import apply_matrix
from .cases import Case
from .sar_truth import corrected_truth

CATEGORIES = {"mm-optical": "Optical-Optical", "mm-infrared": "Optical-Infrared", "mm-sar": "Optical-SAR",
              "mm-depth": "Optical-Depth", "mm-map": "Optical-Map", "mm-night": "Nighttime"}
TOLERANCE_PX = 15.0
QUICK_PAIRS = (1, 2)
CENTRE_TO_CORNER = np.array([[1.0, 0.0, 0.5], [0.0, 1.0, 0.5], [0.0, 0.0, 1.0]])


def folder(data_dir: str, family: str) -> str:
    return os.path.join(data_dir, "multimodal", CATEGORIES[family])


def available(data_dir: str, family: str) -> bool:
    return os.path.isfile(os.path.join(folder(data_dir, family), "gt_1.txt"))


def pair_ids(quick: bool) -> List[int]:
    return list(QUICK_PAIRS) if quick else list(range(1, 101))


def truth_matrix(path: str) -> np.ndarray:
    """The ground-truth 3 x 3 map as published, image-1 corner px -> image-2 corner px."""
    m = np.vstack([np.loadtxt(path).reshape(2, 3), [0.0, 0.0, 1.0]])
    return CENTRE_TO_CORNER @ m @ np.linalg.inv(CENTRE_TO_CORNER)


def build(family: str, pair: int, data_dir: str, published_truth: bool = False) -> Case:
    import rasterio

    base = folder(data_dir, family)
    target, reference = os.path.join(base, f"pair{pair}_1.jpg"), os.path.join(base, f"pair{pair}_2.jpg")
    g = truth_matrix(os.path.join(base, f"gt_{pair}.txt"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", rasterio.errors.NotGeoreferencedWarning)
        with rasterio.open(target) as t, rasterio.open(reference) as r:
            (tw, th), (rw, rh) = (t.width, t.height), (r.width, r.height)
    if CATEGORIES[family] == "Optical-SAR" and not published_truth:
        g = corrected_truth(g @ np.diag([rw / tw, rh / th, 1.0]), target, reference)
    gx, gy = np.meshgrid((np.arange(20) + 0.5) * tw / 20, (np.arange(20) + 0.5) * th / 20)
    pts = np.column_stack([gx.ravel(), gy.ravel()])
    mapped = apply_matrix(g, pts)
    inside = (mapped[:, 0] >= 0) & (mapped[:, 1] >= 0) & (mapped[:, 0] <= rw) & (mapped[:, 1] <= rh)
    return Case(f"{family}_{pair}", target, reference, lambda p: apply_matrix(g, p), pts[inside],
                tolerance_px=TOLERANCE_PX, info={"family": family, "category": CATEGORIES[family], "pair": pair,
                                                 "target_px_to_reference_px": g.tolist()})
