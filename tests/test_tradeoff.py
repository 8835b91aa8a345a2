"""The work-precision chart: `python -m demos tradeoff --quick` writes a PNG and a CSV whose
numbers obey the theory (orders 1, 1, 2, 4; the closed form exact; auto as cheap as the best)."""

from __future__ import annotations

import csv
import io
import math
import re
from pathlib import Path

import numpy as np
import pygame
import pytest

from demos import cli
from demos.bench import pendulum, solver
from demos.tradeoff import (
    AUTO_TARGET,
    COLORS,
    FULL,
    OUTPUTS,
    PENDULUM_NOTE,
    QUICK,
    SOLVER_COLORS,
    TAKES,
    _hidden_under,
    _level_spot,
    _pendulum_captions,
    draw_contacts,
    draw_work_precision,
    summary,
)
from engine import World
from engine.measure import PROBLEMS, Point, measure

ORDERS = {"explicit_euler": 1, "semi_implicit_euler": 1, "velocity_verlet": 2, "rk4": 4}


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, list[dict[str, str]], str]:
    out = tmp_path_factory.mktemp("tradeoff")
    text = io.StringIO()
    import contextlib

    with contextlib.redirect_stdout(text):
        code = cli.main(["tradeoff", "--quick", "--out", str(out)], out=text)
    assert code == 0
    with open(out / "work_precision.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    return out, rows, text.getvalue()


def test_quick_run_writes_png_and_csv(quick_run: tuple[Path, list[dict[str, str]], str]) -> None:
    out, rows, _ = quick_run
    for name in (
        "work_precision.png",
        "work_precision.csv",
        "pendulum.csv",
        "throughput.png",
        "throughput.csv",
    ):
        assert (out / name).stat().st_size > 0, name
    methods = {(r["problem"], r["method"]) for r in rows}
    for problem in PROBLEMS:
        for method in ("explicit_euler", "semi_implicit_euler", "velocity_verlet", "rk4", "auto"):
            assert (problem, method) in methods
    assert ("gravity", "exact") in methods and ("spring", "exact") not in methods


def test_spring_slopes_match_the_orders(quick_run: tuple[Path, list[dict[str, str]], str]) -> None:
    # Fit log(error) against log(dt) over the asymptotic range: omega dt <= 1/4, above round-off.
    _, rows, _ = quick_run
    for method, order in ORDERS.items():
        pts = [
            (math.log(float(r["dt_s"])), math.log(float(r["error_m"])))
            for r in rows
            if r["problem"] == "spring"
            and r["method"] == method
            and 2 * math.pi * float(r["dt_s"]) <= 0.25
            and 1e-11 < float(r["error_m"]) < math.inf
        ]
        assert len(pts) >= 3, method
        x, y = np.array(pts).T
        slope = np.polyfit(x, y, 1)[0]
        assert abs(slope - order) <= 0.15, (method, slope)


def test_closed_form_is_exact_on_gravity(quick_run: tuple[Path, list[dict[str, str]], str]) -> None:
    _, rows, _ = quick_run
    errors = [
        float(r["error_m"]) for r in rows if r["problem"] == "gravity" and r["method"] == "exact"
    ]
    assert errors and max(errors) < 1e-12


def test_explicit_euler_on_gravity_lags_by_a_t_h_over_2(
    quick_run: tuple[Path, list[dict[str, str]], str],
) -> None:
    # Under constant acceleration a, explicit Euler's position error after time T with step h
    # is exactly a T h / 2: it sums a h^2 / 2 short each step, T / h steps.
    _, rows, _ = quick_run
    for r in rows:
        if r["problem"] == "gravity" and r["method"] == "explicit_euler":
            assert float(r["error_m"]) == pytest.approx(9.81 * 1.0 * float(r["dt_s"]) / 2, rel=1e-9)


def test_auto_meets_each_tolerance_as_cheaply_as_the_best_point(
    quick_run: tuple[Path, list[dict[str, str]], str],
) -> None:
    # At each error level (auto's tolerance), the cheapest measured point of any method that
    # reaches it, by work (steps + evaluations: machine independent), against auto's.
    _, rows, _ = quick_run
    autos = [r for r in rows if r["method"] == "auto"]
    assert len(autos) >= 3 * 6
    for a in autos:
        tol = float(a["tolerance_m"])
        assert float(a["error_m"]) <= tol, a
        rivals = [
            int(r["work"])
            for r in rows
            if r["problem"] == a["problem"]
            and r["method"] != "auto"
            and r["finite"] == "1"
            and r["warned"] == "0"
            and float(r["error_m"]) <= tol
        ]
        assert rivals
        assert int(a["work"]) <= 1.2 * min(rivals), a


def _load(path: Path) -> np.ndarray:
    return pygame.surfarray.array3d(pygame.image.load(str(path)))


def test_chart_is_not_flat_and_has_one_line_colour_per_method(
    quick_run: tuple[Path, list[dict[str, str]], str],
) -> None:
    out, _, _ = quick_run
    pixels = _load(out / "work_precision.png")
    assert pixels.shape[:2] == (1280, 720)
    flat = pixels.reshape(-1, 3)
    assert len(np.unique(flat, axis=0)) > 20
    colours = list(COLORS.values())
    assert len(set(colours)) == len(colours)
    for method, colour in COLORS.items():
        count = int(np.all(flat == np.array(colour), axis=1).sum())
        assert count > 300, (method, count)  # a line, not just the legend swatch


def _point(method: str, dt: float, error: float, finite: bool = True) -> Point:
    return Point("spring", method, method, dt, round(1 / dt), error, finite, False, dt, 0.0, 1, 0)


def test_a_diverged_point_is_marked_in_the_top_strip() -> None:
    points = [_point("rk4", 2.0**-k, 10.0**-k) for k in range(2, 8)]
    points.append(_point("rk4", 0.5, math.inf, finite=False))
    pixels = pygame.surfarray.array3d(draw_work_precision(points))
    colour = np.array(COLORS["rk4"])
    # The plotting area of the one panel starts 30 + 16 px below its top (66): the strip for
    # non-finite points is the 16 px above it.
    strip = pixels[:, 66 + 30 : 66 + 30 + 16]
    assert np.all(strip == colour, axis=2).sum() > 10
    without = pygame.surfarray.array3d(draw_work_precision(points[:-1]))
    assert np.all(without[:, 96:112] == colour, axis=2).sum() == 0


def test_the_euler_lines_coincide_under_gravity_and_the_chart_says_so() -> None:
    # Under constant g the two Euler methods err by -+ g dt t / 2: the same size, so one line
    # hides the other. Under a spring they differ, and nothing is said.
    dts = [2.0**-k for k in range(3, 7)]
    eulers = ("explicit_euler", "semi_implicit_euler")
    for name, expected in (("gravity", [eulers]), ("spring", []), ("wind", [])):
        points = [
            measure(PROBLEMS[name], m, dt, repeats=1, min_steps=16) for m in eulers for dt in dts
        ]
        assert _hidden_under(points) == expected, name
    nearly = [_point(m, dt, dt * (1.1 if m == eulers[0] else 1.0)) for m in eulers for dt in dts]
    assert _hidden_under(nearly) == []  # 10% apart: both lines show


def test_a_hidden_line_gets_a_note_in_its_colour() -> None:
    dts = [2.0**-k for k in range(3, 7)]
    same = [_point(m, dt, dt) for m in ("explicit_euler", "semi_implicit_euler") for dt in dts]
    apart = [
        _point(m, dt, dt * (3.0 if m == "explicit_euler" else 1.0))
        for m, dt in [(p.method, p.dt) for p in same]
    ]
    colour = np.array(COLORS["explicit_euler"])
    for points, noted in ((same, True), (apart, False)):
        pixels = pygame.surfarray.array3d(draw_work_precision(points))
        # The note sits in the top 40 px of the plotting area (which starts at y = 96), right.
        corner = pixels[pixels.shape[0] // 2 :, 96:136]
        assert (np.all(corner == colour, axis=2).sum() > 20) == noted


def test_measure_counts_evaluations_through_the_world() -> None:
    p = measure(PROBLEMS["spring"], "rk4", 1 / 16, repeats=1, min_steps=16)
    assert p.evaluations == 16 * 4 and p.work == 16 * 5
    q = measure(PROBLEMS["gravity"], "exact", 1 / 16, repeats=1, min_steps=16)
    assert q.evaluations == 0 and q.error < 1e-12


def test_a_second_run_gives_the_same_errors_and_choices(
    quick_run: tuple[Path, list[dict[str, str]], str], tmp_path: Path
) -> None:
    # Costs are wall-clock times and differ from run to run; everything else is physics and
    # must come out bit for bit the same.
    timed = {"cost_s_per_s", "choose_s"}
    assert cli.main(["tradeoff", "--quick", "--out", str(tmp_path)], out=io.StringIO()) == 0
    with open(tmp_path / "work_precision.csv", newline="") as handle:
        again = list(csv.DictReader(handle))
    first = quick_run[1]
    assert len(again) == len(first) > 0
    for a, b in zip(first, again, strict=True):
        assert {k: v for k, v in a.items() if k not in timed} == {
            k: v for k, v in b.items() if k not in timed
        }
    # The pendulum panel's errors too.
    swing, swing_again = _pendulum_rows(quick_run[0]), _pendulum_rows(tmp_path)
    assert swing.keys() == swing_again.keys()
    for key, row in swing.items():
        del row["cost_s_per_step"], swing_again[key]["cost_s_per_step"]
        assert row == swing_again[key], key
    # The contacts chart's errors too (both engines are deterministic).
    contacts, contacts_again = _contact_rows(quick_run[0]), _contact_rows(tmp_path)
    assert contacts.keys() == contacts_again.keys()
    for setting, row in contacts.items():
        del row["cost_s_per_step"], contacts_again[setting]["cost_s_per_step"]
        assert row == contacts_again[setting], setting


# -- the contacts chart: solver iterations against cost, this engine and pymunk ----------------

try:
    import pymunk  # noqa: F401

    HAS_PYMUNK = True
except ImportError:  # pragma: no cover - the bench extra is not installed
    HAS_PYMUNK = False


def _contact_rows(out: Path) -> dict[tuple[str, str, int], dict[str, str]]:
    with open(out / "contacts.csv", newline="") as handle:
        return {(r["scene"], r["solver"], int(r["iterations"])): r for r in csv.DictReader(handle)}


def test_quick_run_writes_the_contacts_chart_with_both_engines(
    quick_run: tuple[Path, list[dict[str, str]], str],
) -> None:
    out, _, text = quick_run
    assert (out / "contacts.png").stat().st_size > 0
    rows = _contact_rows(out)
    default = World().contact_iterations
    for scene in solver.SCENES:
        for count in solver.QUICK_ITERATIONS["World"]:
            assert (scene, "World", count) in rows
        for name in ("pymunk", "pymunk 1 mm"):
            found = [k for k in rows if k[:2] == (scene, name)]
            assert len(found) == (len(solver.QUICK_ITERATIONS[name]) if HAS_PYMUNK else 0)
    assert ("pit", "World", default) in rows
    assert "Newton's cradle" in text and "Ball pit" in text  # the table is printed too
    for row in rows.values():
        # Every setting is timed over its whole window, awake: the pit's first 2 s, the
        # cradle's 1 s, the stacks' 2 s with --quick (5 s in a full run; a sleeping World's
        # steps would not count).
        cost, steps = float(row["cost_s_per_step"]), int(row["timed_steps"])
        assert 0.0 < cost < 1.0 and math.isfinite(cost), row
        assert steps == {"pit": 120, "cradle": 60, "stack": 120, "pyramid": 120}[row["scene"]]
        assert math.isfinite(float(row["error"])) and math.isfinite(float(row["energy"])), row


def test_this_engines_cradle_is_exact_and_its_pit_within_1_percent_at_the_default(
    quick_run: tuple[Path, list[dict[str, str]], str],
) -> None:
    rows = _contact_rows(quick_run[0])
    default = World().contact_iterations
    cradle = rows[("cradle", "World", default)]
    assert float(cradle["error"]) < 1e-6  # the last ball leaves at v0, the others stand
    assert float(cradle["energy"]) < 1e-6  # elastic: kinetic energy comes through
    pit = rows[("pit", "World", default)]
    assert 1e-4 < float(pit["error"]) <= 0.01  # balls at rest touch, by at most 1% of r
    assert int(pit["asleep"]) == solver.PIT_BALLS and float(pit["energy"]) == 0.0


def test_one_iteration_leaves_the_pit_deeper(
    quick_run: tuple[Path, list[dict[str, str]], str],
) -> None:
    # The measures tell settings apart: with one iteration a step the 20 rows of balls come
    # to rest (the bottom-up pass holds them) but overlapping more than with the default.
    rows = _contact_rows(quick_run[0])
    one, default = rows[("pit", "World", 1)], rows[("pit", "World", World().contact_iterations)]
    assert float(one["error"]) > float(default["error"])
    assert float(default["error"]) <= 0.01 and int(default["asleep"]) == 240


def test_the_stacks_drift_less_with_more_iterations_and_the_pyramid_within_1_cm(
    quick_run: tuple[Path, list[dict[str, str]], str],
) -> None:
    # The tower of 10 and the pyramid of 210 boxes, sleeping off, after 2 s (--quick's window;
    # a full run's is 5 s). Measured (the physics is deterministic): one substep lets the tower
    # walk 0.28 m and the pyramid 70 mm (the World warns); the default 4 holds them to 10.3 mm
    # and 7.1 mm (after 5 s: 0.86 m and 0.11 m, 9.6 mm and 6.9 mm). The full sweep's 1, 2, 4,
    # 8, 16 never drifted more with more substeps (tower 858, 31, 9.6, 6.2, 6.2 mm at 5 s).
    rows = _contact_rows(quick_run[0])
    default = World().contact_iterations
    for scene, bound in (("stack", 0.02), ("pyramid", 0.01)):
        one, four = rows[(scene, "World", 1)], rows[(scene, "World", default)]
        assert float(four["error"]) < float(one["error"]) / 5, scene
        assert one["warned"] == "1" and four["warned"] == "0", scene
        # A bound with margin: 10.3 mm measured for the tower, 7.1 mm for the pyramid (the
        # issue's 1 cm, there by 60 s); a box does not stand still to the micrometre either.
        assert 1e-4 < float(four["error"]) < bound, (scene, four["error"])
        assert int(four["asleep"]) == 0  # sleeping off: every step solved
    assert "Tower of boxes" in quick_run[2] and "Pyramid of boxes" in quick_run[2]


@pytest.mark.skipif(not HAS_PYMUNK, reason="pymunk (the bench extra) is absent")
def test_pymunks_pyramid_drifts_further_at_its_default_iterations(
    quick_run: tuple[Path, list[dict[str, str]], str],
) -> None:
    # Measured: pymunk's 210 boxes at its default 10 iterations move 46 mm in --quick's 2 s
    # (33 mm with a 1 mm slop; 48 and 32 mm in 5 s), this engine's 7.1 mm at its default; one
    # iteration lets pymunk's tower fall (a box 1.15 m from its place by 2 s, 19 m by 5 s).
    rows = _contact_rows(quick_run[0])
    world = float(rows[("pyramid", "World", World().contact_iterations)]["error"])
    for name in ("pymunk", "pymunk 1 mm"):
        assert float(rows[("pyramid", name, 10)]["error"]) > 2 * world, name
    assert float(rows[("stack", "pymunk", 1)]["error"]) > 1.0  # fallen: boxes metres away


@pytest.mark.skipif(not HAS_PYMUNK, reason="pymunk (the bench extra) is absent")
def test_pymunks_rows_show_its_slop_and_its_one_iteration_cradle(
    quick_run: tuple[Path, list[dict[str, str]], str],
) -> None:
    rows = _contact_rows(quick_run[0])
    # Its default collision_slop, 0.1 m, leaves overlaps of up to 20% of these radii alone.
    assert 0.1 < float(rows[("pit", "pymunk", 10)]["error"]) < 0.3
    # With a 1 mm slop its 10 iterations hold the pile tighter.
    assert float(rows[("pit", "pymunk 1 mm", 10)]["error"]) < 0.1
    # One iteration on the cradle: the speed goes wrong and energy appears from nowhere.
    assert float(rows[("cradle", "pymunk", 1)]["error"]) > 0.1
    assert float(rows[("cradle", "pymunk", 1)]["energy"]) > 0.1


def test_the_cradle_error_counts_every_wrong_speed() -> None:
    assert solver.cradle_error(np.array([[0.0, 0.0], [0.0, 0.0], [2.0, 0.0]])) == 0.0
    # A solver that spreads the blow over the row (plain Jacobi): momentum right, speeds wrong.
    spread = np.array([[0.4, 0.0], [0.8, 0.0], [0.8, 0.0]])
    assert solver.cradle_error(spread) == pytest.approx(1.2)
    hop = np.array([[0.0, 0.1], [0.0, 0.0], [2.0, 0.0]])  # a ball hopping on the floor
    assert solver.cradle_error(hop) == pytest.approx(0.05)


def test_contacts_chart_is_not_flat_and_draws_each_solver(
    quick_run: tuple[Path, list[dict[str, str]], str],
) -> None:
    pixels = _load(quick_run[0] / "contacts.png")
    assert pixels.shape[:2] == (1280, 720)
    flat = pixels.reshape(-1, 3)
    assert len(np.unique(flat, axis=0)) > 20
    for name, colour in SOLVER_COLORS.items():
        count = int(np.all(flat == np.array(colour), axis=1).sum())
        if name == "World" or HAS_PYMUNK:
            assert count > 300, (name, count)  # lines and dots in three panels, not a swatch
        else:  # pragma: no cover - the bench extra is not installed
            assert count == 0, name


def _row(scene: str, name: str, k: int, error: float, cost: float) -> solver.Row:
    return solver.Row(scene, name, k, error, 0.0, cost, False, 0, 60)


def test_contacts_chart_labels_each_dot_with_its_iterations() -> None:
    # The same dots numbered 1, 2, 3 and then 10, 20, 30: only the labels beside them (and the
    # captions under the panels) differ; without pymunk's rows none of its colours appear.
    def chart(counts: tuple[int, ...]) -> np.ndarray:
        rows = [
            _row(s, "World", k, 10.0 ** -(i + 1), 1e-4 * 4**i)
            for s in solver.SCENES
            for i, k in enumerate(counts)
        ]
        pixels = pygame.surfarray.array3d(draw_contacts(rows))
        for name in ("pymunk", "pymunk 1 mm"):
            assert not np.all(pixels == np.array(SOLVER_COLORS[name]), axis=2).any()
        return pixels

    ones, tens = chart((1, 2, 3)), chart((10, 20, 30))
    differ = np.any(ones != tens, axis=2)
    assert not differ[:, :66].any()  # the titles do not change
    bottom = 720 - 100 - 24 - 19 * 3  # the panels' (the captions below them name counts too)
    inside = differ[:, 66:bottom]
    assert inside.sum() > 5 * 3 * 20  # five panels, three labels, some pixels each
    # In the series' colour: the changed pixels are blue, drawn on white.
    changed = tens[:, 66:bottom][inside].astype(float)
    assert changed[:, 2].mean() > changed[:, 0].mean() + 40


def test_a_targets_label_keeps_clear_of_the_lines_that_cross_it() -> None:
    """The dashed target's label sits beside its line where no series' line or dot crosses
    it: at the right end when nothing is there; left of a line that crosses the line near
    the right end; shortened to "1 cm target" where the whole label fits nowhere."""
    from engine.render import font, init_headless

    init_headless()
    area, py = pygame.Rect(0, 0, 300, 300), 150
    text = "1 cm: the issue's, by 60 s"

    def rect(label: str, anchor: str, where: tuple[int, int]) -> pygame.Rect:
        return font(16).render(label, True, (0, 0, 0)).get_rect(**{anchor: where})

    assert _level_spot(text, area, py, []) == (text, "bottomright", (294, 148))
    crossing = [[(270.0, 250.0, 1), (270.0, 50.0, 4)]]  # a line through the target's, right
    label, anchor, where = _level_spot(text, area, py, crossing)
    assert label == text and not rect(label, anchor, where).clipline((270, 250), (270, 50))
    assert rect(label, anchor, where).right < 270
    # Lines at a third and two thirds across: no 135 px gap, but a 90 px one for the short.
    two = [[(100.0, 250.0, 1), (100.0, 50.0, 4)], [(200.0, 250.0, 1), (200.0, 50.0, 4)]]
    label, anchor, where = _level_spot(text, area, py, two)
    assert label == "1 cm target"
    box = rect(label, anchor, where)
    assert not box.clipline((100, 250), (100, 50)) and not box.clipline((200, 250), (200, 50))


# -- the pendulum panel: energy over many periods against cost, per method --------------------


def _pendulum_rows(out: Path) -> dict[tuple[str, float], dict[str, str]]:
    with open(out / "pendulum.csv", newline="") as handle:
        return {(r["method"], float(r["dt_s"])): r for r in csv.DictReader(handle)}


def test_quick_run_writes_the_pendulum_rows_for_every_method_and_dt(
    quick_run: tuple[Path, list[dict[str, str]], str],
) -> None:
    rows = _pendulum_rows(quick_run[0])
    assert set(rows) == {(m, dt) for m in pendulum.METHODS for dt in pendulum.QUICK_DTS}
    span = pendulum.QUICK_PERIODS * pendulum.period(pendulum.THETA0)
    for (method, dt), row in rows.items():
        assert row["chosen"] == ("exact" if method == "auto" else method)  # gravity and rods
        assert int(row["steps"]) == math.ceil(span / dt)
        cost = float(row["cost_s_per_step"])
        assert 0.0 < cost < 0.1 and math.isfinite(cost), row
    assert "Pendulum on a rod" in quick_run[2]  # the table is printed too


def test_the_pendulums_energy_errors_follow_the_methods_orders(
    quick_run: tuple[Path, list[dict[str, str]], str],
) -> None:
    rows = _pendulum_rows(quick_run[0])
    coarse, fine = pendulum.QUICK_DTS
    assert fine == coarse / 2

    def energy(method: str, dt: float) -> float:
        return float(rows[(method, dt)]["energy_error"])

    for dt in (coarse, fine):
        # Under constant gravity the free step of Verlet and RK4 is exact (a quadratic in t),
        # as the closed form's is: the three runs are the same, and so are their errors.
        same = energy("auto", dt)
        assert energy("velocity_verlet", dt) == pytest.approx(same, rel=1e-6)
        assert energy("rk4", dt) == pytest.approx(same, rel=1e-6)
        # Semi-implicit Euler's free step is first order: far worse at the same step.
        assert energy("semi_implicit_euler", dt) > 5 * same
    # Halving dt: RATTLE's error falls fourfold (order 2), semi-implicit Euler's twofold.
    assert 3.0 < energy("auto", coarse) / energy("auto", fine) < 5.0
    ratio = energy("semi_implicit_euler", coarse) / energy("semi_implicit_euler", fine)
    assert 1.6 < ratio < 2.5
    # Bounded: within 1% of m g L at dt = 1/60 s (no blow-up, no drift over the run).
    assert energy("auto", fine) < 0.01


def test_the_chart_has_a_pendulum_panel_in_each_methods_colour(
    quick_run: tuple[Path, list[dict[str, str]], str],
) -> None:
    pixels = _load(quick_run[0] / "work_precision.png")
    # The fourth panel: the right quarter, above the legend.
    panel = pixels[3 * 1280 // 4 + 10 :, 66:600].reshape(-1, 3)
    for key in ("semi_implicit_euler", "velocity_verlet", "rk4", "exact"):
        count = int(np.all(panel == np.array(COLORS[key]), axis=1).sum())
        assert count > 40, (key, count)  # its line or band, not only a dot
    # Without pendulum rows the chart keeps three panels: nothing drawn in the right quarter's
    # plotting area then but the third panel's edge.
    points = [_point("rk4", 2.0**-k, 10.0**-k) for k in range(2, 8)]
    three = pygame.surfarray.array3d(draw_work_precision(points))
    four = pygame.surfarray.array3d(draw_work_precision(points, pendulum_rows=_fake_rows()))
    assert np.any(three != four)
    right = four[1000:1260, 120:500].reshape(-1, 3)
    assert int(np.all(right == np.array(COLORS["exact"]), axis=1).sum()) > 40


def _fake_rows() -> list[pendulum.Row]:
    return [
        pendulum.Row(
            m, "exact" if m == "auto" else m, dt, dt * dt * (10 if m[0] == "s" else 1), 3e-4, 100
        )
        for m in pendulum.METHODS
        for dt in (1 / 30, 1 / 60, 1 / 120)
    ]


def test_charts_already_in_the_folder_are_refused_without_overwrite(
    quick_run: tuple[Path, list[dict[str, str]], str], capsys: pytest.CaptureFixture[str]
) -> None:
    # tradeoff overwrote its charts in --out without --overwrite; now it refuses, before
    # minutes of measuring, as the frame folders are refused.
    out, _, text = quick_run
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    assert sorted(before) == sorted(OUTPUTS)
    code = cli.main(["tradeoff", "--quick", "--out", str(out)], out=io.StringIO())
    err = capsys.readouterr().err
    assert code == 1
    assert f"error: {out / 'work_precision.png'} already exists; add --overwrite" in err
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before  # nothing measured, kept
    # Before it starts, a run says how long it takes (the whole run, and --quick).
    assert f"tradeoff: four measurements, {TAKES[True]} in all" in text


# -- --quick is quick: it measures less, and leaves out no panel ------------------------------


def test_quick_measures_a_small_sweep_and_every_panel(
    quick_run: tuple[Path, list[dict[str, str]], str],
) -> None:
    # --quick took about a minute where the README and its first line say 10 to 20 s: it now
    # measures fewer steps, tolerances, repetitions, sizes and seconds, and every panel still.
    out, rows, _ = quick_run
    assert QUICK.dts == tuple(2.0**-k for k in range(2, 9))  # 1/4 to 1/256 s: 7 steps
    assert len(QUICK.tolerances) == 7 and len(FULL.dts) == 12 and len(FULL.tolerances) == 10
    assert QUICK.repeats * QUICK.min_steps <= 100 and QUICK.rounds <= 3
    assert {float(r["dt_s"]) for r in rows if r["method"] != "auto"} == set(QUICK.dts)
    autos = [r for r in rows if r["method"] == "auto"]
    assert len(autos) == 3 * len(QUICK.tolerances)
    assert len(rows) == (5 + 4 + 4) * len(QUICK.dts) + len(autos)  # gravity has the closed form
    with open(out / "throughput.csv", newline="") as handle:
        sizes = {int(r["bodies"]) for r in csv.DictReader(handle)}
    assert sizes == {10, 100, 1000}
    contacts = _contact_rows(out)
    assert {k[0] for k in contacts} == set(solver.SCENES)  # every contacts panel
    assert solver.QUICK_STACK_TIME == 2.0 and solver.STACK_TIME == 5.0
    assert all(len(solver.QUICK_ITERATIONS[s]) == 2 for s in solver.SOLVERS)
    assert pendulum.QUICK_PERIODS == 4 and len(pendulum.QUICK_DTS) == 2


# -- auto against the fastest method: the rows over the 1.2x target say so --------------------


def _auto_point(tolerance: float, evaluations: int) -> Point:
    return Point(
        "spring", "auto", "rk4", 1 / 32, 32, 6e-5, True, False, 1e-3, 0.0, evaluations, 0,
        tolerance,
    )  # fmt: skip


def test_a_row_over_the_1_2x_target_is_flagged_and_one_under_is_not() -> None:
    # Two rows came out at 1.23x and 1.47x the best method's time, unflagged.
    rival = _point("rk4", 1 / 32, 6e-5)  # 32 steps, 1 evaluation: work 33
    rows = [rival, _auto_point(1e-3, 1), _auto_point(1e-4, 1), _auto_point(2e-4, 1)]
    rows.append(_auto_point(1e-2, 17))  # work 49: 1.48x the rival's
    text = summary(rows, {0: 1.23, 1: 1.19, 2: 1.2004, 3: 1.0})
    lines = [line for line in text.splitlines() if " tol " in line]
    assert len(lines) == 4
    assert lines[0].endswith("time 1.23x  OVER 1.2x (time)"), lines[0]
    assert lines[1].endswith("time 1.19x") and "OVER" not in lines[1]
    assert lines[2].endswith("time 1.20x") and "OVER" not in lines[2]  # as printed: within
    assert lines[3].endswith("work 1.48x, time 1.00x  OVER 1.2x (work)"), lines[3]
    assert "  2 of 4 rows over the 1.2x target (marked OVER)" in text.splitlines()
    assert "every row within" in summary(rows[:2], {0: 1.0})
    assert AUTO_TARGET == 1.2


def test_the_quick_runs_table_flags_exactly_its_rows_over_the_target(
    quick_run: tuple[Path, list[dict[str, str]], str],
) -> None:
    rows = [line for line in quick_run[2].splitlines() if " tol " in line and "auto:" in line]
    assert len(rows) == 3 * len(QUICK.tolerances)
    for line in rows:
        ratios = [float(x) for x in re.findall(r"(?:work|time) (\d+\.\d+)x", line)]
        assert len(ratios) == 2, line
        assert ("OVER 1.2x" in line) == any(x > AUTO_TARGET for x in ratios), line


# -- the pendulum panel says what it draws -----------------------------------------------------


def test_the_pendulum_panel_calls_its_three_lines_parallel_not_one() -> None:
    # It said the three methods "lie on one line" where it draws three parallel lines: the
    # same error at each dt, each at its own cost.
    note = " ".join(PENDULUM_NOTE)
    assert "parallel" in note and "one line" not in note
    captions = " ".join(_pendulum_captions(_fake_rows()))
    assert "one line" not in captions and "Verlet, RK4 and closed form (auto) all" in captions
