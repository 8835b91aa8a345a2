"""Which path the hot loops take: numpy (the reference, everywhere) or compiled loops (``fast``).

Most of a step is a few array calls, and numpy carries them well. A few stages are loops by
nature: a Gauss-Seidel sweep over a pile's contacts (each row sees the velocities the rows
before it left), the broadphase's cells, a union-find. In numpy they become one array call a
colour, a cell size or a round, and at the sizes of a game numpy's fixed cost per call (a few
microseconds) is most of their time. With the ``fast`` extra installed
(``pip install -e ".[fast]"``: numba), each such stage also has a **loop kernel**: the same
algorithm written as the loop it is, in plain Python beside its numpy twin in the stage's own
module, which numba compiles to machine code the first time it is used (``cache=True``: later
runs load it from disk).

**The path** is chosen once, when a World is made (``World(kernels=...)``; ``world.kernels``
says which it runs):

* ``"fast"``: the loop kernels, compiled; the default where numba is installed;
* ``"numpy"``: the numpy twins; the default without numba, and forced by
  ``ENGINE_KERNELS=numpy`` in the environment or ``World(kernels="numpy")``.

``import engine`` does not import numba: a kernel is compiled on its first call on the fast
path. Both paths give the same numbers to rounding (tests/test_kernels.py checks each kernel
against its twin to 1e-12 relative), so every exactness test holds on both. Validation stays
before the kernels, so an error reads the same on either path.

>>> choose("numpy")
'numpy'
>>> choose("gpu")  # doctest: +ELLIPSIS
Traceback (most recent call last):
    ...
ValueError: kernels must be 'numpy' or 'fast' ..., got 'gpu'
"""

from __future__ import annotations

import importlib.util
import os
import threading
import time
from collections.abc import Callable
from typing import Any, Generic, TypeVar

__all__ = [
    "PATHS",
    "LoopKernel",
    "available",
    "choose",
    "default",
    "kernels",
    "loop",
    "prepare",
]

#: The paths, the reference first.
PATHS = ("numpy", "fast")
#: The environment variable that picks the default path (``numpy`` or ``fast``).
ENV = "ENGINE_KERNELS"

F = TypeVar("F", bound=Callable[..., Any])


def available() -> bool:
    """Whether numba is installed (the ``fast`` extra), without importing it."""
    return importlib.util.find_spec("numba") is not None


def default() -> str:
    """The path a World takes when not told: ``ENGINE_KERNELS`` if set, else ``"fast"``
    where numba is installed and ``"numpy"`` where it is not."""
    wanted = os.environ.get(ENV, "").strip().lower()
    if wanted:
        if wanted not in PATHS:
            raise ValueError(
                f"the environment variable {ENV} must be 'numpy' or 'fast' (or unset), "
                f"got {wanted!r}"
            )
        return choose(wanted)
    return "fast" if available() else "numpy"


def choose(kernels: str | None) -> str:
    """The path for a World's ``kernels`` argument (None: ``default()``); ValueError for a
    name that is not a path, or for ``"fast"`` without numba installed."""
    if kernels is None:
        return default()
    if kernels not in PATHS:
        raise ValueError(
            f"kernels must be 'numpy' or 'fast' (or None: the default, fast where numba is "
            f"installed), got {kernels!r}"
        )
    if kernels == "fast" and not available():
        raise ValueError(
            "kernels='fast' needs numba, the fast extra: pip install -e '.[fast]' "
            "(or use kernels='numpy', the reference path)"
        )
    return kernels


class LoopKernel(Generic[F]):
    """A stage's loop, in plain Python (``py``: runs anywhere, slowly) and compiled by numba
    on first use (``fast``). Made by the ``@loop`` decorator."""

    def __init__(self, fn: F) -> None:
        self.py: F = fn
        self.name = f"{fn.__module__}.{fn.__qualname__}"
        self._compiled: Any = None
        _ALL.append(self)

    @property
    def fast(self) -> F:
        """The compiled kernel (numba.njit, cached on disk); compiled on the first call."""
        if self._compiled is None:
            import numba  # only here: import engine does not import numba

            self._compiled = numba.njit(cache=True, nogil=True)(self.py)
        return self._compiled  # type: ignore[no-any-return]

    def __call__(self, *args: Any) -> Any:
        """The compiled kernel's result for ``args`` (the fast path's call)."""
        f = self._compiled
        if f is None:
            return self._first(args)
        return f(*args)

    def _first(self, args: tuple[Any, ...]) -> Any:
        """The first call: compile (or load from the cache) and run, telling ``waiting``
        if that takes long enough to be a compile."""
        fast = self.fast  # numba imported and the kernel made: not yet compiled or loaded
        timer = _timer()
        try:
            return fast(*args)
        finally:
            if timer is not None:
                timer.cancel()

    def __repr__(self) -> str:
        return f"LoopKernel({self.name})"


_ALL: list[LoopKernel[Any]] = []
#: Told "compiling (first run only)" when a kernel's first call waits on numba's compiler
#: (a demo's progress line sets it); None: nobody is told.
waiting: Callable[[str], None] | None = None
#: Seconds a first call may take before it counts as a compile (a cache load takes less).
COMPILE_AFTER = 0.3
_told = False


def _tell() -> None:
    global _told
    if waiting is not None and not _told:
        _told = True
        waiting("compiling (first run only)")


def _timer() -> threading.Timer | None:
    """A timer that tells ``waiting`` after COMPILE_AFTER s (None: nobody to tell)."""
    if waiting is None or _told:
        return None
    timer = threading.Timer(COMPILE_AFTER, _tell)
    timer.daemon = True
    timer.start()
    return timer


#: The modules that hold loop kernels (``prepare`` imports them all).
MODULES = (
    "engine.pair_grid",
    "engine.pair_plan",
    "engine.pair_impacts",
    "engine.coloring",
    "engine.soft",
    "engine.pile",
    "engine.pile_rows",
    "engine.push_out",
    "engine.face_looks",
    "engine.sweep_paths",
    "engine.manifold_polygon",
    "engine.manifold",
    "engine.joint_rows",
    "engine.events",
)
#: Each kernel's smallest call, run by ``prepare`` to compile it (or load it from disk).
_SAMPLES: dict[str, Callable[[], tuple[Any, ...]]] = {}


def loop(sample: Callable[[], tuple[Any, ...]] | None = None) -> Callable[[F], LoopKernel[F]]:
    """Decorator: the function is a stage's loop kernel (``LoopKernel``). ``sample``: a
    function giving the arguments of a small call, which ``prepare`` compiles it with."""

    def wrap(fn: F) -> LoopKernel[F]:
        k = LoopKernel(fn)
        if sample is not None:
            _SAMPLES[k.name] = sample
        return k

    return wrap


def kernels() -> list[LoopKernel[Any]]:
    """Every loop kernel of the engine's modules imported so far."""
    return list(_ALL)


def prepare() -> float:
    """Compile every loop kernel of the engine now (or load them from numba's cache), telling
    ``waiting`` if it takes long, and return the seconds it took (0 without numba)."""
    if not available():
        return 0.0
    for name in MODULES:
        importlib.import_module(name)
    timer = _timer()
    t0 = time.perf_counter()
    try:
        for k in _ALL:
            sample = _SAMPLES.get(k.name)
            if sample is None:
                k.fast  # noqa: B018  (numba compiles it at its first real call)
            else:
                k.fast(*sample())
    finally:
        if timer is not None:
            timer.cancel()
    return time.perf_counter() - t0
