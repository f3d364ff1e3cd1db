"""rBRIEF (steered BRIEF) descriptors at given keypoints, with the intensity-centroid angle.

Rublee, E., Rabaud, V., Konolige, K., & Bradski, G. (2011). ORB: an efficient alternative to SIFT
or SURF. ICCV 2011. :DOI:`10.1109/ICCV.2011.6126544`. Intensity centroid: Rosin (1999).

OpenCV's ``ORB.compute`` on keypoints from another detector has two traps (spec 001, section 6):
it reads ``KeyPoint.octave`` as a pyramid level (SIFT packs other data there), and it does not
recompute the orientation, steering the test pattern by whatever ``angle`` the keypoint carries.
Here every keypoint is handed to OpenCV with octave 0 and the intensity-centroid angle of the
paper's Eq. 4, ``atan2(m01, m10)`` over a disk of radius 15, computed in one vectorised pass.
"""
from __future__ import annotations

from typing import Tuple

import cv2
import numpy as np

ORB_PATCH = 31
ORB_BORDER = 31  # OpenCV's edgeThreshold for a 31-pixel patch


def intensity_centroid_angle(gray: np.ndarray, xy: np.ndarray, radius: int = 15) -> np.ndarray:
    """Angle in degrees (OpenCV's convention: image axes, y down, 0..360) of the intensity centroid
    of a disk of ``radius`` around each keypoint (corner-convention ``xy``, rounded to a pixel)."""
    h, w = gray.shape
    if len(xy) == 0 or min(h, w) < 2 * radius + 1:  # no full disk fits: ORB drops such keypoints anyway
        return np.zeros(len(xy))
    col = np.floor(xy[:, 0]).astype(int)
    row = np.floor(xy[:, 1]).astype(int)
    off = np.arange(-radius, radius + 1)
    dy, dx = np.meshgrid(off, off, indexing="ij")
    disk = dx ** 2 + dy ** 2 <= radius * radius
    # Near the border the disk is clamped (ORB drops those keypoints anyway: its border is 31 px).
    row = np.clip(row, radius, h - 1 - radius)
    col = np.clip(col, radius, w - 1 - radius)
    flat = (row * w + col)[:, None] + (dy[disk] * w + dx[disk])[None]
    vals = np.take(gray.ravel(), flat).astype(np.float32)
    m10 = vals @ dx[disk].astype(np.float32)
    m01 = vals @ dy[disk].astype(np.float32)
    return np.degrees(np.arctan2(m01, m10)) % 360.0


def rbrief_descriptors(gray: np.ndarray, xy: np.ndarray, angle_deg: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """256-bit rBRIEF descriptors (OpenCV's learned pattern, 31 x 31 patch) of ``gray`` (uint8).

    Returns
    -------
    index : (M,) int
        Which keypoints kept a descriptor (OpenCV drops those within 31 px of the border).
    descriptors : (M, 32) uint8
    """
    kps = [cv2.KeyPoint(float(x - 0.5), float(y - 0.5), float(ORB_PATCH), float(a), 0.0, 0, i)
           for i, ((x, y), a) in enumerate(zip(xy, angle_deg))]
    orb = cv2.ORB_create(edgeThreshold=ORB_BORDER, patchSize=ORB_PATCH)
    kept, desc = orb.compute(gray, kps)
    if desc is None or len(kept) == 0:
        return np.zeros(0, int), np.zeros((0, 32), np.uint8)
    return np.array([k.class_id for k in kept], int), desc
