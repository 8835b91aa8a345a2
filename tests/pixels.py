"""Pixel measurements the picture tests share: where a sprite is and which way it points."""

from __future__ import annotations

import math

import numpy as np


def long_axis(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray, float, float]:
    """Centroid (x, y) of a mask's pixels, the unit vector along their long axis pointing to
    the end that reaches further from the centroid, and how far (px) each end reaches."""
    xs, ys = np.nonzero(mask)
    assert len(xs) > 20, "no ant in the picture"
    points = np.stack([xs, ys], axis=1).astype(float)
    centroid = points.mean(axis=0)
    # The principal axis: the eigenvector of the covariance of the coordinates with the larger
    # eigenvalue (the direction along which the pixels spread most).
    values, vectors = np.linalg.eigh(np.cov((points - centroid).T))
    assert values[1] > 4 * values[0], "the pixels are not elongated: no long axis to measure"
    axis = vectors[:, 1]
    along = (points - centroid) @ axis
    if along.max() < -along.min():
        axis, along = -axis, -along
    return centroid, axis, float(along.max()), float(-along.min())


def angle_between(u: np.ndarray, v: np.ndarray) -> float:
    """Angle (degrees, 0 to 180) between two pixel directions."""
    cos = np.dot(u, v) / (np.linalg.norm(u) * np.linalg.norm(v))
    return math.degrees(math.acos(max(-1.0, min(1.0, float(cos)))))
