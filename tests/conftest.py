"""Test set-up: run pygame headless (no screen, no sound card) before anything imports it, and
choose how hypothesis explores."""

import os

from hypothesis import settings

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

# No per-example deadline anywhere: the machines are shared, and a slow moment is not a bug.
# On a developer's machine hypothesis tries new examples every run, to keep finding edge
# cases; in CI (CI=true) it replays a fixed derandomized set, so a submission's verdict does
# not depend on the luck of the draw.
settings.register_profile("dev", deadline=None)
settings.register_profile("ci", deadline=None, derandomize=True, print_blob=True)
settings.load_profile("ci" if os.environ.get("CI") else "dev")
