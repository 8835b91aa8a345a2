"""The step pipeline: what ``World.step`` does after the fast affine kernel (engine.dynamics.affine)
declines a step, top to bottom.

1. The plan for a step of dt, made once per (dt, what the World holds): the method and its
   integrator function, whether any two bodies may collide, whether the affine kernel can
   take the steps.
2. Time: a new dt folds the time so far into the base (t = t_base + n dt, n whole).
3. Kinematic bodies given a position take the velocity that reaches it in the step.
4. The method's step (the closed form from its anchor, or the integrator), every entry
   checked finite; then the static contacts (engine.exact.contacts: the path swept for impacts),
   the contacts between bodies (engine.exact.collisions: impacts and piles), and the links
   (engine.dynamics.links: RATTLE). A step in which a linked body is struck is taken again in parts.
5. The step's contact events, and the on_contact handlers (engine.pipeline.event_dispatch).
"""

from __future__ import annotations

import math
import warnings
from typing import TYPE_CHECKING, Any

import numpy as np

from ..body import Body
from ..dynamics.affine import EULERS
from ..dynamics.forcefield import ForceModel
from ..dynamics.links import LinkSolver
from ..dynamics.rotation import Spin
from ..dynamics.store import BodyStore
from ..exact.joint_rows import Touch
from ..exact.joint_solver import JointSolver
from ..exact.pile import THRESH
from ..integrators import Integrator
from ..stability import SimulationDiverged, StabilityWarning
from . import collision_handlers, readout
from .event_dispatch import quiet, report, settle
from .game_step import unsupported

if TYPE_CHECKING:
    from ..exact.collisions import Collisions
    from .world_state import WorldState

__all__ = ["SUBSTEPS_AT_IMPACT", "Plan", "advance", "plan"]

# np.add.reduce(a, None) sums every entry without the Python wrapper of ndarray.sum.
_sum = np.add.reduce

#: How many parts a step is taken again in when a linked body is struck in it.
SUBSTEPS_AT_IMPACT = 16

#: A step's plan: (dt, the World's version, method, integrator or None, force model, affine).
Plan = tuple[float, int, str, Integrator | None, ForceModel, bool]


def plan(state: WorldState, dt: float, model: ForceModel, name: str) -> Plan:
    """The plan for steps of ``dt`` (s) by the method ``name``; kept as ``state.fast``."""
    step = None if name == "exact" else state.policy.integrator(name)
    # Either Euler method on forces that are all folded (a = a0 - c v) is a fixed
    # affine map of the state: the World takes it in four array operations.
    st = state.store
    state.pairs_on = (
        st is not None
        and st.dim == 2
        and (
            state.collisions.active(st.radius, st.group, st.categories, st.mask, st.shapes)
            or (state.contacts is not None and state.contacts.surface_velocities() is not None)
        )
    )
    affine = (
        name in EULERS
        and state.policy.custom is None
        and model.affine
        and state.contacts is None
        and not state.pairs_on
        and not state.links
        and not state.springs
        and not state.drags
        and not state.events.busy
    )
    made: Plan = (dt, state.version, name, step, model, affine)
    state.fast = made
    torques = state.torques() if st is not None and st.turns_any else None
    if torques is not None and st is not None:
        # The torques held over a step have a limit, said before the first step past it.
        touches = state.contacts is not None or state.pairs_on or bool(state.links)
        torques.warn_if_unstable(dt, state.policy.warned, 3, st.inv_moment, touches)
    return made


def _read_only(a: np.ndarray) -> np.ndarray:
    """``a``, made read only (a constant handed to every step)."""
    a.flags.writeable = False
    return a


#: No faces and no pairs ignored by pre_solve (read only: the most steps' ``ignored``).
_NONE_IGNORED = (
    _read_only(np.zeros((0, 2), dtype=np.int64)),
    _read_only(np.zeros(0, dtype=np.int64)),
)


def advance(state: WorldState, dt: float, made: Plan) -> bool:
    """Take one step of ``dt`` (s) by the plan; True: the affine kernel is ready to take it
    instead (nothing has moved yet)."""
    _, _, name, step, model, affine = made
    if state.game is not None:
        why = unsupported(state)
        if why is not None:
            raise ValueError(
                f"World(solver='soft') does not take {why} yet: make this World with "
                f"solver='exact' (nothing was stepped)"
            )
    count = state.count
    if dt != state.dt:
        # Fold the time so far into the base before counting steps of a new dt.
        state.void_budget()
        state.t_base, state.steps_base = state.t, state.steps_base + state.n
        state.n, state.dt = 0, dt
    if state.t_base + (count.n + 1) * dt == math.inf:
        raise ValueError(
            f"dt must keep the time finite: a step of dt={dt!r} s from t={state.t!r} s would "
            f"pass the float range (1.8e308 s)"
        )
    state.slept = None  # (True: every body slept through every part of the step)
    if state.links:
        state.note_link_edits()
    if state.springs:
        state.note_spring_edits()
    after = _apply_targets(state, dt) if state.targets else None
    turned = _apply_turn_targets(state, dt) if state.turn_targets else None
    store = state.store
    # Bodies that turn, or are turned by a generator, or a force applied for this step only
    # (Body.apply_force), take the general step: the affine kernel knows none of them.
    plain = store is None or not (store.spins() or store.pushes or _driven(state, store))
    if state.bodies and affine and after is None and plain:
        if state.prepare_affine(dt, model, name):
            return True
    apart = None
    ignored = _NONE_IGNORED
    if state.collision_handlers and state.bodies:
        # The pre_solve callbacks, before anything moves: the pairs they ignore are filtered
        # for this step (engine.pipeline.collision_handlers): with colliders by the contacts, pairs
        # of bodies as a joint's are (Collisions.apart).
        faces, pairs = collision_handlers.ignored_pairs(state, dt)
        ignored = (faces, pairs)
        if state.contacts is not None:
            state.contacts.set_ignored(faces)
        if len(pairs):
            apart = state.collisions.apart
            state.collisions.apart = np.union1d(apart, pairs)
    if state.bodies and state.game is not None:
        _step_soft(state, dt, name, model, ignored)
    elif state.bodies:
        _step_general(state, dt, name, step, model)
    else:
        _quiet(state)  # nothing moved: no solver reports anything
        if state.game is not None:
            state.game.emptied()
    if state.collision_handlers and state.contacts is not None:
        state.contacts.set_ignored(np.zeros((0, 2), dtype=np.int64))
    if apart is not None:
        state.collisions.apart = apart
    count.n += 1
    if store is not None and store.pushes:
        store.release_pushes()  # Body.apply_force lasts one step, as pymunk's force does
    if after is not None:
        # A kinematic body moved by pos stops there: its velocity is what it was before.
        held = state.store
        assert held is not None
        for body, v in after.items():
            held.v[held.row(body.slot)] = v
    if turned is not None:
        # ... and one turned by angle stops turning there, likewise.
        held = state.store
        assert held is not None
        for body, w in turned.items():
            held.omega[held.row(body.slot)] = w
        held.spin_written()
    if state.slept:
        # Every body slept through the step: nothing moved, so every contact open before it
        # is open after it, and none began or ended (the ledger's gaps are what they were).
        quiet(state)
        report(state)
        collision_handlers.report(state)
    elif state.contacts is not None or state.pairs_on or state.events.busy:
        # The step ran from t0 = t_base + (n - 1) dt (the time it started at, summed the
        # same way) to t.
        settle(state, state.t_base + (state.n - 1) * dt, state.t)
        report(state)
        collision_handlers.report(state)
    return False


def _step_soft(
    state: WorldState,
    dt: float,
    name: str,
    model: ForceModel,
    ignored: tuple[np.ndarray, np.ndarray],
) -> None:
    """One step by the soft-step solver (engine.pipeline.game_step), every entry checked after
    it."""
    store = state.store
    game = state.game
    assert store is not None and game is not None
    t0 = state.t
    if state.springs:
        # Kicked once a substep (engine.dynamics.solver): their limit, said before the first step
        # past it (stacklevel: the line that called World.step).
        state.springs.warn_if_unstable(
            store, dt, state.version, state.policy.warned, 5, game.substeps
        )
    accel = np.asarray(model.accel(t0, store.x, store.v), dtype=float).reshape(store.x.shape)
    torques = state.torques() if store.turns_any else None
    tau = None
    if torques is not None:
        tau = torques.at(t0, store.torque, store.angle, store.omega, store.moment)
    x, v, angle, omega = game.step(state, dt, accel, ignored[0], ignored[1], tau)
    _warn_if_sinking(state, store, game.pile, game.substeps, x, angle)
    sums = game.sums  # (the fast path's step summed them: _check_finite's and _summed's)
    if sums is not None and math.isfinite(sums[0]):
        state.huge = sums[0] > 1e100
    else:
        state.huge = _check_finite(state, x, v, name, dt, t0) > 1e100
    turned = math.isfinite(sums[1] if sums is not None else _summed(state, angle, omega))
    if not turned and not (np.isfinite(angle).all() and np.isfinite(omega).all()):
        raise SimulationDiverged(
            f"a body's angle or angular velocity is not finite after the step from t={t0!r} s "
            f"(dt={dt!r} s, solver 'soft'): the World keeps the state before it; take a "
            f"smaller dt",
            integrator=name,
            dt=dt,
            t=t0,
            max_stable_dt=None,
        )
    state.anchor = None
    store.prev_x = store.x
    store.x, store.v, store.angle, store.omega = x, v, angle, omega
    store.spin_written(None if sums is None else sums[2])


def _apply_targets(state: WorldState, dt: float) -> dict[Body, np.ndarray]:
    """Each kinematic body with a target takes the velocity that reaches it in ``dt``;
    return the velocities they had, to be given back after the step."""
    store = state.store
    assert store is not None
    before = {}
    moves = {}
    for body, target in state.targets.items():
        row = store.row(body.slot)
        with np.errstate(over="ignore", invalid="ignore"):
            v = (np.asarray(target, dtype=float) - store.x[row]) * (1.0 / dt)
        if not np.isfinite(v).all():
            del state.targets[body]
            raise ValueError(
                f"pos={target!r} of a kinematic body is too far to reach in one step of "
                f"dt={dt!r} s (the speed passes the float range): the move was dropped; "
                f"give a nearer position"
            )
        moves[row] = v
    for body in state.targets:
        row = store.row(body.slot)
        before[body] = store.v[row].copy()
        store.v[row] = moves[row]
    state.targets.clear()
    state.anchor = None
    return before


def _apply_turn_targets(state: WorldState, dt: float) -> dict[Body, float]:
    """Each kinematic body with a target angle takes the angular velocity that reaches it in
    ``dt``; return the angular velocities they had, to be given back after the step."""
    store = state.store
    assert store is not None
    before = {}
    for body, target in state.turn_targets.items():
        row = store.row(body.slot)
        w = (target - float(store.angle[row])) * (1.0 / dt)
        if not math.isfinite(w):
            state.turn_targets.clear()
            raise ValueError(
                f"angle={target!r} of a kinematic body is too far to reach in one step of "
                f"dt={dt!r} s (the angular velocity passes the float range): the turn was "
                f"dropped; give a nearer angle"
            )
        before[body] = float(store.omega[row])
        store.omega[row] = w
    store.spin_written()
    state.turn_targets.clear()
    state.anchor = None
    return before


def _quiet(state: WorldState) -> None:
    """A step in which no body moved: the solvers report nothing."""
    if state.contacts is not None:
        state.contacts.quiet()
    state.collisions.quiet()


def _step_general(
    state: WorldState, dt: float, name: str, step: Integrator | None, model: ForceModel
) -> None:
    """One step by the closed form or an integrator function, every entry checked.

    With links and contacts both in the World, a step in which a linked body is struck
    is taken again as SUBSTEPS_AT_IMPACT steps: the blow is found on each body's free
    path, which misses the links' pull within the step, so its error is second order in
    the step (engine.dynamics.links; README "Links"), and 16 times smaller steps make it 256
    times smaller where it matters, at the cost of one step's work 17 times.
    """
    store = state.store
    assert store is not None
    t0 = state.t
    t1 = state.t_base + (state.count.n + 1) * dt
    contacts = state.contacts
    if not state.links or state.substeps or (contacts is None and not state.pairs_on):
        _step_once(state, dt, name, step, model, t0, t1)
        return
    saved = (
        store.x.copy(),
        store.v.copy(),
        store.prev_x,
        state.anchor,
        state.huge,
        state.collisions.state(),
        None if contacts is None else contacts.state(),
    )
    # (A step rebinds the angle arrays, never writes into them: the references are the state.)
    spun = (store.angle, store.omega)
    _step_once(state, dt, name, step, model, t0, t1)
    if not _struck_linked(state):
        return
    store.x, store.v, store.prev_x = saved[0], saved[1], saved[2]
    store.angle, store.omega = spun
    state.anchor, state.huge = saved[3], saved[4]
    state.collisions.set_state(saved[5])
    if contacts is not None and saved[6] is not None:
        contacts.set_state(saved[6], len(store))
    k = SUBSTEPS_AT_IMPACT
    h = dt / k
    sources = [state.collisions] + ([] if contacts is None else [contacts])
    events: list[tuple[list[Any], list[Any]]] = [([], []) for _ in sources]
    state.substeps = True
    try:
        for i in range(k):
            end = t1 if i == k - 1 else t0 + (i + 1) * h
            _step_once(state, h, name, step, model, t0 + i * h, end)
            for source, (began, ended) in zip(sources, events, strict=True):
                began += source.began_arrays
                ended += source.ended_arrays
    finally:
        state.substeps = False
    for source, (began, ended) in zip(sources, events, strict=True):
        source.set_events(began, ended)
    store.prev_x = saved[0]  # drawing blends from where the whole step began


def _struck_linked(state: WorldState) -> bool:
    """Whether a linked body was struck in the last step: an impact between bodies, a
    contact with a collider that began, or a blow the joints' solve caught.

    A pair of bodies that began to touch at rest (the pile's resting contact: a ball set
    down on a bob) took no blow, and is not taken again. A blow the joints' solve caught
    (engine.exact.joint_solver: a contact it held that closed faster than the restitution
    threshold as the step began, as a flipper swung up into a falling ball) is, as an
    impact is: the README's pinball core leaves the bat at 48 cm/s sideways without it,
    26 with it.
    """
    solver = state.link_solver
    if solver is None:
        return False
    if solver.blow:
        return True
    linked = np.zeros(len(state.bodies), dtype=bool)
    linked[solver.i] = True
    linked[solver.j[solver.j >= 0]] = True
    for rows, others, *_ in state.collisions.struck_arrays if state.pairs_on else []:
        if linked[np.asarray(rows, dtype=np.intp)].any():
            return True
        if linked[np.asarray(others, dtype=np.intp)].any():
            return True
    if state.contacts is not None:
        # (The few-bodies path lists its rows as a tuple, the arrays' as an array.)
        for rows, *_ in state.contacts.began_arrays:
            if linked[np.asarray(rows, dtype=np.intp)].any():
                return True
    return False


def _step_once(
    state: WorldState,
    dt: float,
    name: str,
    step: Integrator | None,
    model: ForceModel,
    t0: float,
    t1: float,
) -> None:
    """One step of ``dt`` from time t0 to t1 (what _step_general takes, once or in parts)."""
    store = state.store
    assert store is not None
    drags = state.drags
    if drags and state.pairs_on:
        # A dragged body never sleeps: the game moves its target (engine.dynamics.mouse_joint).
        for row in drags.rows(store):
            state.collisions.wake_body(row, len(store))
    if state.pairs_on and state.collisions.all_asleep(len(store)):
        # Every body sleeps: nothing moves until something wakes them.
        store.prev_x = store.x
        state.collisions.quiet()
        if state.contacts is not None:
            state.contacts.quiet()
        if state.slept is None:
            state.slept = True
        return
    state.slept = False
    springs = state.springs
    kicks = bool(springs) and step is not None  # (the closed form holds them itself)
    v0, omega0 = store.v, store.omega
    if kicks:
        # The springs' kicks have their limit, said before the first step past it (and again
        # when a spring's stiffness changes; stacklevel: the line that called World.step).
        springs.warn_if_unstable(store, dt, state.version, state.policy.warned, 6)
        # The springs' first half kick, from the positions at the step's start
        # (engine.exact.spring_step: velocity Verlet on them, whatever the method).
        v0, omega0 = springs.kick(store, store.x, store.angle, v0, omega0, 0.5 * dt, True)
    if step is None:
        if state.anchor is None:
            state.anchor = (store.x.copy(), store.v.copy(), t0)
        x0, va, ta = state.anchor
        # Closed form from the anchor: s = s0 + v0 T + a T^2 / 2, v = v0 + a T.
        elapsed = t1 - ta
        a = model.a0
        x1 = x0 + va * elapsed + a * (0.5 * elapsed * elapsed)
        v1 = va + a * elapsed
        if springs:
            x1, v1 = _closed_springs(state, store, model, dt, x1, v1)
    elif state.huge:
        # Near overflow (a blow-up under way): numpy's own overflow warnings would
        # only come before our clear SimulationDiverged, so silence them.
        with np.errstate(over="ignore", invalid="ignore"):
            x1, v1 = step(store.x, v0, model.accel, t0, dt)
    else:
        x1, v1 = step(store.x, v0, model.accel, t0, dt)
    state.huge = _check_finite(state, x1, v1, name, dt, t0) > 1e100
    # Bodies that turn turn freely by the closed form (engine.dynamics.rotation), under their own
    # torque and the generators' (engine.dynamics.torquefield); the colliders change the spin of
    # those they touch, and bodies that meet turn each other (the exact impacts' friction and
    # the pile's lever arms: without a spin the pile's friction would act on the centres and
    # turn nothing, where a collider 50 m off would let it turn).
    spin = None
    levered = kicks and store.turns_any and springs.turn(store)  # (a lever, a rotary spring)
    levered = levered or (bool(drags) and store.turns_any and drags.turn(store))
    if (store.turns_any or store.spins()) and (
        state.contacts is not None
        or store.spins()
        or state.jointed
        or state.pairs_on
        or _driven(state, store)
        or levered
    ):
        torques = state.torques()
        if torques is None:
            spin = Spin.free(
                store.angle, omega0, store.inv_moment, store.torque, store.mass,
                store.radius, dt, None, store.kinematic,
            )  # fmt: skip
        else:
            tau = torques.at(t0, store.torque, store.angle, omega0, store.moment)
            with np.errstate(over="ignore", invalid="ignore"):  # (refused just below)
                spin = Spin.free(
                    store.angle, omega0, store.inv_moment, tau, store.mass, store.radius,
                    dt, torques.c, store.kinematic,
                )  # fmt: skip
            torques.check_finite(spin.angle, spin.omega, name, dt, t0)
    if kicks:
        # The second half kick, from where the method's step ends.
        if spin is None:
            v1, _ = springs.kick(store, x1, store.angle, v1, omega0, 0.5 * dt, False)
        else:
            v1, spin.omega = springs.kick(store, x1, spin.angle, v1, spin.omega, 0.5 * dt, False)
        state.huge = _check_finite(state, x1, v1, name, dt, t0) > 1e100
    if drags:
        # The mouse joints pull their anchors toward their targets, before the contacts, as
        # any force does (engine.dynamics.mouse_joint).
        x1, v1 = drags.pull(store, x1, v1, spin, dt)
        state.anchor = None  # (the closed form starts anew from where they leave the bodies)
    v_method = v1
    v_free = v1
    contacts = state.contacts
    pairs = state.collisions
    pull = model.a0 if step is None else (v_method - store.v) * (1.0 / dt)
    frozen = _frozen(state, store)
    if state.pairs_on:
        # Bodies tied by springs sleep as one group (engine.exact.spring_step).
        pairs.tied = springs.ties(store)
        # Which bodies are in a pile (engine.exact.collisions): the soft step takes them, from
        # the start of the step; the static contacts leave them to it.
        held = None if contacts is None else contacts.rest >= 0
        # Bodies within reach of a moving surface (a conveyor) are the soft step's too: its
        # rows carry the surface's velocity (engine.exact.soft, ``slip``).
        carried = None if contacts is None else contacts.near_moving(store, pull, dt)
        pile = pairs.plan(store.x, store.v, x1, v1, pull, dt, store, held, carried)
        if pile is not None:
            frozen = pile if frozen is None else frozen | pile
            if contacts is not None:
                contacts.rest[pile] = -1  # their faces are the pile's rows now
    if contacts is not None:
        # The path of the step is swept for impacts (engine.exact.contacts); under the closed
        # form it is the exact parabola.
        contacts.set_body_filters(store.group, store.categories, store.mask)
        x1, v1 = contacts.resolve(
            store.x,
            store.v,
            x1,
            v1,
            dt,
            t0,
            store.radius,
            store.restitution,
            store.friction,
            store.mass,
            model.a0 if step is None else None,
            frozen,
            sense=not state.pairs_on,
            spin=spin,
        )
        if contacts.moved:
            state.anchor = None  # the closed form starts anew from the changed state
        # What the static contacts did to each velocity (a resting contact's impulse).
        state.contact_dv = v1 - v_free if contacts.moved else None
    if not state.pairs_on:
        pairs.quiet()  # no pair solved: none of its reports is this step's
    sinking = False  # the pile's rows say its bodies overlap past the solver's limit
    if state.pairs_on:
        # Bodies meet one another (engine.exact.collisions) on the paths that end where the
        # method and the static contacts left them.
        A = pull
        if contacts is not None and contacts.moved:
            # A body resting on a collider is carried by it: its acceleration along the
            # path is the step's mean one.
            on = contacts.rest >= 0
            if on.any():
                A = A.copy()
                A[on] = (v1[on] - store.v[on]) * (1.0 / dt)
        # Discs that turn are turned by the impacts' friction (engine.exact.pair_bounce) and the
        # pile's by its rows' (engine.exact.soft: lever arms), from the step's start, in place on
        # the spin.
        x1, v1 = pairs.resolve(
            store.x, store.v, x1, v1, A, dt, t0, store, contacts, pull, spin=spin
        )
        if spin is None:
            spin = pairs.spun  # the impacts turned discs that stood still (or None)
        if pairs.moved:
            state.anchor = None
        if contacts is not None:
            # Where every body ended, turned as it ended (shapes meet sensors by their shape).
            shaped = pairs.shape_table(store) if pairs.has_shapes(store) else None
            turned = store.angle if spin is None else spin.angle
            contacts.sense(x1, dt, t0, store.radius, shaped, turned)
        sinking = pairs.last_overlap > _told(pairs)
    if state.links:
        kinked = None
        if v1 is not v_free:
            kinked = (v1 != v_free).any(axis=1)
        x1, v1 = _solve_links(state, store, x1, v1, dt, kinked, spin)
    if sinking:
        # The resting solver's limit: a pile too deep for its iterations sinks into itself
        # (README: "Limits of the contact solver"). Its shapes measured where they ended,
        # after the joints' solve too, before the World is told (and before it keeps the
        # step: a warning made an error leaves the state before it).
        turned = store.angle if spin is None else spin.angle
        over = pairs.ended_overlap(x1, turned, store, contacts)
        if over > _told(pairs):
            # (stacklevel: the line in World.step, as before the split)
            _tell_sinking(pairs, over, pairs.iterations, stacklevel=4)
    store.prev_x, store.x, store.v = store.x, x1, v1
    if spin is not None:
        if state.pairs_on and state.collisions.any_asleep:
            # A sleeping body stops turning where it fell asleep.
            asleep = state.collisions.asleep
            spin.angle[asleep], spin.omega[asleep] = spin.angle0[asleep], 0.0
        store.angle, store.omega = spin.angle, spin.omega
        store.spin_written()
    state.void_budget()


#: The soft step's give that is not told (a share of the smallest radius): its contacts are
#: springs, and a game's scenes press them a few percent of a radius as they land (the
#: platformer's crates and planks 5%, a pit of 1,000 balls 5% as it forms; the issue's bounds
#: for pits are 10% and 20% of a radius); a quarter of a radius is past them (the tumbler's
#: boxes 73%, a pit of 10,000 balls 26% as it forms).
SOFT_GIVE = 0.25


def _warn_if_sinking(
    state: WorldState, store: Any, pile: float, substeps: int, x: np.ndarray, angle: np.ndarray
) -> None:
    """The soft step's limit, told as the exact models' is (``_told``): two bodies that
    collide end the step (at positions ``x``, angles ``angle``) into each other past
    ``SOFT_GIVE`` of the smallest radius of a body that collides, or AGAIN times what was
    told last (Box2D's tumbler: a box falling 19 m strikes the pile and drives one box into
    another by 13 cm, half a side, where the solve's substeps carry the blow down the pile
    one contact at a time). ``pile`` (m): the deepest of the step's contacts' points moved
    with their bodies (engine.dynamics.game_continuous.ended_depth), which says when to
    measure the shapes where they ended (``readout.overlap``, as ``World.overlap``): the
    points' separations are linearised about the step's start, and a corner that turned
    through the step is deeper or shallower than its row says (a disc's on a face that turns
    is exact: engine.dynamics.turning_faces)."""
    pairs = state.collisions
    if not pile > 0.0:
        return
    # (The bodies that collide, kept as the World's bodies change: and so ``rmin``.)
    pairs.live(store.radius, store.group, store.categories, store.mask)
    told = max(SOFT_GIVE * pairs.rmin, AGAIN * pairs.warned)
    if not (pairs.rmin > 0.0 and pile > told):
        return
    over = readout.overlap(state, x, angle)
    if over > told:
        _tell_sinking(pairs, over, substeps, stacklevel=5)  # (the line that called World.step)


def _tell_sinking(pairs: Collisions, over: float, iterations: int, stacklevel: int) -> None:
    """Warn (StabilityWarning) that bodies overlap by ``over`` (length units), past what
    ``iterations`` contact iterations (the soft step's substeps) a step hold, and keep it as
    the overlap last told; ``stacklevel`` counted from the caller."""
    pairs.warned = over
    warnings.warn(
        f"bodies overlap by {over:.3g} length units "
        f"({100 * over / pairs.rmin:.0f}% of the smallest radius): "
        f"this pile is past what {iterations} contact iterations a step can "
        f"hold; raise world.contact_iterations or take a smaller dt",
        StabilityWarning,
        stacklevel=stacklevel + 1,
    )


#: A pile past the resting solver is told again where it has sunk this many times as deep as
#: the overlap last told (a pile that holds at its depth is told once; one sinking on is told
#: as it goes, a few times at most, as an overlap is bounded by the bodies' size).
AGAIN = 4.0


def _told(pairs: Collisions) -> float:
    """The overlap (length units) past which the resting solver's limit is told: 5% of the
    smallest radius, or AGAIN times what was told last."""
    return max(0.05 * pairs.rmin, AGAIN * pairs.warned)


def _closed_springs(
    state: WorldState,
    store: BodyStore,
    model: ForceModel,
    dt: float,
    x1: np.ndarray,
    v1: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """The step's end for the bodies on springs by the closed form (engine.exact.spring_step);
    where the springs stopped being linear (a damped one's ends left its line), this step
    takes the kicks around the closed form of the constant forces, and the next is planned
    again (``"auto"`` then picks an integrator; ``"exact"`` refuses)."""
    springs = state.springs
    why = state.springs_closed()
    if why is None:
        rows, xs, vs = springs.exact(store, model.a0, state.version, dt)
        x1, v1 = x1.copy(), v1.copy()
        x1[rows], v1[rows] = xs, vs
        return x1, v1
    if state.policy.requested == "exact":
        raise ValueError(
            f"integrator 'exact' moves bodies by the closed form, which holds springs only "
            f"where they are linear, and {why}; use integrator='auto' or an integrator such "
            f"as 'velocity_verlet'"
        )
    # Leave the closed form: the model is compiled again (not all constant now) and the
    # method chosen again at the next step.
    state.evaluations += model.evaluations
    state.model, state.policy.choice, state.fast, state.anchor = None, None, None, None
    h = 0.5 * dt
    a = model.a0
    v, _ = springs.kick(store, store.x, store.angle, store.v, store.omega, h, True)
    x1 = store.x + v * dt + a * (0.5 * dt * dt)
    v1, _ = springs.kick(store, x1, store.angle, v + a * dt, store.omega, h, False)
    return x1, v1


def _driven(state: WorldState, store: BodyStore) -> bool:
    """Whether a generator gives a torque (other than a drag) to a body that turns: then a
    body at rest may start to turn. A World none of whose bodies turn never asks."""
    if not store.turns_any:
        return False
    torques = state.torques()
    return torques is not None and torques.drives


def _frozen(state: WorldState, store: BodyStore) -> np.ndarray | None:
    """Bodies the static contacts leave alone: asleep, or moved by the game."""
    frozen = state.collisions.asleep if state.pairs_on and state.collisions.any_asleep else None
    kin = store.kinematic
    if kin.any():
        frozen = kin if frozen is None else frozen | kin
    return frozen


def _summed(state: WorldState, a: Any, b: Any) -> float:
    """|sum of every entry of a and b|: nan or inf whenever an entry is (or huge finite ones
    overflow it: then quietly, where the World's state is known to be huge)."""
    if state.huge:
        with np.errstate(over="ignore", invalid="ignore"):
            return abs(float(_sum(a, None) + _sum(b, None)))
    return abs(float(_sum(a, None) + _sum(b, None)))


def _check_finite(state: WorldState, x: Any, v: Any, name: str, dt: float, t: float) -> float:
    """Raise SimulationDiverged if x or v has a nan or inf; else return |sum of x and v|."""
    # A sum is nan or inf whenever any of its terms is (nan + anything = nan,
    # inf - inf = nan), so two sums check every entry. Only when one is not finite (or
    # huge finite values overflowed it) look closer. Not a BLAS dot product: OpenBLAS
    # takes milliseconds on arrays that are not 64-byte aligned, which numpy's are not.
    s = _summed(state, x, v)
    if math.isfinite(s):
        return s
    if np.isfinite(x).all() and np.isfinite(v).all():
        return math.inf
    bad = [
        f"{i}"
        for i in range(len(state.bodies))
        if not (np.isfinite(x[i]).all() and np.isfinite(v[i]).all())
    ]
    limit = state.policy.max_stable_dt(name, state.ready()) if name != "exact" else None
    if state.springs and state.store is not None and name != "exact":
        # The springs' kicks have their own limit, whatever the method.
        limit = min(math.inf if limit is None else limit, state.springs.max_stable_dt(state.store))
    hint = ""
    if limit is not None and limit < math.inf:
        hint = (
            f"; for the springs and drags held, {name} is stable only for dt < {limit:.4g} s"
            if limit > 0
            else f"; {name} is unstable at every dt for the springs held"
        )
    raise SimulationDiverged(
        f"{name} diverged in the step from t={t:g} s with dt={dt:g} s: body "
        f"{', '.join(bad[:5])}{' ...' if len(bad) > 5 else ''} would become non-finite "
        f"(nan or inf){hint}. The last finite state is kept.",
        integrator=name,
        dt=dt,
        t=t,
        max_stable_dt=limit,
    )


def _touch(
    state: WorldState, store: BodyStore, solver: JointSolver, x1: np.ndarray
) -> Touch | None:
    """The joints' discs resting on a collider as the step ends, with the impulse their
    contact gave in it (engine.exact.joint_solver: a motor's wheel rolls on that contact)."""
    pile = None
    got = state.collisions.joint_rows if state.pairs_on else None
    if got is not None:
        # The pile's contacts of the joints' bodies: they only push, and only while closing.
        body, other, n, r_body, r_other, gap_p, mu_p, pn_p, turn, poly, radius, e = got
        k = len(body)
        pile = Touch(body, other, n, r_body, r_other, np.maximum(gap_p, 0.0), mu_p, pn_p,
                     np.zeros(k), np.zeros(k, dtype=bool), turn, poly, radius, e)  # fmt: skip
    contacts = state.contacts
    if contacts is None or not len(solver.bodies):
        return pile
    rows, nrm, mu, gap = contacts.touch(solver.bodies, x1, store.radius, store.friction)
    if not len(rows):
        return pile
    dv = state.contact_dv
    p = np.zeros((len(rows), 2)) if dv is None else dv[rows] * store.mass[rows, None]
    pn = p[:, 0] * nrm[:, 0] + p[:, 1] * nrm[:, 1]
    pt = p[:, 1] * nrm[:, 0] - p[:, 0] * nrm[:, 1]  # along t = (-n_y, n_x)
    k = len(rows)
    rest = Touch(
        rows, np.full(k, -1, dtype=np.intp), nrm, -store.radius[rows, None] * nrm,
        np.zeros((k, 2)), gap, mu, pn, pt, np.ones(k, dtype=bool), np.zeros(k, dtype=np.int8),
        np.full(k, -1, dtype=np.intp), np.zeros(k), np.zeros(k),
    )  # fmt: skip
    return Touch.join([rest, pile])


def _solve_links(
    state: WorldState,
    store: BodyStore,
    x1: np.ndarray,
    v1: np.ndarray,
    dt: float,
    kinked: np.ndarray | None = None,
    spin: Spin | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Correct the step's end state for the links (engine.dynamics.links), or for the joints and
    links together (engine.exact.joint_solver: on ``spin`` too), warning once per link stretched
    past what a step can hold."""
    solver = state.link_solver
    if solver is None:
        row_of = lambda b: store.row(b.slot)  # noqa: E731
        solver = state.link_solver = (
            JointSolver(state.links, row_of, state.kernels == "fast")
            if state.jointed
            else LinkSolver(state.links, row_of)
        )
    w = np.where(store.kinematic, 0.0, 1.0 / store.mass)
    if isinstance(solver, JointSolver):
        touch = _touch(state, store, solver, x1)
        pairs = state.collisions if state.pairs_on else None
        # A contact the joints' solve catches closing bounces if it closed faster than the
        # pile's restitution threshold as the step began.
        bounce_at = math.inf if pairs is None else THRESH * pairs.rest_speed
        polygons = None if pairs is None else pairs.joint_polygons
        if spin is None:  # nothing turns: the angles stay, 1 / I = 0
            th, om, k = store.angle, store.omega, np.zeros(len(w))
            x1, v1, _, _ = solver.resolve(
                store.x, x1, v1, th, th, om, w, k, dt, kinked, touch, polygons,
                (store.v, om), bounce_at,
            )  # fmt: skip
        else:
            k = np.where(spin.turns, store.inv_moment, 0.0)
            x1, v1, spin.angle, spin.omega = solver.resolve(
                store.x, x1, v1, spin.angle0, spin.angle, spin.omega, w, k, dt, kinked, touch,
                polygons, (store.v, spin.omega0), bounce_at,
            )  # fmt: skip
        if pairs is not None and touch is not None and len(solver.held):
            # The pairs it held touching touch now, for the events, as the pile's do.
            held = solver.held[touch.other[solver.held] >= 0]
            pairs.hold_touching(touch.other[held].astype(np.int64) * len(store) + touch.body[held])
    else:
        x1, v1 = solver.resolve(store.x, x1, store.v, v1, w, dt, kinked)
    if solver.moved:
        state.anchor = None
    for link in solver.stretched:
        if not link.warned:
            link.warned = True
            what = (
                "it was put back to its length directly; take a smaller dt"
                if isinstance(solver, LinkSolver)
                else "the bodies were put back as near as the joints allow (joints that ask "
                "for what cannot all hold, such as two pins of one body, or a step too large: "
                "take a smaller dt)"
            )
            warnings.warn(
                f"{link!r} was stretched past what one step of dt={dt:g} s can pull back "
                f"along it: {what}",
                StabilityWarning,
                stacklevel=5,  # (the line in World.step, as before the split)
            )
    return x1, v1
