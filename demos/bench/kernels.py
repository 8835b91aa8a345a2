"""The fast extra's cost: what installing numba adds, and how long its kernels take to compile.

Run with ``python -m demos.bench kernels``. The kernels (engine.kernels) are compiled the first
time a World on the fast path uses them and cached on disk (numba's ``cache=True``); this
measures both in fresh processes, with numba's cache in an empty temporary folder, so the
machine's own cache is neither used nor touched:

* ``import numba``: what the fast path adds to the first step of a program;
* the first run: every kernel compiled (``engine.kernels.prepare``);
* every later run: the same kernels loaded from the cache.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

__all__ = ["report", "measure"]

_PROBE = """
import json, time
t0 = time.perf_counter()
import numba
t1 = time.perf_counter()
from engine import kernels
seconds = kernels.prepare()
print(json.dumps({"import": t1 - t0, "prepare": seconds, "count": len(kernels.kernels()),
                  "numba": numba.__version__}))
"""


def measure() -> dict[str, float] | None:
    """{"import", "compile", "load" (s), "count"} measured in fresh processes; None without
    numba."""
    from engine import kernels

    if not kernels.available():
        return None
    root = Path(__file__).resolve().parents[2]
    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache, "ENGINE_KERNELS": "fast"}
        runs = []
        for _ in range(2):  # the first compiles into the empty cache; the second loads
            out = subprocess.run(
                [sys.executable, "-c", _PROBE],
                capture_output=True,
                text=True,
                env=env,
                cwd=root,
                check=True,
            )
            runs.append(json.loads(out.stdout.strip().splitlines()[-1]))
    first, second = runs
    return {
        "import": second["import"],
        "compile": first["prepare"],
        "load": second["prepare"],
        "count": first["count"],
        "numba": first["numba"],
    }


def _size() -> str:
    """The installed size of numba and llvmlite (MB), read from their folders."""
    import importlib.util

    total = 0
    for name in ("numba", "llvmlite"):
        spec = importlib.util.find_spec(name)
        if spec is None or spec.origin is None:
            continue
        for path in Path(spec.origin).parent.rglob("*"):
            if path.is_file():
                total += path.stat().st_size
    return f"{total / 1e6:.0f} MB"


def report(quick: bool = False) -> str:
    """The fast extra's install size, import time, and first and cached compile times."""
    got = measure()
    if got is None:
        return "kernels: numba is not installed (pip install -e '.[fast]'): the numpy path only"
    return (
        f"kernels: numba {got['numba']} ({_size()} with llvmlite); {got['count']:.0f} loop "
        f"kernels; import numba {got['import']:.2f} s; the first run compiles them in "
        f"{got['compile']:.1f} s, later runs load them from the cache in {got['load']:.2f} s"
    )
