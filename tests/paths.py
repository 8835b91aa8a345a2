"""The paths a test may run on (engine.kernels): numpy, the reference, always; fast only where
numba (the ``fast`` extra) is installed. The README's test command installs no numba, so a test
of the fast path is skipped there, with the reason; CI's second run installs it."""

import pytest

from engine import kernels

#: Marks a test that needs the fast path (a comparison of both paths, say).
FAST = pytest.mark.skipif(
    not kernels.available(), reason="numba is not installed (the fast extra): no fast path here"
)
#: Both paths, for ``parametrize`` or a fixture's ``params``; fast skipped without numba.
PATHS = ["numpy", pytest.param("fast", marks=FAST)]
