"""ORB keypoints and rBRIEF descriptors through OpenCV.

Rublee, E., Rabaud, V., Konolige, K., & Bradski, G. (2011). ORB: an efficient alternative to SIFT
or SURF. ICCV 2011, 2564-2571. :DOI:`10.1109/ICCV.2011.6126544`

Notes
-----
OpenCV detects ORB keypoints on pyramid levels of ``round(W / 1.2**l)`` pixels but maps them back
with the nominal factor ``1.2**l`` and without the half-pixel shift between level and image
grids, which misplaces keypoints by up to a pixel on coarse levels (measured here with OpenCV 4.6
and 5.0: up to 0.84 px on level 6 under a 180-degree rotation). :func:`orb_positions` places
each keypoint exactly on the level grid it was detected on.
"""
from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

from ..types import Features, Keypoints


@dataclass(frozen=True)
class OrbDetector:
    """OpenCV ORB settings (defaults: OpenCV's, with more features for remote-sensing scenes)."""

    n_features: int = 8000
    scale_factor: float = 1.2
    n_levels: int = 8
    edge_threshold: int = 31
    fast_threshold: int = 20
    harris_score: bool = True

    def create(self):
        score = cv2.ORB_HARRIS_SCORE if self.harris_score else cv2.ORB_FAST_SCORE
        return cv2.ORB_create(nfeatures=self.n_features, scaleFactor=self.scale_factor, nlevels=self.n_levels,
                              edgeThreshold=self.edge_threshold, patchSize=31, fastThreshold=self.fast_threshold,
                              scoreType=score)


def orb_positions(kps, image_shape, scale_factor: float) -> np.ndarray:
    """Corner-convention positions of OpenCV ORB keypoints on their own pyramid-level grids."""
    h, w = image_shape
    octave = np.array([k.octave for k in kps], int)
    nominal = scale_factor ** octave.astype(float)
    level_w = np.rint(w / nominal)
    level_h = np.rint(h / nominal)
    level_px = cv2.KeyPoint_convert(kps).astype(np.float64) / nominal[:, None]
    return (level_px + 0.5) * np.column_stack([w / level_w, h / level_h])


def orb_features(image: np.ndarray, mask: np.ndarray, detector: OrbDetector = OrbDetector()) -> Features:
    """Detect ORB keypoints and compute 256-bit rBRIEF descriptors (Hamming metric).

    Parameters
    ----------
    image : (H, W) uint8, working pixels.
    mask : (H, W) uint8, 255 where keypoints may be detected.
    """
    kps, desc = detector.create().detectAndCompute(image, mask)
    if desc is None or len(kps) == 0:
        return Features(Keypoints.empty(), np.zeros((0, 32), np.uint8), "hamming")
    xy = orb_positions(kps, image.shape, detector.scale_factor)
    kp = Keypoints(xy, np.array([k.size for k in kps], float), np.array([k.angle for k in kps], float),
                   np.array([k.response for k in kps], float))
    return Features(kp, desc, "hamming")
