"""Compile the fast path's loop kernels now, once, not in a game: ``python -m engine.warmup``.

The README's install line for the ``fast`` extra ends with this command, so the first run's
compile (40 to 75 s for the 35 kernels on machines of our kind, shared with a second process
where there is a second core) happens at install time, with its progress on stderr, and
numba's cache (``engine.kernels.cache_dir()``) holds them all. A World on the fast path
still calls ``engine.kernels.prepare()`` when it is made, which then only loads them (about
0.2 s), and compiles them there, before any step, if the cache was emptied since. Without
numba there is nothing to compile: it says so and exits with 0, so the line never fails.
"""

from __future__ import annotations

import importlib
import sys
import time
from pathlib import Path

from . import kernels

__all__ = ["main"]


def main(argv: list[str] | None = None) -> int:
    """Prepare every kernel (``engine.kernels.prepare``) and say how many, how long, where.
    ``--claims DIR NAME ...``: a compile's helper process (engine.kernels._Helper)."""
    args = sys.argv[1:] if argv is None else argv
    if not kernels.available():
        print("engine.warmup: numba is not installed (the fast extra): nothing to compile")
        return 0
    if args[:1] == ["--claims"] and len(args) >= 2:
        # A compile's helper (engine.kernels._Helper): the kernels named, from the back, each
        # one it claims before the process that started it does.
        for name in kernels.MODULES:
            importlib.import_module(name)
        by_name = {k.name: k for k in kernels.kernels()}
        claims, names = Path(args[1]), args[2:]
        unknown = [n for n in names if n not in by_name]
        if unknown:
            print(f"engine.warmup: no loop kernel is named {', '.join(unknown)}", file=sys.stderr)
            return 2
        count, t0 = 0, time.perf_counter()
        for name in reversed(names):
            if not kernels.claim(claims, name):
                break  # the other process has reached it: the rest are its
            kernels.prepare([by_name[name]])
            count += 1
        seconds = time.perf_counter() - t0
    elif args:
        print(f"engine.warmup takes no arguments, got {args}", file=sys.stderr)
        return 2
    else:
        seconds = kernels.prepare()
        count = len(kernels.kernels())
    print(
        f"engine.warmup: {count} loop kernels ready in {seconds:.1f} s "
        f"(numba's cache: {kernels.cache_dir()})"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
