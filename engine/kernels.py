"""Which path the hot loops take: numpy (the reference, everywhere) or compiled loops (``fast``).

Most of a step is a few array calls, and numpy carries them well. A few stages are loops by
nature: a Gauss-Seidel sweep over a pile's contacts (each row sees the velocities the rows
before it left), the broadphase's cells, a union-find. In numpy they become one array call a
colour, a cell size or a round, and at the sizes of a game numpy's fixed cost per call (a few
microseconds) is most of their time. With the ``fast`` extra installed
(``pip install -e ".[fast]"``: numba), each such stage also has a **loop kernel**: the same
algorithm written as the loop it is, in plain Python beside its numpy twin in the stage's own
module, which numba compiles to machine code.

**The path** is chosen once, when a World is made (``World(kernels=...)``; ``world.kernels``
says which it runs):

* ``"fast"``: the loop kernels, compiled; the default where numba is installed;
* ``"numpy"``: the numpy twins; the default without numba, and forced by
  ``ENGINE_KERNELS=numpy`` in the environment or ``World(kernels="numpy")``.

**No compile in play.** numba compiles a function once for each set of argument types it
meets (int32 or int64, a C-contiguous or strided or read-only array, a float or an int), each
new one when it is met. So every kernel has a sample call (``@loop(sample=...)``) with the
types its callers pass, and the callers pass those types (C-contiguous, writable, int64
arrays; Python floats). ``prepare`` compiles every kernel for its sample, or loads it from
numba's cache (under a second for all): the first World on the fast path calls it when it is
made, before any step, and ``python -m engine.warmup`` (the install line's last command) does
the first run's compile once: about 33 s on two cores, where a second process compiles from
the other end of the list (``_Helper``), about a minute on one. A kernel that calls another
calls it through its address (engine.kernel_calls), so each is compiled once, not again
inside every kernel that calls it. The cache lives in the user's
cache folder (``cache_dir()``), not beside the sources, unless ``NUMBA_CACHE_DIR`` says
otherwise.
tests/test_compile_before_play.py checks that stepping the demos' scenes after ``prepare``
adds no specialisation to any kernel.

``import engine`` does not import numba; a World on the fast path does. Both paths give the
same numbers to rounding (tests/test_kernels.py checks each kernel against its twin to 1e-12
relative), so every exactness test holds on both. Validation stays before the kernels, so an
error reads the same on either path.

>>> choose("numpy")
'numpy'
>>> choose("gpu")  # doctest: +ELLIPSIS
Traceback (most recent call last):
    ...
ValueError: kernels must be 'numpy' or 'fast' ..., got 'gpu'
"""

from __future__ import annotations

import ast
import importlib.util
import os
import sys
import threading
import time
import types
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, Generic, TypeVar

import numpy as np

from . import kernel_calls

__all__ = [
    "floats",
    "helper",
    "stable_order",
    "PATHS",
    "LoopKernel",
    "available",
    "cache_dir",
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
#: numba's own variable for its cache's folder; set to ``cache_dir()`` where it is unset.
CACHE_ENV = "NUMBA_CACHE_DIR"

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
        return _path(wanted)
    return "fast" if available() else "numpy"


def choose(kernels: str | None) -> str:
    """The path for a World's ``kernels`` argument (None: ``default()``); ValueError for a
    name that is not a path, or for ``"fast"`` without numba installed. On the fast path
    every kernel is compiled or loaded now (``prepare``): the World is made before its first
    step, so no step waits on numba."""
    path = default() if kernels is None else _path(kernels)
    if path == "fast":
        prepare()
    return path


def _path(kernels: str) -> str:
    """``kernels`` if it names a path that can run here, else ValueError (``choose``)."""
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


def cache_dir() -> Path:
    """The folder numba caches the compiled kernels in: ``NUMBA_CACHE_DIR`` where it is set,
    else the user's cache folder (``%LOCALAPPDATA%`` on Windows, ``XDG_CACHE_HOME`` or
    ``~/.cache`` elsewhere) + ``alfred-engine/numba``, never beside the engine's sources."""
    chosen = os.environ.get(CACHE_ENV, "")
    if chosen:
        return Path(chosen)
    if sys.platform == "win32":
        base = os.environ.get("LOCALAPPDATA", "") or str(Path.home() / "AppData" / "Local")
    else:
        base = os.environ.get("XDG_CACHE_HOME", "")
        if not os.path.isabs(base):  # unset, or relative: the spec says ignore it
            base = str(Path.home() / ".cache")
    return Path(base) / "alfred-engine" / "numba"


def _numba() -> Any:
    """numba, imported with its cache in ``cache_dir()`` (``NUMBA_CACHE_DIR`` set first, if
    unset, since numba reads it when imported and when it compiles)."""
    if not os.environ.get(CACHE_ENV):
        os.environ[CACHE_ENV] = str(cache_dir())
    import numba  # only here: import engine does not import numba

    if not getattr(numba.config, "CACHE_DIR", ""):  # numba was imported before it was set
        numba.core.config.reload_config()
    return numba


class LoopKernel(Generic[F]):
    """A stage's loop, in plain Python (``py``: runs anywhere, slowly) and compiled by numba
    (``fast``), for the argument types of its sample call, by ``prepare``. Made by the
    ``@loop`` decorator."""

    def __init__(self, fn: F) -> None:
        self.py: F = fn
        self.name = f"{fn.__module__}.{fn.__qualname__}"
        self._compiled: Any = None
        #: The kernels it calls (known once it is compiled: ``fast``).
        self._called: list[LoopKernel[Any]] = []
        #: Whether ``prepare`` has compiled (or loaded) it for its sample's argument types.
        self.ready = False
        #: The names of the kernels it calls (known once it is compiled: ``fast``).
        self.calls: list[str] = []
        self._types: tuple[Any, ...] | None = None
        _ALL.append(self)

    @property
    def fast(self) -> F:
        """The compiled kernel (numba.njit, cached on disk in ``cache_dir()``); it compiles
        (or loads) a specialisation at its first call with each new set of argument types.
        A kernel may call another (a step's kernel calls the manifolds' and the solver's):
        compiled, it calls the other's compiled code through its address (engine.kernel_calls),
        and numba's cache entry for it is kept only while the other's source file is as it was
        (numba's own check looks at the caller's file alone)."""
        if self._compiled is None:
            fn, called, helped = _calling_compiled(self.py)
            self._compiled = _numba().njit(cache=True, nogil=True)(fn)
            self._called = called
            files = self.sources() | helped
            files.discard(self.py.__code__.co_filename)  # (numba's own stamp)
            _stamp_with(self._compiled, sorted(files))
            self.calls = [k.name for k in called]
        return self._compiled  # type: ignore[no-any-return]

    def sources(self) -> set[str]:
        """The files its compiled code depends on: its own, those of the constants it reads
        (numba compiles a global's value in: ``_constants_from``), and the same of each kernel
        it calls (compiled into it), and of theirs."""
        files = {self.py.__code__.co_filename} | _constants_from(self.py)
        for k in self._called:
            files |= k.sources()
        return files

    def sample_types(self) -> tuple[Any, ...]:
        """The numba types of its sample's arguments (those ``prepare`` compiles it for)."""
        if self._types is None:
            from numba.core.typing.typeof import Purpose, typeof

            self._types = tuple(typeof(a, Purpose.argument) for a in _SAMPLES[self.name]())
        return self._types

    def __call__(self, *args: Any) -> Any:
        """The compiled kernel's result for ``args`` (the fast path's call)."""
        f = self._compiled
        if f is None:
            return self._first(args)
        return f(*args)

    def _first(self, args: tuple[Any, ...]) -> Any:
        """A first call before any ``prepare`` (a World on the fast path prepares when it is
        made): every kernel is compiled or loaded now, this one with them."""
        prepare()
        return self.fast(*args)

    def __repr__(self) -> str:
        return f"LoopKernel({self.name})"


def floats(n: int, value: float) -> Any:
    """A loop kernel's scratch of ``n`` floats, each ``value``: a list in plain Python (quick
    to index there), an array where the kernel is compiled (numba indexes its arrays faster
    than its lists: a pile's solve took 1.6 times as long on lists)."""
    return [value] * n


def _floats_compiled(n: int, value: float) -> Any:
    return np.full(n, value)


def stable_order(keys: Any) -> Any:
    """The order that sorts the int64 array ``keys`` stably (numpy's ``argsort`` of kind
    ``"stable"``: a stable sort has one answer, so either twin's is the other's). Where the
    kernel is compiled, a counting sort by the keys' leading bits and a merge sort of each
    bucket, by insertion in runs of 16 (about five times as quick as numba's merge sort on a
    pile's contact keys)."""
    return np.argsort(keys, kind="stable")


#: The largest int64.
_INT64_MAX = 2**63 - 1


def _stable_order_compiled(keys: Any) -> Any:
    n = len(keys)
    lo, hi = (keys[0], keys[0]) if n else (0, 0)
    for i in range(1, n):
        v = keys[i]
        if v < lo:
            lo = v
        elif v > hi:
            hi = v
    order = np.empty(n, dtype=np.int64)
    vals = np.empty(n, dtype=np.int64)
    # Few, or hi - lo past an int64 (asked without the subtraction, which would overflow):
    # one bucket.
    if n < 64 or (lo < 0 and hi > _INT64_MAX + lo):
        nb = 1
        start = np.zeros(2, dtype=np.int64)
        start[1] = n
        for i in range(n):
            order[i], vals[i] = i, keys[i]
    else:
        # Buckets of the keys' leading bits, at most n of them, each bucket's keys in their
        # order.
        span = hi - lo
        shift = 0
        while (span >> shift) >= n:
            shift += 1
        nb = (span >> shift) + 1
        start = np.zeros(nb + 1, dtype=np.int64)
        for i in range(n):
            start[((keys[i] - lo) >> shift) + 1] += 1
        for b in range(nb):
            start[b + 1] += start[b]
        fill = start[:nb].copy()
        for i in range(n):
            b = (keys[i] - lo) >> shift
            at = fill[b]
            fill[b] = at + 1
            order[at] = i
            vals[at] = keys[i]
    # Each bucket sorted stably: runs of 16 by insertion, then merged bottom up, the left
    # run first among equals. (Written out: numba's merge sort for np.argsort took 2 s of a
    # cold compile.)
    sv = np.empty(n, dtype=np.int64)
    so = np.empty(n, dtype=np.int64)
    for b in range(nb):
        first, end = start[b], start[b + 1]
        for r in range(first, end, 16):
            for i in range(r + 1, min(r + 16, end)):
                v, o = vals[i], order[i]
                j = i - 1
                while j >= r and vals[j] > v:
                    vals[j + 1], order[j + 1] = vals[j], order[j]
                    j -= 1
                vals[j + 1], order[j + 1] = v, o
        width = 16
        while width < end - first:
            for left in range(first, end, 2 * width):
                mid, right = min(left + width, end), min(left + 2 * width, end)
                i, j, k = left, mid, 0
                while i < mid or j < right:
                    if j >= right or (i < mid and not vals[j] < vals[i]):
                        sv[k], so[k] = vals[i], order[i]
                        i += 1
                    else:
                        sv[k], so[k] = vals[j], order[j]
                        j += 1
                    k += 1
                for t in range(k):
                    vals[left + t], order[left + t] = sv[t], so[t]
            width *= 2
    return order


#: Helpers a loop kernel may call, each with what a compiled kernel calls in its place.
_COMPILED_AS: dict[Callable[..., Any], Callable[..., Any]] = {
    floats: _floats_compiled,
    stable_order: _stable_order_compiled,
}


def helper(fn: F) -> F:
    """Decorator: ``fn`` is a small function that loop kernels call, the same code in plain
    Python and compiled. A compiled kernel calls it as a function numba compiles once for each
    set of argument types (shared by every kernel that calls it), where a closure defined inside
    the kernel is inlined and typed again at each of its call sites: the solver's velocity at a
    point and its impulse, called at about eight sites each, cost the cold compile seconds so."""
    _COMPILED_AS[fn] = fn
    return fn


#: The compiled helpers made so far (``_calling_compiled``), each with the files its code
#: comes from (its own, those of the constants it reads and of the helpers it calls).
_HELPERS_COMPILED: dict[Callable[..., Any], tuple[Any, set[str]]] = {}


def _names(code: Any) -> set[str]:
    """The global names a function's code (and the functions made inside it) reads."""
    names = set(code.co_names)
    for const in code.co_consts:
        if hasattr(const, "co_names"):
            names |= _names(const)
    return names


def _constants_from(fn: Callable[..., Any]) -> set[str]:
    """The files of its own package that the globals ``fn`` reads come from: a module it reads
    (``solver.HINGE``) or a name it imported (``from .game_sleep import RISE``). numba
    compiles a global's value into the code, and its cache checks only the function's own
    file: without these, a constant edited in its module would run as it was."""
    glob = fn.__globals__
    package = str(glob.get("__name__", "")).split(".")[0]
    origin = _imported(glob.get("__file__"), glob.get("__package__"))
    files = set()
    for name in _names(fn.__code__):
        value = glob.get(name)
        if isinstance(value, types.ModuleType):
            module: Any = value
        elif name in origin:
            module = sys.modules.get(origin[name])
        else:
            continue
        found = getattr(module, "__file__", None)
        if found and str(getattr(module, "__name__", "")).split(".")[0] == package:
            files.add(found)
    return files


_IMPORTED: dict[str, dict[str, str]] = {}


def _imported(path: str | None, package: str | None) -> dict[str, str]:
    """Each name a module's ``from ... import`` statements bind, and the module it comes
    from (read once from its source, ``path``)."""
    if path is None or not path.endswith(".py"):
        return {}
    if path not in _IMPORTED:
        out: dict[str, str] = {}
        with open(path, encoding="utf-8") as f:
            tree = ast.parse(f.read(), path)
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                where = "." * node.level + (node.module or "")
                try:
                    module = importlib.util.resolve_name(where, package)
                except (ImportError, ValueError):
                    continue
                for alias in node.names:
                    out[alias.asname or alias.name] = module
        _IMPORTED[path] = out
    return _IMPORTED[path]


def _helper(value: Any) -> bool:
    """Whether ``value`` is one of the helpers of ``_COMPILED_AS``."""
    try:
        return value in _COMPILED_AS
    except TypeError:  # not hashable
        return False


def _calling_compiled(
    fn: Callable[..., Any],
) -> tuple[Callable[..., Any], list[LoopKernel[Any]], set[str]]:
    """``fn``, with each loop kernel among the globals it reads replaced by that kernel's
    compiled dispatcher (numba compiles a call to a dispatcher, not to a LoopKernel), and
    each helper of ``_COMPILED_AS`` by its compiled twin; and those kernels, and the files
    of the helpers it calls (compiled into it: its cache entry is kept only while they are
    as they were)."""
    glob = fn.__globals__
    names = _names(fn.__code__)
    called = {n: glob[n] for n in names if isinstance(glob.get(n), LoopKernel)}
    helpers = {n: glob[n] for n in names if _helper(glob.get(n))}
    for n, h in list(helpers.items()):
        if isinstance(_COMPILED_AS[h], LoopKernel):  # (a kernel of its own: stable_order)
            called[n] = _COMPILED_AS[helpers.pop(n)]
    if not called and not helpers:
        return fn, [], set()
    new_globals = dict(glob)
    for name, k in called.items():
        # Called through its address, not compiled in again (engine.kernel_calls).
        new_globals[name] = kernel_calls.calling(k)
    files = set()
    for name, h in helpers.items():
        if h not in _HELPERS_COMPILED:
            # One dispatcher a helper, shared by the kernels that call it: compiled once a
            # process for a type, not once a kernel; the helpers it calls compiled likewise.
            twin, _, theirs = _calling_compiled(_COMPILED_AS[h])
            theirs |= _constants_from(_COMPILED_AS[h])  # (its constants compiled in, too)
            compiled = _numba().njit(cache=True, nogil=True)(twin)
            own = twin.__code__.co_filename
            _stamp_with(compiled, sorted(theirs - {own}))  # (numba's own stamp: its file)
            _HELPERS_COMPILED[h] = (compiled, theirs | {own})
        new_globals[name], theirs = _HELPERS_COMPILED[h]
        files |= theirs
    out = types.FunctionType(fn.__code__, new_globals, fn.__name__, fn.__defaults__, fn.__closure__)
    out.__qualname__, out.__module__ = fn.__qualname__, fn.__module__
    return out, list(called.values()), files


def _stamp_with(dispatcher: Any, files: list[str]) -> None:
    """Make numba's cache entry of ``dispatcher`` stale when any of ``files`` changes: its
    source stamp (the caller's file's time and size) gets theirs beside it. (numba keeps
    the stamp on the cache's index file object; where a numba release moves it, the entry
    goes stale only with the caller's file, as before.)"""
    index = getattr(getattr(dispatcher, "_cache", None), "_cache_file", None)
    if not files or index is None or not hasattr(index, "_source_stamp"):
        return
    stamps = []
    for f in files:
        st = os.stat(f)
        stamps.append((st.st_mtime, st.st_size))
    index._source_stamp = (index._source_stamp, *stamps)


_ALL: list[LoopKernel[Any]] = []
_LOCK = threading.RLock()
#: Told how the first run's compile goes ("compiling the engine's kernels (first run only):
#: 5/22"), and of a kernel compiled again for argument types its sample did not have (a
#: demo's progress line sets it); None: those lines go to stderr.
waiting: Callable[[str], None] | None = None
#: Seconds between two lines of the compile's progress, at least (the first and last always).
PROGRESS_EVERY = 2.0


#: The modules that hold loop kernels (``prepare`` imports them all).
MODULES = (
    "engine.geometry.pair_grid",
    "engine.exact.pair_plan",
    "engine.exact.pair_impacts",
    "engine.dynamics.coloring",
    "engine.dynamics.turning_faces",
    "engine.exact.soft",
    "engine.dynamics.solver",
    "engine.exact.pile",
    "engine.exact.pile_rows",
    "engine.exact.push_out",
    "engine.geometry.face_looks",
    "engine.exact.sweep_paths",
    "engine.geometry.manifold_polygon",
    "engine.geometry.manifold",
    "engine.geometry.passing",
    "engine.geometry.narrowphase",
    "engine.pipeline.game_contacts",
    "engine.pipeline.game_loop",
    "engine.dynamics.game_continuous",
    "engine.exact.joint_rows",
    "engine.dynamics.events",
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


def _keys_sample() -> tuple[Any, ...]:
    return (np.array([3, 1, 2], dtype=np.int64),)


#: ``stable_order`` where a kernel calls it: a kernel of its own, compiled once and called
#: through its address by each kernel that sorts (engine.kernel_calls), for int64 keys.
_COMPILED_AS[stable_order] = loop(sample=_keys_sample)(_stable_order_compiled)


def kernels() -> list[LoopKernel[Any]]:
    """Every loop kernel of the engine's modules imported so far."""
    return list(_ALL)


def prepare(only: Sequence[LoopKernel[Any]] | None = None) -> float:
    """Compile every loop kernel of the engine now, for its sample's argument types (or load
    it from numba's cache), and return the seconds it took (0 without numba). A World on the
    fast path calls it when it is made, and ``python -m engine.warmup`` at install time, so no
    step waits on the compiler. The kernels already prepared are skipped, so a second call
    costs nothing. While kernels compile (not while they load) it says so as it goes, through
    ``waiting`` or on stderr: "compiling the engine's kernels (first run only): 5/22". On a
    cold cache, with a second core, a second process compiles them too, from the other end of
    the list (``_Helper``), and what it compiled is loaded from the cache it fills.
    ``only``: these kernels, not all the engine's; a helper shares them too when each is one
    of the engine's (it finds them by name), and otherwise (the tests' own) this process
    compiles them alone."""
    if not available():
        return 0.0
    with _LOCK:
        if only is None:
            for name in MODULES:
                importlib.import_module(name)
        todo = [k for k in (_ALL if only is None else only) if not k.ready]
        todo.sort(key=_rank)
        if not todo:
            return 0.0
        t0 = time.perf_counter()
        progress = _Progress(len(todo), t0)
        ev = _numba().core.event
        watch = _watcher(ev, progress.compiling)
        ev.register("numba:compile", watch)
        try:
            queue = list(todo)
            helpers: list[_Helper] = []
            if only is None or all(k.py.__module__ in MODULES for k in todo):
                # As numba starts the first compile (the cache is cold), a second process
                # starts on the kernels left, from the back, each one that neither has
                # claimed yet, as this one goes on from the front.
                progress.cold = lambda: helpers.extend(filter(None, [_Helper.start(queue)]))
            done = 0
            while queue:
                k = queue.pop(0)
                if helpers and not helpers[0].claim(k):
                    # The helper took the rest, from the back: it has compiled them (or
                    # stopped) when it exits, and they load from the cache it filled.
                    helpers.pop().wait()
                    for left in [k, *queue]:
                        _compile(left)  # (compiled here where the helper failed)
                        done += 1
                        progress.step(done)
                    break
                _compile(k)
                done += 1
                progress.step(done)
            for helper in helpers:
                helper.wait()  # (it claimed nothing this one did not leave it)
        finally:
            ev.unregister("numba:compile", watch)
        _watch_play(ev)
        return time.perf_counter() - t0


#: The order of a cold compile (the rest between, as imported), balanced for two processes
#: (this one from the front, the helper from the back; seconds each on this machine kind):
#: the sort that six kernels call (1 s) and the solver (13 s) here, the contacts (polygon_loop
#: 3 s ... contacts_loop 7 s) in the helper meanwhile, and the step that calls both
#: (engine.pipeline.game_loop, 5 s) after the colouring (2 s), by which time the helper has
#: cached the contacts, so this one loads them rather than compiling them a second time.
FRONT = (
    "engine.kernels._stable_order_compiled",
    "engine.dynamics.solver.solve",
    "engine.dynamics.coloring.color_rows",
    "engine.pipeline.game_loop.step_loop",
)
BACK = (
    "engine.pipeline.game_contacts.report_loop",
    "engine.pipeline.game_contacts.contacts_loop",
    "engine.geometry.narrowphase.round_loop",
    "engine.geometry.manifold.half_plane_polygon_loop",
    "engine.geometry.manifold_polygon.polygon_loop",
)


def _rank(k: LoopKernel[Any]) -> tuple[int, int]:
    """Where ``k`` goes in a cold compile's list (``FRONT``, the rest, ``BACK``)."""
    if k.name in FRONT:
        return 0, FRONT.index(k.name)
    if k.name in BACK:
        return 2, BACK.index(k.name)
    return 1, 0  # (a stable sort: the rest keep their order)


def _compile(k: LoopKernel[Any]) -> None:
    """Compile ``k`` for its sample's argument types (or load it from numba's cache), after
    the kernels it calls (it calls them through their addresses: engine.kernel_calls)."""
    sample = _SAMPLES.get(k.name)
    if sample is None:
        raise RuntimeError(
            f"loop kernel {k.name} has no sample (@loop(sample=...)): it would "
            f"compile at its first call, during play"
        )
    compiled = k.fast
    for called in k._called:
        if not called.ready:
            _compile(called)
    compiled(*sample())
    kernel_calls.fill(k)
    k.ready = True


#: The fewest kernels left to compile for which a second process is worth its start (about
#: a second: Python, numba and the engine imported).
HELPED_FROM = 4
#: Seconds a compile's helper process may take before this one compiles its kernels itself.
HELPER_TIMEOUT = 600.0


class _Helper:
    """A second process compiling kernels into the same cache (``python -m engine.warmup
    --claims DIR NAME ...``): it takes them from the back of the list and this process from
    the front, each compiling a kernel only if it claimed it first (a file made in ``DIR``
    with O_EXCL, which one of the two makes), so the halves balance whatever each costs."""

    def __init__(self, process: Any, claims: Path) -> None:
        self.process, self.claims = process, claims

    @staticmethod
    def start(queue: Sequence[LoopKernel[Any]]) -> _Helper | None:
        """A helper for the kernels of ``queue``, or None (too few, one core, or no process
        can be started here: this one compiles them all)."""
        if len(queue) < HELPED_FROM or (os.cpu_count() or 1) < 2:
            return None
        import subprocess
        import tempfile

        claims = Path(tempfile.mkdtemp(prefix="engine-kernels-"))
        env = dict(os.environ)
        env[CACHE_ENV] = str(cache_dir())  # the same cache, wherever this process found it
        root = str(Path(__file__).resolve().parent.parent)  # the engine's package, first
        env["PYTHONPATH"] = os.pathsep.join(p for p in (root, env.get("PYTHONPATH", "")) if p)
        names = [k.name for k in queue]
        try:
            process = subprocess.Popen(
                [sys.executable, "-m", "engine.warmup", "--claims", str(claims), *names],
                env=env, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )  # fmt: skip
        except OSError:
            return None
        return _Helper(process, claims)

    def claim(self, k: LoopKernel[Any]) -> bool:
        """Whether this process claimed ``k`` first (then it compiles it)."""
        return claim(self.claims, k.name)

    def wait(self) -> None:
        """Wait for the helper, at most HELPER_TIMEOUT s (then stop it: what it has not
        cached, this process compiles); its claims are removed."""
        import shutil
        import subprocess

        try:
            self.process.wait(timeout=HELPER_TIMEOUT)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        shutil.rmtree(self.claims, ignore_errors=True)


def claim(claims: Path, name: str) -> bool:
    """Whether this process is the first to claim the kernel ``name`` in the folder ``claims``
    (a compile shared by two processes, ``_Helper``)."""
    try:
        os.close(os.open(claims / name, os.O_CREAT | os.O_EXCL | os.O_WRONLY))
    except FileExistsError:
        return False
    return True


class _Progress:
    """The lines of a compile's progress: the first when numba starts compiling, then one at
    least every PROGRESS_EVERY s as kernels finish, and the last when all are ready."""

    def __init__(self, total: int, t0: float) -> None:
        self.total, self.t0 = total, t0
        self.done = 0
        self.said: float | None = None  # when the last line was said (None: not compiling)
        #: Called once, as numba starts the first compile (the cache was cold).
        self.cold: Callable[[], None] | None = None

    def compiling(self, _dispatcher: Any) -> None:
        if self.said is None:
            self._say()
            if self.cold is not None:
                self.cold()

    def step(self, done: int) -> None:
        self.done = done
        if self.said is None:
            return  # loaded from the cache: nothing to say
        now = time.perf_counter()
        if done == self.total or now - self.said >= PROGRESS_EVERY:
            self._say(f", {now - self.t0:.1f} s" if done == self.total else "")

    def _say(self, tail: str = "") -> None:
        self.said = time.perf_counter()
        tell(f"compiling the engine's kernels (first run only): {self.done}/{self.total}{tail}")


def tell(message: str) -> None:
    """Say ``message`` through ``waiting``, or on stderr where nobody listens."""
    if waiting is not None:
        waiting(message)
    else:
        print(f"engine: {message}", file=sys.stderr, flush=True)


def _watcher(ev: Any, on_start: Callable[[Any], None]) -> Any:
    """A listener of numba's "numba:compile" events (a compile, not a load from the cache)
    that calls ``on_start(dispatcher)`` as one starts."""

    class Watch(ev.Listener):  # type: ignore[misc,name-defined]
        def on_start(self, event: Any) -> None:
            on_start(event.data["dispatcher"])

        def on_end(self, event: Any) -> None:
            pass

    return Watch()


_late: list[Any] = []  # the listener of compiles during play, once registered


def _watch_play(ev: Any) -> None:
    """From the first ``prepare`` on, a kernel compiled again (for argument types its sample
    did not have: a stall in play) is told by name, so it can be found and fixed."""
    if _late:
        return

    def late(dispatcher: Any) -> None:
        for k in _ALL:
            if k.ready and k._compiled is dispatcher:
                tell(
                    f"compiling {k.name} again during play, for argument types its sample "
                    f"did not have (engine.kernels)"
                )

    _late.append(_watcher(ev, late))
    ev.register("numba:compile", _late[0])
