"""One interface for everything a scene steps: step(dt), t, snapshot(), restore(snapshot).

Particles speak it like the World: a system saved mid-run and restored gives, step after
step, the arrays of a run never interrupted, bit for bit.
"""

from __future__ import annotations

import numpy as np
import pytest

from engine import Body, Steppable, Vector, World
from engine.forces import Drag, Gravity, Spring, Wind
from engine.particles import Particles


def _system(fast: bool = True) -> Particles:
    """Particles under gravity, a gusting wind and (general path) a spring, with lifetimes."""
    forces: list[object] = [Gravity((0.0, -9.81)), Wind(lambda t: Vector(np.sin(t), 0.0), 0.2)]
    if not fast:
        forces.append(Spring((0.0, 0.0), 3.0))
    p = Particles(500, dt=1 / 60, forces=forces, mass=0.5)
    assert p.uses_fast_path is fast
    return p


def _emit_some(p: Particles, rng: np.random.Generator) -> None:
    n = int(rng.integers(0, 40))
    p.emit(n, rng.normal(0, 3, (n, 2)), rng.normal(0, 5, (n, 2)), rng.uniform(0.1, 1.5, n), 2)


def _state(p: Particles) -> list[object]:
    """Every public number and array of ``p``, copied."""
    gone = p.expired
    return [
        p.t,
        p.steps,
        len(p),
        p.emitted,
        p.dropped,
        p.positions.copy(),
        p.velocities,
        p.ages,
        p.lifetimes.copy(),
        p.kinds.copy(),
        p.ids.copy(),
        p.positions_at(0.25),
        *gone,
    ]


def _same(a: object, b: object) -> bool:
    """Equal bit for bit: arrays by value and dtype, lists item by item, numbers by ==."""
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, np.ndarray) and isinstance(b, np.ndarray):
        return a.dtype == b.dtype and np.array_equal(a, b)
    return type(a) is type(b) and a == b


def _run(p: Particles, steps: int, seed: int) -> list[list[object]]:
    rng = np.random.default_rng(seed)
    states = []
    for _ in range(steps):
        _emit_some(p, rng)
        p.step(p.dt)
        states.append(_state(p))
    return states


@pytest.mark.parametrize("fast", [True, False], ids=["fast path", "general path"])
def test_particles_restored_mid_run_rerun_bit_for_bit(fast: bool) -> None:
    p = _system(fast)
    _run(p, 40, seed=1)  # particles born and expired: holes filled, expiries recorded
    assert p.emitted > len(p) > 0
    saved, at_save = p.snapshot(), _state(p)
    ahead = _run(p, 60, seed=2)
    assert not _same(_state(p), ahead[0])  # the run moved on
    p.restore(saved)
    assert _same(_state(p), at_save)  # the particles that expired in the last step too
    assert _same(_run(p, 60, seed=2), ahead)
    # Into a fresh system made alike: nothing of the state hides outside the snapshot.
    other = _system(fast)
    other.restore(saved)
    assert _same(_state(other), at_save)
    assert _same(_run(other, 60, seed=2), ahead)


def test_a_snapshot_is_a_copy_that_later_steps_do_not_change() -> None:
    p = _system()
    _run(p, 20, seed=3)
    saved = p.snapshot()
    before = saved.pos.copy()
    _run(p, 5, seed=4)
    np.testing.assert_array_equal(saved.pos, before)


def test_restore_refuses_what_does_not_fit_and_changes_nothing() -> None:
    p = _system()
    _run(p, 20, seed=5)
    state = _state(p)
    with pytest.raises(TypeError, match="ParticlesSnapshot"):
        p.restore(World().snapshot())  # type: ignore[arg-type]
    other_dt = Particles(500, dt=1 / 30, forces=[Gravity((0, -9.81))])
    with pytest.raises(ValueError, match=r"snapshot\.dt"):
        p.restore(other_dt.snapshot())
    small = Particles(2, dt=1 / 60)
    with pytest.raises(ValueError, match="capacity"):
        small.restore(p.snapshot())
    assert _same(_state(p), state)


def test_step_takes_the_systems_dt_and_refuses_another_naming_it() -> None:
    a, b = _system(), _system()
    for q in (a, b):
        q.emit(3, (0, 0), (1, 2), 10.0)
    a.step()
    b.step(1 / 60)
    assert _same(_state(a), _state(b))
    with pytest.raises(ValueError, match=r"dt must be this system's step, 0\.016.* got 0\.02"):
        b.step(0.02)
    assert b.steps == 1


def test_world_and_particles_speak_the_interface_and_a_plain_object_does_not() -> None:
    world = World()
    world.add(Body(0.0, 1.0, 0.0))
    assert isinstance(world, Steppable)
    assert isinstance(Particles(1), Steppable)
    assert not isinstance(object(), Steppable)

    class OnlySteps:
        t = 0.0

        def step(self, dt: float) -> None: ...

    assert not isinstance(OnlySteps(), Steppable)  # no snapshot/restore: cannot be resumed


def test_drag_only_system_also_restores() -> None:
    # A drag-only system: the fast path with no constant push.
    p = Particles(50, dt=0.01, forces=[Drag(0.3)])
    p.emit(50, (0, 0), np.linspace(-1, 1, 100).reshape(50, 2))
    saved = p.snapshot()
    ahead = [_state(p) for _ in range(10) if p.step() >= 0]
    p.restore(saved)
    assert _same([_state(p) for _ in range(10) if p.step() >= 0], ahead)


def test_a_restored_world_does_not_warn_again_about_what_it_warned_about() -> None:
    # Resuming must give the run's own warnings, no more: the stability demo shows each one.
    import warnings

    from engine import StabilityWarning

    world = World(integrator="explicit_euler")
    world.add(Body(Vector(1.0, 0.0), Vector(0.0, 1.0), Vector(0.0, 0.0)))
    world.add_force(Spring((0.0, 0.0), 1.0))
    with pytest.warns(StabilityWarning):
        world.step(0.1)
    saved = world.snapshot()
    world.step(0.1)
    world.restore(saved)
    with warnings.catch_warnings():
        warnings.simplefilter("error", StabilityWarning)
        world.step(0.1)
