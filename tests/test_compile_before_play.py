"""The fast path compiles before play, never during it (engine.kernels: "No compile in play").

numba compiles a kernel once for each set of argument types it meets, each new one when it is
met: a game stalled for seconds mid-play where a caller passed a strided or read-only array
its kernel's sample did not have. So every kernel has a sample, ``prepare`` compiles them all
(a World on the fast path calls it when it is made), and stepping the demos' scenes after it
adds no specialisation to any kernel. The compile says how it goes, and numba's cache lives in
the user's cache folder, not beside the engine's sources.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from engine import kernels
from engine.kernels import LoopKernel

ROOT = Path(__file__).resolve().parent.parent
COMPILED = kernels.available()
needs_numba = pytest.mark.skipif(not COMPILED, reason="numba is not installed: nothing compiles")


def test_every_kernel_has_a_sample_and_its_module_is_prepared() -> None:
    """Each ``@kernels.loop`` of the engine is in a module of ``kernels.MODULES`` (so
    ``prepare`` imports it) and has a sample call (so ``prepare`` compiles it)."""
    decorated = set()
    for path in (ROOT / "engine").rglob("*.py"):
        if "@kernels.loop" in path.read_text():
            decorated.add(".".join(path.relative_to(ROOT).with_suffix("").parts))
    assert decorated, "no kernel found: the search is wrong"
    assert decorated <= set(kernels.MODULES), decorated - set(kernels.MODULES)
    for name in kernels.MODULES:
        __import__(name)
    mine = [k for k in kernels.kernels() if k.name.startswith("engine.")]
    # (and engine.kernels' own: stable_order's compiled twin, which kernels call by address)
    assert {k.name.rsplit(".", 1)[0] for k in mine} == decorated | {"engine.kernels"}
    assert [k.name for k in mine if k.name not in kernels._SAMPLES] == []


def test_the_cache_folder_is_the_users_unless_numba_cache_dir_says(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "mine"))
    assert kernels.cache_dir() == tmp_path / "mine"
    monkeypatch.delenv("NUMBA_CACHE_DIR")
    monkeypatch.setattr(sys, "platform", "linux")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert kernels.cache_dir() == tmp_path / "xdg" / "alfred-engine" / "numba"
    monkeypatch.setenv("XDG_CACHE_HOME", "relative/is/ignored")
    assert kernels.cache_dir() == Path.home() / ".cache" / "alfred-engine" / "numba"
    monkeypatch.setattr(sys, "platform", "win32")
    monkeypatch.setenv("LOCALAPPDATA", str(tmp_path / "local"))
    assert kernels.cache_dir() == tmp_path / "local" / "alfred-engine" / "numba"


# Two small kernels of the engine, prepared in a fresh process; then (with WAITING) one is
# called with int32 arrays, which its sample (int64) does not have: a compile in play.
_PROBE = """
import os, sys
import numpy as np
from engine import kernels
from engine.exact.pile import carry_keys, label_rows
if os.environ.get("WAITING"):
    kernels.waiting = lambda message: print("told:", message)
kernels.prepare([label_rows, carry_keys])
print("cache:", kernels.cache_dir())
if os.environ.get("WAITING"):
    label_rows(2, np.array([0, 1], dtype=np.int32), np.array([1, 2], dtype=np.int32))
"""


def _numba_files(root: Path) -> dict[Path, int]:
    return {p: p.stat().st_mtime_ns for p in root.rglob("*.nb[ic]")}


@needs_numba
def test_the_cache_goes_to_the_users_cache_folder_and_a_compile_says_so(tmp_path: Path) -> None:
    """With NUMBA_CACHE_DIR unset, the kernels are cached under the user's cache folder
    (XDG_CACHE_HOME here) and nothing is written beside the engine's sources; a cold
    compile says its progress on stderr, a warm load says nothing, and a kernel compiled again
    in play (new argument types) is told by name."""
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    env.update(
        XDG_CACHE_HOME=str(tmp_path / "xdg"), HOME=str(tmp_path / "home"),
        LOCALAPPDATA=str(tmp_path / "local"), PYTHONPATH=str(ROOT),
    )  # fmt: skip
    beside = _numba_files(ROOT / "engine")

    def run(**more: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [sys.executable, "-c", _PROBE], env={**env, **more}, cwd=tmp_path,
            capture_output=True, text=True, check=True,
        )  # fmt: skip

    cold = run()
    where = Path(re.findall(r"cache: (.*)", cold.stdout)[0])
    expected = tmp_path / ("local" if sys.platform == "win32" else "xdg") / "alfred-engine"
    assert where == expected / "numba"
    made = sorted(p.name for p in where.rglob("*.nb[ic]"))
    assert any(n.startswith("pile.label_rows-") and n.endswith(".nbi") for n in made), made
    assert any(n.startswith("pile.carry_keys-") and n.endswith(".nbc") for n in made), made
    assert _numba_files(ROOT / "engine") == beside  # nothing new or rewritten beside sources
    lines = re.findall(
        r"engine: compiling the engine's kernels \(first run only\): (.*)", cold.stderr
    )
    assert lines[0] == "0/2" and lines[-1].startswith("2/2, "), cold.stderr

    warm = run(WAITING="1")
    told = re.findall(r"told: (.*)", warm.stdout)
    assert told == [
        "compiling engine.exact.pile.label_rows again during play, for argument types its sample "
        "did not have (engine.kernels)"
    ], warm.stdout + warm.stderr
    assert "compiling" not in warm.stderr


@needs_numba
def test_a_compiles_helper_takes_kernels_from_the_back_until_it_meets_a_claimed_one(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A cold compile is shared with a second process (engine.kernels._Helper): each kernel is
    compiled by the one of the two that claims it first, this one from the front of the list and
    the helper (``python -m engine.warmup --claims DIR NAME ...``) from the back; the helper
    stops at the first kernel already claimed, so none is compiled twice."""
    from engine import warmup

    kernels.prepare()  # (loaded from the cache, or compiled: what the helper takes then loads)
    names = [k.name for k in kernels.kernels()]
    assert kernels.claim(tmp_path, names[0]) and not kernels.claim(tmp_path, names[0])
    for name in names[1:-2]:  # this process has reached all but the last two
        assert kernels.claim(tmp_path, name)
    assert warmup.main(["--claims", str(tmp_path), *names]) == 0
    assert "engine.warmup: 2 loop kernels ready" in capsys.readouterr().out
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(names)
    assert warmup.main(["--claims", str(tmp_path), "engine.nothing"]) == 2
    assert "no loop kernel is named engine.nothing" in capsys.readouterr().err
    assert warmup.main(["--fast"]) == 2
    assert "takes no arguments" in capsys.readouterr().err


#: A handful of the engine's cheapest kernels: a cold compile of them starts a helper as a
#: cold compile of all does (each is found by name in the helper), in seconds, not a minute.
_SMALL = (
    "engine.dynamics.events.merge_loop",
    "engine.exact.pile.label_rows",
    "engine.exact.pile.dissipate_rows",
    "engine.exact.pile.carry_keys",
    "engine.exact.pile.carry_gather",
    "engine.geometry.pair_grid.reach_pairs",
)


@needs_numba
def test_a_cold_compile_is_shared_with_a_helper_process(tmp_path: Path) -> None:
    """On an empty cache a compile starts a helper as numba starts compiling, and both fill
    one cache: a later process loads every kernel from it, compiling none."""
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache"), "PYTHONPATH": str(ROOT)}
    probe = (
        "import importlib\n"
        "from engine import kernels\n"
        "for m in kernels.MODULES: importlib.import_module(m)\n"
        "by_name = {k.name: k for k in kernels.kernels()}\n"
        f"small = [by_name[n] for n in {_SMALL!r}]\n"
        "kernels.prepare(small)\n"
        "print('compiled', sum(len(k.fast.stats.cache_misses) for k in small))\n"
        "print('loaded', sum(len(k.fast.stats.cache_hits) for k in small))\n"
    )

    def run() -> tuple[int, int]:
        out = subprocess.run(
            [sys.executable, "-c", probe], env=env, cwd=tmp_path, capture_output=True,
            text=True, check=True,
        ).stdout  # fmt: skip
        return int(re.findall(r"compiled (\d+)", out)[0]), int(re.findall(r"loaded (\d+)", out)[0])

    compiled, loaded = run()
    count = len(_SMALL)
    assert count >= kernels.HELPED_FROM  # (enough to be worth a helper)
    # Cold: this process compiled some, and loaded the helper's (both at least one).
    assert compiled + loaded == count and compiled >= 1 and loaded >= 1, (compiled, loaded)
    assert run() == (0, count)  # warm: every kernel loaded, none compiled


# -- no specialisation added in play ------------------------------------------------------------


def _signatures() -> dict[str, int]:
    return {k.name: len(k.fast.signatures) for k in kernels.kernels()}


def _added(
    before: dict[str, int], among: list[LoopKernel[Any]] | None = None
) -> dict[str, list[str]]:
    """The specialisations each kernel (the engine's, or ``among``) gained since ``before``,
    by name; none: {}."""
    out = {}
    for k in kernels.kernels() if among is None else among:
        new = k.fast.signatures[before.get(k.name, 0) :]
        if new:
            out[k.name] = [str(s) for s in new]
    return out


def _scenes() -> Iterator[tuple[str, Callable[[], Any], float, int]]:
    """The demos' scenes, small: (name, made, dt, steps). Between them they call every
    kernel (the test checks), with the types a game's steps give them."""
    from demos import ballpit, galton, hinges, pinball, platformer_scene, stack

    def scene(cls: type) -> Callable[[], Any]:
        def made() -> Any:
            s = cls()
            s.build((320, 240))
            return s

        return made

    yield "pinball", scene(pinball.PinballScene), pinball.DT, 480

    def struck() -> Any:
        # The left bat flipped up into a ball just above it: the joints' solve over a disc
        # against a polygon that turns (engine.exact.joint_rows' turned_loop), which the
        # game's first 4 s above do not reach.
        from engine import World
        from engine.forces import Gravity

        world = World(integrator="auto", solver="exact")
        world.add_force(Gravity((0.0, -pinball.GRAVITY)))
        _, hinge = pinball.add_flipper(world, -1)
        x, y = pinball.LEFT_PIVOT
        pinball.add_ball(world, (x + 5.0, y + 3.0))
        pinball.drive(hinge, -1, True)
        return world

    yield "a pinball's bat struck", struck, pinball.DT, 40
    yield "ballpit", lambda: ballpit.pit_world(200)[0], 1 / 60, 150
    # (It meets at 1.1 s.)
    yield "stack tumbler", lambda: stack.tumbler(60, solver="exact")[0], 1 / 60, 90
    # The soft step past a few bodies: its broadphase's grid and big bodies (the walls).
    yield "stack tumbler (soft)", lambda: stack.tumbler(60, solver="soft")[0], 1 / 60, 90
    yield "stack tower", lambda: stack.tower(6, solver="exact")[0], 1 / 60, 60
    yield "hinges chain", scene(hinges.ChainScene), hinges.ChainScene.dt, 240
    yield "hinges car", scene(hinges.CarScene), hinges.CarScene.dt, 240
    yield "galton", scene(galton.GaltonScene), galton.GaltonScene.dt, 240
    yield "platformer (soft)", lambda: platformer_scene.build(solver="soft").world, 1 / 60, 120

    def thrown() -> Any:
        # Its ball thrown at 60 m/s along the ground: fast, swept (engine.dynamics.game_continuous).
        game = platformer_scene.build(solver="soft")
        game.ball.vel = (60.0, -20.0)
        return game.world

    yield "platformer (soft), its ball thrown", thrown, 1 / 60, 30


@needs_numba
@pytest.mark.filterwarnings("ignore::engine.StabilityWarning")  # the pile's, not this test's
def test_stepping_the_demos_scenes_adds_no_specialisation(monkeypatch: pytest.MonkeyPatch) -> None:
    """After ``prepare`` (here: the first World on the fast path), stepping the demos' scenes
    on the fast path compiles nothing: no kernel gains a signature, and every kernel ran."""
    monkeypatch.setenv("ENGINE_KERNELS", "fast")
    kernels.prepare()
    before = _signatures()
    called: set[str] = set()
    call = LoopKernel.__call__

    def counted(self: LoopKernel[Any], *args: Any) -> Any:
        called.add(self.name)
        return call(self, *args)

    monkeypatch.setattr(LoopKernel, "__call__", counted)
    for name, made, dt, steps in _scenes():
        world = made()
        for _ in range(steps):
            world.step(dt)
        assert _added(before) == {}, f"{name} compiled in play"
    # The scenes reach every kernel (or a kernel that calls it, or one that calls that ...).
    grown = True
    while grown:
        size = len(called)
        for k in kernels.kernels():
            if k.name in called:
                called.update(k.calls)
        grown = len(called) > size
    assert sorted(set(before) - called) == []


@needs_numba
def test_a_specialisation_added_in_play_is_seen() -> None:
    """The check can fail: a kernel called with types its sample lacks (an int where the
    sample had a float) gains a signature, and ``_added`` names it."""

    def double(x: float) -> float:
        return 2.0 * x

    k = kernels.loop(sample=lambda: (1.5,))(double)
    kernels._ALL.remove(k)  # not one of the engine's kernels
    kernels.prepare([k])
    before = {k.name: len(k.fast.signatures)}
    assert k(2.5) == 5.0
    assert _added(before, [k]) == {}
    assert k(np.int64(2)) == 4.0
    assert _added(before, [k]) == {k.name: ["(int64,)"]}


# A kernel that calls another, in a package of the test's own: compiled into numba's cache in
# one process, then the callee's source changed and the caller loaded in a second.
_CALLEE = """
from engine import kernels

@kernels.loop(sample=lambda: (2.0,))
def scaled(x):
    return x * {factor}
"""
_CALLER = """
from engine import kernels
from .callee import scaled

@kernels.loop(sample=lambda: (2.0,))
def twice(x):
    return scaled(x) + scaled(x)
"""
_RUN = """
from engine import kernels
from probe.callee import scaled
from probe.caller import twice
kernels.prepare([scaled, twice])
print("got:", twice(2.0))
"""


def _probe(tmp_path: Path, kept: dict[str, str], edited: str, script: str) -> Any:
    """A package ``probe`` of the test's own in ``tmp_path``: its files ``kept`` written once,
    and a ``run(text)`` that writes ``text`` to its file ``edited`` and runs ``script`` in a
    fresh Python on one numba cache, returning what it printed after "got: "."""
    package = tmp_path / "probe"
    package.mkdir()
    (package / "__init__.py").write_text("")
    for name, text in kept.items():
        (package / name).write_text(text)
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    env["PYTHONPATH"] = f"{ROOT}{os.pathsep}{tmp_path}"

    def run(text: str) -> str:
        # (A new size as well as a new time: file systems with coarse times still see it.)
        (package / edited).write_text(text)
        out = subprocess.run(
            [sys.executable, "-c", script], env=env, cwd=tmp_path, capture_output=True,
            text=True, check=True,
        )  # fmt: skip
        return str(re.findall(r"got: (.*)", out.stdout)[0])

    return run


@needs_numba
def test_a_kernel_that_calls_another_is_compiled_again_when_the_other_changes(
    tmp_path: Path,
) -> None:
    """numba's cache checks only the caller's file; engine.kernels stamps a caller's entry with
    its callees' files too, so an edited callee is never run as its old compiled self."""
    run = _probe(tmp_path, {"caller.py": _CALLER}, "callee.py", _RUN)
    assert run(_CALLEE.format(factor=3)) == "12.0"
    assert run(_CALLEE.format(factor=3)) == "12.0"  # from the cache
    assert run(_CALLEE.format(factor=50)) == "200.0"  # the callee changed: not the cached 12.0


# A kernel that reads a constant of another module: numba compiles the constant's value in.
_CONSTANT = "FACTOR = {factor}\n"
_READER = """
from engine import kernels
from .constant import FACTOR

@kernels.loop(sample=lambda: (2.0,))
def scaled(x):
    return x * FACTOR
"""
_READ = """
from engine import kernels
from probe.reader import scaled
kernels.prepare([scaled])
print("got:", scaled(2.0))
"""


@needs_numba
def test_a_kernel_is_compiled_again_when_a_constant_it_imported_changes(tmp_path: Path) -> None:
    """numba's cache checks only the kernel's own file, and compiles the value of a global
    it reads into the code; engine.kernels stamps its entry with the files its constants come
    from too (a sleep tolerance edited in engine.pipeline.game_sleep ran as it was in the fast
    path's step until the step's own file changed)."""
    run = _probe(tmp_path, {"reader.py": _READER}, "constant.py", _READ)
    assert run(_CONSTANT.format(factor=3)) == "6.0"
    assert run(_CONSTANT.format(factor=3)) == "6.0"  # from the cache
    assert run(_CONSTANT.format(factor=50)) == "100.0"  # the constant changed: not 6.0


# A kernel that calls a helper (kernels.helper) of another module, which calls a helper of a
# third: numba compiles each helper once, as its own function, and the kernel calls them.
_INNER = """
from engine import kernels

@kernels.helper
def scale(x):
    return x * {factor}
"""
_OUTER = """
from engine import kernels
from .inner import scale

@kernels.helper
def shifted(x):
    return scale(x) + 1.0
"""
_USER = """
from engine import kernels
from .outer import shifted

@kernels.loop(sample=lambda: (2.0,))
def twice(x):
    return shifted(x) + shifted(x)
"""
_USE = """
from engine import kernels
from probe.user import twice
kernels.prepare([twice])
print("got:", twice(2.0), twice.py(2.0))
"""


@needs_numba
def test_a_kernel_is_compiled_again_when_a_helper_its_helper_calls_changes(
    tmp_path: Path,
) -> None:
    """A helper is the same code in plain Python and compiled (its own numba function, not a
    closure inlined at each call site); the kernel's cache entry, and the helper's, are
    stamped with the files of the helpers they call, so an edited helper two calls down is
    never run as its old compiled self."""
    run = _probe(tmp_path, {"user.py": _USER, "outer.py": _OUTER}, "inner.py", _USE)
    assert run(_INNER.format(factor=3)) == "14.0 14.0"
    assert run(_INNER.format(factor=3)) == "14.0 14.0"  # from the cache
    assert run(_INNER.format(factor=50)) == "202.0 202.0"  # the helper changed: not 14.0


_READING_INNER = """
from engine import kernels
from .constant import FACTOR

@kernels.helper
def scale(x):
    return x * FACTOR
"""


@needs_numba
def test_a_kernel_is_compiled_again_when_a_constant_its_helper_reads_changes(
    tmp_path: Path,
) -> None:
    kept = {"user.py": _USER, "outer.py": _OUTER, "inner.py": _READING_INNER}
    run = _probe(tmp_path, kept, "constant.py", _USE)
    assert run(_CONSTANT.format(factor=3)) == "14.0 14.0"
    assert run(_CONSTANT.format(factor=3)) == "14.0 14.0"  # from the cache
    assert run(_CONSTANT.format(factor=50)) == "202.0 202.0"  # the constant changed
