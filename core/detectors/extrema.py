"""Local extrema over 3 x 3 x 3 (x, y, scale) neighbourhoods of a stack of response layers."""
from __future__ import annotations

import cv2
import numpy as np

_KERNEL = np.ones((3, 3), np.uint8)


def scale_space_extrema(stack: np.ndarray, threshold: float, *, end_layers: bool, valid=None, border: int = 0):
    """(layer, row, col) of every point >= its 26 neighbours and > ``threshold``, or <= them and
    < -``threshold``.

    Parameters
    ----------
    stack : (L, H, W) float32 responses.
    end_layers : bool
        Also search the first and last layer, comparing them with their one neighbour layer
        (CenSurE); otherwise only layers 1 .. L-2 (Lowe's DoG).
    valid : (H, W) bool, optional
        Where extrema may lie.
    border : int
        Pixels at the image edge that are never returned.
    """
    stack = np.ascontiguousarray(stack, dtype=np.float32)
    n = len(stack)
    big = [cv2.dilate(s, _KERNEL, borderType=cv2.BORDER_REPLICATE) for s in stack]
    small = [cv2.erode(s, _KERNEL, borderType=cv2.BORDER_REPLICATE) for s in stack]
    allowed = np.ones(stack.shape[1:], np.uint8) if valid is None else valid.astype(np.uint8)
    if border > 0:
        allowed = allowed.copy()
        allowed[:border] = allowed[-border:] = 0
        allowed[:, :border] = allowed[:, -border:] = 0
    layers = range(n) if end_layers else range(1, n - 1)
    out_l, out_r, out_c = [], [], []
    for k in layers:
        lo, hi = max(k - 1, 0), min(k + 1, n - 1)
        mx, mn = big[lo], small[lo]
        for j in range(lo + 1, hi + 1):
            mx, mn = cv2.max(mx, big[j]), cv2.min(mn, small[j])
        s = stack[k]
        peak = cv2.compare(s, mx, cv2.CMP_GE) & cv2.compare(s, float(threshold), cv2.CMP_GT)
        pit = cv2.compare(s, mn, cv2.CMP_LE) & cv2.compare(s, -float(threshold), cv2.CMP_LT)
        hits = cv2.findNonZero((peak | pit) & allowed)
        if hits is not None:
            xy = hits.reshape(-1, 2)
            out_l.append(np.full(len(xy), k))
            out_c.append(xy[:, 0])
            out_r.append(xy[:, 1])
    if not out_l:
        z = np.zeros(0, np.int64)
        return z, z, z
    layer, row, col = (np.concatenate(a).astype(np.int64) for a in (out_l, out_r, out_c))
    order = np.lexsort((col, row, layer))
    return layer[order], row[order], col[order]
