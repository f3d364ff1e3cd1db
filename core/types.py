"""Small value objects passed between stages: keypoints, features and matches.

Coordinates are working pixels (corner convention, see :mod:`hamta.core.coords`) unless a name
says otherwise. An empty result is a valid zero-length object, never ``None``.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

METRICS = ("l2", "hamming")


@dataclass(frozen=True, eq=False)
class Keypoints:
    """Detected keypoints: ``xy`` (N, 2) working pixels, ``size`` diameter in pixels,
    ``angle`` in degrees (NaN when the detector assigns none), ``response`` (higher = stronger)."""

    xy: np.ndarray
    size: np.ndarray
    angle: np.ndarray
    response: np.ndarray

    def __len__(self) -> int:
        return len(self.xy)

    @classmethod
    def empty(cls) -> "Keypoints":
        return cls(np.zeros((0, 2)), np.zeros(0), np.zeros(0), np.zeros(0))

    def subset(self, index) -> "Keypoints":
        return Keypoints(self.xy[index], self.size[index], self.angle[index], self.response[index])


@dataclass(frozen=True, eq=False)
class Features:
    """Keypoints with one descriptor row each; ``metric`` says how descriptors are compared
    ('l2' for float vectors, 'hamming' for packed uint8 bit strings)."""

    keypoints: Keypoints
    descriptors: np.ndarray
    metric: str

    def __post_init__(self):
        if self.metric not in METRICS:
            raise ValueError(f"metric must be one of {METRICS}, got {self.metric!r}")
        if len(self.descriptors) != len(self.keypoints):
            raise ValueError("one descriptor per keypoint is required")

    def __len__(self) -> int:
        return len(self.keypoints)

    def subset(self, index) -> "Features":
        return Features(self.keypoints.subset(index), self.descriptors[index], self.metric)


@dataclass(frozen=True, eq=False)
class Matches:
    """Correspondences in working pixels: ``target_xy[i]`` <-> ``reference_xy[i]``.

    ``score`` ranks them (higher = more distinctive). ``n_target`` / ``n_reference`` count the
    keypoints the method started from (diagnostics only). ``diagnostics`` holds method-specific
    numbers for reports (plain JSON-able values).
    """

    target_xy: np.ndarray
    reference_xy: np.ndarray
    score: np.ndarray
    n_target: int = 0
    n_reference: int = 0
    diagnostics: Optional[dict] = None

    def __len__(self) -> int:
        return len(self.target_xy)

    @classmethod
    def empty(cls, n_target: int = 0, n_reference: int = 0) -> "Matches":
        return cls(np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0), n_target, n_reference)


@dataclass(frozen=True, eq=False)
class Correspondences:
    """Correspondences in full-resolution target and reference pixels, with a score each and whether
    the robust fit kept them (all False before any fit)."""

    target_px: np.ndarray
    reference_px: np.ndarray
    score: np.ndarray
    inlier: np.ndarray

    def __len__(self) -> int:
        return len(self.target_px)

    @classmethod
    def unfitted(cls, target_px, reference_px, score) -> "Correspondences":
        score = np.asarray(score, float)
        return cls(np.asarray(target_px, float).reshape(-1, 2), np.asarray(reference_px, float).reshape(-1, 2), score,
                   np.zeros(len(score), bool))

    @classmethod
    def from_matches(cls, matches: Matches, target, reference) -> "Correspondences":
        """Working-pixel ``matches`` as full-resolution pixels of each raster, through the working
        images' ``to_source`` maps."""
        if not len(matches):
            return cls.unfitted(np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0))
        return cls.unfitted(target.to_source.forward(matches.target_xy),
                            reference.to_source.forward(matches.reference_xy), matches.score)
