"""A compiled loop kernel calls another through the other's address (engine.kernel_calls): the
callee's code is compiled once, in its own module, not again inside every caller; its result and
its exceptions reach the caller; the call works from numba's cache in a new process; a caller
run before its callee is ready raises, never jumps to nowhere; and a caller that passes other
types than the callee's sample does not compile, and says why."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from engine import kernels

ROOT = Path(__file__).parent.parent

needs_numba = pytest.mark.skipif(not kernels.available(), reason="numba (the fast extra)")

_CALLEE = """
from engine import kernels

@kernels.loop(sample=lambda: (2.0,))
def scaled(x):
    if x < 0.0:
        raise ValueError("scaled: x < 0")
    return x * 3.0
"""
_CALLER = """
from engine import kernels
from .callee import scaled

@kernels.loop(sample=lambda: (2.0,))
def twice(x):
    return scaled(x) + scaled(x + 1.0)
"""
_PREPARED = """
from engine import kernel_calls, kernels
from probe.caller import twice
kernels.prepare([twice])  # (its callee first: engine.kernels._compile)
print("got:", twice(2.0))
try:
    twice(-5.0)
except ValueError as e:
    print("raised:", e)
(sig,) = twice.fast.signatures
print("hits:", sum(twice.fast.stats.cache_hits.values()))
if not sum(twice.fast.stats.cache_hits.values()):
    ir = twice.fast.inspect_llvm(sig)
    defined = [l for l in ir.splitlines() if l.startswith("define") and "6scaled" in l]
    print("defined:", len(defined))
    print("slot:", (kernel_calls.SYMBOL + "probe.callee.scaled") in ir)
"""
_UNPREPARED = """
from probe.caller import twice
try:
    twice.fast(2.0)  # the compiled caller, loaded from the cache, its callee never loaded
except RuntimeError as e:
    print("got:", e)
"""


def _run(tmp_path: Path, script: str) -> dict[str, str]:
    """``script`` run in a fresh Python with the package ``probe`` (a caller and its callee)
    and one numba cache, both in ``tmp_path``: what it printed, by the word before ":"."""
    package = tmp_path / "probe"
    if not package.exists():
        package.mkdir()
        (package / "__init__.py").write_text("")
        (package / "callee.py").write_text(_CALLEE)
        (package / "caller.py").write_text(_CALLER)
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    env["PYTHONPATH"] = f"{ROOT}{os.pathsep}{tmp_path}"
    out = subprocess.run(
        [sys.executable, "-c", script], env=env, cwd=tmp_path, capture_output=True, text=True,
    )  # fmt: skip
    assert out.returncode == 0, f"exit {out.returncode}: {out.stderr[-2000:]}"
    return dict(re.findall(r"^(\w+): (.*)$", out.stdout, flags=re.M))


@needs_numba
def test_a_kernel_calls_another_by_its_address_compiled_or_from_the_cache(tmp_path: Path) -> None:
    cold = _run(tmp_path, _PREPARED)
    assert cold["got"] == "15.0"  # 2 * 3 + 3 * 3
    assert cold["raised"] == "scaled: x < 0"  # the callee's exception, through the caller
    assert cold["hits"] == "0"
    assert cold["defined"] == "0"  # no copy of the callee's code in the caller's module
    assert cold["slot"] == "True"  # but its slot
    warm = _run(tmp_path, _PREPARED)  # a new process: both from numba's cache
    assert warm["got"] == "15.0"
    assert warm["raised"] == "scaled: x < 0"
    assert warm["hits"] == "1"
    # A caller called before its callee is loaded raises (the slot holds numba's function for
    # an unresolved symbol), rather than jumping to an empty slot.
    early = _run(tmp_path, _UNPREPARED)
    assert "unresolved symbol" in early["got"]


def _cube(x: float) -> float:
    return x * x * x


_CUBE = kernels.loop(sample=lambda: (2.0,))(_cube)


def _uses(x: float) -> float:
    return float(_CUBE(3) + x)  # an int: the cube's sample has a float


_USES = kernels.loop(sample=lambda: (1.0,))(_uses)
kernels._ALL.remove(_CUBE)  # (not the engine's kernels: its prepare() leaves them)
kernels._ALL.remove(_USES)


@needs_numba
def test_a_kernel_that_passes_other_types_than_its_callees_sample_is_refused() -> None:
    from numba.core.errors import TypingError

    with pytest.raises(TypingError) as raised:
        kernels.prepare([_USES])
    message = str(raised.value)
    assert _CUBE.name in message
    assert "argument 0: int64, not float64" in message
    assert not _USES.ready
