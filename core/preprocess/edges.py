"""Edge images for detectors that look at structure rather than brightness."""
from __future__ import annotations

import cv2
import numpy as np


def sobel_edge_image(gray: np.ndarray, threshold: float) -> np.ndarray:
    """Sobel gradient magnitude ``0.5 |Gx| + 0.5 |Gy|`` (3 x 3 kernels, uint8 as OpenCV's Sobel
    tutorial computes it), with values not above ``threshold`` set to zero (threshold-to-zero:
    strong edges keep their magnitude)."""
    gx = cv2.convertScaleAbs(cv2.Sobel(gray, cv2.CV_16S, 1, 0, ksize=3))
    gy = cv2.convertScaleAbs(cv2.Sobel(gray, cv2.CV_16S, 0, 1, ksize=3))
    grad = cv2.addWeighted(gx, 0.5, gy, 0.5, 0)
    _, edge = cv2.threshold(grad, float(threshold), 255, cv2.THRESH_TOZERO)
    return edge
