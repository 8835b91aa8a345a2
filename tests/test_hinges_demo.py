"""The hinges demo: a rod on a hinge swings with the exact elliptic period of a point pendulum
of 2L/3, a chain of planks holds every hinge, a car on motors climbs (a few percent short of
its closed form, as its docstring says); the frames checked by their pixels.

Each scene is run once per module (a few seconds in all) and its frames kept for the tests."""

from __future__ import annotations

import io
import math
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
import pygame
import pytest
from pixels import angle_between, long_axis

import demos.hinges as hinges
from demos.bench.pendulum import agm, period
from demos.cli import main
from engine import Vector
from engine.render import INK, iter_frames, marks
from engine.render.world_view import BODY, RING, pose_of


class Frame(NamedTuple):
    t: float
    alpha: float  # the blend the frame was drawn with
    pixels: np.ndarray  # (width, height, 3), as pygame.surfarray gives it
    problems: list[str]  # marks.problems of the frame
    words: list[pygame.Rect]  # where its labels are


class Run(NamedTuple):
    scene: Any
    frames: list[Frame]
    poses: list[dict[int, tuple[float, float, float]]]  # each frame's pose of every body


def record(scene: Any, fps: int, seconds: float) -> Run:
    """The scene's frames (and each body's drawn pose in each) over ``seconds`` at ``fps``."""
    frames, poses = [], []
    for _, t, surface in iter_frames(scene, fps=fps, seconds=seconds, size=(640, 360)):
        world = scene.world.world
        alpha = 1.0 - (world.t - t) / scene.dt
        pixels = pygame.surfarray.array3d(surface).copy()
        words = [m.rect for m in marks.marks(surface) if m.kind == "text"]
        frames.append(Frame(t, alpha, pixels, marks.problems(surface), words))
        poses.append({id(b): pose_of(world, b, alpha) for b in world.bodies})
    return Run(scene, frames, poses)


@pytest.fixture(scope="module")
def rod() -> Run:
    # Two crossings of the bottom (at 0.48 s and 2.42 s): one whole period measured.
    return record(hinges.RodScene(), fps=4, seconds=2.5)


@pytest.fixture(scope="module")
def chain() -> Run:
    return record(hinges.ChainScene(), fps=4, seconds=1.5)  # the first whip is at 0.8 s


@pytest.fixture(scope="module")
def car() -> Run:
    return record(hinges.CarScene(), fps=4, seconds=2.5)  # the motors' speed is reached at 1.7 s


def clear_of_words(run: Run, plot: Any, ys: list[float], history: list[Any]) -> None:
    """No label of any frame lies on the curve of ``ys`` (one a sample of ``history``) in
    ``plot``, with a pixel of air around the letters (the pendulum's check)."""
    ts = np.array([q.t for q in history])
    px, py = plot.to_px(ts, np.clip(ys, plot.y_min, plot.y_max))
    for frame in run.frames:
        shown = ts <= frame.t + 1e-9
        for box in frame.words:
            near = box.inflate(2, 2)
            inside = (
                shown
                & (px >= near.left)
                & (px < near.right)
                & (py >= near.top)
                & (py < near.bottom)
            )
            assert not inside.any(), (frame.t, box)


# -- the physics the frames show ---------------------------------------------------------------


def test_the_rods_period_is_the_exact_elliptic_one_and_the_points_of_2l_3_with_it(
    rod: Run,
) -> None:
    p = rod.scene.pendulums
    measured, point = p.rod_crossings.period(), p.point_crossings.period()
    assert measured is not None and point is not None
    exact = period(math.pi / 2, hinges.equivalent_length())
    # K(sin 45 deg) by the AGM, written out: T = 4 sqrt(L_eq / g) pi / (2 AGM(1, cos 45 deg)).
    by_hand = (
        4
        * math.sqrt(hinges.equivalent_length() / hinges.G)
        * math.pi
        / (2 * agm(1.0, math.sqrt(0.5)))
    )
    assert exact == pytest.approx(by_hand, rel=1e-15)
    assert abs(measured / exact - 1) < 1e-4, (measured, exact)
    assert abs(point / period(math.pi / 2, 2 * hinges.ROD_LENGTH / 3) - 1) < 1e-4
    # Together: the periods differ by the rod's width, w^2 / (8 L^2) = 2e-4 of them.
    assert abs(measured / point - 1) < 3e-4
    assert max(abs(s.rod - s.point) for s in p.history) < 1.0  # degrees, over 2.5 s
    # The small-angle formula is far off: the test tells the two apart.
    small = 2 * math.pi * math.sqrt(hinges.equivalent_length() / hinges.G)
    assert abs(measured / small - 1) > 0.1
    assert p.hinge.point.length() < 1e-12  # the hinge holds the rod's end at the origin


def test_the_equivalent_length_is_the_thin_rods_two_thirds_plus_its_width() -> None:
    assert hinges.equivalent_length(1.0, 0.0) == pytest.approx(2 / 3, rel=1e-15)
    rod = hinges.Pendulums().rod
    d = hinges.ROD_LENGTH / 2
    assert hinges.equivalent_length() == pytest.approx(
        (rod.moment + rod.mass * d * d) / (rod.mass * d), rel=1e-14
    )  # the moment the engine gives the box, about the hinge (parallel axes)


def test_every_hinge_of_the_chain_holds_while_it_whips(chain: Run) -> None:
    c = chain.scene.chain
    assert len(c.planks) == len(c.hinges) == 20
    assert max(s.gap for s in c.history) < 1e-9  # measured: under 2e-15 m
    assert max(s.force for s in c.history) > 3 * hinges.PLANKS * hinges.PLANK_MASS * hinges.G
    assert c.planks[-1].pos.distance_to((hinges.PLANKS * hinges.PLANK, 0.0)) > 1.0  # it fell


def test_the_cars_velocity_and_distance_are_the_closed_forms(car: Run) -> None:
    history = car.scene.car.history
    cruise = abs(hinges.MOTOR_SPEED) * hinges.WHEEL_RADIUS
    # a t up to the motors' speed, then |w| r: the World's velocity, at every step.
    worst = max(abs(s.velocity - hinges.Car.closed_form(s.t)) for s in history)
    assert worst < 1e-9, worst  # measured: 4e-14 m/s
    assert history[-1].velocity == pytest.approx(cruise, abs=1e-9)
    # The closed form tells a wrong model apart: the speed without the wheels' turning mass
    # (I = 0) grows faster.
    mass = hinges.CHASSIS_MASS + 2 * hinges.WHEEL_MASS
    bare = 2 * hinges.MAX_TORQUE / hinges.WHEEL_RADIUS / mass - hinges.G * math.sin(hinges.SLOPE)
    assert abs(bare / hinges.Car.acceleration() - 1) > 0.2
    # Its positions follow (what the motors do to the speeds acts on the positions through
    # the step, a dt^2 / 2): measured 1.2e-5 m at most, the step where the motors reach their
    # speed; it moves as fast as its velocity says.
    gap = max(abs(s.climbed - hinges.Car.closed_distance(s.t)) for s in history)
    assert gap < 2e-5, gap
    end = history[-1]
    assert end.speed == pytest.approx(end.velocity, rel=1e-9)
    for motor in car.scene.car.motors:
        assert (motor.end_a() - motor.end_b()).length() < 1e-9


# -- the frames --------------------------------------------------------------------------------


def mask(pixels: np.ndarray, colour: tuple[int, int, int], box: pygame.Rect) -> np.ndarray:
    """Where ``colour`` is within ``box`` (pixels outside it are False)."""
    out = np.zeros(pixels.shape[:2], dtype=bool)
    x0, y0, x1, y1 = box.left, box.top, box.right, box.bottom
    out[x0:x1, y0:y1] = np.all(pixels[x0:x1, y0:y1] == colour, axis=2)
    return out


def near(
    pixels: np.ndarray, at: tuple[float, float], reach: float, colour: tuple[int, int, int] = INK
) -> bool:
    """Whether ``colour`` (INK: a hinge's ring) lies within ``reach`` px of the pixel ``at``."""
    x, y = round(at[0]), round(at[1])
    r = math.ceil(reach)
    patch = pixels[x - r : x + r + 1, y - r : y + r + 1]
    return bool(np.all(patch == colour, axis=2).any())


def ring(pixels: np.ndarray, at: tuple[float, float]) -> bool:
    """Whether ink rings the pixel ``at``: ink 1.5 to RING + 1.5 px from it on all four sides
    (right, up, left, down), as a hinge's ring has and the end of a body's outline or a disc's
    radius line alone has not."""
    cx, cy = at
    r = RING + 2
    sides = set()
    for x in range(math.floor(cx) - r, math.ceil(cx) + r + 1):
        for y in range(math.floor(cy) - r, math.ceil(cy) + r + 1):
            dx, dy = x - cx, y - cy
            if 1.5 <= math.hypot(dx, dy) <= RING + 1.5 and tuple(pixels[x, y]) == INK:
                sides.add(
                    int(((math.atan2(-dy, dx) + math.pi / 4) % (2 * math.pi)) // (math.pi / 2))
                )
    return len(sides) == 4


def test_the_rod_frames_draw_the_rod_along_its_angle_and_the_bob_where_they_are(rod: Run) -> None:
    scene = rod.scene
    camera = scene.camera
    left = pygame.Rect(0, 0, round(camera.to_px(1.15, 0.0)[0]), scene.theta_plot.rect.top)
    right_x = round(camera.to_px(hinges.POINT_PIVOT[0] - 0.8, 0.0)[0])
    legend = round(0.8 * 640)  # the legend's words (some green) start here
    right = pygame.Rect(right_x, 0, legend - right_x, scene.theta_plot.rect.top)
    for frame, poses in zip(rod.frames, rod.poses, strict=True):
        assert frame.problems == [], (frame.t, frame.problems)
        x, y, angle = poses[id(scene.pendulums.rod)]
        _, axis, _, _ = long_axis(mask(frame.pixels, hinges.BODY, left))
        along = np.array([math.cos(angle), -math.sin(angle)])  # the rod's x axis, in pixels
        assert min(angle_between(axis, along), angle_between(-axis, along)) < 3.0, frame.t
        c, s = math.cos(angle), math.sin(angle)
        for u in (-0.35, 0.0, 0.2, 0.45):  # blue along the rod's middle line ...
            at = camera.to_px(x + u * c, y + u * s)
            assert near(frame.pixels, at, 1.0, hinges.BODY), (frame.t, u)
        for v in (-0.08, 0.08):  # ... and not across it, 8 cm to either side of its middle
            at = camera.to_px(x - v * s, y + v * c)
            assert not near(frame.pixels, at, 1.0, hinges.BODY), (frame.t, v)
        assert ring(frame.pixels, camera.to_px(0.0, 0.0)), frame.t  # the hinge's ring
        bx, by, _ = poses[id(scene.pendulums.bob)]
        xs, ys = np.nonzero(mask(frame.pixels, hinges.BOB, right))
        r = camera.length(hinges.BOB_RADIUS)
        assert len(xs) > 0.6 * math.pi * r * r, frame.t  # a whole disc
        want = camera.to_px(bx, by)
        assert abs(xs.mean() - want[0]) < 1.5 and abs(ys.mean() - want[1]) < 1.5, frame.t


def test_the_rod_plot_marks_the_exact_period_and_both_curves_agree(rod: Run) -> None:
    scene = rod.scene
    history = scene.pendulums.history
    for values in ([q.rod for q in history], [q.point for q in history]):
        clear_of_words(rod, scene.theta_plot, values, history)
    pixels = rod.frames[-1].pixels  # t = 2.5 s
    plot, a = scene.theta_plot, scene.theta_plot.area
    px = int(float(plot.to_px(scene.exact, 0.0)[0]))
    dark = max(
        int(np.all(pixels[x, a.top : a.bottom] < 80, axis=1).sum()) for x in (px - 1, px, px + 1)
    )
    assert 0.3 * a.height < dark < 0.8 * a.height, dark  # dashed: about half dark
    # Where both curves are drawn the rod's (blue, on top) lies within the point's (green,
    # wide): at every column the curves cover, blue has green a few pixels above or below.
    shown = np.array(pixels[a.left : a.left + round(0.3 * a.width), a.top : a.bottom])
    columns = 0
    for column in shown:
        blue = np.flatnonzero(np.all(column == hinges.BODY, axis=1))
        green = np.flatnonzero(np.all(column == hinges.BOB, axis=1))
        if len(blue):
            columns += 1
            assert len(green) and np.abs(green[:, None] - blue[None, :]).min() <= 3
    assert columns > 0.25 * a.width


def test_the_chain_frames_draw_every_plank_and_a_ring_at_every_hinge(chain: Run) -> None:
    scene = chain.scene
    history = scene.chain.history
    clear_of_words(chain, scene.force_plot, [q.force for q in history], history)
    logs = [math.log10(max(q.gap, 1e-17)) for q in history]
    clear_of_words(chain, scene.gap_plot, logs, history)
    camera = scene.camera
    for frame, poses in zip(chain.frames, chain.poses, strict=True):
        assert frame.problems == [], (frame.t, frame.problems)
        for plank in scene.chain.planks:  # blue at each plank's middle, between its rings
            middle = camera.to_px(*poses[id(plank)][:2])
            assert near(frame.pixels, middle, 1.5, BODY), (frame.t, middle)
        for hinge in scene.chain.hinges:
            x, y, angle = poses[id(hinge.body_a)]
            ax, ay = hinge.anchor_a
            c, s = math.cos(angle), math.sin(angle)
            point = camera.to_px(x + c * ax - s * ay, y + s * ax + c * ay)
            assert near(frame.pixels, point, RING + 1), (frame.t, point)
        assert ring(frame.pixels, camera.to_px(0.0, 0.0)), frame.t  # the top hinge's


def test_the_car_frames_draw_its_wheels_with_rings_at_their_axles(car: Run) -> None:
    scene = car.scene
    history = scene.car.history
    clear_of_words(car, scene.speed_plot, [q.velocity for q in history], history)
    camera = scene.camera
    for frame, poses in zip(car.frames, car.poses, strict=True):
        assert frame.problems == [], (frame.t, frame.problems)
        for wheel in scene.car.wheels:
            x, y, _ = poses[id(wheel)]
            cx, cy = camera.to_px(x, y)
            centre = tuple(frame.pixels[round(cx), round(cy)])
            assert centre == BODY, frame.t  # the hub keeps the wheel's colour: a ring round it
            assert ring(frame.pixels, (cx, cy)), frame.t
            r = camera.length(hinges.WHEEL_RADIUS)
            inside = mask(
                frame.pixels, BODY, pygame.Rect(round(cx - r), round(cy - r), 2 * r, 2 * r)
            )
            assert inside.sum() > 0.6 * math.pi * r * r, frame.t
    # The plot: the World's velocity (blue) lies within the closed form's wide line (purple).
    plot = scene.speed_plot
    pixels = car.frames[-1].pixels
    columns = 0
    knee = abs(hinges.MOTOR_SPEED) * hinges.WHEEL_RADIUS / hinges.Car.acceleration()
    corner = [round(float(plot.to_px(knee + d, 0.0)[0])) for d in (-0.05, 0.05)]
    for px in range(plot.area.left + 2, round(float(plot.to_px(2.4, 0.0)[0]))):
        if corner[0] <= px <= corner[1]:
            continue  # pygame's wide line is notched at its corner
        column = pixels[px, plot.area.top : plot.area.bottom]
        blue = np.flatnonzero(np.all(column == BODY, axis=1))
        purple = np.flatnonzero(np.all(column == hinges.CLOSED, axis=1))
        if len(blue):
            columns += 1
            assert len(purple) and np.abs(purple[:, None] - blue[None, :]).min() <= 3, px
    assert columns > 0.5 * (float(plot.to_px(2.4, 0.0)[0]) - plot.area.left)


def test_the_command_line_writes_the_frames_the_scenes_draw(
    tmp_path: Path, rod: Run, chain: Run, car: Run
) -> None:
    # python -m demos hinges, run apart from the fixtures' runs, writes the same pixels for
    # the same moments: the scenes are deterministic and the command line adds nothing.
    argv = ["hinges", "--fps", "4", "--seconds", "0.25", "--out", str(tmp_path)]
    assert main(argv, io.StringIO()) == 0
    for name, run in (("rod", rod), ("chain", chain), ("car", car)):
        files = sorted((tmp_path / name).glob("frame_*.png"))
        assert [f.name for f in files] == ["frame_00000.png", "frame_00001.png"], name
        image = pygame.surfarray.array3d(pygame.image.load(str(files[1])))
        assert run.frames[1].t == 0.25
        assert np.array_equal(image, run.frames[1].pixels), name
        assert len(np.unique(image.reshape(-1, 3), axis=0)) > 10, name  # not one flat colour


def test_the_demo_lists_its_scenes() -> None:
    assert list(hinges.DEMO.scenes) == ["rod", "chain", "car"]
    assert isinstance(hinges.Pendulums().bob.pos, Vector)


def test_the_headers_write_their_formula_and_units_as_meant() -> None:
    # The rod's caption wrote "w^2/6L" for w^2 / (6 L), and the chain's "(weight 19.6)" had
    # no unit. At 480x270 the chain's header has room for the force alone (it is written at
    # 12 px, and it was measured at 10 px: it ran into the force plot once it said "N").
    weight = hinges.PLANKS * hinges.PLANK_MASS * hinges.G
    for size, weighed in (((640, 360), True), ((480, 270), False)):
        said = []
        for scene in (hinges.RodScene(), hinges.ChainScene()):
            for _, _, surface in iter_frames(scene, fps=30, seconds=0.1, size=size, only={0}):
                said += [m.text for m in marks.marks(surface)]
                assert marks.problems(surface) == [], size
        caption = next(text for text in said if text.startswith("dashed:"))
        assert caption.endswith("L_eq = 2L/3 + w\u00b2/(6L)"), caption
        header = next(text for text in said if "top hinge" in text)
        assert header.endswith(f"N (weight {weight:.1f} N)" if weighed else " N"), header
