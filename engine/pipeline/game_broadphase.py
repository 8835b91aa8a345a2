"""Which pairs a game's step tests: the soft step's broadphase, on the numpy path.

engine.pipeline.game_step finds a step's contacts in stages; the first is this module's, on numpy
(the fast path's ``engine.pipeline.game_contacts.contacts_loop`` does the same in its compiled loop,
with the same products, so both paths meet the same pairs in the same order):

* ``collider_arrays``: what the stages read of the colliders (materials, filters, sensors),
  read once until a collider comes, goes or has a material set;
* ``pairs``: of the candidate pairs of bodies (every pair, or a grid's: engine.pipeline.game_step),
  those whose bounding circles and then boxes (``boxes``) come within what the two can move
  in the step, one of them awake and pushed by contacts, neither a sensor, their filters
  passed, not kept apart (``apart_keys``: a joint's, a pre_solve's);
* ``faces``: each body against each static shape whose box (``static_bounds``) its reach
  toward static shapes overlaps (``struck``: its own, grown by what its pairs' partners can
  strike it with), filtered likewise (``ignored_keys``: the faces a pre_solve ignored).
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from ..geometry.colliders import Collider
from ..geometry.manifold import StaticShapes
from ..geometry.manifold_kinds import SPECULATIVE_DISTANCE
from ..geometry.narrowphase import Places

#: The World's state (engine.pipeline.world_state.WorldState), named by what is read of it.
WorldState = Any

__all__ = [
    "BoxRows",
    "Colliders",
    "allowed",
    "box_rows",
    "apart_keys",
    "boxes",
    "collider_arrays",
    "columns",
    "face_filters",
    "faces",
    "filters_meet",
    "ignored_keys",
    "in_sorted",
    "pairs",
    "reaching",
    "static_bounds",
    "struck",
]


class Colliders(NamedTuple):
    """What the stages read of the World's colliders, each an array by collider place, read
    once a step (materials, filters and sensors may change between steps). The materials are
    the rows of ``floats`` (2, K) and the filters those of ``ints`` (3, K): the fast path's
    step takes the two tables, two arguments where the five arrays were five."""

    sensor: np.ndarray
    serial: np.ndarray
    restitution: np.ndarray
    friction: np.ndarray
    surface: np.ndarray  # (K, 2) surface velocity (m/s)
    group: np.ndarray
    categories: np.ndarray
    mask: np.ndarray
    floats: np.ndarray  # (2, K): restitution, friction
    ints: np.ndarray  # (3, K): group, categories, mask


def collider_arrays(colliders: list[Collider], serial: Any) -> Colliders:
    """The colliders' arrays (``serial``: the World's serial number of a collider)."""

    def col(values: list[Any], dtype: Any) -> np.ndarray:
        return np.array(values, dtype=dtype)

    floats = col([[c.restitution for c in colliders], [c.friction for c in colliders]], float)
    ints = col(
        [[c.filter.group for c in colliders], [c.filter.categories for c in colliders],
         [c.filter.mask for c in colliders]],
        np.int64,
    ).reshape(3, -1)  # fmt: skip
    floats = floats.reshape(2, -1)
    return Colliders(
        col([c.sensor for c in colliders], bool),
        col([serial(c) for c in colliders], np.int64),
        floats[0],
        floats[1],
        col([tuple(c.surface_velocity) for c in colliders], float).reshape(-1, 2),
        ints[0],
        ints[1],
        ints[2],
        floats,
        ints,
    )


def static_bounds(shapes: StaticShapes) -> tuple[np.ndarray, np.ndarray]:
    """Each static shape's collider place and bounding box (K, 4), in the order
    ``collide_pairs`` takes them (half planes, circles, capsules, polygons)."""
    owners, boxes = [], []
    for _kind, own in shapes.kinds():
        if own is shapes.half_plane_owner:
            box = np.tile([-np.inf, -np.inf, np.inf, np.inf], (len(own), 1))
        elif own is shapes.circle_owner:
            c, r = shapes.circles.center, shapes.circles.radius[:, None]
            box = np.concatenate([c - r, c + r], axis=1)
        elif own is shapes.capsule_owner:
            cap = shapes.capsules
            r = cap.radius[:, None]
            box = np.concatenate([np.minimum(cap.a, cap.b) - r, np.maximum(cap.a, cap.b) + r], 1)
        else:
            p = shapes.polygons
            r = p.radius[:, None]
            box = np.concatenate([p.vertices.min(axis=1) - r, p.vertices.max(axis=1) + r], 1)
        owners.append(own)
        boxes.append(box)
    if not owners:
        return np.zeros(0, dtype=np.intp), np.zeros((0, 4))
    return np.concatenate(owners), np.concatenate(boxes)


def apart_keys(state: WorldState, ignored: np.ndarray) -> np.ndarray:
    """The pairs of bodies kept apart, as sorted keys a n + b of rows a < b: by a pre_solve
    (``ignored``, such keys) or by a joint that does not let its bodies collide (the World's
    ``joint_apart``, found again whenever the bodies or the links change)."""
    joints = state.joint_apart
    if not len(ignored):
        return joints
    return np.union1d(joints, np.asarray(ignored, dtype=np.int64))


#: No keys (what ``ignored_keys`` gives on most steps; empty, so nothing can write to it).
_NO_KEYS = np.zeros(0, dtype=np.int64)


def ignored_keys(ignored: np.ndarray, colliders: int) -> np.ndarray:
    """The faces pre_solve ignored ((K, 2) of body row, collider place) as sorted keys
    row (colliders + 1) + place."""
    if not len(ignored):
        return _NO_KEYS
    k = colliders + 1
    return np.unique(np.asarray(ignored[:, 0], dtype=np.int64) * k + ignored[:, 1])


def in_sorted(keys: np.ndarray, sorted_keys: np.ndarray) -> np.ndarray:
    """Which of ``keys`` are in ``sorted_keys`` (sorted ascending; bool, one a key): each key's
    place in them by a binary search, and whether the key there is it (a place past the end
    clipped to the last). ``np.isin``'s answer, in a few calls where np.isin's Python body
    costs about 30 us on a game's dozen keys."""
    if not len(sorted_keys):
        return np.zeros(len(keys), dtype=bool)
    at = np.searchsorted(sorted_keys, keys)
    return sorted_keys.take(at, mode="clip") == keys


def columns(*cols: np.ndarray) -> np.ndarray:
    """The 1D arrays ``cols`` (k each) as the columns of one (k, len(cols)) C-contiguous array:
    ``np.stack(cols, axis=1)``'s, without np.stack's checks (a few microseconds a call on a
    game's arrays of a dozen)."""
    out = np.empty((len(cols[0]), len(cols)), dtype=np.result_type(*cols))
    for j, col in enumerate(cols):
        out[:, j] = col
    return out


def reaching(
    store: Any,
    margin: np.ndarray,
    boxes: np.ndarray | None,
    a: np.ndarray,
    b: np.ndarray,
    unit: float = 1.0,
) -> np.ndarray:
    """Which pairs of bodies (rows ``a``, ``b``) may come within the speculative distance of
    each other in the step (bool, one a pair): their bounding circles (``store.radius`` about
    ``store.x``) and then their ``boxes`` ((N, 4) xmin, ymin, xmax, ymax: ``boxes``; None:
    the circles alone), each grown by what the two can move in the step (``margin``, m).
    Each test holds whenever the shapes can touch (a shape is inside its circle and its box),
    so together they keep no fewer pairs than need to be. ``unit``: the World's length units
    a metre (its ``length_units_per_meter``), which the speculative distance is scaled by."""
    x, r = store.x, store.radius
    speculative = SPECULATIVE_DISTANCE * unit
    # (A table's rows by index as ndarray.take(rows, axis=0): indexing's answer, at a third
    # of its cost on a game's few rows; a 1D array's indexing is the faster.)
    d = x.take(b, axis=0) - x.take(a, axis=0)
    reach = r[a] + r[b] + margin[a] + margin[b] + speculative
    near = d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1] <= reach * reach
    if boxes is not None:
        rows = near.nonzero()[0]  # (np.flatnonzero's answer, without its Python wrapper)
        a, b = a[rows], b[rows]
        gap = margin[a] + margin[b] + speculative
        ba, bb = boxes.take(a, axis=0), boxes.take(b, axis=0)
        close = (bb[:, 0] - ba[:, 2] <= gap) & (ba[:, 0] - bb[:, 2] <= gap)
        close &= (bb[:, 1] - ba[:, 3] <= gap) & (ba[:, 1] - bb[:, 3] <= gap)
        near[rows] = close
    return near


def filters_meet(store: Any, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Which pairs of bodies (rows ``a``, ``b``) their filters let collide (bool, one a pair:
    engine.filters; a sensor's filter meets nothing)."""
    g = store.group
    keep = (g[a] == 0) | (g[a] != g[b])
    keep &= ((store.categories[a] & store.mask[b]) != 0) & (
        (store.categories[b] & store.mask[a]) != 0
    )
    return keep


def allowed(
    store: Any, sensors: np.ndarray, a: np.ndarray, b: np.ndarray, apart: np.ndarray
) -> np.ndarray:
    """Which pairs of bodies (rows ``a`` < ``b``) the broadphase may keep whatever their
    motion (bool, one a pair): neither a sensor, not two points (no radius, no shape: they
    pass, as on the exact step), their filters passed, not ``apart`` (sorted keys a n + b).
    What ``pairs`` asks of the bodies' filters and shapes, which change only when the World
    does (engine.pipeline.game_step keeps it)."""
    r = store.radius
    keep = ~sensors[a] & ~sensors[b]
    keep &= r[a] + r[b] > 0.0
    keep &= filters_meet(store, a, b)
    if len(apart):
        keep &= ~in_sorted(a * len(store) + b, apart)
    return keep


def pairs(
    store: Any,
    sensors: np.ndarray,
    moving: np.ndarray,
    margin: np.ndarray,
    candidates: tuple[np.ndarray, np.ndarray],
    apart: np.ndarray,
    boxes: np.ndarray | None = None,
    kept: np.ndarray | None = None,
    unit: float = 1.0,
) -> np.ndarray:
    """The pairs of bodies (rows a < b, (K, 2)) among ``candidates`` that may touch in the
    step: bounding circles, and ``boxes`` (``boxes``; None: not tested), within both bodies'
    reach and the speculative distance, the
    filters passed, one of them ``moving`` (pushed by contacts: dynamic and awake), neither a
    sensor, not ``apart``; ``kept``: ``allowed``'s answer for the candidates where the
    caller has kept it (None: asked here); ``unit``: ``reaching``'s."""
    a, b = candidates
    if kept is None:
        # (Many candidates, a grid's, new each step: the reach first, which leaves few.)
        near = reaching(store, margin, boxes, a, b, unit)
        a, b = a[near], b[near]
        keep = (moving[a] | moving[b]) & allowed(store, sensors, a, b, apart)
        return columns(a[keep], b[keep])
    # (Each test is one bool a pair, and a pair is kept where all hold: the pairs ``kept``
    # and moving are taken first, so the reach is measured for fewer.)
    may = kept & (moving[a] | moving[b])
    a, b = a[may], b[may]
    near = reaching(store, margin, boxes, a, b, unit)
    return columns(a[near], b[near])


def struck(margin: np.ndarray, pairs: np.ndarray) -> np.ndarray:
    """How far each body can move toward a static shape in the step (m): its own reach
    (``margin``), or, where it is one of ``pairs`` (rows, (K, 2)), its reach and twice the
    farthest partner's. A body at rest that a partner strikes within the step moves beyond
    its own reach: a body of speed u striking one at rest gives it (1 + e) m_b / (m_a + m_b) u,
    less than 2 u, so a box at rest 3.7 cm from a wall, struck by a disc at 19.7 m/s, has a row
    with the wall before it is struck, which stops it there (tests/test_fuzz_shapes.py's find
    12: it moved 0.146 m, 0.114 m into the wall, where a row did not hold it). The products of
    engine.pipeline.game_contacts.contacts_loop's own, so both paths meet the same shapes."""
    out = margin.copy()
    if len(pairs):
        a, b = pairs[:, 0], pairs[:, 1]
        np.maximum.at(out, a, margin[a] + 2.0 * margin[b])
        np.maximum.at(out, b, margin[b] + 2.0 * margin[a])
    return out


class BoxRows(NamedTuple):
    """What ``boxes`` reads of the shapes, but the bodies' poses: the rows of the bodies whose
    box is turned corners (a polygon's, a capsule's: ``rows``), their corners' x and y in the
    body's frame ((k, M) each, padded by repeating the last corner), their rounding
    (``grow``, (k,)); and the rows of several shapes (``several``, engine.body_shapes)."""

    rows: np.ndarray
    vx: np.ndarray
    vy: np.ndarray
    grow: np.ndarray
    several: list[int]


def box_rows(places: Places, parts: Any = None) -> BoxRows:
    """``boxes``' ``BoxRows`` of the shapes' ``places`` (and ``parts``: ``boxes``')."""
    several = None if parts is None else parts[0].size != 1
    round_ = places.body_circle if several is None else places.body_circle | several
    rows = np.flatnonzero(~round_)
    t = places.tables
    j = places.body_index[rows]
    if len(rows):
        v = t.vertices[j]
        vx, vy, grow = v[:, :, 0].copy(), v[:, :, 1].copy(), t.radius[j]
    else:
        vx = vy = np.zeros((0, 1))
        grow = np.zeros(0)
    many = [] if several is None else np.flatnonzero(several).tolist()
    return BoxRows(rows, vx, vy, grow, many)


def boxes(places: Places, store: Any, parts: Any = None, kept: BoxRows | None = None) -> np.ndarray:
    """Each body's box (N, 4: xmin, ymin, xmax, ymax): a disc's centre +- its radius, a
    polygon's (a capsule's) corners turned and moved +- its radius; the products of
    engine.pipeline.game_contacts' own, in its order. Where a body is of several shapes
    (engine.body_shapes), ``parts``: (engine.geometry.shaped.Parts, their Places), and such a
    body's box is its parts' boxes' (``part_boxes``). ``kept``: ``box_rows`` of the places
    and parts where the caller has kept it (None: read here)."""
    x, q, r = store.x, store.angle, store.radius
    rr = r[:, None]
    box = np.empty((len(x), 4))
    box[:, 0:2] = x - rr
    box[:, 2:4] = x + rr
    rows, vx, vy, grow, several = box_rows(places, parts) if kept is None else kept
    if len(rows):
        c, s = np.cos(q[rows])[:, None], np.sin(q[rows])[:, None]
        at = x.take(rows, axis=0)  # (``reaching``'s note on take)
        # The corners in the world, x then y ((2, k, M)): each row's least and greatest
        # x and y in two reductions where four were.
        w = np.empty((2, *vx.shape))
        w[0] = c * vx - s * vy + at[:, 0:1]
        w[1] = s * vx + c * vy + at[:, 1:2]
        box[rows, 0:2] = (w.min(axis=2) - grow).T
        box[rows, 2:4] = (w.max(axis=2) + grow).T
    for a in several:
        box[a] = part_boxes(parts[0], parts[1], store, a)
    return box


def part_boxes(parts: Any, places: Places, store: Any, a: int) -> tuple[float, ...]:
    """The box of body a of several shapes (engine.body_shapes; ``parts`` its
    engine.geometry.shaped.Parts, ``places`` theirs): the least and greatest of its parts'
    corners (a round part's centre) turned and moved to its pose, each part's +- its rounding;
    engine.pipeline.game_contacts.body_boxes' products, in its order."""
    t = places.tables
    x, y, angle = float(store.x[a, 0]), float(store.x[a, 1]), float(store.angle[a])
    co, si = np.cos(angle), np.sin(angle)
    out = [0.0, 0.0, 0.0, 0.0]
    start = int(parts.first[a])
    for u in range(int(parts.size[a])):
        j = int(places.body_index[start + u])
        if places.body_circle[start + u]:
            cx, cy = t.center[j]
            wx, wy = co * cx - si * cy + x, si * cx + co * cy + y
            r = t.round[j]
            lox, loy, hix, hiy = wx - r, wy - r, wx + r, wy + r
        else:
            v = t.vertices[j]
            wx_ = co * v[:, 0] - si * v[:, 1] + x
            wy_ = si * v[:, 0] + co * v[:, 1] + y
            g = t.radius[j]
            lox, loy = wx_.min() - g, wy_.min() - g
            hix, hiy = wx_.max() + g, wy_.max() + g
        if u == 0:
            out = [lox, loy, hix, hiy]
        else:
            out = [min(out[0], lox), min(out[1], loy), max(out[2], hix), max(out[3], hiy)]
    return tuple(float(c) for c in out)


def face_filters(
    store: Any, cs: Colliders, owner: np.ndarray, sensors: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """What ``faces`` asks of each body and static shape whatever their motion: whether the
    two may meet ((N, K) bool: no sensor body, the filters passed), and which shapes are a
    sensor collider's ((K,) bool: such a shape meets a body at rest too). These change only
    when the World's bodies, filters or colliders do (engine.pipeline.game_step keeps them)."""
    g = store.group[:, None]
    cats, mask = store.categories[:, None], store.mask[:, None]
    meet = ~sensors[:, None] & ((g == 0) | (g != cs.group[owner]))
    meet &= ((cats & cs.mask[owner]) != 0) & ((cs.categories[owner] & mask) != 0)
    return meet, cs.sensor[owner]


def faces(
    store: Any,
    cs: Colliders,
    owner: np.ndarray,
    bounds: np.ndarray,
    sensors: np.ndarray,
    moving: np.ndarray,
    margin: np.ndarray,
    ignored: np.ndarray,
    kept: tuple[np.ndarray, np.ndarray] | None = None,
    unit: float = 1.0,
) -> np.ndarray:
    """The pairs of a body and a static shape ((K, 2): row, the shape's place) whose boxes
    overlap within the body's reach: filters passed, no sensor body, a ``moving`` body, not
    ignored by a pre_solve (``ignored``: ``ignored_keys``) (a sensor collider is kept: its
    overlaps are events); ``kept``: ``face_filters``' answer where the caller has kept it
    (None: asked here); ``unit``: ``reaching``'s."""
    n = len(store)
    if not n or not len(owner):
        return np.zeros((0, 2), dtype=np.intp)
    x = store.x
    grow = store.radius + margin + SPECULATIVE_DISTANCE * unit
    lo = x - grow[:, None]
    hi = x + grow[:, None]
    hit = (
        (lo[:, None, 0] <= bounds[None, :, 2])
        & (hi[:, None, 0] >= bounds[None, :, 0])
        & (lo[:, None, 1] <= bounds[None, :, 3])
        & (hi[:, None, 1] >= bounds[None, :, 1])
    )
    # (Each test one bool a body and shape, all of them to hold: on the whole table.)
    meet, sensor = face_filters(store, cs, owner, sensors) if kept is None else kept
    hit &= meet
    hit &= moving[:, None] | sensor
    rows, shapes = np.nonzero(hit)
    if len(ignored):
        keep = ~in_sorted(rows.astype(np.int64) * (len(cs.sensor) + 1) + owner[shapes], ignored)
        rows, shapes = rows[keep], shapes[keep]
    return columns(rows, shapes)
