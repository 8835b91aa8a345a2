"""The bounce demo: it runs, the physics it shows is the closed form's, the ball is drawn there."""

from __future__ import annotations

import math

import numpy as np
import pygame
import pytest

import demos.bounce as bounce
from demos.cli import main
from engine.render import iter_frames, marks
from engine.render.recorder import draw_strobe

E = bounce.Drop.restitution  # 0.8


def exact_bottom(t: float, h0: float = bounce.H0, e: float = E, g: float = bounce.G) -> float:
    """The closed form: the height (m) of the ball's bottom at time t for a drop from h0.

    It falls for sqrt(2 h0 / g), hits at v1 = sqrt(2 g h0), and each bounce leaves at e times
    the speed it came in with, flying 2 v / g.
    """
    t_hit = math.sqrt(2.0 * h0 / g)
    if t <= t_hit:
        return h0 - 0.5 * g * t * t
    v = e * math.sqrt(2.0 * g * h0)
    while t > t_hit + 2.0 * v / g:
        t_hit += 2.0 * v / g
        v *= e
    s = t - t_hit
    return v * s - 0.5 * g * s * s


def impact_times(
    h0: float = bounce.H0, e: float = E, g: float = bounce.G, n: int = 30
) -> list[float]:
    t = math.sqrt(2.0 * h0 / g)
    v = e * math.sqrt(2.0 * g * h0)
    times = [t]
    for _ in range(n):
        t += 2.0 * v / g
        v *= e
        times.append(t)
    return times


def test_the_demo_runs_headless_and_writes_each_scenes_frames(tmp_path, capsys) -> None:
    out = tmp_path / "bounce"
    assert (
        main(["bounce", "--fps", "5", "--seconds", "1", "--size", "480x270", "--out", str(out)])
        == 0
    )
    for scene in ("drop", "tunnel", "drift"):
        frames = sorted((out / scene).glob("frame_*.png"))
        assert len(frames) == 6, scene  # t = 0, 0.2, ..., 1 s
        assert pygame.image.load(str(frames[-1])).get_size() == (480, 270)
    assert "bounce/drift: wrote 6 frames" in capsys.readouterr().out
    assert main(["bounce", "--strobe", "--out", str(out), "--overwrite"]) == 0
    assert (out / "drop" / "strobe.png").is_file() and (out / "tunnel" / "strobe.png").is_file()


def test_the_apexes_it_labels_are_h0_e_2n_and_the_energy_steps_down_by_e2() -> None:
    drop = bounce.Drop()
    assert drop.world.method == "exact"
    while drop.t < bounce.DropScene.duration:
        drop.step(bounce.DT)
    heights = [h for _, h in drop.apexes]
    assert len(heights) >= 10
    for n, h in enumerate(heights[:10], 1):
        assert h == pytest.approx(bounce.H0 * E ** (2 * n), rel=1e-9, abs=0.0)
    # Each apex is labelled at its time: the top of the n-th flight in the closed form.
    hits = impact_times()
    for n, (t, _) in enumerate(drop.apexes[:10], 1):
        assert t == pytest.approx(0.5 * (hits[n - 1] + hits[n]), rel=1e-9)
    # Between bounces the energy is E0 e^(2n): sampled at every step of the n-th flight.
    e0 = bounce.G * bounce.H0
    for t, _, energy in drop.samples:
        n = sum(1 for hit in hits if hit < t)
        if all(abs(t - hit) > 1e-9 for hit in hits) and n <= 10:
            assert energy == pytest.approx(e0 * E ** (2 * n), rel=1e-9)
    assert drop.bounces[:10] == pytest.approx(hits[:10], rel=1e-12)


def test_the_discrete_ball_passes_the_thin_wall_and_the_engines_bounces() -> None:
    tunnel = bounce.Tunnel()
    for _ in range(8):
        tunnel.step(bounce.TunnelScene.dt)
    r = tunnel.radius
    # The discrete check never saw an overlap: every step's centre is more than r off the
    # wall at x = 0, the ball went from x < 0 to x > 0, and it keeps its 200 m/s.
    xs = [x for x, _ in tunnel.naive_path]
    assert all(abs(x) > r for x in xs) and not tunnel.naive.hit_wall
    assert xs[0] < 0.0 < xs[-1] and tunnel.naive.vx == 200.0
    # The engine's ball hit at the exact moment (11.9 m at 200 m/s) and left at the same speed.
    (t_hit, x_hit, _), *more = tunnel.impacts
    assert not more
    assert t_hit == pytest.approx((-tunnel.start - r) / tunnel.speed, rel=1e-12)
    assert abs(x_hit) < 1e-12  # on the wall
    assert all(x <= -r for x, _ in tunnel.engine_path)
    assert tunnel.ball.vel.x == pytest.approx(-200.0, rel=1e-9)
    assert tunnel.ball.pos.x == pytest.approx(-r - 200.0 * (8 * bounce.DT - t_hit), rel=1e-9)


def test_with_e_1_the_discrete_apexes_climb_and_the_engines_stay_at_h0() -> None:
    drift = bounce.Drift()
    while drift.t < bounce.DriftScene.duration:
        drift.step(bounce.DT)
    engine = [h for _, h in drift.apexes["engine"]]
    naive = [h for _, h in drift.apexes["naive"]]
    assert len(engine) >= 4 and len(naive) >= 4
    assert engine == pytest.approx([bounce.H0] * len(engine), rel=1e-9)
    assert naive[0] > bounce.H0 + 0.01
    assert all(b > a for a, b in zip(naive, naive[1:], strict=False))  # it gains every bounce
    *_, naive_energy, engine_energy = drift.samples[-1]
    assert naive_energy > 1.05 and engine_energy == pytest.approx(1.0, rel=1e-9)


def test_the_ball_is_drawn_where_the_closed_form_puts_it() -> None:
    scene = bounce.DropScene()
    size = (640, 360)
    hits = impact_times()
    checked = 0
    for _index, t, surface in iter_frames(scene, fps=10, seconds=6.0, size=size):
        if min(abs(t - hit) for hit in hits) < 2 * bounce.DT:
            continue  # a frame within a bounce step is a blend across the impact
        pixels = pygame.surfarray.pixels3d(surface)
        mask = np.all(pixels == bounce.BALL, axis=2)
        del pixels
        xs, ys = np.nonzero(mask)
        radius = scene.camera.length(bounce.Drop.radius)
        assert abs(len(xs) - math.pi * radius * radius) < 0.25 * math.pi * radius * radius
        centre = np.array([xs.mean(), ys.mean()])
        want = scene.camera.to_px(0.0, exact_bottom(t) + bounce.Drop.radius)
        assert np.abs(centre - np.array(want)).max() < 1.0, t
        checked += 1
    assert checked >= 50


def test_the_drop_strobe_spreads_the_balls_by_time_and_labels_each() -> None:
    # The balls overlapped each other, hid the n = 2 and n = 3 apex labels and carried no time.
    scene = bounce.DropScene()
    size = (640, 360)
    scene.build(size)
    surface = pygame.Surface(size)
    draw_strobe(scene, surface)
    found = marks.marks(surface)
    balls = [m.rect for m in found if m.kind == "marker"]
    times = [t for t in scene.strobe_times() if t <= 4.0]
    assert len(balls) == len(times) == 17
    for i, a in enumerate(balls):
        assert a.collidelist(balls[i + 1 :]) < 0, i  # no ball on another
    texts = [m.text for m in found if m.kind == "text"]
    assert [f"{t:g}" for t in times] == [x for x in texts if x in {f"{t:g}" for t in times}]
    assert {"h0 = 10 m", "n=1: 6.40 m", "n=2: 4.10 m", "n=3: 2.62 m"} <= set(texts)
    assert marks.problems(surface) == []  # no label on a ball, on a label, or cut


def test_the_drift_frame_lists_every_apex_numbered() -> None:
    # Only the last 3 apexes were kept, unnumbered: by frame 450 the 10.077 m and 10.313 m
    # apexes of the discrete check were gone.
    scene = bounce.DriftScene()
    for _, t, surface in iter_frames(scene, fps=30, size=(640, 360), only={450}):
        texts = [m.text for m in marks.marks(surface)]
        for name in ("naive", "engine"):
            heights = [h for ta, h in scene.drift.apexes[name] if ta <= t]
            assert len(heights) == 5
            shown = [f"{h:.3f} m" for h in heights]
            assert [x for x in texts if x in shown] == shown, name
        column = [m.text for m in marks.marks(surface) if m.rect.right < scene.column]
        assert [x for x in column if x.isdigit()] == ["1", "2", "3", "4", "5"]
        assert "10.077 m" in texts and "10.313 m" in texts
        assert marks.problems(surface) == []
