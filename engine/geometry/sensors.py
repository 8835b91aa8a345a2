"""Sensors: colliders that do not push, and report when a body begins and ends overlapping.

A body overlaps a sensor when the signed distance of its centre from the sensor's surface
(``engine.geometry.faces.signed_distance``, positive in free space) is less than its radius; for a
Box, whose free space is its room, when it is more than minus the radius (some of the ball is in
the room). For a body with a shape other than a disc (a box, a polygon, a capsule) that
radius is only its bounding circle's: such a body found near a sensor is then tested by its
shape, turned by its angle (the narrowphase of ``engine.geometry.manifold`` with no margin: it
overlaps where the two surfaces have a point of negative separation), so a coin beside a
player's box, within its bounding circle but clear of its corners, is not collected. It is
measured where the bodies end each step.
A sensor's filter (engine.filters) says which bodies it senses.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .colliders import Box, Collider
from .faces import signed_distance
from .manifold import Kind, collide, static_shapes
from .shaped import ShapeTable

__all__ = ["sense", "shape_overlaps"]


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
    shapes: ShapeTable | None = None,
    angle: np.ndarray | None = None,
) -> None:
    """Report bodies that began or ended overlapping each sensor in the step from t0 to
    t0 + dt, in ``began`` and ``ended`` (as the solvers' reports are kept: arrays of rows,
    colliders, points, normals, impulses, times), and update ``inside`` (N, sensors) bool,
    in place. ``sensors``: the sensors' places among ``colliders``; x1: where the bodies
    ended the step; ``body_filters``: the bodies' (group, categories, mask) arrays or None;
    ``shapes`` and ``angle``: the bodies' shapes by row (engine.geometry.shaped) and angles (rad) at
    x1, for the shaped bodies' test by their shape (None: every body is taken as its bounding
    circle)."""
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
        if shapes is not None and not isinstance(c, Box):
            for i in np.flatnonzero(now & shapes.shaped).tolist():
                q = 0.0 if angle is None else float(angle[i])
                now[i] = shape_overlaps(shapes.kinds(np.array([i])), x1[i], q, c)
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


def shape_overlaps(body: Kind, x: np.ndarray, angle: float, sensor: Collider) -> bool:
    """Whether a body's shape (``body``, one row) at ``x`` turned by ``angle`` (rad) overlaps
    ``sensor`` (not a Box): some point of their manifold, made with no margin, has a negative
    separation."""
    X, Q = np.asarray(x, dtype=float).reshape(1, 2), np.array([angle])
    for kind, _ in static_shapes([sensor]).kinds():  # (one kind, one row: not a Box)
        m = collide(body, X, Q, kind, (0.0, 0.0), 0.0, 0.0)
        n = int(m.count[0])
        if n and float(m.separation[0, :n].min()) < 0.0:
            return True
    return False
