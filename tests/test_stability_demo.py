"""The stability lesson's frames: the engine's warning and error text are drawn, each method
behaves as theory says, and no frame ever holds a non-finite position."""

from __future__ import annotations

import math

import numpy as np
import pytest

from demos.stability import METHODS, OMEGA, LimitsScene, OrbitsScene, wrap
from engine.render import iter_frames as frames


def _finite_frame(scene: LimitsScene | OrbitsScene) -> None:
    assert scene.drawn_positions
    assert np.isfinite(np.asarray(scene.drawn_positions)).all()
    for world, _ in scene.worlds.values():
        assert np.isfinite(world.positions()).all() and np.isfinite(world.velocities()).all()


def test_limits_scene_shows_the_warning_then_the_error_for_every_method() -> None:
    scene = LimitsScene()
    seen: dict[str, set[str]] = {m: set() for m in METHODS}
    for _, _, surface in frames(scene, fps=10, size=(640, 360)):
        _finite_frame(scene)
        if scene.latest is not None:
            method, message = scene.latest
            assert message.split(":")[0] in ("StabilityWarning", "SimulationDiverged")
            # The whole message is on the frame, wrapped: its lines were drawn in order.
            lines = wrap(message, 15, surface.get_width() - 24)
            shown = [t for t in scene.drawn_text if t in lines]
            if shown == lines:
                seen[method].add(message.split(":")[0])
    for method in METHODS:
        assert seen[method] == {"StabilityWarning", "SimulationDiverged"}, (method, seen)
        assert scene.status[method] == "diverged"


def test_limits_scene_warns_only_past_each_limit() -> None:
    scene = LimitsScene()
    scene.build((640, 360))
    while scene.status["rk4"] == "stable":
        before = scene.omega_dt
        scene.step(scene.dt)
        for method in ("semi_implicit_euler", "velocity_verlet"):
            if scene.status[method] != "stable":
                assert scene.omega_dt > 2.0
        if scene.omega_dt < 2.0:
            assert scene.status["semi_implicit_euler"] == "stable"
    assert scene.omega_dt > 2 * math.sqrt(2) and before <= scene.omega_dt
    assert scene.status["explicit_euler"] != "stable"  # no stable dt on a spring at all


def test_orbits_energy_follows_theory() -> None:
    scene = OrbitsScene()
    for _ in frames(scene, fps=10, size=(640, 360)):
        _finite_frame(scene)
    y = OMEGA * scene.dt
    e = {m: np.array([v for _, v in scene.energy[m]]) for m in METHODS}
    n = np.arange(len(e["explicit_euler"]))
    # Explicit Euler: energy multiplied by exactly 1 + (omega dt)^2 each step (the README's
    # "Choosing an integrator" table).
    assert e["explicit_euler"] == pytest.approx((1 + y * y) ** n, rel=1e-9)
    # Symplectic methods: bounded, within the modified-energy band of width ~omega dt.
    assert np.all(np.abs(e["semi_implicit_euler"] - 1) < y)
    assert np.all(np.abs(e["velocity_verlet"] - 1) < y * y / 2)
    # RK4: loses energy slowly and steadily, by |R(i omega dt)|^2 a step.
    r2 = (1 - y**2 / 2 + y**4 / 24) ** 2 + (y - y**3 / 6) ** 2
    assert e["rk4"] == pytest.approx(r2**n, rel=1e-9)
    assert e["rk4"][-1] < 0.99


def test_frames_are_not_flat() -> None:
    for scene in (OrbitsScene(), LimitsScene()):
        for index, _, surface in frames(scene, fps=2, seconds=2.0, size=(640, 360)):
            if index == 2:
                import pygame

                pixels = pygame.surfarray.array3d(surface).reshape(-1, 3)
                assert len(np.unique(pixels, axis=0)) > 10


def test_orbits_frames_show_each_method_at_its_last_step_with_the_time() -> None:
    # Frames 0 to 2 (t < dt = 0.1 s) drew the ball at its start while the read-out and the
    # energy plot already said E/E0 = 1.39 (explicit Euler), 1.08, 0.999: the next step's.
    from engine.render import marks

    scene = OrbitsScene()
    y = OMEGA * scene.dt
    seen = {}
    for k, t, surface in frames(scene, fps=30, seconds=0.2, size=(640, 360)):
        texts = [m.text for m in marks.marks(surface)]
        steps = math.floor(t / scene.dt + 1e-9)  # the steps taken by the frame's time
        assert f"t = {t:.2f} s: step {steps}" in texts, (k, texts)
        readouts = [x for x in texts if x.startswith("E/E0 = ")]
        assert len(readouts) == 4
        seen[k] = readouts
        # Explicit Euler's energy is exactly (1 + (omega dt)^2)^n after n steps.
        assert readouts[0] == f"E/E0 = {(1 + y * y) ** steps:.3g}", (k, readouts)
        # The ball is where explicit Euler has it after those steps: no blend, none ahead.
        x, v = np.array([1.0, 0.0]), np.array([0.0, OMEGA])
        for _ in range(steps):
            x, v = x + v * scene.dt, v - OMEGA * OMEGA * x * scene.dt
        assert scene.drawn_positions[0] == pytest.approx(tuple(x), abs=1e-12), k
        assert marks.problems(surface) == []
    assert seen[0] == seen[1] == seen[2] == ["E/E0 = 1"] * 4
    assert seen[3] == ["E/E0 = 1.39", "E/E0 = 1.08", "E/E0 = 1", "E/E0 = 0.999"]


def test_limits_marker_of_omega_dt_never_covers_a_limits_name() -> None:
    # At frame 173 (omega dt = 2.4) the marker covered "Euler, Verlet: 2".
    from engine.render import marks

    scene = LimitsScene()
    for k, _, surface in frames(scene, fps=30, size=(640, 360), only={173, *range(0, 346, 9)}):
        found = marks.marks(surface)
        (marker,) = [m for m in found if m.text == "omega dt now"]
        names = [m for m in found if m.text in ("Euler, Verlet: 2", "RK4: 2.83")]
        assert len(names) == 2
        assert not any(marker.rect.colliderect(n.rect) for n in names), k
        assert marks.problems(surface) == [], k
