"""CFOG descriptor windows compared by normalised cross-correlation over all channels at once: the
matchers' own part of CFOG (the descriptor itself, shared with the independent check, is
:func:`hamta.core.similarity.cfog.cfog`).

Ye, Y., Bruzzone, L., Shan, J., Bovolo, F. & Zhu, Q. (2019). Fast and robust matching for
multimodal remote sensing image registration. IEEE TGRS 57(11):9059-9070.
:DOI:`10.1109/TGRS.2019.2924684`
"""
from __future__ import annotations

import cv2
import numpy as np


def ncc_surface(search: np.ndarray, template: np.ndarray) -> np.ndarray:
    """Normalised cross-correlation of a (C, h, w) ``template`` at every position in a (C, H, W)
    ``search`` stack, with one mean and one norm over all channels."""
    c, h, w = template.shape
    t = template - template.mean()
    tn = float(np.sqrt((t ** 2).sum()))
    num = sum(cv2.matchTemplate(search[k], t[k], cv2.TM_CCORR) for k in range(c))
    ones = np.ones((h, w), np.float32)
    s1 = cv2.matchTemplate(search.sum(axis=0), ones, cv2.TM_CCORR)
    s2 = cv2.matchTemplate((search ** 2).sum(axis=0), ones, cv2.TM_CCORR)
    var = np.maximum(s2 - s1 ** 2 / (c * h * w), 0.0)
    return num / np.maximum(np.sqrt(var) * tn, 1e-9)

