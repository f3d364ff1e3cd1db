"""Descriptor normalisation shared by every float descriptor."""
import numpy as np


def l2_normalise(desc: np.ndarray, clip: float = 0.0) -> np.ndarray:
    """Rows to unit L2 norm; with ``clip`` > 0 also Lowe's clipping and renormalisation (float32)."""
    desc = desc / np.maximum(np.linalg.norm(desc, axis=1, keepdims=True), 1e-12)
    if clip > 0:
        desc = np.minimum(desc, clip)
        desc = desc / np.maximum(np.linalg.norm(desc, axis=1, keepdims=True), 1e-12)
    return desc.astype(np.float32)
