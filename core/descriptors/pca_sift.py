"""PCA-SIFT descriptors: normalised gradient patches projected on a learnt principal subspace.

Ke, Y., & Sukthankar, R. (2004). PCA-SIFT: a more distinctive representation for local image
descriptors. CVPR 2004, II-506-513. :DOI:`10.1109/CVPR.2004.1315206`

At each SIFT keypoint a 41 x 41 patch is sampled in the keypoint's orientation and scale (half a
keypoint sigma per patch pixel, smoothed to the keypoint's scale, as the Gaussian level it comes
from), horizontal and vertical gradients of the inner 39 x 39 pixels form a 3042-vector of unit
length, and its projection on the first 36 principal components of such vectors is the
descriptor (Euclidean distance). The basis shipped in ``data/pca_sift_basis.npz`` was learnt by
:func:`train_basis` from the public-domain Landsat sample of the development data (its three
bands, rotated and rescaled); ``hamta train-pca-sift`` rebuilds it.
"""
from __future__ import annotations

import os
from functools import lru_cache

import cv2
import numpy as np

from ..detectors.patches import patch_gradients, sample_patches
from .normalise import l2_normalise

PATCH_RADIUS = 20
N_COMPONENTS = 36
BASIS_PATH = os.path.join(os.path.dirname(__file__), "data", "pca_sift_basis.npz")


def gradient_vectors(image: np.ndarray, xy: np.ndarray, size: np.ndarray, angle_rad: np.ndarray) -> np.ndarray:
    """(K, 3042) unit-length gradient vectors of 41 x 41 oriented patches (float32)."""
    support = 5.0 * np.asarray(size, float)  # 20 patch pixels = 10 keypoint sigmas (size = 2 sigma)
    patches = sample_patches(image.astype(np.float32), xy, support, PATCH_RADIUS, 0, angle_rad=angle_rad,
                             smoothing=2.0)
    gx, gy = patch_gradients(patches)
    return l2_normalise(np.concatenate([gx.reshape(len(xy), -1), gy.reshape(len(xy), -1)], axis=1))


@lru_cache(maxsize=1)
def load_basis():
    with np.load(BASIS_PATH) as data:
        return data["mean"].astype(np.float32), data["components"].astype(np.float32)


def pca_sift_descriptors(image: np.ndarray, xy: np.ndarray, size: np.ndarray, angle_rad: np.ndarray) -> np.ndarray:
    """(K, 36) PCA-SIFT descriptors."""
    if len(xy) == 0:
        return np.zeros((0, N_COMPONENTS), np.float32)
    mean, components = load_basis()
    return (gradient_vectors(image, xy, size, angle_rad) - mean) @ components.T


def train_basis(paths, n_components: int = N_COMPONENTS, max_patches: int = 20000, seed: int = 0):
    """Learn (mean, components) from SIFT patches of every band of ``paths``, each also rotated by
    30 and 60 degrees and scaled by 0.7. Deterministic for a seed."""
    import rasterio

    from ..preprocess.normalize import stretch_to_uint8
    from .sift import OPENCV_SIFT_BIAS_PX, SiftDetector, keypoints_from_opencv

    vectors = []
    sift = SiftDetector(n_features=3000).create()
    for path in paths:
        with rasterio.open(path) as ds:
            bands, valid = ds.read().astype(np.float32), ds.read_masks(1) > 0
        for band in bands:
            base = stretch_to_uint8(band, valid)
            for angle, scale in ((0, 1.0), (30, 1.0), (60, 1.0), (0, 0.7)):
                h, w = base.shape
                m = cv2.getRotationMatrix2D((w / 2, h / 2), angle, scale)
                img = cv2.warpAffine(base, m, (w, h), flags=cv2.INTER_CUBIC)
                kps = sift.detect(img, None)
                kp = keypoints_from_opencv(kps, OPENCV_SIFT_BIAS_PX)
                vectors.append(gradient_vectors(img, kp.xy, kp.size, -np.radians(kp.angle)))
    data = np.concatenate(vectors)
    rng = np.random.default_rng(seed)
    if len(data) > max_patches:
        data = data[np.sort(rng.choice(len(data), max_patches, replace=False))]
    mean = data.mean(axis=0)
    centred = (data - mean).astype(np.float64)
    eigval, eigvec = np.linalg.eigh(centred.T @ centred)
    components = eigvec[:, ::-1][:, :n_components].T
    components *= np.sign(components[:, :1] + 1e-30)  # a fixed sign per component
    return mean.astype(np.float32), components.astype(np.float32), len(data)


def save_basis(path: str, mean, components, n_patches: int, sources) -> None:
    np.savez_compressed(path, mean=mean, components=components, n_patches=n_patches,
                        sources=np.array([os.path.basename(p) for p in sources]))
