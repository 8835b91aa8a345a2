"""Demos of the engine, run with ``python -m demos`` (see :mod:`demos.cli`).

Each module here that defines ``DEMO = demos.cli.Demo(...)`` is found automatically.
"""

import os

# pygame prints a banner on import unless this is set; a user's own setting wins.
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
