"""A pile's step: the bodies that rest on one another, stepped together by the soft step.

Which pairs are a pile's is decided as the step begins (engine.exact.collisions, ``plan``): a pair
that carried load in the last step, or that is near enough to touch, closes or parts no faster
than its rest speed and is pressed together by the forces, or that overlaps past ``SLOP``;
and whatever can reach such a pair's body within the step at a speed its contacts can catch.
The bodies of a pile are stepped again here from the start of the step (x0, v0), by Box2D
v3's soft step (engine.exact.soft), with every contact among them and with the faces they can reach
(the static contacts leave them to it).

**Rows** (``step_pile``). A contact is a row between bodies A and B (the lower World row A;
the static world is one more body, the last slot, of infinite mass) with the unit normal n
from A to B, the gap along it at the step's start, friction mu = mu_a mu_b and restitution
e = e_a e_b:

* two discs: n = (x_b - x_a) / |x_b - x_a|, gap |x_b - x_a| - r_a - r_b;
* a disc and a face within reach (``face_rows``): the face's normal toward the disc, the gap
  from the face grown by the radius;
* bodies with shapes (engine.geometry.shaped): a row a point of each manifold, pair against pair or
  shape against the colliders' shapes.

(The rows of discs and faces are assembled, warm started and checked after the step in
engine.exact.pile_rows; on the fast path each of those parts, the carry below, ``dissipative``
and the push out of the walls runs as a loop kernel beside its numpy twin, to the same bits.)

Each row is keyed by one integer, stable from step to step, so the last step's impulses warm
start it: a * base + b for two discs, a * base + n + f for a disc and face f (base: the bodies
and faces, n + faces), and past n * base the rows of shapes, by pair and point. The impulses
(``Carried``) are kept over the whole step lam_dt, and start each of the next step's parts at
lam dt / (lam_dt iterations), so a change of dt or of ``iterations`` scales them; a sleeping
group's rows keep theirs (``asleep_rows``), so that it wakes holding its weight (without them
a woken pile would sag for a step and ring), and each row keeps its colour
(engine.dynamics.coloring), so the solver's order does not shuffle.

**The soft step** (engine.exact.soft): ``iterations`` parts, each integrating the velocities, warm
starting, solving the rows as soft springs (pushing an overlap out at most ``PUSH`` smallest
radii a second), moving the positions and relaxing the springs' push out of the speeds; then
restitution for rows that closed faster than ``THRESH`` times the rest speed 2 |a| dt.

**No energy added** (``dissipative``). Contacts only take energy: an exact solution of
resting contacts is a projection of V0 (what the forces alone would give) in the mass metric,
which never lengthens it; friction dissipates; restitution e <= 1 gives back at most what the
impact took. The soft step's few iterations, and its push apart of an overlap, can stop short
and add a little; then the change dV = V - V0 is scaled by the s in [0, 1] that leaves the
least energy,

    KE(s) = KE0 + s B + s^2 C,    B = sum m V0.dV,    C = sum m |dV|^2 / 2,    s = -B / (2 C),

which keeps momentum (the impulses between bodies are equal and opposite at any s). Nothing
the pile moves is left inside a wall (``Contacts.push_out_rows``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, NamedTuple, overload

import numpy as np

from .. import kernels
from ..geometry.manifold import StaticShapes, static_shapes
from ..geometry.pair_math import SLOP, dot, norm, sorted_unique
from ..geometry.shaped import ShapeTable, pair_rows, static_rows
from .joint_contacts import joined_rows
from .pile_rows import (
    Carried,
    disc_rows,
    face_rows,
    held,
    lever_arms,
    shape_arms,
    turning,
    warm_start,
)
from .shape_impacts import retake
from .soft import Rows, SoftStep
from .sweep import first_hits

if TYPE_CHECKING:
    from ..dynamics.rotation import Spin
    from .contacts import Contacts

__all__ = [
    "PUSH",
    "PUSHOUT",
    "THRESH",
    "Carried",
    "Pile",
    "Statics",
    "asleep_rows",
    "carry_out",
    "dissipative",
    "keep_asleep",
    "set_back",
    "slept_colors",
    "step_pile",
]

#: The fastest the soft step pushes overlapping bodies apart, in smallest radii a second
#: (Box2D's 3 m/s for bodies of half a metre).
PUSH = 6.0
#: Restitution acts on a pile's contacts that closed faster than this many times the rest
#: speed 2 |a| dt (3: 6 |a| dt, 1 m/s under gravity at dt = 1/60, Box2D's threshold).
THRESH = 3.0
#: Whether the discs of a pile are pushed out of the walls after the soft step.
PUSHOUT = True


class Pile(NamedTuple):
    """What ``step_pile`` found, besides the new state it wrote."""

    #: Keys (a * N + b) of the pairs touching now (for the events).
    touching: np.ndarray
    #: The pairs near enough to touch (World rows), which join bodies for sleep.
    near_a: np.ndarray
    near_b: np.ndarray
    #: The contacts of the pile's bodies with faces now: (World rows, faces).
    face_touching: tuple[np.ndarray, np.ndarray]
    #: Each shaped body's deepest overlap (length units), (N,).
    shape_over: np.ndarray
    #: The impulses to carry into the next step.
    carried: Carried
    #: The contacts of bodies held by joints (engine.exact.joint_solver takes them into its solve):
    #: (body, other (-1: the static world), normal from the other to the body, the contact
    #: point less each one's position, the gap, friction, the normal impulse given, and
    #: engine.exact.joint_contacts' turn, polygon, radius and restitution), or None.
    joined: tuple[np.ndarray, ...] | None = None


class Statics:
    """The colliders as narrowphase kinds, built again when the faces change."""

    def __init__(self) -> None:
        self._cached: tuple[Any, StaticShapes, np.ndarray, np.ndarray] | None = None

    def of(self, contacts: Contacts) -> tuple[StaticShapes, np.ndarray, np.ndarray]:
        """The colliders as narrowphase kinds, which are solid, and each collider's first
        face (what the events and filters name a shape's contact with it by)."""
        faces = contacts.faces
        if self._cached is None or self._cached[0] is not faces:
            cols = contacts.colliders
            solid = np.array([not c.sensor for c in cols], dtype=bool)
            first = np.full(len(cols), -1, dtype=np.intp)
            owner = faces.owner
            order = np.arange(len(owner))[::-1]
            first[owner[order]] = order
            self._cached = (faces, static_shapes(cols), solid, first)
        return self._cached[1], self._cached[2], self._cached[3]


def asleep_rows(carried: Carried, asleep: np.ndarray, n: int, base: int) -> np.ndarray:
    """Which of the last step's contact rows (``carried.keys``) join only sleepers: they keep
    their impulses while the group sleeps, so that it wakes holding its weight (without
    them a woken pile would sag for a step and ring)."""
    keys = carried.keys
    if not len(keys) or base != carried.base or len(asleep) != n:
        return np.zeros(len(keys), dtype=bool)
    disc = keys < n * base  # the rows of bodies with shapes are keyed past those
    a, b = np.divmod(np.where(disc, keys, 0), base)
    face = b >= n
    return disc & asleep[a] & (face | asleep[np.where(face, 0, b)])


def slept_colors(carried: Carried, kept: np.ndarray) -> np.ndarray:
    """The colours of the kept rows, where the cache still has them (else -1)."""
    keys = carried.keys
    if len(carried.color_keys) == len(keys) and len(carried.colors) == len(keys):
        return carried.colors[kept]
    return np.full(int(kept.sum()), -1, dtype=np.int64)


def keep_asleep(carried: Carried, asleep: np.ndarray, n: int) -> Carried:
    """What a step without a pile carries on: the rows of the sleepers alone."""
    kept = asleep_rows(carried, asleep, n, carried.base)
    keys = carried.keys[kept]
    return carried._replace(
        keys=keys, lam=carried.lam[kept], color_keys=keys, colors=slept_colors(carried, kept)
    )


def carry_out(
    carried: Carried,
    asleep: np.ndarray,
    n: int,
    base: int,
    key: np.ndarray,
    lam_n: np.ndarray,
    lam_t: np.ndarray,
    iterations: int,
    color: np.ndarray,
    dt: float,
    fast: bool = False,
) -> Carried:
    """What a step carries into the next: its rows' (``key``) impulses over the whole step
    (lam_n, lam_t: a part's, ``iterations`` parts) and colours, with the rows the sleepers
    keep (``asleep_rows``), sorted by key. ``fast``: the loop kernels ``carry_keys`` and
    ``carry_gather`` around the twin's sort."""
    if fast:
        # The keys in loops, numpy's own sort (so repeated keys fall as the twin's do), then
        # the impulses and colours taken in its order in a loop.
        keys = carried.keys
        colors = carried.colors
        if not (len(carried.color_keys) == len(keys) and len(colors) == len(keys)):
            colors = np.full(len(keys), -1, dtype=np.int64)  # slept_colors: none kept
        keep = len(keys) > 0 and base == carried.base and len(asleep) == n
        all_keys, kept = carry_keys(key, keys, asleep, n, base, keep)
        order = np.argsort(all_keys)
        lam, color_now = carry_gather(
            order, lam_n, lam_t, iterations, color, carried.lam, colors, kept
        )
        keys_now = all_keys[order]
        return Carried(keys_now, lam, dt, base, keys_now, color_now)
    kept = asleep_rows(carried, asleep, n, base)
    key = np.concatenate([key, carried.keys[kept]])
    lam = np.concatenate([np.stack([lam_n, lam_t], axis=1) * iterations, carried.lam[kept]])
    color = np.concatenate([color, slept_colors(carried, kept)])
    order = np.argsort(key)
    keys_now = key[order]
    return Carried(keys_now, lam[order], dt, base, keys_now, color[order])


def step_pile(
    island: np.ndarray,
    a: np.ndarray,
    b: np.ndarray,
    x0: np.ndarray,
    v0: np.ndarray,
    x: np.ndarray,
    v: np.ndarray,
    P: np.ndarray,
    dt: float,
    store: Any,
    contacts: Contacts | None,
    table: ShapeTable,
    statics: Statics,
    carried: Carried,
    asleep: np.ndarray,
    iterations: int,
    rest_speed: float,
    fast: bool = False,
    spin: Spin | None = None,
    joined: np.ndarray | None = None,
) -> Pile:
    """Step the bodies of the pile (``island``) again from (x0, v0) by the soft step
    (engine.exact.soft), with every contact among them (pairs a, b) and with the faces they can
    reach, in place on (x, v). ``P`` (N, 2): the forces' pull; ``table``: the bodies' shapes;
    ``carried``: the last step's impulses; ``asleep`` (N,): the sleepers, whose rows keep
    theirs; ``iterations``: the soft step's parts; ``rest_speed``: 2 dt times the largest
    pull (restitution acts on contacts closing faster than ``THRESH`` times it); ``fast``:
    run the loop kernels (engine.kernels: the soft step's, the colouring's, the piles');
    ``spin``: the step's rotation (engine.dynamics.rotation), whose discs of the pile that turn are
    turned by their rows' friction (engine.exact.soft, ``Arms``), in place on its angle and omega;
    ``joined`` (N,) bool or None: bodies held by joints, whose contacts the pile hands on."""
    n = len(x)
    U = np.flatnonzero(island)
    nU = len(U)
    local = np.full(n, -1, dtype=np.intp)
    local[U] = np.arange(nU)
    shapedU = table.shaped[U]
    both = island[a] & island[b]
    pa, pb = a[both], b[both]
    with_shape = table.shaped[pa] | table.shaped[pb]
    sa, sb = pa[with_shape], pb[with_shape]  # pairs with a shape: engine.geometry.shaped
    pa, pb = pa[~with_shape], pb[~with_shape]
    la, lb = local[pa], local[pb]
    r = store.radius[U]
    x0U, v0U = x0[U], v0[U]
    mu, e = store.friction[U], store.restitution[U]
    n_faces = 0 if contacts is None else len(contacts.faces.owner)
    base = n + n_faces
    # Pairs: A the lower row, B the higher; the normal from A to B.
    nrm, sep, pair_mu, pair_e, pair_slop, pair_key = disc_rows(
        pa, pb, la, lb, x0U, r, mu, e, base, fast
    )
    rows_a, rows_b = [la], [lb]
    # Each row's collider (its place among the World's colliders), -1 between bodies: for the
    # colliders' surface velocities.
    owners = [np.full(len(la), -1, dtype=np.intp)]
    normals, seps = [nrm], [sep]
    fric, rest = [pair_mu], [pair_e]
    slops = [pair_slop]
    keys = [pair_key]
    fa = fk = np.zeros(0, dtype=np.intp)
    speed = norm(v0U) + norm(P[U]) * dt
    kin = store.kinematic[U]
    if n_faces and contacts is not None:
        # Faces within reach of a body this step: the static world is B, the slot nU.
        fa, fn, fg, fmu, fk = face_rows(contacts, x0U, r, 0.05 * r + speed * dt, fast)
        ok = ~kin[fa] & ~shapedU[fa]  # walls do not hold what the game moves
        if contacts.filtering:
            ok &= contacts.allowed(U[fa], fk)  # faces a body's filter does not meet
        fa, fn, fg, fmu, fk = fa[ok], fn[ok], fg[ok], fmu[ok], fk[ok]
        rows_a.append(np.full(len(fa), nU))
        owners.append(contacts.faces.owner[fk])
        rows_b.append(fa)
        normals.append(fn)
        seps.append(fg)
        fric.append(mu[fa] * fmu)
        rest.append(e[fa] * contacts.faces.e[fk])
        slops.append(SLOP * r[fa])
        keys.append(U[fa].astype(np.int64) * base + n + fk)
    m_disc = sum(len(k) for k in keys)
    # Bodies with shapes (engine.geometry.shaped): a row a point of each manifold, keyed past the
    # discs' keys (n * base), by pair and point, or by body, static shape and point.
    s_off = np.int64(n) * base
    reach = 0.05 * r + speed * dt
    angle = store.angle if spin is None else spin.angle0
    if spin is not None:
        # A body that turns sweeps its corners round by up to |omega| R dt in the step (R:
        # its bounding radius), so a spinning box does not pass a wall.
        turns_u = spin.turns[U] & shapedU
        reach = reach + np.where(
            turns_u, (np.abs(spin.omega0[U]) + np.abs(spin.alpha[U]) * dt) * r * dt, 0.0
        )
    margin = float(reach.max()) if nU else 0.0
    m_pairs = 0
    anchors = [np.zeros((0, 2))] * 3
    if len(sa):
        ia, ib, sn, ss, slot, anchors[0], anchors[1] = pair_rows(
            table, sa, sb, x0, margin, angle, fast
        )
        m_pairs = len(ia)
        rows_a.append(local[ia])
        owners.append(np.full(len(ia), -1, dtype=np.intp))
        rows_b.append(local[ib])
        normals.append(sn)
        seps.append(ss)
        fric.append(store.friction[ia] * store.friction[ib])
        rest.append(store.restitution[ia] * store.restitution[ib])
        slops.append(SLOP * np.minimum(store.radius[ia], store.radius[ib]))
        keys.append(s_off + (ia.astype(np.int64) * n + ib) * 65536 + slot)
    s_rows = s_col = np.zeros(0, dtype=np.intp)
    if n_faces and contacts is not None and (shapedU & ~kin).any():
        shapes, solid, first = statics.of(contacts)
        mine = U[shapedU & ~kin]
        meets = None
        if contacts.filtering:
            # Pairs a body's filter does not meet are left out before the narrowphase.
            allowed = contacts.allowed
            meets = lambda rows, cols: allowed(rows, first[cols])  # noqa: E731
        s_rows, s_col, sn, ss, skey, anchors[2] = static_rows(
            table, mine, x0, shapes, solid, margin, angle, meets, fast
        )
        rows_a.append(np.full(len(s_rows), nU))
        owners.append(np.asarray(s_col, dtype=np.intp))
        rows_b.append(local[s_rows])
        normals.append(sn)
        seps.append(ss)
        cols = contacts.colliders
        fric.append(store.friction[s_rows] * np.array([cols[k].friction for k in s_col]))
        rest.append(store.restitution[s_rows] * np.array([cols[k].restitution for k in s_col]))
        slops.append(SLOP * store.radius[s_rows])
        keys.append(s_off + 65536 * np.int64(n) * n + s_rows.astype(np.int64) * 2**40 + skey)
    ra, rb = np.concatenate(rows_a), np.concatenate(rows_b)
    nv = np.concatenate(normals)
    sep_all = np.concatenate(seps)
    key = np.concatenate(keys)
    if not len(key):
        # No row reaches a body of the pile (a flipper whose ball is far: shapes always come
        # here): each keeps the method's step and its free spin, as ``alone`` below gives
        # them, bit for bit, without the soft step's cost; the sleepers' rows carry on.
        none = np.zeros(0)
        now_carried = carry_out(carried, asleep, n, base, key, none, none, iterations,
                                np.zeros(0, dtype=np.int64), dt, fast)  # fmt: skip
        empty = np.zeros(0, dtype=np.intp)
        return Pile(np.zeros(0, dtype=np.int64), empty, empty, (empty, empty), np.zeros(n),
                    now_carried, None)  # fmt: skip
    static = ra == nU
    w = np.append(1.0 / store.mass[U], 0.0)
    moves = np.append(~kin, False)
    w[:-1][~moves[:-1]] = 0.0
    # Warm start: the last step's impulses of the same contacts, per part of this step, and
    # each row's colour from the last step where its key had one (engine.dynamics.coloring).
    lam, prior = warm_start(carried, key, base, dt, iterations, fast)
    rows = Rows(
        ra,
        rb,
        nv[:, 0] + 1j * nv[:, 1],
        sep_all,
        np.concatenate(fric),
        np.concatenate(rest),
        lam[:, 0].copy(),
        lam[:, 1].copy(),
        static,
    )
    slop_rows = np.concatenate(slops)
    surface = None if contacts is None else contacts.surface_velocities()
    slip = None if surface is None else surface_slip(surface, np.concatenate(owners), nv)
    acc = np.append(P[U, 0] + 1j * P[U, 1], 0.0)
    acc[:-1][~moves[:-1]] = 0.0
    turn = None
    if spin is not None:
        turn = turning(spin, store, U, moves[:-1])
    arms = None
    if turn is not None:
        arms = lever_arms(turn, r, ra, rb, sep_all, m_disc, len(pa), fa, nU)
        if m_disc < len(ra):
            # The rows of shapes: lever arms from the manifolds' anchors (engine.geometry.shaped).
            arms = shape_arms(arms, turn, ra, rb, nv, m_disc, m_pairs, anchors)
    solver = SoftStep(
        rows,
        w,
        moves,
        dt,
        iterations,
        push_speed=PUSH * slop_rows / SLOP,  # PUSH radii a second, the pair's smaller
        threshold=THRESH * rest_speed,
        slop=slop_rows,
        prior=prior,
        fast=fast,
        arms=arms,
        slip=slip,
    )
    X, V = solver.run(
        np.append(x0U[:, 0] + 1j * x0U[:, 1], 0.0),
        np.append(v0U[:, 0] + 1j * v0U[:, 1], 0.0),
        acc,
        None if turn is None else turn.omega0,
        None if turn is None else turn.alpha,
    )
    Xr = np.stack([X[:nU].real, X[:nU].imag], axis=1)
    Vr = np.stack([V[:nU].real, V[:nU].imag], axis=1)
    W = solver.omega[:nU]
    # A kinematic body goes where the game sends it, whatever it touched.
    if not kin.any():
        # Each pile on its own: the bodies of one never change another's motion.
        group = components(nU, ra, rb, fast)
        solved = (Vr, W)
        if turn is None:
            Vr = dissipative(Vr, v0U + P[U] * dt, store.mass[U], group, fast)
        else:
            # The spins' energy I omega^2 / 2 counts too (friction trades it with v's).
            W0 = turn.omega0[:nU] + turn.alpha[:nU] * dt
            Vr, W = dissipative(
                Vr, v0U + P[U] * dt, store.mass[U], group, fast, (W, W0, turn.moment)
            )
        if slip is not None:
            # A pile on a moving surface (a conveyor) gains the energy the surface gives it:
            # its velocities stay as solved.
            carried_on = np.zeros(nU, dtype=bool)
            carried_on[group[rb[slip != 0.0]]] = True
            on = carried_on[group]
            Vr, W = Vr.copy(), W.copy()
            Vr[on], W[on] = solved[0][on], solved[1][on]
    # A body of the pile that no row reaches (a box in flight: shapes always come here)
    # meets nothing in the step: it keeps the method's step and its free spin, bit for bit
    # (exact under the closed form, and RATTLE's for a body on joints).
    alone = np.ones(nU, dtype=bool)
    alone[ra[ra < nU]] = False
    alone[rb] = False
    if alone.any():
        Xr[alone], Vr[alone] = x[U][alone], v[U][alone]
    if turn is not None:
        # The discs that turn end the step at the soft step's spin, having turned by the
        # sum of omega h over its parts (as the positions by v h).
        t = turn.turns & ~alone
        spin.angle[U[t]] = spin.angle0[U[t]] + solver.turned[:nU][t]  # type: ignore[union-attr]
        spin.omega[U[t]] = W[t]  # type: ignore[union-attr]
    if kin.any():
        Xr[kin], Vr[kin] = x[U][kin], v[U][kin]
    if n_faces and contacts is not None:
        # A disc the pile sent farther than its reach (squeezed out between bodies at many
        # times its start speed) may cross a face it had no row with: it stops where it
        # first touches one (``set_back``).
        set_back(contacts, x0U, Xr, r, 0.05 * r + speed * dt, ~kin & ~shapedU, U, fa, fk, dt)
        # No disc of the pile ends inside a wall: the soft contacts give a little. (A
        # shape is held out by its rows alone; a kinematic body is no wall's business.)
        if PUSHOUT:
            contacts.push_out_rows(Xr, Vr, np.where(kin | shapedU, -np.inf, r), U, fast)
    x[U], v[U] = Xr, Vr
    statics_met = n_faces and contacts is not None and (shapedU & ~kin).any()
    if m_pairs or statics_met:
        # Fast shapes the rows left deep in each other or a wall meet at their moment instead
        # (every shape of the pile: one pushed by another may reach a wall it had no row with).
        walls = None
        if statics_met:

            def walls_at(rows: np.ndarray, xs: np.ndarray, qs: np.ndarray, reach: float) -> Any:
                got = static_rows(table, rows, xs, shapes, solid, reach, qs, meets, fast)
                return got[0], got[1], got[2], got[3]

            walls = (walls_at, mine)
        pairs = (ia, ib) if m_pairs else (s_rows[:0], s_rows[:0])
        again = retake(table, pairs, walls, (x0, v0), (x, v), spin, P, store, dt, fast, joined)
        if again is not None:
            Xr[local[again]] = x[again]
    # The impulses over the whole step, kept by key (sorted) for the next one.
    now_carried = carry_out(
        carried, asleep, n, base, key, rows.lam_n, rows.lam_t, iterations, solver.color, dt, fast
    )
    # Which contacts touch now: the pairs for the events and sleep, the faces too.
    m = len(pa)
    sep_now = sep_all
    if arms is not None and arms.na is not None and arms.nb is not None and m_disc < len(ra):
        # The rows of shapes: their points moved with the angles turned too (linearized, as
        # in the soft step).
        sep_now = sep_all.copy()
        th, sh = solver.turned, slice(m_disc, len(ra))
        sep_now[sh] += th[rb[sh]] * arms.nb[sh] - th[ra[sh]] * arms.na[sh]
    hold, near, now, held_rows = held(Xr, x0U, la, lb, r, ra, rb, nv, sep_now, slop_rows,
                                      solver.total, fast)  # fmt: skip
    f = slice(m, m_disc)
    face_touching = (U[fa[held_rows[f]]], fk[held_rows[f]])
    touching = pa[hold].astype(np.int64) * n + pb[hold]
    near_a, near_b = pa[near], pb[near]
    shape_over = np.zeros(n)
    if m_disc < len(ra):
        # The rows of shapes: touching pairs and faces for the events, sleep joined by
        # them, and their overlaps (a shape's bounding circle says nothing of them).
        sp = slice(m_disc, m_disc + m_pairs)
        st = slice(m_disc + m_pairs, len(ra))
        ua, ub = U[ra[sp]], U[rb[sp]]
        hs = held_rows[sp]
        tk = sorted_unique(ua[hs].astype(np.int64) * n + ub[hs])
        touching = np.concatenate([touching, tk])
        near_s = now[sp] <= 0.05 * np.minimum(store.radius[ua], store.radius[ub])
        near_a = np.concatenate([near_a, ua[near_s]])
        near_b = np.concatenate([near_b, ub[near_s]])
        hf = held_rows[st]
        if contacts is not None and hf.any():
            first = statics.of(contacts)[2]
            face_touching = (
                np.concatenate([face_touching[0], s_rows[hf]]),
                np.concatenate([face_touching[1], first[s_col[hf]]]),
            )
        over = np.maximum(-now[m_disc:], 0.0)
        body = np.concatenate([ua, ub, U[rb[st]]])
        depth = np.concatenate([over[:m_pairs], over[:m_pairs], over[m_pairs:]])
        np.maximum.at(shape_over, body, depth)
    out = None
    if joined is not None:
        fr = np.concatenate(fric)
        out = joined_rows(pushed_on(joined, U, ra, rb), U, ra, rb, nv, now, sep_all, r,
                          fr, rows.restitution,
                          solver.total, m, m_disc, m_pairs, anchors, table)  # fmt: skip
    return Pile(touching, near_a, near_b, face_touching, shape_over, now_carried, out)


def set_back(
    contacts: Contacts,
    x0: np.ndarray,
    X: np.ndarray,
    r: np.ndarray,
    reach: np.ndarray,
    discs: np.ndarray,
    U: np.ndarray,
    fa: np.ndarray,
    fk: np.ndarray,
    dt: float,
) -> None:
    """Set back, in place on ``X``, each of the pile's discs (mask ``discs``) that the soft
    step moved farther than its ``reach`` from its start ``x0`` to where its straight path
    from there first touches a solid face it had no row with (rows: its faces ``fk`` by
    ``fa``, the pile's rows), its velocity kept (Box2D's continuous stage does as much): the
    next step's rows, taken there, hold it. A disc at rest beside a wall, struck within the
    step by a body that squeezes it out along the floor at 88 m/s, had no row with the wall
    and passed a polygon wall 1 m thick (tests/test_fuzz_shapes.py). ``r``: the radii;
    ``U``: the discs' World rows (for the filters)."""
    move = X - x0
    far = np.flatnonzero(discs & (norm(move) > reach))
    if not len(far):
        return
    # The faces near each path: within half its length and the radius of its middle.
    half = 0.5 * norm(move[far])
    bi, fj = contacts.grid.pairs(x0[far] + 0.5 * move[far], r[far] + half)
    if len(fa) and len(bi):
        n_f = np.int64(len(contacts.faces.owner))
        rowed = np.sort(fa.astype(np.int64) * n_f + fk)
        keys = far[bi].astype(np.int64) * n_f + fj
        pos = np.minimum(np.searchsorted(rowed, keys), len(rowed) - 1)
        bi, fj = bi[rowed[pos] != keys], fj[rowed[pos] != keys]
    if contacts.filtering and len(bi):
        ok = contacts.allowed(U[far[bi]], fj)
        bi, fj = bi[ok], fj[ok]
    if not len(bi):
        return
    k = len(far)
    V = move[far] * (1.0 / dt)
    t, _, _ = first_hits(
        contacts.faces, x0[far], V, np.zeros((k, 2)), np.full(k, dt), r[far], bi, fj
    )
    hit = t < dt
    if hit.any():
        X[far[hit]] = x0[far[hit]] + V[hit] * t[hit, None]


def surface_slip(surface: np.ndarray, owners: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """Each row's surfaces' own motion (u_A - u_B).t (engine.exact.soft, SoftStep's ``slip``; length
    units/s) for rows whose A is the static world on collider ``owners`` (-1: a pair of
    bodies, 0) with surface velocities ``surface`` (C, 2), and normals (R, 2) from A to B:
    t = (-n_y, n_x), so u.t = u_y n_x - u_x n_y."""
    u = surface[np.maximum(owners, 0)]
    slip = u[:, 1] * normal[:, 0] - u[:, 0] * normal[:, 1]
    return np.where(owners >= 0, slip, 0.0)


#: The most pile rows the joints' solve is handed through bodies a joint's body pushes on
#: (``pushed_on``): its Newton steps solve all its rows densely, so its cost grows as their
#: cube (a seesaw under 100 balls, all handed: a step of 13 s).
PUSHED_ON_ROWS = 32


def pushed_on(joined: np.ndarray, U: np.ndarray, ra: np.ndarray, rb: np.ndarray) -> np.ndarray:
    """``joined`` (N,) grown by the bodies of a pile (``U``, its rows ra, rb; the static slot
    past U) that a body held by a joint pushes on through others, a ring of rows at a time
    while the rows handed on stay within ``PUSHED_ON_ROWS`` (the rows that touch a joint's
    body itself are handed on however many).

    The joints' solve (engine.exact.joint_solver) runs after the pile's and takes the rows it
    is handed as its own. Handed only the rows that touch a joint's body, it moved a ball on
    a bat swinging up into a heavier ball above it, which the pile's row between the two,
    left behind, did not push aside: the two ended 7 cm (27% of a radius) into each other
    for five steps (tests/test_fuzz_joints.py, two balls on a flipping bat). Handed the ball
    above too, it pushes it aside (and the motor feels its mass), as one solve would. Past
    the rings that fit, a pile keeps its own rows alone, as before (a seesaw under a heap)."""
    nU = len(U)
    inner = ra < nU  # (rows between two of the pile's bodies; the others meet the static world)
    a = np.where(inner, ra, 0)
    reach = joined[U]
    hit = reach[rb] | (inner & reach[a])
    count = int(np.count_nonzero(hit))
    while True:
        grown = reach.copy()
        grown[rb[hit]] = True
        grown[a[hit & inner]] = True
        more = grown[rb] | (inner & grown[a])
        now = int(np.count_nonzero(more))
        if now == count or now > PUSHED_ON_ROWS:
            break
        reach, hit, count = grown, more, now
    out = joined.copy()
    out[U] = reach
    return out


def components(n: int, a: np.ndarray, b: np.ndarray, fast: bool = False) -> np.ndarray:
    """The connected component of each of ``n`` bodies joined by rows (a, b), as a label
    (the least body of it; b = n, the static world, joins nothing): label propagation with
    pointer jumping, a few rounds of array operations. ``fast``: the loop kernel
    ``label_rows``, a union-find (the same labels: a component's least body is one)."""
    if fast:
        return label_rows(n, a, b)  # type: ignore[no-any-return]
    label = np.arange(n + 1)
    inner = (a < n) & (b < n)
    a, b = a[inner], b[inner]
    if not len(a):
        return label[:n]
    while True:
        low = np.minimum(label[a], label[b])
        before = label.copy()
        np.minimum.at(label, a, low)
        np.minimum.at(label, b, low)
        for _ in range(4):  # pointer jumping: each body takes its label's label
            label = label[label]
        if np.array_equal(label, before):
            return label[:n]


def _sample_labels() -> tuple[object, ...]:
    """The smallest call of ``label_rows``: two bodies joined, one on the static world."""
    return 3, np.array([0, 3]), np.array([1, 2])


@kernels.loop(sample=_sample_labels)
def label_rows(n: int, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``components`` as a loop (int64 label by body): a union-find whose root is always the
    least body of its set (a union hangs the greater root under the lesser), so the labels
    are the twin's."""
    parent = np.arange(n)  # parent[j] <= j: a chain from a body falls to its root
    for k in range(len(a)):
        i, j = a[k], b[k]
        if i >= n or j >= n:  # the static world joins nothing
            continue
        while parent[i] != i:  # the roots, halving the paths on the way
            parent[i] = parent[parent[i]]
            i = parent[i]
        while parent[j] != j:
            parent[j] = parent[parent[j]]
            j = parent[j]
        if i < j:
            parent[j] = i
        elif j < i:
            parent[i] = j
    # In body order each body's parent, a lesser body, already holds its root.
    for j in range(n):
        parent[j] = parent[parent[j]]
    return parent


@overload
def dissipative(
    V: np.ndarray,
    V0: np.ndarray,
    m: np.ndarray,
    group: np.ndarray | None = None,
    fast: bool = False,
    spins: None = None,
) -> np.ndarray: ...


@overload
def dissipative(
    V: np.ndarray,
    V0: np.ndarray,
    m: np.ndarray,
    group: np.ndarray | None,
    fast: bool,
    spins: tuple[np.ndarray, np.ndarray, np.ndarray],
) -> tuple[np.ndarray, np.ndarray]: ...


def dissipative(
    V: np.ndarray,
    V0: np.ndarray,
    m: np.ndarray,
    group: np.ndarray | None = None,
    fast: bool = False,
    spins: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None,
) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
    """The pile's velocities V (the forces alone would give V0), with the contacts' change
    scaled back if it gained kinetic energy.

    Contacts only take energy (an exact solution of resting contacts is a projection of V0
    in the mass metric, which never lengthens it; friction dissipates; restitution e <= 1
    gives back at most what the impact took), but the soft step's few iterations, and its
    push apart of an overlap, can stop short and add a little. Then the change dV = V - V0
    is scaled, in each ``group`` (a pile; by default all one), by the s in [0, 1] that leaves
    the least energy: KE(s) = KE0 + s B + s^2 C
    with B = sum m V0.dV, C = sum m |dV|^2 / 2, so s = -B / (2 C). Momentum is kept: the
    contacts' impulses between bodies are equal and opposite at any s (a wall's are not,
    and lose only what s takes off them). ``fast``: the loop kernel ``dissipate_rows``.

    ``spins``: (W, W0, I) of bodies that turn (rad/s, rad/s, kg m^2; I = 0 for one that does
    not): their energy I omega^2 / 2 counts in each sum (B += I W0 dW, ...) and dW is scaled
    with dV (the same s scales every impulse, so angular momentum is kept as momentum is);
    then (V, W) is returned.
    """
    n = len(V)
    if group is None:
        group = np.zeros(n, dtype=np.intp)
    if spins is None:
        W = W0 = inertia = np.zeros(n)
    else:
        W, W0, inertia = spins
    if fast:
        out, w_out = dissipate_rows(V, V0, m, group, W, W0, inertia)
        return out if spins is None else (out, w_out)
    dV = V - V0
    dW = W - W0
    b, c, k = m * dot(V0, dV), m * dot(dV, dV), m * dot(V0, V0)
    if spins is not None:
        # The spins' terms (0 for bodies that do not turn: x + 0.0 is x, the same bits).
        i = inertia
        b, c, k = b + i * (W0 * dW), c + i * (dW * dW), k + i * (W0 * W0)
    B = np.bincount(group, b, minlength=n)
    C = 0.5 * np.bincount(group, c, minlength=n)
    KE0 = 0.5 * np.bincount(group, k, minlength=n)
    gained = B + C > 1e-13 * KE0 + 1e-300
    if not gained.any():
        return V if spins is None else (V, W)
    s = np.ones(n)
    g = np.flatnonzero(gained)
    s[g] = np.clip(-B[g] / (2.0 * C[g]), 0.0, 1.0)
    # Only the piles that gained change: V0 + 1 dV is V only to rounding, and a pile must move
    # as if the others were not there (tests/test_fuzz_collisions.py, "as if alone").
    out = V.copy()
    sel = gained[group]
    out[sel] = V0[sel] + s[group[sel]][:, None] * dV[sel]
    if spins is None:
        return out
    w_out = W.copy()
    w_out[sel] = W0[sel] + s[group[sel]] * dW[sel]
    return out, w_out


# -- the loop kernels (engine.kernels: the fast path) -----------------------------------------
# Each does its numpy twin's products and sums in the same order, so the two paths give the
# same bits (engine.exact.pile_rows has the kernels of a pile's rows).


def _sample_dissipate() -> tuple[object, ...]:
    """The smallest call of ``dissipate_rows``: one body that gained speed."""
    z = np.zeros(1)
    return np.ones((1, 2)), np.zeros((1, 2)), np.ones(1), np.zeros(1, dtype=np.intp), z, z, z


@kernels.loop(sample=_sample_dissipate)
def dissipate_rows(
    V: np.ndarray,
    V0: np.ndarray,
    m: np.ndarray,
    group: np.ndarray,
    W: np.ndarray,
    W0: np.ndarray,
    inertia: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """``dissipative`` as a loop: each group's B, C and KE0 summed in row order (the spins'
    terms I W0 dW, ... (``inertia``: I) added to each body's as in the twin), then the rows
    of the groups that gained V0 + s dV and W0 + s dW (the others keep V and W)."""
    n = len(V)
    B, C, K = np.zeros(n), np.zeros(n), np.zeros(n)
    for i in range(n):
        g = group[i]
        dx, dy = V[i, 0] - V0[i, 0], V[i, 1] - V0[i, 1]
        dw = W[i] - W0[i]
        mi, ii = m[i], inertia[i]
        B[g] += mi * (V0[i, 0] * dx + V0[i, 1] * dy) + ii * (W0[i] * dw)
        C[g] += mi * (dx * dx + dy * dy) + ii * (dw * dw)
        K[g] += mi * (V0[i, 0] * V0[i, 0] + V0[i, 1] * V0[i, 1]) + ii * (W0[i] * W0[i])
    s = np.ones(n)
    gained = np.zeros(n, dtype=np.bool_)
    some = False
    for g in range(n):
        c = 0.5 * C[g]
        if B[g] + c > 1e-13 * (0.5 * K[g]) + 1e-300:
            gained[g] = some = True
            s[g] = min(max(-B[g] / (2.0 * c), 0.0), 1.0)
    if not some:
        return V, W
    out = V.copy()  # only the groups that gained change (as in the twin)
    w_out = W.copy()
    for i in range(n):
        if gained[group[i]]:
            sg = s[group[i]]
            out[i, 0] = V0[i, 0] + sg * (V[i, 0] - V0[i, 0])
            out[i, 1] = V0[i, 1] + sg * (V[i, 1] - V0[i, 1])
            w_out[i] = W0[i] + sg * (W[i] - W0[i])
    return out, w_out


def _sample_carry_keys() -> tuple[object, ...]:
    """The smallest call of ``carry_keys``: one row, and one a sleeper keeps."""
    k = np.array([5], dtype=np.int64)
    return k, k - 4, np.ones(2, dtype=bool), 2, 3, True


@kernels.loop(sample=_sample_carry_keys)
def carry_keys(
    key: np.ndarray, keys: np.ndarray, asleep: np.ndarray, n: int, base: int, keep: bool
) -> tuple[np.ndarray, np.ndarray]:
    """``carry_out``'s keys as a loop: (the rows' keys, then those of the carried rows the
    sleepers keep; which carried rows those are)."""
    # The carried rows the sleepers keep (``asleep_rows``): both bodies asleep, or one on a
    # face; the rows of shapes (keys from n * base on) are not kept.
    kept = np.zeros(len(keys), dtype=np.bool_)
    if keep:
        for k in range(len(keys)):
            q = keys[k]
            if q < n * base:
                a, b = q // base, q % base
                kept[k] = asleep[a] and (b >= n or asleep[b])
    m = len(key)
    out = np.empty(m + int(kept.sum()), dtype=np.int64)
    for k in range(m):  # (a loop: a slice's assignment compiles numba's mismatch message)
        out[k] = key[k]
    j = m
    for k in range(len(keys)):
        if kept[k]:
            out[j] = keys[k]
            j += 1
    return out, kept


def _sample_carry_gather() -> tuple[object, ...]:
    """The smallest call of ``carry_gather``: a row and a kept one, swapped."""
    one = np.ones(1)
    return np.array([1, 0]), one, one, 4, np.zeros(1, dtype=np.int64), np.ones((1, 2)), \
        np.zeros(1, dtype=np.int64), np.ones(1, dtype=bool)  # fmt: skip


@kernels.loop(sample=_sample_carry_gather)
def carry_gather(
    order: np.ndarray,
    lam_n: np.ndarray,
    lam_t: np.ndarray,
    iterations: int,
    color: np.ndarray,
    lam: np.ndarray,
    colors: np.ndarray,
    kept: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """``carry_out``'s impulses and colours as a loop: the rows' (over the whole step), then
    the kept carried rows', taken in ``order``."""
    m = len(lam_n)
    place = np.empty(len(order) - m, dtype=np.int64)  # each kept row's place in the carried
    j = 0
    for k in range(len(kept)):
        if kept[k]:
            place[j] = k
            j += 1
    out_lam, out_color = np.empty((len(order), 2)), np.empty(len(order), dtype=np.int64)
    for k in range(len(order)):
        o = order[k]
        if o < m:
            out_lam[k, 0], out_lam[k, 1] = lam_n[o] * iterations, lam_t[o] * iterations
            out_color[k] = color[o]
        else:
            q = place[o - m]
            out_lam[k, 0], out_lam[k, 1] = lam[q, 0], lam[q, 1]
            out_color[k] = colors[q]
    return out_lam, out_color
