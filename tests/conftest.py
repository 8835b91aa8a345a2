"""Test set-up: run pygame headless (no screen, no sound card) before anything imports it, and
choose how hypothesis draws its examples (a fixed set by default; ``explore`` on request)."""

import os
from collections.abc import Iterator
from typing import Any

import pytest
from hypothesis import settings

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

# No per-example deadline anywhere: the machines are shared, and a slow moment is not a bug.
# The README's test command replays a fixed derandomized set of examples (the "replay"
# profile, the default, in CI and on a newcomer's fresh clone alike), so its verdict does not
# depend on the luck of the draw. A developer hunting new edge cases asks for fresh examples
# every run with `python -m pytest --hypothesis-profile=explore`; what that finds becomes a
# regression test (an explicit example or a scene of its own).
settings.register_profile("replay", deadline=None, derandomize=True, print_blob=True)
settings.register_profile("explore", deadline=None, print_blob=True)
settings.load_profile("replay")

# A long exploration: `FUZZ_EXAMPLES=3000 python -m pytest --hypothesis-profile=explore` runs
# every hypothesis test (its own `@settings` or tests.fuzzing.fuzz, the stateful machines
# too) with at least that many examples; a test that asks for more keeps its count. (A
# profile cannot do it: a test's own max_examples overrides the profile's.) Unset, every test
# runs its own count. A strict xfail that runs only its `@example`s (fuzzing.fuzz's
# known_bug) still runs only them.
FUZZ_EXAMPLES = int(os.environ.get("FUZZ_EXAMPLES") or 0)


# Hypothesis also draws, now and then, a constant it found in any local module imported so far
# (hypothesis.internal.conjecture.providers: "local constants"), so a new number anywhere in
# the engine, the demos or the tests changed the fixed set the replay profile draws: a commit
# that touched no fuzzed code could meet new examples. Replaying, the set depends on the tests'
# own strategies alone; exploring keeps the constants (they find edge cases).
def _stable_constants() -> None:
    from hypothesis.internal.conjecture import providers

    found = getattr(providers, "_get_local_constants", None)
    if found is None or getattr(found, "stable", False):
        return  # (a hypothesis without them, or set already)

    def local_constants():  # type: ignore[no-untyped-def]
        return providers.Constants() if settings.default.derandomize else found()

    local_constants.stable = True  # type: ignore[attr-defined]
    providers._get_local_constants = local_constants


_stable_constants()


# Hypothesis draws its examples partly from the constants of the project's modules loaded so
# far (hypothesis.internal.conjecture.providers: "local constants"), so a derandomized fuzz
# test drew other examples after other tests had imported more of the project: its verdict
# depended on which tests ran before it in its worker (pytest-xdist shares them out by
# timing). Every module of the engine and the demos is imported here, before any test, so the
# examples are the same whatever runs first.
def _import_everything() -> None:
    import importlib
    import pkgutil

    import demos
    import engine

    for package in (engine, demos):
        for info in pkgutil.walk_packages(package.__path__, package.__name__ + "."):
            if not info.name.endswith("__main__"):
                importlib.import_module(info.name)


_import_everything()


# -- the fast path's kernels, compiled once for all of xdist's workers ---------------------------
#
# On a cold numba cache (a fresh machine: CI's run on the fast path) each of `-n 2`'s workers
# met it at its first World and compiled every kernel itself, each with its helper process
# (engine.kernels.prepare: the helpers share out one process's list, not another's): the whole
# compile twice over, 64 s of one core each, with the tests of both workers waiting on it. The
# controller, which runs no test, now prepares them before it starts the workers, who load
# them from the cache it filled. A run without workers keeps its own first compile, as a
# developer's does, and the tests of the compile (test_compile_before_play) use caches of
# their own.
def pytest_configure(config: pytest.Config) -> None:
    if hasattr(config, "workerinput") or not getattr(config.option, "numprocesses", None):
        return  # an xdist worker, or a run without workers
    from engine import kernels

    if kernels.default() == "fast":
        kernels.prepare()


# -- the fast path's run: the files that never reach a kernel ------------------------------------
#
# CI runs the suite twice: the README's test command on numpy (the reference), then again with
# the fast extra and ENGINE_KERNELS=fast. A test that never calls one of the engine's loop
# kernels (engine.kernels.LoopKernel) takes the same code on both paths, so its second run
# proves nothing new: `--skip-path-free` leaves out the files below, every test of which called
# no kernel on the fast path (measured on 2026-12-02: 72 of 136 files, a quarter of the fast
# run's time). A file stays listed only while that holds: whenever the suite runs on the fast
# path without that option (a developer with the fast extra installed, whose default path is
# fast), each test of a listed file is watched, and one that calls a kernel fails, naming the
# file to take out of this list. A new file is not listed, so it runs on both paths.
PATH_FREE = frozenset(
    """
engine/__init__.py engine/accuracy.py engine/body.py engine/checks.py engine/geometry/colliders.py
engine/dynamics/coloring.py engine/geometry/convex.py engine/filters.py
engine/dynamics/forcefield.py engine/forces.py engine/geometry/impact.py engine/integrators.py
engine/kernels.py engine/kinematics.py engine/loop.py engine/geometry/manifold.py
engine/geometry/mass.py engine/geometry/pair_grid.py engine/particles.py engine/points.py
engine/pipeline/queries.py engine/render/camera.py engine/render/clips.py engine/render/recorder.py
engine/geometry/shaped.py engine/stability.py engine/dynamics/store.py
engine/dynamics/torquefield.py engine/vector.py engine/world.py tests/test_alfred.py
tests/test_auto.py tests/test_bench_platformer.py tests/test_body.py tests/test_car.py
tests/test_events_open.py
tests/test_clips.py tests/test_determinism.py tests/test_fireworks.py tests/test_forces.py
tests/test_frames.py tests/test_fuzz_cli.py tests/test_fuzz_core.py tests/test_fuzz_particles.py
tests/test_fuzz_render.py tests/test_fuzz_world.py tests/test_import_layers.py
tests/test_integrators.py tests/test_interruptions.py tests/test_joint_contacts.py
tests/test_kernels_ledger.py tests/test_kinematics.py tests/test_layers.py tests/test_limits.py
tests/test_long_runs.py tests/test_loop.py tests/test_manifold.py tests/test_module_table.py
tests/test_packaging.py tests/test_particles.py tests/test_pendulum.py tests/test_render_camera.py
tests/test_render_recorder.py tests/test_shape_queries.py tests/test_stability.py
tests/test_stability_demo.py tests/test_steppable.py tests/test_vector.py tests/test_vector_names.py
tests/test_vector_pygame.py tests/test_world.py tests/test_world_parts.py
tests/test_world_view_spin.py
""".split()
)


# For the same reason `--skip-path-free` leaves out a test given the numpy path by name (a
# parameter "numpy", or "soft-numpy" and the like: tests.paths.PATHS' first): it ran in the first
# run as it would in the second. It is watched as a PATH_FREE file's test is, and one that calls
# a compiled kernel all the same fails, saying so.


def _numpy_by_name(item: pytest.Item) -> bool:
    """Whether ``item`` is given the numpy path by a parameter ("numpy", "soft-numpy", ...)."""
    spec = getattr(item, "callspec", None)
    return spec is not None and any(
        isinstance(v, str) and (v == "numpy" or v.endswith("-numpy")) for v in spec.params.values()
    )


def _same_on_both(item: pytest.Item) -> bool:
    """Whether ``item`` takes the same code on both paths: a PATH_FREE file's, or named numpy."""
    return _file(item) in PATH_FREE or _numpy_by_name(item)


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption(
        "--skip-path-free",
        action="store_true",
        help="leave out the files that call none of the engine's kernels (tests/conftest.py: "
        "PATH_FREE) and the tests given the numpy path by name: for a second run on the fast "
        "path, after one on numpy",
    )


def _file(item: pytest.Item) -> str:
    """The item's file, relative to the project, with / between folders."""
    return item.nodeid.split("::", 1)[0]


def _raise_examples(items: list[pytest.Item]) -> None:
    """Give every hypothesis test among ``items`` at least FUZZ_EXAMPLES examples."""
    for item in items:
        test = getattr(getattr(item, "obj", None), "__func__", getattr(item, "obj", None))
        own = getattr(test, "_hypothesis_internal_use_settings", None)
        if own is None:
            owner = getattr(item, "cls", None)  # a stateful machine's TestCase
            own = getattr(owner, "settings", None) if owner is not None else None
            if isinstance(own, settings) and own.max_examples < FUZZ_EXAMPLES:
                owner.settings = settings(own, max_examples=FUZZ_EXAMPLES)  # type: ignore[union-attr]
            continue
        if own.max_examples < FUZZ_EXAMPLES:
            test._hypothesis_internal_use_settings = settings(own, max_examples=FUZZ_EXAMPLES)


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    if FUZZ_EXAMPLES:
        _raise_examples(items)
    if not config.getoption("--skip-path-free"):
        return
    from engine import kernels

    if kernels.default() != "fast":
        raise pytest.UsageError(
            "--skip-path-free is for a run on the fast path (ENGINE_KERNELS=fast, numba "
            f"installed), after the same suite on numpy; this run's path is {kernels.default()!r}"
        )
    kept = [item for item in items if not _same_on_both(item)]
    config.hook.pytest_deselected(items=[item for item in items if _same_on_both(item)])
    items[:] = kept


_kernel_calls = [0]


def _count_kernel_calls() -> None:
    """Count every call of a loop kernel (engine.kernels.LoopKernel) in ``_kernel_calls``."""
    from engine import kernels

    call = kernels.LoopKernel.__call__
    if getattr(call, "counted", False):
        return

    def counted(self: Any, *args: Any) -> Any:
        _kernel_calls[0] += 1
        return call(self, *args)

    counted.counted = True  # type: ignore[attr-defined]
    kernels.LoopKernel.__call__ = counted  # type: ignore[method-assign]


_START = pytest.StashKey[int]()


def _watched(item: pytest.Item) -> bool:
    """Whether ``item`` takes the same code on both paths (``_same_on_both``) and runs where
    the default path is fast."""
    from engine import kernels

    return _same_on_both(item) and kernels.default() == "fast"


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_setup(item: pytest.Item) -> Iterator[None]:
    # The count starts before the test's fixtures are made (a module's shared scene too).
    if _watched(item):
        _count_kernel_calls()
        item.stash[_START] = _kernel_calls[0]
    yield


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo[None]) -> Iterator[None]:
    # A test of a PATH_FREE file that called a kernel fails at its teardown (the list's rule).
    outcome = yield
    report = outcome.get_result()  # type: ignore[attr-defined]
    if call.when != "teardown" or _START not in item.stash or not report.passed:
        return
    calls = _kernel_calls[0] - item.stash[_START]
    if calls:
        report.outcome = "failed"
        if _file(item) in PATH_FREE:
            report.longrepr = (
                f"{_file(item)} called the engine's loop kernels on the fast path ({calls} calls "
                "in this test): take it out of PATH_FREE in tests/conftest.py, so that CI's run "
                "on the fast path runs it"
            )
        else:
            report.longrepr = (
                f"{item.nodeid} is given the numpy path by name but called the engine's loop "
                f"kernels on the fast path ({calls} calls): give its Worlds that path "
                "(kernels=...), or name the parameter otherwise, so that CI's run on the fast "
                "path, which leaves it out, loses nothing"
            )
