"""World(solver="auto"): the soft step for a scene with bodies with corners, the exact models
for discs and points (engine.pipeline.solver_choice), chosen at the first step and said."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from engine import Body, Circle, Polygon, SolverWarning, Vector, World
from engine.forces import Gravity
from tests.paths import PATHS
from tests.rigid_scenes import measure_hello_world


def _drop(
    solver: str, shape: object, kernels: str = "numpy", iterations: int = 4, steps: int = 90
) -> World:
    """A body of ``shape`` (None: a 0.5 m disc) dropped from 4 m onto a floor, ``steps``
    steps."""
    w = World(integrator="auto", kernels=kernels, solver=solver)
    w.contact_iterations = iterations
    w.add_force(Gravity((0.0, -10.0)))
    w.add_collider(Polygon.box(100.0, 20.0, center=(0.0, -10.0), restitution=0.5, friction=1.0))
    radius = 0.5 if shape is None else 0.0
    w.add(Body(Vector(0.3, 4.0), shape=shape, radius=radius, mass=4.0, restitution=0.5))
    for _ in range(steps):
        w.step(1 / 60)
    return w


def _state(w: World) -> np.ndarray:
    b = w.bodies[0]
    return np.array([b.position.x, b.position.y, b.velocity.x, b.velocity.y, b.angle])


@pytest.mark.parametrize("kernels", PATHS)
def test_a_crate_chooses_the_soft_step_and_passes_box2ds_hello_world(kernels: str) -> None:
    auto = measure_hello_world(f"auto-{kernels}")
    soft = measure_hello_world(f"soft-{kernels}")
    assert auto == soft  # the same step, bit for bit
    # Box2D's own bounds (test/test_world.c), which the exact solver misses (x = -0.025).
    assert abs(auto.x) < 0.01 and abs(auto.y - 1.0) < 0.01 and abs(auto.angle) < 0.01
    w = _drop("auto", Polygon.box(2.0, 2.0), kernels)
    assert w.solver == "soft"
    assert w.solver_reason.startswith("auto, chosen at the first step: the soft step")
    assert "Polygon" in w.solver_reason


@pytest.mark.parametrize("kernels", PATHS)
def test_a_ball_chooses_the_exact_models_and_moves_as_they_do(kernels: str) -> None:
    auto = _drop("auto", None, kernels)
    exact = _drop("exact", None, kernels)
    assert auto.solver == "exact" and np.array_equal(_state(auto), _state(exact))
    assert "round" in auto.solver_reason
    # And not as the soft step would have moved it: the choice is felt. (At rest after 90
    # steps both have the ball still on the floor; in flight after its first bounce, at 60,
    # the two differ by 0.13 m/s, measured.)
    early = _drop("auto", None, kernels, steps=60)
    assert not np.array_equal(_state(early), _state(_drop("soft", None, kernels, steps=60)))


def test_the_soft_step_it_chooses_takes_the_worlds_contact_iterations_as_substeps() -> None:
    box = Polygon.box(2.0, 2.0)
    auto, soft = _drop("auto", box, iterations=8), _drop("soft", box, iterations=8)
    assert np.array_equal(_state(auto), _state(soft))
    assert not np.array_equal(_state(auto), _state(_drop("soft", box, iterations=4)))


def test_before_the_first_step_the_choice_follows_the_scene_then_it_is_kept() -> None:
    w = World(solver="auto")
    assert w.solver == "exact" and w.solver_reason.startswith("auto, before the first step")
    w.add(Body(Vector(0.0, 0.0), radius=0.5))
    assert w.solver == "exact"
    crate = w.add(Body(Vector(3.0, 0.0), shape=Polygon.box(1.0, 1.0)))
    assert w.solver == "soft"
    w.remove(crate)
    assert w.solver == "exact"
    w.step(1 / 60)
    assert w.solver_reason.startswith("auto, chosen at the first step: the exact models")
    # A crate added once the World moves: the exact models stay, and it is said once, at the
    # game's own line.
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        w.add(Body(Vector(6.0, 0.0), shape=Polygon.box(1.0, 1.0)))
        w.step(1 / 60)
        w.add(Body(Vector(9.0, 0.0), shape=Polygon.box(1.0, 1.0)))
        w.step(1 / 60)
    said = [c for c in caught if issubclass(c.category, SolverWarning)]
    assert len(said) == 1 and said[0].filename == __file__
    assert "World(solver='soft')" in str(said[0].message)
    assert w.solver == "exact"


def test_what_contacts_do_not_push_does_not_choose() -> None:
    """A kinematic paddle and a static crate (a Pin holds none here) are moved by the game:
    with a ball, the scene is breakout's, and keeps the exact models."""
    w = World(solver="auto")
    w.add(Body(Vector(0.0, 0.0), radius=0.25))
    w.add(Body(Vector(0.0, -2.0), shape=Polygon.box(2.0, 0.3), kinematic=True))
    w.add_collider(Polygon.box(1.0, 1.0, center=(5.0, 0.0)))
    w.add_collider(Circle((8.0, 0.0), 1.0))
    assert w.solver == "exact"


def test_the_default_chooses_and_a_body_nothing_can_touch_keeps_the_exact_models() -> None:
    """World() is World(solver="auto"). A box that no contact could push (alone in space, a
    filter that meets no collider, a joint keeping it from its one neighbour, a sensor) keeps
    the exact models: its spin and its joints stay exact; a floor it meets chooses the soft
    step."""
    from engine import Filter, Hinge, Plane

    def box(w: World, x: float, **kw: object) -> Body:
        return w.add(Body(Vector(x, 2.0), shape=Polygon.box(1.0, 1.0), **kw))  # type: ignore[arg-type]

    w = World()
    assert w.solver_reason.startswith("auto, before the first step")
    box(w, 0.0)
    assert w.solver == "exact"  # alone in space: nothing can push it
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    assert w.solver == "soft" and "Polygon" in w.solver_reason
    w2 = World()  # a filter that meets no collider
    w2.add_collider(Plane((0.0, 0.0), (0.0, 1.0), filter=Filter(categories=0b10, mask=0b10)))
    box(w2, 0.0, filter=Filter(categories=0b01, mask=0b01))
    assert w2.solver == "exact"
    w3 = World()  # two planks hinged, kept apart by their joint (collide=False)
    a, b = box(w3, 0.0), box(w3, 1.0)
    w3.add_link(Hinge(a, b, (0.5, 2.0)))
    assert w3.solver == "exact"
    box(w3, 3.0)  # a third, which no joint keeps from them
    assert w3.solver == "soft"
    w4 = World()  # a sensor box on a floor pushes nothing and nothing pushes it
    w4.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    box(w4, 0.0, sensor=True)
    assert w4.solver == "exact"


def test_a_1d_world_keeps_the_exact_models() -> None:
    w = World(solver="auto")
    w.add(Body(0.0, 1.0))
    w.step(0.1)
    assert w.solver == "exact" and "1D" in w.solver_reason


def test_a_solver_asked_for_is_said_so() -> None:
    for name in ("exact", "soft"):
        w = World(solver=name)
        assert w.solver == name and w.solver_reason == f"asked for: World(solver={name!r})"


@pytest.mark.parametrize("bad", ["Soft", "", None, 1])
def test_an_unknown_solver_is_refused_naming_the_choices(bad: object) -> None:
    with pytest.raises(ValueError, match=r"solver must be 'exact'.*'soft'.*'auto'.*got"):
        World(solver=bad)  # type: ignore[arg-type]


def test_a_copy_and_a_snapshot_keep_the_choice_and_the_motion() -> None:
    w = World(solver="auto", integrator="auto")
    w.add_force(Gravity((0.0, -10.0)))
    w.add_collider(Polygon.box(100.0, 20.0, center=(0.0, -10.0), restitution=0.0))
    w.add(Body(Vector(0.0, 2.0), shape=Polygon.box(1.0, 1.0), mass=1.0))
    for _ in range(30):
        w.step(1 / 60)
    twin, saved = w.copy(), w.snapshot()
    for _ in range(30):
        w.step(1 / 60)
        twin.step(1 / 60)
    assert twin.solver == "soft" and np.array_equal(_state(twin), _state(w))
    end = _state(w)
    w.restore(saved)
    for _ in range(30):
        w.step(1 / 60)
    assert np.array_equal(_state(w), end)


def test_a_soft_only_joint_chooses_the_soft_step_and_one_added_later_is_refused() -> None:
    from engine import GearJoint

    w = World(solver="auto")
    a = w.add(Body(Vector(0.0, 0.0), radius=0.5))
    b = w.add(Body(Vector(2.0, 0.0), radius=0.5))
    gear = w.add_link(GearJoint(a, b, 0.0, 2.0))
    assert w.solver == "soft" and "GearJoint" in w.solver_reason
    w.remove_link(gear)
    w.step(1 / 60)
    assert w.solver == "exact"
    with pytest.raises(ValueError, match=r"solver='auto' chose them at its first step"):
        w.add_link(GearJoint(a, b, 0.0, 2.0))
    assert w.links == ()
