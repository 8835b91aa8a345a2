"""Sensors: colliders that do not push, and report when a body begins and ends overlapping.

A body overlaps a sensor when the signed distance of its centre from the sensor's surface
(``engine.faces.signed_distance``, positive in free space) is less than its radius; for a Box,
whose free space is its room, when it is more than minus the radius (some of the ball is in
the room). It is measured where the bodies end each step.
A sensor's filter (engine.filters) says which bodies it senses.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .colliders import Box, Collider
from .faces import signed_distance

__all__ = ["sense"]


def sense(
    colliders: list[Collider],
    sensors: list[int],
    inside: np.ndarray,
    body_filters: tuple[np.ndarray, np.ndarray, np.ndarray] | None,
    x1: np.ndarray,
    dt: float,
    t0: float,
    radius: np.ndarray,
    began: list[Any],
    ended: list[Any],
) -> None:
    """Report bodies that began or ended overlapping each sensor in the step from t0 to
    t0 + dt, in ``began`` and ``ended`` (as the solvers' reports are kept: arrays of rows,
    colliders, points, normals, impulses, times), and update ``inside`` (N, sensors) bool,
    in place. ``sensors``: the sensors' places among ``colliders``; x1: where the bodies
    ended the step; ``body_filters``: the bodies' (group, categories, mask) arrays or None."""
    if not sensors:
        return
    for s, k in enumerate(sensors):
        c = colliders[k]
        d = signed_distance(c, x1)
        now = d > -radius if isinstance(c, Box) else d < radius
        bf = body_filters
        if bf is not None:
            f = c.filter  # a sensor senses only the bodies its filter meets
            now &= ((bf[1] & f.mask) != 0) & ((f.categories & bf[2]) != 0)
            now &= ~((bf[0] == f.group) & (bf[0] != 0))
        was = inside[:, s]
        for where, rows in (
            (began, np.flatnonzero(now & ~was)),
            (ended, np.flatnonzero(was & ~now)),
        ):
            if len(rows):
                pts, nrms = [], []
                for i in rows:
                    point, normal, _ = c.closest((float(x1[i, 0]), float(x1[i, 1])))
                    pts.append(tuple(point))
                    nrms.append(tuple(normal))
                where.append(
                    (
                        rows,
                        np.full(len(rows), k),
                        np.array(pts, float),
                        np.array(nrms, float),
                        np.zeros((len(rows), 2)),
                        np.full(len(rows), t0 + dt),
                    )
                )
        inside[:, s] = now
