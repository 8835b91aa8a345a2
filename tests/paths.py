"""The paths a test may run on (engine.kernels): numpy, the reference, always; fast only where
numba (the ``fast`` extra) is installed. The README's test command installs no numba, so a test
of the fast path is skipped there, with the reason; CI's second run installs it."""

from collections.abc import Iterator

import pytest

from engine import kernels

#: Marks a test that needs the fast path (a comparison of both paths, say).
FAST = pytest.mark.skipif(
    not kernels.available(), reason="numba is not installed (the fast extra): no fast path here"
)
#: Both paths, for ``parametrize`` or a fixture's ``params``; fast skipped without numba.
PATHS = ["numpy", pytest.param("fast", marks=FAST)]


@pytest.fixture(scope="module", params=["numpy"])
def drawn_on_numpy(request: pytest.FixtureRequest) -> Iterator[str]:
    """A module's Worlds on the numpy path alone (``ENGINE_KERNELS=numpy`` while it runs), for
    the checks of what the demos draw: their labels and the README's stills are drawn by the
    same code on both paths, and each demo's own tests run on both. Named
    "numpy" (tests/conftest.py), CI's second run, on the fast path, leaves them out; a run on
    the fast path without that option fails a test that calls a compiled kernel all the same.
    Use with ``pytestmark = pytest.mark.usefixtures("drawn_on_numpy")``."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv(kernels.ENV, "numpy")
        yield request.param
