"""Fuzzing the World and the fixed-step loop: no nan enters a World silently.

Every accepted call leaves the World's positions, velocities and time finite; every refused
call is a TypeError / ValueError naming its argument, and changes nothing. A step may also
end in SimulationDiverged (the documented outcome when forces drive the state to overflow),
which keeps the last finite state.

Examples per test: World constructor 400, World call sequences 1200, restore 300,
FixedStep/VirtualClock 1000. This file: 2,900. All fuzz files: test_fuzz_core 6,200 +
test_fuzz_world 2,900 + test_fuzz_particles 900 + test_fuzz_render 900 + test_fuzz_cli 1,100
= 12,000 generated calls (most examples make several calls).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from fractions import Fraction
from typing import Any

import numpy as np
from fuzzing import (
    anything,
    attempt,
    check_message,
    fuzz,
    in_float_range,
    is_real,
    junk,
    moderate,
    numbers,
    pairs,
)
from hypothesis import given
from hypothesis import strategies as st

from engine import Body, FixedStep, SimulationDiverged, Vector, VirtualClock, World
from engine.forces import CallableForce, ConstantForce, Drag, Gravity, Spring, Wind
from engine.world import METHODS


def assert_finite(world: World) -> None:
    """The World's whole state is finite: positions (now and blended), velocities, time."""
    assert np.isfinite(world.positions()).all(), world.positions()
    assert np.isfinite(world.positions(0.0)).all()
    assert np.isfinite(world.velocities()).all(), world.velocities()
    assert math.isfinite(world.t) and world.t >= 0.0
    assert isinstance(world.steps, int) and world.steps >= 0


def fingerprint(world: World) -> tuple[Any, ...]:
    return (
        world.positions().tobytes(),
        world.positions(0.0).tobytes(),
        world.velocities().tobytes(),
        world.t,
        world.steps,
        len(world.bodies),
        len(world.forces),
    )


@fuzz(400)
@given(integrator=st.one_of(st.sampled_from(METHODS), anything), tolerance=anything)
def test_world_constructor_names_a_bad_integrator_or_tolerance(
    integrator: Any, tolerance: Any
) -> None:
    ok, world = attempt(lambda: World(integrator, tolerance), "integrator", "tolerance")
    if ok:
        assert world is not None
        assert_finite(world)
        valid_name = integrator in METHODS or callable(integrator)
        assert valid_name
        assert tolerance is None or (integrator == "auto" and 0 < float(tolerance) < math.inf)


# One operation on the world: a name and up to two generated arguments.
OPERATIONS = (
    "add",
    "add_junk",
    "add_force",
    "add_force_to",
    "step",
    "step_many",
    "positions",
    "position_of",
    "set_pos",
    "set_vel",
    "set_own_acc",
    "set_mass",
    "remove",
    "snapshot_restore",
    "choose_method",
    "energy",
)

FORCE_MAKERS = (
    lambda a: Gravity(a),
    lambda a: ConstantForce(a),
    lambda a: Drag(a),
    lambda a: Wind(a, 0.5),
    lambda a: Spring(a, 4.0),
    lambda a: Spring((0.0, 0.0), a),
    # A user's force that returns nan or inf (or a huge number) at every call.
    lambda a: CallableForce(
        lambda t, x, v, m: v * 0.0 + (float(a) if is_real(a) and in_float_range(a) else 0.0)
    ),
    lambda a: a,  # not a force at all
)

state_like = st.one_of(numbers, pairs, junk, st.tuples(moderate, moderate), moderate)
op_args = st.tuples(
    st.sampled_from(OPERATIONS),
    st.one_of(state_like, anything),
    st.one_of(state_like, anything),
    st.integers(0, len(FORCE_MAKERS) - 1),
)


def _apply(world: World, op: str, a: Any, b: Any, maker: int) -> None:
    bodies = world.bodies
    target = bodies[0] if bodies else Body(0.0, 0.0, 0.0)
    if op == "add":
        body = Body(a, b, 0.0 if is_real(a) else (0.0, 0.0))
        world.add(body)
    elif op == "add_junk":
        world.add(a)
    elif op in ("add_force", "add_force_to"):
        force = FORCE_MAKERS[maker](a)
        world.add_force(force, bodies=b if op == "add_force_to" else None)
    elif op == "step":
        world.step(a)
    elif op == "step_many":
        for _ in range(20):
            world.step(1 / 120)
    elif op == "positions":
        world.positions(a)
    elif op == "position_of":
        world.position_of(a if not bodies else bodies[-1], b)
    elif op.startswith("set_"):
        setattr(target, op[4:], a)
    elif op == "remove":
        world.remove(a if not bodies or is_real(a) else bodies[0])
    elif op == "snapshot_restore":
        snap = world.snapshot()
        world.step(1 / 60)
        world.restore(snap)
    elif op == "choose_method":
        world.choose_method(a)
    elif op == "energy":
        world.energy()


NAMES = {
    "add": ("position", "velocity", "acceleration", "body", "mix"),
    "add_junk": ("body",),
    "add_force": ("force", "g", "f", "k", "air_velocity", "anchor", "world is", "1d", "2d"),
    "add_force_to": (
        "force",
        "bodies",
        "g",
        "f",
        "k",
        "air_velocity",
        "anchor",
        "world is",
        "1d",
        "2d",
    ),
    "step": ("dt",),
    "step_many": ("dt",),
    "positions": ("alpha",),
    "position_of": ("alpha", "body"),
    "set_pos": ("pos",),
    "set_vel": ("vel",),
    "set_own_acc": ("own_acc",),
    "set_mass": ("mass",),
    "remove": ("body",),
    "snapshot_restore": ("snapshot",),
    "choose_method": ("dt",),
    "energy": ("energy",),
}


@fuzz(1200)
@given(
    integrator=st.sampled_from(METHODS),
    ops=st.lists(op_args, min_size=1, max_size=10),
)
def test_any_sequence_of_calls_leaves_the_world_finite_or_is_refused_by_name(
    integrator: str, ops: list[tuple[str, Any, Any, int]]
) -> None:
    world = World(integrator)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # StabilityWarning for stiff generated springs
        for op, a, b, maker in ops:
            before = fingerprint(world)
            try:
                _apply(world, op, a, b, maker)
            except SimulationDiverged as exc:
                # Forces drove the state past the float range: the last finite state is kept.
                assert op in ("step", "step_many", "snapshot_restore")
                assert "dt=" in str(exc) and "last finite state is kept" in str(exc)
            except (TypeError, ValueError) as exc:
                check_message(exc, NAMES[op])
                if op in ("step", "positions", "position_of", "choose_method", "set_pos"):
                    assert fingerprint(world) == before, (op, a, exc)
            assert_finite(world)


@fuzz(300)
@given(
    field=st.sampled_from(
        ["x", "v", "prev_x", "masses", "own_acc", "t_base", "dt", "n_since_base", "steps"]
    ),
    value=st.one_of(
        anything,
        st.sampled_from(
            [
                np.array([math.nan]),
                np.array([[math.inf, 0.0]]),
                np.zeros((1, 2)),
                np.zeros((2, 2)),
                np.zeros(1),
                (math.nan,),
                (-1.0,),
                (Vector(math.nan, 0.0),),
                (Vector(1.0, 2.0),),
                -1,
                2**70,
            ]
        ),
    ),
)
def test_restore_refuses_a_tampered_snapshot_by_name(field: str, value: Any) -> None:
    # A WorldSnapshot is a plain dataclass: a caller can build or alter one. restore must not
    # let nan, inf, a wrong shape or a nonsense count or time into the World.
    world = World()
    body = world.add(Body(Vector(1.0, 2.0), Vector(0.5, 0.0), Vector(0.0, -1.0)))
    for _ in range(3):
        world.step(1 / 60)
    snap = dataclasses.replace(world.snapshot(), **{field: value})
    world.step(1 / 60)
    before = fingerprint(world)
    ok, _ = attempt(lambda: world.restore(snap), field, "snapshot")
    if not ok:
        assert fingerprint(world) == before  # a refused snapshot changes nothing
    assert_finite(world)
    assert body.mass > 0 and math.isfinite(body.mass)
    assert Vector.coerce(body.own_acc).is_finite()
    world.step(1 / 60)
    assert_finite(world)


@fuzz(1000)
@given(
    dt=st.one_of(numbers, junk, st.fractions(min_value=Fraction(1, 10**6), max_value=1)),
    max_frame=st.one_of(st.just(0.25), numbers, junk),
    fps=st.one_of(st.integers(-5, 10**6), numbers, junk),
    frames=st.lists(st.one_of(numbers, junk, st.floats(0, 1)), max_size=6),
)
def test_fixed_step_and_virtual_clock_keep_whole_steps_and_alpha_in_0_1(
    dt: Any, max_frame: Any, fps: Any, frames: list[Any]
) -> None:
    ok, clock = attempt(lambda: VirtualClock(fps), "fps")
    if ok:
        assert clock is not None
        assert isinstance(fps, int) and not isinstance(fps, bool) and fps > 0
        assert clock.tick() == Fraction(1, fps) and clock.frames == 1
    ok, loop = attempt(lambda: FixedStep(dt, max_frame), "dt", "max_frame")
    if not ok:
        return
    assert loop is not None
    assert 0.0 < loop.dt < math.inf and loop.max_frame >= loop.dt * (1 - 1e-15)
    for frame in frames:
        steps_before, t_before = loop.steps, loop.t
        ok, steps = attempt(lambda f=frame: loop.advance(f), "frame_seconds")
        if not ok:
            assert (loop.steps, loop.t) == (steps_before, t_before)
            continue
        assert isinstance(steps, int) and steps >= 0
        assert loop.steps == steps_before + steps
        assert 0.0 <= loop.alpha < 1.0
        assert 0.0 <= loop.accumulated and math.isfinite(loop.t) and loop.t >= t_before
        assert loop.dropped >= 0.0
