"""A game step's stages from waking to sleep in one compiled call, on the fast path.

The soft step (engine.pipeline.game_step) is a handful of stages: the sleepers an awake body comes
near woken, the solver's bodies, the contacts found (engine.pipeline.game_contacts'
``contacts_loop``), every contact and joint solved (engine.dynamics.solver's ``solve``), what the
contacts did kept and reported (``report_loop``), and still islands put to sleep. Each is a loop
kernel or a few numpy calls, and at a game's size (ten bodies, a dozen segments, a hinge) the Python
and numpy between them were most of the step: about 0.2 ms where the kernels' own work is a
few tens of microseconds. ``step_loop`` is those stages as one loop kernel: the same
products in the same order as the numpy path's (engine.pipeline.game_step's ``_wake``, ``_bodies``,
``_found``, ``_keep``, ``_events``, ``_sleep``; engine.pipeline.game_sleep's ``woken`` and
``fall_asleep``), so the fast path's bodies, impulses, events and sleep are the numpy path's
to the bit (tests/test_soft_solver.py and tests/test_soft_sleep.py step whole games on both).

What stays in Python, before and after it: what changes only when the World does (the
shapes' tables, the colliders' arrays, the joints' rows, the pairs kept apart), and a
sleeper's contacts held open (engine.pipeline.game_step's ``_hold``: only while something sleeps).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .. import kernels
from ..dynamics.events import COLLIDER
from ..dynamics.game_continuous import DEEP, SAFETY, ended_depth
from ..dynamics.game_joints import INT_ROWS
from ..dynamics.solver import FIRST_REACH, MOUSE, solve
from ..dynamics.turning_faces import FACE_NUMBERS, face_rows
from ..exact.pile import label_rows
from ..geometry.manifold_kinds import SPECULATIVE_DISTANCE
from ..kernels import stable_order
from .game_contacts import body_boxes, contacts_loop, contacts_sample, report_loop
from .game_sleep import ANGULAR, LINEAR, RISE

__all__ = ["step_loop"]


def _sample() -> tuple[Any, ...]:
    """The smallest call: ``contacts_loop``'s sample (a unit box resting on a segment, a disc
    beside it), both bodies awake and falling, the box held to the world by a hinge."""
    c = contacts_sample()
    x, q, radius, reach, moving, sensor, group, cats, mask, slots, fric, rest = c[:12]
    body_circle, body_index, kind, body_parts, part_of, pa, pb = c[12:19]
    statics = c[19:23]  # owner ... static_index
    c_sensor, c_fric, c_rest, surface, c_group, c_cats, c_mask = c[23:30]
    colliders = (c_sensor, np.stack([c_rest, c_fric]), surface, np.stack([c_group, c_cats, c_mask]))
    tables = c[30:38]  # V ... hn
    apart, ignored, warm_keys, warm_lam = c[38:42]
    f = np.zeros
    # The hinge's row (solver.solve's 22 joint arrays: a hinge, bodies 0 and 2, anchors at
    # 0.5) as the two tables (engine.dynamics.game_joints' INT_ROWS).
    row = [0.0, 2.0, 0.0, 0.5, 0.5, 0.5, 0.5, *[0.0] * 15]
    jtable = np.array(row).reshape(22, 1)
    jints = jtable[list(INT_ROWS)].astype(np.int64)
    v = f((2, 2))
    mass = np.array([1.0, 2.0])
    accel = np.array([[0.0, -9.81], [0.0, -9.81]])
    no = np.zeros(2, dtype=bool)
    island = np.zeros(2, dtype=np.int64)
    serial = np.array([1], dtype=np.int64)
    last = (np.array([1], dtype=np.int64), f((1, 6)))
    return (x, v, q, f(2), mass, np.array([6.0, 2.0]), accel, f(2), no, radius, reach,
            sensor, group, cats, mask, slots, fric, rest, body_circle, body_index, kind,
            body_parts, part_of, no.copy(), f(2), island, 0.5, 1.0 / 60.0, pa, pb, *statics,
            *colliders, *tables,
            apart, ignored, warm_keys, warm_lam, jints, jtable, serial, slots.copy(), *last, 4,
            30.0, 10.0, 60.0, 2.0, 3.0, 1.0, 0.005, 1.0)  # fmt: skip


@kernels.loop(sample=_sample)
def step_loop(
    x: Any, v: Any, angle: Any, omega: Any, mass: Any, inv_moment: Any, accel: Any,
    torque: Any, kinematic: Any, radius: Any, margin: Any,
    sensor: Any, group: Any, cats: Any, mask: Any, slots: Any, friction: Any,
    restitution: Any, body_circle: Any, body_index: Any, kind: Any, body_parts: Any,
    part_of: Any,
    asleep: Any, still: Any, island: Any, sleep_time: float, dt: float,
    pa: Any, pb: Any,
    owner: Any, bounds: Any, static_circle: Any, static_index: Any,
    c_sensor: Any, c_floats: Any, c_surface: Any, c_ints: Any,
    V: Any, Nrm: Any, cnt: Any, rad: Any, center: Any, rnd: Any, hp: Any, hn: Any,
    apart: Any, ignored: Any, warm_keys: Any, warm_lam: Any,
    jints: Any, jtable: Any, serial: Any, row_of: Any, last_keys: Any, last_table: Any,
    substeps: int, contact_hertz: float,
    contact_damping: float, joint_hertz: float, joint_damping: float, push: float,
    threshold: float, slop: float, unit: float,
) -> tuple[Any, ...]:  # fmt: skip
    """One soft step of ``dt`` (s) from waking to sleep (module doc).

    Bodies (n rows): ``x`` (n, 2) m, ``v`` (n, 2) m/s, ``angle`` rad, ``omega`` rad/s at the
    step's start; ``mass`` kg (inf: static), ``inv_moment`` 1/(kg m^2), ``accel`` (n, 2) m/s^2
    and ``torque`` N m held over the step, ``kinematic``, the bounding ``radius`` m and
    ``margin`` (how far each can move in the step, m; empty: measured here, as
    engine.pipeline.game_step's ``_reach``), then ``contacts_loop``'s body arrays
    from ``sensor`` to ``kind``. Sleep (engine.pipeline.game_sleep; in place): ``asleep``, ``still``
    (s), ``island`` (each sleeper's island label), ``sleep_time`` (s; inf: never).
    ``pa``, ``pb``: the pairs the broadphase tests (rows a < b). ``owner`` ... ``warm_lam``:
    ``contacts_loop``'s static shapes, colliders, tables, pairs kept apart and warm start, but
    the colliders' materials and filters as the rows of two tables, ``c_floats`` and
    ``c_ints`` (engine.pipeline.game_broadphase.Colliders' ``floats`` and ``ints``).
    ``jints``, ``jtable``: ``solve``'s 22 joint arrays as the rows of two tables
    (engine.dynamics.game_joints: the ints' rows INT_ROWS, the floats' all 22; their impulses
    out in place). ``serial``: each collider's serial number by place (the events' keys);
    ``row_of`` each body slot's row; ``last_keys``, ``last_table``: the touching contacts the
    step before reported (sorted by key), each one's point, normal and impulse the columns of
    the table (t, 6). Then ``solve``'s parameters and the slop within which a contact touches
    (m), and ``unit``, the World's length units a metre (its ``length_units_per_meter``): the
    speculative distance, a fresh contact's reach and sleep's speed and rise are scaled by it
    (``push``, ``threshold`` and ``slop`` come scaled).

    Returns the bodies' ``x``, ``v``, ``angle``, ``omega`` after the step, the kept warm-start
    keys, impulses and held loads ((k, 3) N s a substep), the touching contacts' event keys and
    their points, normals and impulses as one table (t, 6) (``report_loop``'s, and the last
    step's of bodies asleep through this one, held open; sorted by key), the sensor colliders'
    overlaps as event keys, and the touching pairs of bodies (keys a n + b, a < b: contacts,
    then joints between two bodies) for ``Body.sleep``'s island, and whether a body may be fast
    (moved more than about engine.dynamics.game_continuous.SAFETY of its least extent, or ended
    deeper than about its DEEP in what the solve does not move: the continuous stage's test),
    then what the World checks of the bodies after it: |the sum of x and v|, |the sum of angle
    and omega| (each nan or inf where an entry is) and whether any body spins; last, each body's
    least separation at the end from what the solve does not move (m) and the deepest overlap at
    the end of two bodies the solve moves (m; both
    engine.dynamics.game_continuous.ended_depth's)."""
    # The lengths in the World's units (``unit`` of them a metre): the speculative distance,
    # the squared speed (units^2/s^2) below which a body is still and the rise it may have
    # left (engine.pipeline.game_sleep's LINEAR and RISE).
    speculative = SPECULATIVE_DISTANCE * unit
    linear = LINEAR * unit
    linear_sq = linear * linear
    rise_most = RISE * unit
    n = len(radius)
    if len(margin) != n:
        # |v| dt + |a| dt^2 + |omega| dt r: what the shape can move in the step (``_reach``'s
        # products, in its order).
        margin = np.empty(n)
        for i in range(n):
            speed = np.hypot(v[i, 0], v[i, 1])
            acc = np.hypot(accel[i, 0], accel[i, 1])
            margin[i] = speed * dt + acc * dt * dt + np.abs(omega[i]) * dt * radius[i]
    # The colliders' materials and filters, the rows of their tables
    # (engine.pipeline.game_broadphase.Colliders).
    c_restitution, c_friction = c_floats[0], c_floats[1]
    c_group, c_cats, c_mask = c_ints[0], c_ints[1], c_ints[2]
    # The joints' arrays, the rows of their tables (engine.dynamics.game_joints' INT_ROWS).
    jkind, ja, jb, jlimit, jmotor = jints[0], jints[1], jints[2], jints[3], jints[4]
    jlax, jlay, jlbx, jlby, jref = jtable[3], jtable[4], jtable[5], jtable[6], jtable[7]
    jhertz, jdamp, jlower, jupper = jtable[8], jtable[9], jtable[11], jtable[12]
    jspeed, jmaxtorque = jtable[14], jtable[15]
    jpx, jpy, jpa = jtable[16], jtable[17], jtable[18]  # (the impulses, solved in place)
    jlo, jhi, jmi = jtable[19], jtable[20], jtable[21]
    # -- waking (engine.pipeline.game_step._wake, engine.pipeline.game_sleep.woken) ----------------
    dynamic = np.empty(n, dtype=np.bool_)
    any_asleep = False
    for i in range(n):
        dynamic[i] = not kinematic[i] and np.isfinite(mass[i])
        if asleep[i]:
            any_asleep = True
    if any_asleep:
        labels = 0
        for i in range(n):
            if asleep[i] and island[i] + 1 > labels:
                labels = island[i] + 1
        woken = np.zeros(labels, dtype=np.bool_)
        box = body_boxes(x, angle, radius, body_circle, body_index, body_parts, V, rad, center, rnd)
        active = np.empty(n, dtype=np.bool_)
        for i in range(n):
            spins = v[i, 0] != 0.0 or v[i, 1] != 0.0 or omega[i] != 0.0
            active[i] = (dynamic[i] and not asleep[i]) or (kinematic[i] and spins)
        for k in range(len(pa)):
            a, b = pa[k], pb[k]
            if not ((asleep[a] and active[b]) or (asleep[b] and active[a])):
                continue
            if group[a] != 0 and group[a] == group[b]:
                continue  # filtered apart (a sensor's filter meets nothing): no waking
            if (cats[a] & mask[b]) == 0 or (cats[b] & mask[a]) == 0:
                continue
            dx, dy = x[b, 0] - x[a, 0], x[b, 1] - x[a, 1]
            reach = radius[a] + radius[b] + margin[a] + margin[b] + speculative
            grown = margin[a] + margin[b] + speculative
            if box[b, 0] - box[a, 2] > grown or box[a, 0] - box[b, 2] > grown:
                continue  # their boxes too far apart (engine.pipeline.game_sleep.woken)
            if box[b, 1] - box[a, 3] > grown or box[a, 1] - box[b, 3] > grown:
                continue
            if dx * dx + dy * dy <= reach * reach:
                if asleep[a]:
                    woken[island[a]] = True
                if asleep[b]:
                    woken[island[b]] = True
        for i in range(n):
            if asleep[i] and woken[island[i]]:
                asleep[i] = False
                still[i] = 0.0
    moving = np.empty(n, dtype=np.bool_)
    before = np.empty(n, dtype=np.bool_)  # asleep through the step
    for i in range(n):
        moving[i] = dynamic[i] and not asleep[i]
        before[i] = asleep[i]
    # -- the solver's bodies (engine.pipeline.game_step._bodies): the rows, then the static body ---
    nb = n + 1
    bx, by, bq = np.zeros(nb), np.zeros(nb), np.zeros(nb)
    bvx, bvy, bw = np.zeros(nb), np.zeros(nb), np.zeros(nb)
    bim, bii = np.zeros(nb), np.zeros(nb)
    bax, bay, balpha = np.zeros(nb), np.zeros(nb), np.zeros(nb)
    for i in range(n):
        bx[i], by[i], bq[i] = x[i, 0], x[i, 1], angle[i]
        bvx[i], bvy[i], bw[i] = v[i, 0], v[i, 1], omega[i]
        if moving[i]:
            bim[i] = 1.0 / mass[i]
            bii[i] = inv_moment[i]
            bax[i], bay[i] = accel[i, 0], accel[i, 1]
            balpha[i] = torque[i] * inv_moment[i]
    # -- the contacts (engine.pipeline.game_contacts) ----------------------------------------------
    found = contacts_loop(
        x, angle, radius, margin, moving, sensor, group, cats, mask, slots, friction,
        restitution, body_circle, body_index, kind, body_parts, part_of, pa, pb, owner,
        bounds, static_circle,
        static_index, c_sensor, c_friction, c_restitution, c_surface, c_group, c_cats, c_mask,
        V, Nrm, cnt, rad, center, rnd, hp, hn, apart, ignored, warm_keys, warm_lam, v, dt, unit,
    )  # fmt: skip
    ca, cb, nx, ny, count = found[0], found[1], found[2], found[3], found[4]
    sep, ln, lt, lh = found[9], found[13], found[14], found[15]
    keys, place, px, py = found[16], found[17], found[18], found[19]
    sense_row, sense_place = found[20], found[21]
    # The rows of a point on a face that turns (engine.dynamics.turning_faces), taken again as
    # the face turns.
    # (Asked only where a row pairs two bodies that are not both discs.)
    several = False
    for i in range(n):
        if body_parts[i, 1] != 1:
            several = True
    # (And where a disc meets a static shape that is no half plane: a round feature's rows.)
    mixed = False
    for k in range(len(ca) if not several else 0):
        b = cb[k]
        disc = body_circle[body_parts[ca[k], 0]]
        if b < n and not (disc and body_circle[body_parts[b, 0]]):
            mixed = True
            break
        if b >= n and disc and place[k] >= 0 and static_index[place[k]] >= 0:
            mixed = True
            break
    if mixed:
        face, fround = face_rows(
            ca, cb, nx, ny, n, several, angle, body_circle, body_index, body_parts, Nrm, cnt,
            rad, rnd, place, static_circle, static_index, V,
        )  # fmt: skip
    else:
        face, fround = np.zeros(len(ca), dtype=np.int64), np.zeros(FACE_NUMBERS * len(ca))
    total = np.zeros(2 * len(ca))
    most = np.zeros(2 * len(ca))
    rise = np.zeros(nb)  # out: how far each body's held loads have yet to lift it (m)
    # -- the solve (engine.dynamics.solver) --------------------------------------------------------
    solve(
        bx, by, bq, bvx, bvy, bw, bim, bii, bax, bay, balpha,
        ca, cb, nx, ny, count, found[5], found[6], found[7], found[8], sep,
        found[10], found[11], found[12], ln, lt, lh, total, most,
        jkind, ja, jb, jlax, jlay, jlbx, jlby, jref, jhertz, jdamp, jlimit, jlower, jupper,
        jmotor, jspeed, jmaxtorque, jpx, jpy, jpa, jlo, jhi, jmi, face, fround,
        dt, substeps, contact_hertz, contact_damping, joint_hertz, joint_damping, push,
        threshold, FIRST_REACH * unit, rise,
    )  # fmt: skip
    # -- the bodies' poses after it, and how deep each ended in what the solve does not move
    # (engine.dynamics.game_continuous.ended_depth: the continuous stage sweeps one too deep)
    x_out = np.empty((n, 2))
    for i in range(n):
        x_out[i, 0], x_out[i, 1] = bx[i], by[i]
    q_out = bq[:n].copy()
    solved = np.zeros(nb, dtype=np.bool_)
    for i in range(n):
        solved[i] = moving[i]
    ended, pile = ended_depth(
        x, angle, x_out, q_out, solved, ca, cb, nx, ny, count, found[5], found[6], found[7],
        found[8], sep, face, fround,
    )  # fmt: skip
    # -- what the contacts did (engine.pipeline.game_contacts.report_loop) -------------------------
    kept, lam, event, table = report_loop(
        ca, cb, nx, ny, count, sep, keys, place, px, py, ln, lt, lh, total, slots, owner, serial,
        substeps, slop,
    )  # fmt: skip
    # The last step's touching contacts whose bodies slept through this one (a sleeper and
    # a collider, or two sleepers) stay open: they were not found, nor solved, and nothing
    # ends (engine.pipeline.game_step._hold).
    held = np.zeros(len(last_keys), dtype=np.bool_)
    extra = 0
    for i in range(n):
        if before[i]:
            for k in range(len(last_keys)):
                key = last_keys[k]
                other = key & (COLLIDER - 1)
                collider = (key & COLLIDER) != 0
                a = row_of[key >> 32]
                b = row_of[0 if collider else other]
                if before[a] and (collider or before[b]):
                    held[k] = True
                    extra += 1
            break
    if extra:
        event = np.concatenate((event, last_keys[held]))
        table = np.concatenate((table, last_table[held]))
        order = stable_order(event)  # stable, as numpy's: sorted by key
        event, table = event[order], table[order]
    sensing = np.empty(len(sense_row), dtype=np.int64)
    for i in range(len(sense_row)):
        sensing[i] = (slots[sense_row[i]] << 32) | (serial[sense_place[i]] | COLLIDER)
    # -- sleep (engine.pipeline.game_step._sleep, engine.pipeline.game_sleep.fall_asleep) ----------
    # The touching pairs of bodies: a contact between two, a joint between two (either end
    # may be the world, which joins nothing), each as (least, greatest).
    m = 0
    for i in range(len(ca)):
        if cb[i] < n:
            m += 1
    for i in range(len(ja)):
        if ja[i] < n and jb[i] < n:
            m += 1
    ea = np.empty(m, dtype=np.int64)
    eb = np.empty(m, dtype=np.int64)
    m = 0
    for i in range(len(ca)):
        if cb[i] < n:
            ea[m], eb[m] = min(ca[i], cb[i]), max(ca[i], cb[i])
            m += 1
    for i in range(len(ja)):
        if ja[i] < n and jb[i] < n:
            ea[m], eb[m] = min(jb[i], ja[i]), max(jb[i], ja[i])
            m += 1
    touching = ea * n + eb
    # A pymunk constraint's bodies (jmotor's bit 2) are still only while the step moved them
    # by less than LINEAR dt and turned them by less than ANGULAR dt: its correction moves
    # them with no speed left (engine.pipeline.game_sleep.drifting's products).
    held = np.zeros(n + 1, dtype=np.bool_)
    for i in range(len(jmotor)):
        if (jmotor[i] & 2) != 0:
            held[ja[i]] = True
            held[jb[i]] = True
    near = linear_sq * dt * dt
    level = ANGULAR * dt
    ripe = False  # a body still for sleep_time
    for i in range(n):
        # (Its shape's fastest point: |v| + r |omega|, game_sleep.fall_asleep's products.)
        slow = math.sqrt(bvx[i] * bvx[i] + bvy[i] * bvy[i]) + radius[i] * abs(bw[i]) < linear
        slow = slow and not rise[i] > rise_most  # (its held loads yet to lift it: game_sleep)
        if slow and held[i]:
            dx, dy = bx[i] - x[i, 0], by[i] - x[i, 1]
            slow = dx * dx + dy * dy < near and abs(bq[i] - angle[i]) < level
        still[i] = still[i] + dt if moving[i] and slow else 0.0
        if still[i] >= sleep_time:
            ripe = True
    if np.isfinite(sleep_time) and ripe:
        never = kinematic.copy()
        for i in range(len(jkind)):
            if jkind[i] == MOUSE and jb[i] < n:
                never[jb[i]] = True
        # The islands of awake bodies; one sleeps when its least still time is enough.
        inner = 0
        for i in range(m):
            if moving[ea[i]] and moving[eb[i]]:
                inner += 1
        ia = np.empty(inner, dtype=np.int64)
        ib = np.empty(inner, dtype=np.int64)
        inner = 0
        for i in range(m):
            if moving[ea[i]] and moving[eb[i]]:
                ia[inner], ib[inner] = ea[i], eb[i]
                inner += 1
        label = label_rows(n, ia, ib)
        least = np.full(n, np.inf)
        for i in range(n):
            t = still[i] if moving[i] and not never[i] else -np.inf
            if t < least[label[i]]:
                least[label[i]] = t
        for i in range(n):
            if moving[i] and least[label[i]] >= sleep_time:
                asleep[i] = True
                island[i] = label[i]
                bvx[i], bvy[i], bw[i] = 0.0, 0.0, 0.0
    # -- whether a body may be fast (engine.dynamics.game_continuous's test from above of the move,
    # |dx| + |dy| + |dq| R > SAFETY e, its extents from the tables; a share looser, as
    # engine.geometry.shaped.ShapeTable.extents sums in another order)
    # ----------------------------------
    fast = False
    for i in range(n):
        if not moving[i] or sensor[i]:
            continue
        # (A body of several shapes: its least part's extent, its farthest part's reach.)
        small, far = np.inf, 0.0
        for part in range(body_parts[i, 0], body_parts[i, 0] + body_parts[i, 1]):
            j = body_index[part]
            if body_circle[part]:
                small = min(small, rnd[j])
                far = max(far, np.hypot(center[j, 0], center[j, 1]))
                continue
            k = cnt[j]
            cx, cy = 0.0, 0.0
            for e in range(k):
                cx += V[j, e, 0]
                cy += V[j, e, 1]
            cx, cy = cx / k, cy / k
            depth = np.inf
            for e in range(k):
                d = Nrm[j, e, 0] * (V[j, e, 0] - cx) + Nrm[j, e, 1] * (V[j, e, 1] - cy)
                depth = min(depth, d)
                far = max(far, np.hypot(V[j, e, 0], V[j, e, 1]))
            small = min(small, max(depth, 0.0) + rad[j])
        move = abs(bx[i] - x[i, 0]) + abs(by[i] - x[i, 1]) + abs(bq[i] - angle[i]) * far
        if move > SAFETY * small * (1.0 - 1e-6) or ended[i] < -DEEP * small * (1.0 - 1e-6):
            fast = True
            break
    # The bodies after the step, and what the World checks of them (engine.pipeline.stepping):
    # the sums of their positions and velocities, and of their angles and angular velocities
    # (nan or inf where an entry is), and whether any body spins (a nan does).
    v_out = np.empty((n, 2))
    linear, turning, spinning = 0.0, 0.0, False
    for i in range(n):
        v_out[i, 0], v_out[i, 1] = bvx[i], bvy[i]
        linear += (bx[i] + by[i]) + (bvx[i] + bvy[i])
        turning += bq[i] + bw[i]
        if bw[i] != 0.0:
            spinning = True
    return (x_out, v_out, q_out, bw[:n].copy(), kept, lam, event, table, sensing, touching,
            fast, abs(linear), abs(turning), spinning, ended, pile)  # fmt: skip
