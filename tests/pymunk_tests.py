"""pymunk's own test files, read as a port's completeness check reads them (the ``bench``
extra installs pymunk, whose wheel ships its tests): which tests a file holds, and whether a
port names each one as ported or missing, and none that pymunk lacks."""

from __future__ import annotations

import re
from collections.abc import Callable
from pathlib import Path

import pytest


def their_tests(file: str, name: Callable[[str], str | None]) -> set[str]:
    """The test methods of pymunk's ``file`` (``test_body.py``, say) as ``name(cls) + '.' +
    method``, for each class ``cls`` that ``name`` gives a prefix to (None: left out); skips
    the caller where pymunk is not installed."""
    pymunk = pytest.importorskip("pymunk", reason="pymunk (the bench extra) holds the tests")
    source = (Path(pymunk.__file__).parent / "tests" / file).read_text()
    out, prefix = set(), None
    for line in source.splitlines():
        m = re.match(r"class (\w+)\(", line)
        if m:
            prefix = name(m.group(1))
        m = re.match(r"    def (test\w*)\(", line)
        if m and prefix is not None:
            out.add(f"{prefix}.{m.group(1)}")
    return out


def check_ported(theirs: set[str], ported: set[str], missing: set[str], least: int) -> None:
    """Every one of pymunk's tests (at least ``least`` read) is ported or listed missing, no
    name is both, and neither list names a test pymunk does not have."""
    assert len(theirs) >= least, "pymunk's tests were not read"
    unsaid = theirs - ported - missing
    assert not unsaid, f"pymunk tests neither ported nor listed in MISSING: {sorted(unsaid)}"
    stale = (missing | ported) - theirs
    assert not stale, f"ported or MISSING names tests pymunk does not have: {sorted(stale)}"
    assert not (ported & missing), "a test both ported and listed as missing"
