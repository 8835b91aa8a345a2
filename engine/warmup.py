"""Compile the fast path's loop kernels now, once, not in a game: ``python -m engine.warmup``.

The README's install line for the ``fast`` extra ends with this command, so the first run's
compile (about 20 s for the 22 kernels) happens at install time, with its progress on stderr,
and numba's cache (``engine.kernels.cache_dir()``) holds them all. A World on the fast path
still calls ``engine.kernels.prepare()`` when it is made, which then only loads them (about
0.2 s), and compiles them there, before any step, if the cache was emptied since. Without
numba there is nothing to compile: it says so and exits with 0, so the line never fails.
"""

from __future__ import annotations

import sys

from . import kernels

__all__ = ["main"]


def main() -> int:
    """Prepare every kernel (``engine.kernels.prepare``) and say how many, how long, where."""
    if not kernels.available():
        print("engine.warmup: numba is not installed (the fast extra): nothing to compile")
        return 0
    seconds = kernels.prepare()
    count = len(kernels.kernels())
    print(
        f"engine.warmup: {count} loop kernels ready in {seconds:.1f} s "
        f"(numba's cache: {kernels.cache_dir()})"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
