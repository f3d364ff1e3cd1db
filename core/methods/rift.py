"""RIFT2: the published rotation-invariant multimodal matcher, as a baseline for ``xmodal``.

Li, J., Hu, Q., & Ai, M. (2020). RIFT: multi-modal image matching based on radiation-variation
insensitive feature transform. IEEE TIP 29, 3296-3310. :DOI:`10.1109/TIP.2019.2959244`
Li, J., Shi, P., Hu, Q., & Zhang, Y. (2023). RIFT2: speeding-up RIFT with a new rotation-invariance
technique. arXiv:2303.00319.

Phase-congruency maps (4 scales, 6 orientations, RIFT's parameters), FAST corners on the maximum
moment, RIFT2 orientations and rotation-invariant MIM descriptors
(:mod:`hamta.core.descriptors.rift`), nearest-neighbour matching without a ratio test (RIFT's demo:
``matchFeatures`` with ``MaxRatio`` 1), one match per reference point, then the shared robust fit
(2 px, as RIFT's FSC). Not scale-invariant, as published. Deviations, neutral or in its favour:
keypoints in invalid pixels (a rotated image's fill) are ignored, and the robust fit is seeded.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..descriptors import rift
from ..progress import Monitor
from ..types import Matches
from .registry import Method, param, register_method, validate


@dataclass(frozen=True)
class RiftParams:
    """RIFT2 as published."""

    points: int = param(5000, "Strongest FAST corners kept per image (RIFT: 5000).", minimum=10)

    def __post_init__(self):
        validate(self)


def match(target, reference, params: RiftParams, monitor: Monitor, seed: int = 0) -> Matches:
    ft = rift.rotated_features(target.data, target.valid, params.points)
    monitor.report(0.45, "RIFT features")
    fr = rift.rotated_features(reference.data, reference.valid, params.points)
    monitor.report(0.9, "RIFT features")
    if len(ft) < 3 or len(fr) < 3:
        return Matches.empty(len(ft), len(fr))
    td, rd = ft.descriptors, fr.descriptors
    d2 = np.maximum((td ** 2).sum(1)[:, None] + (rd ** 2).sum(1)[None] - 2 * td @ rd.T, 0)
    j = d2.argmin(axis=1)
    dist = np.sqrt(d2[np.arange(len(j)), j])
    order = np.argsort(dist, kind="stable")
    _, first = np.unique(j[order], return_index=True)
    keep = order[first]
    monitor.report(1.0, "matching")
    return Matches(ft.keypoints.xy[keep], fr.keypoints.xy[j[keep]], 1.0 - dist[keep], len(ft), len(fr))


METHOD = register_method(Method(
    name="rift", title="RIFT2 (published multimodal matcher, baseline)",
    summary="Phase-congruency corners with rotation-invariant maximum-index-map descriptors, nearest-neighbour "
            "matching, robust fit. The field's reference for multimodal pairs at any rotation (not scale).",
    citation="Li, Hu & Ai 2020, IEEE TIP 29:3296; Li et al. 2023, arXiv:2303.00319", params_type=RiftParams,
    match=match, kind="baseline", ransac_threshold_px=2.0))
