"""Shared inputs and checks for the fuzz tests (tests/test_fuzz_*.py).

The strategies throw what a careless or unlucky caller passes: wrong types, nan, inf, huge and
tiny numbers (floats near the ends of their range, ints far beyond it), zero, negatives, empty
things. :func:`attempt` lets a call either succeed or raise TypeError / ValueError whose
message names the argument and says what would be valid; anything else fails the test.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from decimal import Decimal
from fractions import Fraction
from typing import Any, TypeVar

import numpy as np
from hypothesis import HealthCheck, Phase, settings
from hypothesis import strategies as st
from pygame.math import Vector2

from engine import Vector

T = TypeVar("T")

#: Floats a test cares about by name: the ends of the range, the smallest subnormal, zeros.
SPECIAL_FLOATS = (
    0.0,
    -0.0,
    1.0,
    -1.0,
    5e-324,
    -5e-324,
    2.2250738585072014e-308,
    1e-300,
    1e300,
    1.7976931348623157e308,
    -1.7976931348623157e308,
    math.nan,
    -math.nan,
    math.inf,
    -math.inf,
)

#: Real numbers of every kind Python and numpy make, finite or not, small or far too big.
numbers: st.SearchStrategy[Any] = st.one_of(
    st.sampled_from(SPECIAL_FLOATS),
    st.floats(),  # nan, inf, subnormals, 1e308 ...
    st.integers(-1000, 1000),
    st.integers(min_value=-(10**400), max_value=10**400),  # beyond float range
    st.fractions(max_denominator=10**6),
    st.sampled_from([Fraction(10**400), Fraction(1, 10**400), Fraction(-(10**309), 3)]),
    st.floats().map(np.float64),
    st.floats(width=32).map(np.float32),
    st.integers(-(2**63), 2**63 - 1).map(np.int64),
)

#: Finite floats of a size that sums and products keep finite.
moderate = st.floats(-1e6, 1e6, allow_nan=False, allow_infinity=False)

#: Things that are not numbers at all (and some that only look like them).
junk: st.SearchStrategy[Any] = st.one_of(
    st.none(),
    st.booleans(),
    st.sampled_from([np.bool_(True), "1.0", "nan", b"1", "", Decimal("1.5"), Decimal("nan")]),
    st.text(max_size=4),
    st.complex_numbers(max_magnitude=10),
    st.just([]),
    st.just({}),
    st.just(()),
    st.just(object()),
    st.just(lambda: 1.0),
    st.just(np.array([1.0, 2.0])),
    st.just(np.array([[1.0, 2.0]])),
    st.just(np.zeros(0)),
    st.lists(st.integers(-3, 3), max_size=3),
)

#: Pairs, good and bad: the shapes a 2D argument arrives in.
pairs: st.SearchStrategy[Any] = st.one_of(
    st.tuples(numbers, numbers),
    st.lists(numbers, min_size=2, max_size=2),
    st.builds(Vector, moderate, moderate),
    st.builds(Vector2, moderate, moderate),  # pygame's, which the Vector takes as a pair
    st.tuples(numbers),
    st.tuples(numbers, numbers, numbers),
    st.tuples(junk, numbers),
    st.tuples(numbers, junk),
)

#: Anything at all that a caller might pass.
anything: st.SearchStrategy[Any] = st.one_of(numbers, junk, pairs)


def is_real(value: Any) -> bool:
    """A real number that is not a bool (what the engine accepts as a scalar)."""
    from numbers import Real

    return isinstance(value, Real) and not isinstance(value, (bool, np.bool_))


def in_float_range(value: Any) -> bool:
    """A real number that converts to a float without overflow."""
    try:
        float(value)
    except OverflowError:
        return False
    return True


def as_float(value: Any) -> float:
    return float(value)


def same_float(a: float, b: float) -> bool:
    """Equal as floats, counting nan == nan."""
    return a == b or (math.isnan(a) and math.isnan(b))


# A message says what would be valid when it uses one of these words.
_VALID_WORDS = re.compile(r"must|valid|takes|needs|expected|use |give |cannot|only|not in|holds")


def check_message(exc: BaseException, names: tuple[str, ...]) -> None:
    """``exc``'s message names one of ``names`` (case-insensitive) and says what is valid."""
    text = str(exc)
    low = text.lower()
    assert any(n.lower() in low for n in names), (
        f"{type(exc).__name__} does not name the argument ({' or '.join(names)}): {text!r}"
    )
    assert _VALID_WORDS.search(low), (
        f"{type(exc).__name__} does not say what would be valid: {text!r}"
    )


def attempt(call: Callable[[], T], *names: str) -> tuple[bool, T | None]:
    """Run ``call``: (True, result) or, for a TypeError / ValueError naming one of ``names``
    and what is valid, (False, None). Any other exception propagates and fails the test."""
    try:
        return True, call()
    except (TypeError, ValueError) as exc:
        check_message(exc, names)
        return False, None


def fuzz(examples: int, *, known_bug: bool = False) -> settings:
    """Hypothesis settings for ``examples`` generated calls, no per-example deadline.

    ``known_bug``: the test is a strict xfail for an engine bug that one of its ``@example``s
    reproduces, so only the ``@example``s run. The xfail is decided by them; generating and
    shrinking again, each run, a failure already known cost a minute of the suite. When the
    bug is fixed the example passes, the strict xfail fails, and the marker and ``known_bug``
    go together: the whole fuzz runs again.
    """
    only_examples = {"phases": (Phase.explicit,)} if known_bug else {}
    return settings(
        max_examples=examples,
        deadline=None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
        **only_examples,
    )
