"""Alfred's scenes: valid frames, Alfred drawn where the physics puts him, the sprint's lesson."""

import math
from typing import cast

import numpy as np
import pygame
import pytest
from pixels import angle_between, hidden_arrows, long_axis, watching

from demos import alfred
from engine import Vector
from engine.render import init_headless, iter_frames, marks, record, strobe
from engine.render.recorder import draw_strobe

SIZE = (640, 360)


@pytest.fixture(autouse=True)
def _pygame():
    init_headless()


def load(path) -> np.ndarray:
    """A PNG's pixels as an array indexed [x, y, channel]."""
    return pygame.surfarray.array3d(pygame.image.load(str(path)))


def sprite_body_centroid(sprite: pygame.Surface, color) -> np.ndarray:
    """Centroid (x, y) of the sprite's fully opaque pixels of ``color``, in sprite pixels."""
    rgb = pygame.surfarray.array3d(sprite)
    alpha = pygame.surfarray.array_alpha(sprite)
    xs, ys = np.nonzero((rgb == color).all(axis=-1) & (alpha == 255))
    assert len(xs) > 20, "the sprite must show its body colour"
    return np.array([xs.mean(), ys.mean()])


def find_anchor(pixels: np.ndarray, sprite: pygame.Surface, color, region=None) -> np.ndarray:
    """Where the sprite's midbottom anchor is in a frame, found by the colour only it uses."""
    mask = (pixels == color).all(axis=-1)
    if region is not None:
        keep = np.zeros_like(mask)
        keep[:, region[0] : region[1]] = True
        mask &= keep
    xs, ys = np.nonzero(mask)
    assert len(xs) > 20, f"no sprite of colour {color} in the frame"
    w, h = sprite.get_size()
    # pygame's midbottom of a w x h rect at topleft (x, y) is (x + w // 2, y + h).
    topleft = np.array([xs.mean(), ys.mean()]) - sprite_body_centroid(sprite, color)
    return topleft + np.array([w // 2, h])


@pytest.mark.parametrize("name", list(alfred.DEMO.scenes))
def test_each_scene_renders_valid_frames_of_the_requested_size(tmp_path, name):
    scene = alfred.DEMO.scenes[name]()
    rec = record(scene, tmp_path, fps=2, seconds=1.0, size=(480, 270), progress=False)
    assert rec.count == 3
    for path in rec.paths():
        surface = pygame.image.load(str(path))
        assert surface.get_size() == (480, 270)
        colours = np.unique(pygame.surfarray.array3d(surface).reshape(-1, 3), axis=0)
        assert len(colours) > 50, "a flat frame: the classic headless failure"


@pytest.mark.parametrize("name", list(alfred.DEMO.scenes))
def test_each_scene_draws_a_strobe_still(tmp_path, name):
    path = strobe(alfred.DEMO.scenes[name](), tmp_path / "strobe.png", size=SIZE)
    pixels = load(path)
    assert pixels.shape[:2] == SIZE
    assert len(np.unique(pixels.reshape(-1, 3), axis=0)) > 50


def exact_1d(s0, v0, a, t):
    return s0 + v0 * t + 0.5 * a * t * t


@pytest.mark.parametrize(
    ("name", "s0", "v0", "a"),
    [("lazy", 5.0, 0.0, 0.0), ("stroll", 0.0, 1.0, 0.0)],
)
def test_alfred_is_drawn_where_the_exact_motion_puts_him(tmp_path, name, s0, v0, a):
    scene = alfred.DEMO.scenes[name]()
    fps = 3
    rec = record(scene, tmp_path, fps=fps, size=SIZE, progress=False)
    (ant,) = scene.ants
    for k, path in enumerate(rec.paths()):
        t = k / fps
        s = min(exact_1d(s0, v0, a, t), alfred.TUBE_LENGTH)
        expected = np.array(scene.camera.to_px(s, ant.row))
        found = find_anchor(load(path), ant.sprite, alfred.ANT_BODY)
        assert np.all(np.abs(found - expected) <= 1.0), (t, found, expected)


def euler_positions(a: float, dt: float, steps: int) -> list[float]:
    """Semi-implicit Euler from rest by hand: v += a dt, then x += v dt."""
    x, v, out = 0.0, 0.0, [0.0]
    for _ in range(steps):
        v += a * dt
        x += v * dt
        out.append(x)
    return out


def euler_at(t: float) -> float:
    # Between steps the ant moves in a straight line from one step's position to the next.
    xs = euler_positions(1.0, 1.0, 8)
    n = min(int(t), 7)
    return xs[n] + (xs[n + 1] - xs[n]) * (t - n)


def test_sprint_euler_positions_are_the_lessons():
    assert euler_positions(1.0, 1.0, 4) == [0.0, 1.0, 3.0, 6.0, 10.0]


def test_sprint_draws_both_ants_where_their_methods_put_them(tmp_path):
    scene = alfred.Sprint()
    fps = 4
    rec = record(scene, tmp_path, fps=fps, size=SIZE, progress=False)
    euler, exact = scene.ants
    for k, path in enumerate(rec.paths()):
        t = k / fps
        pixels = load(path)
        for ant, color, s in (
            (euler, alfred.EULER_ANT_BODY, euler_at(t)),
            (exact, alfred.ANT_BODY, exact_1d(0.0, 0.0, 1.0, t)),
        ):
            expected = np.array(scene.camera.to_px(min(s, alfred.TUBE_LENGTH), ant.row))
            found = find_anchor(pixels, ant.sprite, color)
            assert np.all(np.abs(found - expected) <= 1.0), (t, ant.short, found, expected)


def test_sprint_ants_reach_the_end_at_4_s_and_sqrt_20_s(tmp_path):
    scene = alfred.Sprint()
    record(scene, tmp_path / "a", fps=2, size=SIZE, progress=False)
    euler, exact = scene.ants
    assert euler.arrival == 4.0
    assert exact.arrival == pytest.approx(math.sqrt(20.0), abs=1e-12)
    assert f"{exact.arrival:.2f}" == "4.47"
    # And in the pictures: the first frame with each ant at the tube's end.
    fps = 20
    scene = alfred.Sprint()
    first_at_end = {}
    for k, _t, surface in iter_frames(scene, fps=fps, seconds=4.6, size=SIZE):
        end_px = scene.camera.to_px(alfred.TUBE_LENGTH, 0.0)[0]
        pixels = pygame.surfarray.array3d(surface)
        for ant, color in (
            (scene.ants[0], alfred.EULER_ANT_BODY),
            (scene.ants[1], alfred.ANT_BODY),
        ):
            x = find_anchor(pixels, ant.sprite, color)[0]
            if abs(x - end_px) <= 0.5 and ant.short not in first_at_end:
                first_at_end[ant.short] = k / fps
    assert first_at_end["Euler"] == 4.0
    assert first_at_end["exact"] == math.ceil(math.sqrt(20.0) * fps) / fps  # 4.5 s at 20 fps


def test_the_top_view_sprite_faces_plus_x_with_his_body_centred():
    sprite = alfred.ant_sprite(top=True)
    assert sprite.get_size() == (39, 27)
    rgb = pygame.surfarray.array3d(sprite)
    alpha = pygame.surfarray.array_alpha(sprite)
    body = (rgb == alfred.ANT_BODY).all(axis=-1) & (alpha == 255)
    centroid, axis, ahead, behind = long_axis(body)
    # The middle of his body is the middle of the image (pixel indices 0..38 and 0..26).
    assert np.abs(centroid - np.array([19.0, 13.0])).max() <= 0.5, centroid
    # Head, thorax and abdomen lie along x, and the head's end reaches further from the middle
    # than the abdomen's: so in a frame the further end of the long axis is his head.
    assert angle_between(axis, np.array([1.0, 0.0])) < 2.0, axis
    assert ahead - behind > 3.0, (ahead, behind)


def test_top_view_and_small_are_exclusive():
    with pytest.raises(ValueError, match="small"):
        alfred.ant_sprite(small=True, top=True)


def paper_checks(pixels: np.ndarray, scene: alfred.Paper, t: float) -> float:
    """Assert Alfred is centred on his exact position at t and faces his exact velocity;
    return the direction (degrees, pixel axes) he faces."""
    pos, vel = scene.exact(t)
    assert (pos.x, pos.y) == (t * t / 2, 2 * t - t * t)
    centroid, axis, _, _ = long_axis((pixels == alfred.ANT_BODY).all(axis=-1))
    expected = np.array(scene.camera.to_px(pos.x, pos.y))
    # Seen from above he is centred on the point; nearest-neighbour rotation moves which
    # pixels keep the exact body colour by up to 1.5 px.
    assert np.abs(centroid - expected).max() <= 2.0, (t, centroid, expected)
    # His velocity (vx, vy), y up, is the pixel direction (vx, -vy) (pixel y points down).
    direction = np.array([vel.x, -vel.y])
    assert angle_between(axis, direction) <= 5.0, (t, axis, direction)
    return math.degrees(math.atan2(axis[1], axis[0]))


@pytest.mark.parametrize(("size", "fps"), [(SIZE, 4), ((1280, 720), 1)])
def test_paper_alfred_is_centred_on_x_t2_over_2_y_2t_minus_t2_facing_v(tmp_path, size, fps):
    scene = alfred.Paper()
    rec = record(scene, tmp_path, fps=fps, size=size, progress=False)
    assert rec.count == 3 * fps + 1
    facing = [paper_checks(load(path), scene, k / fps) for k, path in enumerate(rec.paths())]
    # Up at t = 0 (v = (0, 2)), right at t = 1, down and right at t = 3 (v = (3, -4)): the
    # checks saw him face clearly different ways, so a sprite that never turns fails them.
    assert max(facing) - min(facing) > 120.0, facing


def test_paper_strobe_shows_the_last_alfred_centred_and_facing_v(tmp_path):
    # The older images are faded; the newest (t = 3 s) is the only one in the exact colour.
    scene = alfred.Paper()
    path = strobe(scene, tmp_path / "strobe.png", size=SIZE)
    paper_checks(load(path), scene, 3.0)


class TurningPaper(alfred.Paper):
    """v = (t - 1, 2 - 2t) = (t - 1)(1, -2): he walks up-left, stops at t = 1 s, turns back."""

    v0 = Vector(-1.0, 2.0)


def test_paper_alfred_keeps_his_heading_when_he_stops():
    scene = TurningPaper()
    # At the stop he keeps the way he was walking, -a = (-1, 2), not a direction from 0 / 0.
    assert scene.heading(1.0, Vector(0.0, 0.0)) == pytest.approx(math.degrees(math.atan2(2, -1)))
    for k, t, surface in iter_frames(scene, fps=2, seconds=2.0, size=SIZE):
        _, axis, _, _ = long_axis((pygame.surfarray.array3d(surface) == alfred.ANT_BODY).all(-1))
        # Up and left (pixels (-1, -2)) until he stops, down and right (1, 2) after.
        expected = np.array([-1.0, -2.0]) if t <= 1.0 else np.array([1.0, 2.0])
        assert angle_between(axis, expected) <= 5.0, (k, t, axis)
    # From rest he faces the way he is about to walk (a); with no motion at all, +x.
    resting = alfred.Paper()
    resting.v0 = Vector(0.0, 0.0)
    assert resting.heading(0.0, Vector(0.0, 0.0)) == pytest.approx(math.degrees(math.atan2(-2, 1)))
    resting.a = Vector(0.0, 0.0)
    assert resting.heading(0.0, Vector(0.0, 0.0)) == 0.0
    assert resting.heading(2.0, Vector(0.0, 0.0)) == 0.0


def test_paper_velocity_is_tangent_to_the_path():
    # v = (t, 2 - 2t) is the derivative of s = (t^2/2, 2t - t^2): the lesson's check at t = 1.
    scene = alfred.Paper()
    _, v = scene.exact(1.0)
    assert (v.x, v.y) == (1.0, 0.0)
    h = 1e-6
    for t in (0.3, 1.0, 2.5):
        (s1, _), (s2, _), (_, v) = scene.exact(t - h), scene.exact(t + h), scene.exact(t)
        assert ((s2 - s1) / (2 * h) - v).magnitude() < 1e-6


def test_the_same_recording_twice_is_byte_identical(tmp_path):
    first = record(alfred.Sprint(), tmp_path / "1", fps=3, seconds=2.0, size=(320, 180))
    second = record(alfred.Sprint(), tmp_path / "2", fps=3, seconds=2.0, size=(320, 180))
    assert first.count == second.count == 7
    for a, b in zip(first.paths(), second.paths(), strict=True):
        assert a.read_bytes() == b.read_bytes()


# -- what a teacher sees: nothing cut at an edge, every label where it belongs ----------------


def _ant_box(scene: alfred.Paper, t: float) -> pygame.Rect:
    """The box of Alfred's visible pixels at time t on the paper (px)."""
    pos, vel = scene.exact(t)
    image = scene.facing(t, vel)
    rect = image.get_rect(
        center=tuple(math.floor(c + 0.5) for c in scene.camera.to_px(pos.x, pos.y))
    )
    boxes = cast(list[pygame.Rect], pygame.mask.from_surface(image).get_bounding_rects())
    return boxes[0].unionall(boxes[1:]).move(rect.topleft)


def test_paper_keeps_alfred_and_his_velocity_arrow_on_the_paper_in_every_frame():
    # At frame 90 (t = 3 s) the arrow and the ant ran past the paper's border.
    scene = alfred.Paper()
    for k, t, surface in iter_frames(scene, fps=30, size=SIZE):
        paper = scene.paper_rect
        found = marks.marks(surface)
        for m in found:
            if m.kind == "arrowhead" or m.text == "v":
                assert paper.inflate(-2, -2).contains(m.rect), (k, str(m), paper)
        # The velocity's arrowhead always (he never stops); the position's once he is further
        # from the origin than he is long (before, it would end inside his own body: none).
        heads = sum(m.kind == "arrowhead" for m in found)
        pos, _ = scene.exact(t)
        away = math.dist(scene.camera.to_px(pos.x, pos.y), scene.camera.to_px(0.0, 0.0))
        if away > max(scene.sprite.get_size()):
            assert heads == 2, (k, t)
        elif away < 1.0:
            assert heads == 1, (k, t)
        assert paper.inflate(-2, -2).contains(_ant_box(scene, t)), (k, t)
        assert marks.problems(surface) == [], k


def test_paper_strobe_labels_each_alfred_beside_him_and_off_the_arrows(tmp_path):
    # In the strobe, "t = 0 s" and "t = 0.5 s" sat on the position arrows, away from their ants.
    scene = alfred.Paper()
    scene.build(SIZE)
    surface = pygame.Surface(SIZE)
    draw_strobe(scene, surface)
    times = scene.strobe_times()
    origin = scene.camera.to_px(0.0, 0.0)
    names = {f"t = {alfred.common.number(t)} s" for t in times}
    labels = {m.text: m.rect for m in marks.marks(surface) if m.text in names}
    assert sorted(labels) == sorted(names)
    ants = {t: _ant_box(scene, t) for t in times}
    for t in times:
        box = labels[f"t = {alfred.common.number(t)} s"]
        for other in times:
            pos, _ = scene.exact(other)
            assert not box.clipline(origin, scene.camera.to_px(pos.x, pos.y)), (t, other)
        # Nearer his own dot than any other Alfred's, and within about an ant's length of him.
        dots = {u: scene.camera.to_px(*scene.exact(u)[0]) for u in times}
        near = {u: math.dist(box.center, dots[u]) for u in times}
        assert near[t] == min(near.values()), (t, near)
        assert _gap(box, ants[t]) <= 40, (t, _gap(box, ants[t]))
    assert marks.problems(surface) == []


def _gap(a: pygame.Rect, b: pygame.Rect) -> float:
    """The distance (px) between two rectangles, 0 if they touch."""
    dx = max(b.left - a.right, a.left - b.right, 0)
    dy = max(b.top - a.bottom, a.top - b.bottom, 0)
    return math.hypot(dx, dy)


@pytest.mark.parametrize(("name", "frames"), [("stroll", {297, 299, 300}), ("sprint", None)])
def test_the_velocity_arrow_is_never_cut_at_the_edge(name, frames):
    # The stroll's arrowhead was cut at the right edge at frame 297 and gone at frame 300 while
    # the formula says v = 1 in/s; the sprint's ran off the frame as he neared the end.
    scene = alfred.DEMO.scenes[name]()
    for k, _, surface in iter_frames(scene, fps=30, size=SIZE, only=frames):
        assert marks.problems(surface) == [], k
    if name == "stroll":  # the last frame (t = 10 s, when he arrives) still shows v = 1 in/s
        heads = [m for m in marks.marks(surface) if m.kind == "arrowhead"]
        assert len(heads) == 1 and "v = 1.0 in/s" in [m.text for m in marks.marks(surface)]


def test_the_sprints_euler_ant_says_which_moments_speed_he_walks_at():
    # "From rest", yet the Euler ant showed v = 1.0 in/s at t = 0: semi-implicit Euler walks
    # each step at the speed the step ends with, and the label now says so.
    scene = alfred.Sprint()
    said = {}
    for _, t, surface in iter_frames(scene, fps=2, seconds=4.0, size=SIZE):
        said[t] = [m.text for m in marks.marks(surface)]
    assert "v(1 s) = 1.0 in/s" in said[0.0]
    assert "v = 0 in/s" in said[0.0]  # the exact ant, at rest, says so
    assert "v(2 s) = 2.0 in/s" in said[1.5]
    assert "v(4 s) = 4.0 in/s" in said[3.5]


@pytest.mark.parametrize("size", [SIZE, (1280, 720)], ids=["640x360", "1280x720"])
def test_paper_shows_both_arrows_beside_alfred_not_under_him(size):
    # At t = 1.5 s the velocity arrow (0.25 s of travel, shorter than he is) lay wholly under
    # his sprite, and the position arrow's head under his body. The velocity arrow now starts
    # where his body ends ahead of him, the position arrow ends where it begins: of the
    # pixels each drew, nearly all still show in the finished frame (the label "v" and the
    # path's line may cross a few), and his body is whole.
    with watching() as layers:
        for k, t, surface in iter_frames(alfred.Paper(), fps=30, size=size, only={15, 45, 75}):
            drawn = layers.take(surface)
            pixels = pygame.surfarray.array3d(surface)
            arrows = [d for d in drawn if d.kind == "arrow"]
            assert len(arrows) == 2, k  # the position and the velocity
            for arrow in arrows:
                assert arrow.showing(pixels) > 0.95, (t, str(arrow), arrow.showing(pixels))
            assert hidden_arrows(drawn) == [], t
            (sprite,) = [d for d in drawn if d.kind == "sprite"]
            for arrow in arrows:  # an arrow may touch his legs, not lie on him
                assert (arrow.pixels & sprite.pixels).sum() <= 0.05 * arrow.pixels.sum(), t
