"""Families that test trust rather than accuracy.

``should-fail``: pairs with nothing to find (noise, an unrelated scene, crops that do not
overlap, constant and near-constant images, a checkerboard); any verified result is a confident
wrong answer. ``crops``: targets that are plain crops of the reference in awkward forms (float32 or
complex64 pixels, georeferencing stripped, a zero collar around a rotated footprint), where an
earlier version reported wrong registrations as good ones.
"""
from __future__ import annotations

import math
import os
from typing import List

import numpy as np

from .cases import Canvas, Case, warped_case, write_raster
from .synthetic import make_landscape

SHOULD_FAIL = ("noise", "unrelated", "disjoint", "constant", "near-constant", "checkerboard", "stripes")
CROPS = ("float32", "complex64", "uint16-rot37", "collar-rot25")


def should_fail_names(quick: bool) -> List[str]:
    return list(SHOULD_FAIL[:2]) if quick else list(SHOULD_FAIL)


def crop_names(quick: bool) -> List[str]:
    return list(CROPS[:2]) if quick else list(CROPS)


def build_should_fail(folder: str, name: str, kind: str, canvas: Canvas, seed: int) -> Case:
    """A reference cut from ``canvas`` and a target that shows none of it (``kind`` says how)."""
    os.makedirs(folder, exist_ok=True)
    rng = np.random.default_rng(seed)
    h, w = canvas.shape
    half = w // 2
    ref = canvas.data[:, :, :half]
    reference = write_raster(os.path.join(folder, f"{name}_reference.tif"), ref, canvas.valid[:, :half],
                             canvas.dtype, canvas.crs, canvas.transform)
    shape = (h * 3 // 4, half * 3 // 4)
    if kind == "noise":
        tgt = rng.uniform(0, 255, (1,) + shape)
    elif kind == "unrelated":
        tgt = make_landscape(shape, seed=seed % 1000 + 101).astype(np.float32)
    elif kind == "disjoint":  # the other half of the canvas, which the reference does not show
        tgt = canvas.data[:, : shape[0], w - shape[1]:]
    elif kind == "constant":
        tgt = np.full((1,) + shape, 117.0)
    elif kind == "near-constant":
        tgt = 117.0 + rng.normal(0, 0.7, (1,) + shape)
    elif kind == "checkerboard":
        yy, xx = np.mgrid[: shape[0], : shape[1]]
        tgt = (((yy // 24) + (xx // 24)) % 2 * 200.0 + 20.0)[None]
    else:  # stripes
        xx = np.mgrid[: shape[0], : shape[1]][1]
        tgt = (127.0 + 100.0 * np.sin(2 * math.pi * xx / 37.0))[None]
    target = write_raster(os.path.join(folder, f"{name}_target.tif"), np.asarray(tgt, np.float32),
                          np.ones(shape, bool), "uint8")
    return Case(name, target, reference, None, np.zeros((0, 2)), info={"should_fail": True, "kind": kind})


def build_crop(folder: str, name: str, kind: str, canvas: Canvas, seed: int) -> Case:
    """A target cut from the reference (no georeferencing) in the form ``kind`` says."""
    rng = np.random.default_rng(seed)
    h, w = canvas.shape
    angle = {"uint16-rot37": 37.0, "collar-rot25": 25.0}.get(kind, 0.0)
    shape = (int(0.55 * h), int(0.55 * w))
    c = np.array([w / 2.0 + rng.uniform(-0.1, 0.1) * w, h / 2.0 + rng.uniform(-0.1, 0.1) * h])
    a = math.radians(angle)
    lin = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    g = np.eye(3)
    g[:2, :2] = lin
    g[:2, 2] = c - lin @ np.array([shape[1] / 2.0, shape[0] / 2.0])
    grey = Canvas(canvas.data.mean(axis=0, keepdims=True), canvas.valid, canvas.crs, canvas.transform, canvas.dtype)
    if kind == "float32":
        case = warped_case(folder, name, grey, g, shape, dtype="float32", seed=seed,
                           target_radiometry=lambda v, r: v / 255.0 * 0.37 + 0.01)
    elif kind == "uint16-rot37":
        case = warped_case(folder, name, grey, g, shape, dtype="uint16", seed=seed,
                           target_radiometry=lambda v, r: v * 180.0 + 900.0)
    elif kind == "complex64":
        case = warped_case(folder, name, grey, g, shape, dtype="float32", seed=seed)
        _to_complex(case.target, rng)
    else:  # collar-rot25: rotated footprint inside a 0 fill without a nodata tag
        case = warped_case(folder, name, grey, g, shape, dtype="uint8", seed=seed)
        _strip_nodata(case.target)
    return Case(name, case.target, case.reference, case.truth, case.check_points, info=dict(case.info, kind=kind))


def _to_complex(path: str, rng) -> None:
    import rasterio

    with rasterio.open(path) as src:
        amp, prof = src.read(1), src.profile
    amp = np.nan_to_num(amp)
    phase = rng.uniform(-math.pi, math.pi, amp.shape)
    prof.update(dtype="complex64", nodata=None)
    with rasterio.open(path, "w", **prof) as dst:
        dst.write((amp * np.exp(1j * phase)).astype(np.complex64), 1)


def _strip_nodata(path: str) -> None:
    import rasterio

    with rasterio.open(path) as src:
        data, prof = src.read(), src.profile
    prof.update(nodata=None)
    with rasterio.open(path, "w", **prof) as dst:
        dst.write(data)
