"""SIFT keypoints and descriptors through OpenCV.

Lowe, D. G. (2004). Distinctive image features from scale-invariant keypoints. International
Journal of Computer Vision, 60(2), 91-110. :DOI:`10.1023/B:VISI.0000029664.99615.94`

Notes
-----
OpenCV builds its scale space on the input upsampled x2 with pixel-centre-aligned bilinear
interpolation, then halves coordinates as if the upsampling were corner-aligned. Every keypoint
it returns is therefore 0.25 px right of and below its true position (measured here on OpenCV 4.6
and 5.0 with a 180-degree rotation, where the bias doubles to 0.5 px). :func:`sift_features`
removes it, so keypoints are unbiased in the corner convention.
"""
from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

from ..coords import opencv_to_corner
from ..types import Features, Keypoints

OPENCV_SIFT_BIAS_PX = 0.25


@dataclass(frozen=True)
class SiftDetector:
    """OpenCV SIFT settings.

    Attributes
    ----------
    n_features : int
        Keep the strongest n keypoints (0 keeps all). Default 8000 bounds matching time on
        4-Mpx working images.
    contrast_threshold, edge_threshold, sigma, n_octave_layers
        Lowe's settings as OpenCV names them; defaults are OpenCV's (Lowe 2004).
    """

    n_features: int = 8000
    contrast_threshold: float = 0.04
    edge_threshold: float = 10.0
    sigma: float = 1.6
    n_octave_layers: int = 3

    def create(self):
        return cv2.SIFT_create(nfeatures=self.n_features, nOctaveLayers=self.n_octave_layers,
                               contrastThreshold=self.contrast_threshold,
                               edgeThreshold=self.edge_threshold, sigma=self.sigma)


def keypoints_from_opencv(kps, bias_px: float = 0.0) -> Keypoints:
    """Convert OpenCV keypoints to :class:`Keypoints` in corner-convention pixels."""
    if len(kps) == 0:
        return Keypoints.empty()
    xy = opencv_to_corner(cv2.KeyPoint_convert(kps).astype(np.float64)) - bias_px
    size = np.array([k.size for k in kps], np.float64)
    angle = np.array([k.angle if k.angle >= 0 else np.nan for k in kps], np.float64)
    response = np.array([k.response for k in kps], np.float64)
    return Keypoints(xy, size, angle, response)


def sift_keypoints(image: np.ndarray, mask=None, detector: SiftDetector = SiftDetector()) -> Keypoints:
    """OpenCV SIFT detection only, with OpenCV's 0.25-px bias removed (corner convention)."""
    return keypoints_from_opencv(detector.create().detect(image, mask), OPENCV_SIFT_BIAS_PX)


def sift_features(image: np.ndarray, mask: np.ndarray, detector: SiftDetector = SiftDetector()) -> Features:
    """Detect and describe SIFT keypoints on an 8-bit image.

    Parameters
    ----------
    image : (H, W) uint8, working pixels.
    mask : (H, W) uint8, 255 where keypoints may be detected.

    Returns
    -------
    Features
        128-D float32 descriptors compared with the L2 metric.
    """
    kps, desc = detector.create().detectAndCompute(image, mask)
    if desc is None or len(kps) == 0:
        return Features(Keypoints.empty(), np.zeros((0, 128), np.float32), "l2")
    return Features(keypoints_from_opencv(kps, OPENCV_SIFT_BIAS_PX), desc, "l2")


def sift_descriptors(image: np.ndarray, xy: np.ndarray, support_radius: np.ndarray,
                     angle_rad: np.ndarray) -> np.ndarray:
    """OpenCV SIFT descriptors at given keypoints (no detection, no orientation assignment).

    Parameters
    ----------
    image : (H, W) uint8.
    xy : (K, 2) corner-convention positions.
    support_radius : (K,) half-width of the 4 x 4 descriptor grid in pixels. OpenCV's cells are
        3 x (size / 2) wide, so the grid's half-width is 3 x size and size = radius / 3.
    angle_rad : (K,) orientation, counter-clockwise as displayed (OpenCV's angle is clockwise).

    Returns
    -------
    (K, 128) float32, in the order of ``xy`` (keypoints OpenCV drops get a zero row).
    """
    k = len(xy)
    if k == 0:
        return np.zeros((0, 128), np.float32)
    cv = xy - 0.5
    kps = [cv2.KeyPoint(float(x), float(y), float(r / 3.0), float(np.degrees(-a) % 360.0), 1.0, 0, i)
           for i, ((x, y), r, a) in enumerate(zip(cv, support_radius, angle_rad))]
    kept, desc = SiftDetector().create().compute(image, kps)
    out = np.zeros((k, 128), np.float32)
    if desc is not None and len(kept):
        out[[kp.class_id for kp in kept]] = desc
    return out
