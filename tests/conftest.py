"""Test set-up: run pygame headless (no screen, no sound card) before anything imports it, and
choose how hypothesis draws its examples (a fixed set by default; ``explore`` on request)."""

import os

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
