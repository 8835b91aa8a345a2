"""engine.Vector: the lesson's rbpmath.Vector as an immutable value type, faults fixed."""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from engine import Vector

EPS = sys.float_info.epsilon

# Finite components of ordinary size, plus both signed zeros (0.0 == -0.0 must hash alike).
components = st.one_of(
    st.floats(min_value=-1e6, max_value=1e6, allow_nan=False, allow_infinity=False),
    st.sampled_from([0.0, -0.0, 1.0, -1.0]),
)
vectors = st.builds(Vector, components, components)
scalars = st.floats(min_value=-1e3, max_value=1e3, allow_nan=False, allow_infinity=False)


def close(u: Vector, w: Vector, abs_tol: float) -> bool:
    return math.isclose(u.x, w.x, abs_tol=abs_tol) and math.isclose(u.y, w.y, abs_tol=abs_tol)


# -- algebra as properties ---------------------------------------------------------------------


@given(vectors, vectors, vectors)
def test_addition_is_associative_within_rounding(a: Vector, b: Vector, c: Vector) -> None:
    # Each float addition rounds by at most eps/2 of its result; two additions on each side,
    # so the sides differ by at most ~2 eps (|a| + |b| + |c|) per component.
    scale = sum(abs(comp) for v in (a, b, c) for comp in v)
    assert close((a + b) + c, a + (b + c), abs_tol=2 * EPS * scale + 1e-300)


@given(vectors, vectors)
def test_addition_is_commutative(a: Vector, b: Vector) -> None:
    # IEEE addition is commutative bit for bit, so this holds exactly, not just approximately.
    assert a + b == b + a


@given(vectors, vectors)
def test_subtraction_is_adding_the_negative(a: Vector, b: Vector) -> None:
    # x - y and x + (-y) are the same IEEE operation: exact equality.
    assert a - b == a + (-b)
    assert (a - b).x == a.x - b.x and (a - b).y == a.y - b.y


@given(vectors, scalars)
def test_scaling_scales_the_magnitude_by_abs_s(a: Vector, s: float) -> None:
    expected = abs(s) * a.magnitude()
    assert math.isclose((a * s).magnitude(), expected, rel_tol=4 * EPS, abs_tol=1e-300)
    assert math.isclose((s * a).magnitude(), expected, rel_tol=4 * EPS, abs_tol=1e-300)


@given(vectors, st.one_of(vectors, st.just(None)))
def test_not_equal_is_exactly_not_equal(a: Vector, b: Vector | None) -> None:
    b = Vector(a.x, a.y) if b is None else b  # half the time an equal, distinct vector
    assert (a != b) is (not (a == b))
    assert (a == b) is (a.x == b.x and a.y == b.y)


@given(vectors, st.one_of(vectors, st.just(None)))
def test_hash_agrees_with_equality(a: Vector, b: Vector | None) -> None:
    b = Vector(-a.x if a.x == 0 else a.x, a.y) if b is None else b  # equal, maybe -0.0
    if a == b:
        assert hash(a) == hash(b)
    # A Vector equals the tuple of its components, so it must hash like it too.
    assert a == (a.x, a.y)
    assert hash(a) == hash((a.x, a.y))
    assert len({a, Vector(a.x, a.y)}) == 1


@given(vectors, vectors, scalars)
def test_augmented_assignment_never_mutates_a_shared_vector(a: Vector, b: Vector, s: float) -> None:
    x0, y0 = a.x, a.y
    held = a  # someone else holds the same vector (a body's position, say)
    a += b
    assert (held.x, held.y) == (x0, y0)
    assert a == Vector(x0 + b.x, y0 + b.y)
    a = held
    a -= b
    assert (held.x, held.y) == (x0, y0)
    assert a == Vector(x0 - b.x, y0 - b.y)
    a = held
    a *= s
    assert (held.x, held.y) == (x0, y0)
    assert a == Vector(x0 * s, y0 * s)


def test_a_vector_cannot_be_changed_in_place() -> None:
    v = Vector(1, 2)
    with pytest.raises(AttributeError, match="immutable"):
        v.x = 5.0  # type: ignore[misc]
    with pytest.raises(AttributeError):
        del v.y
    assert v == Vector(1, 2)


# -- the lesson's four faults, each pinned -----------------------------------------------------


def test_lesson_fault_ne_of_equal_vectors_is_false() -> None:
    # rbpmath's __ne__ returned NotImplemented when __eq__ answered, so equal vectors were "!=".
    assert not (Vector(1, 2) != Vector(1, 2))
    assert Vector(1, 2) != Vector(1, 3)
    assert Vector(1, 2).__ne__(Vector(1, 2)) is False


def test_lesson_fault_sub_subtracts_the_y_components() -> None:
    # rbpmath's __sub__ added the y components: (5, 5) - (1, 2) gave (4, 7).
    assert Vector(5, 5) - Vector(1, 2) == Vector(4, 3)
    v = Vector(5, 5)
    v -= Vector(1, 2)
    assert v == Vector(4, 3)


def test_lesson_fault_imul_scales_by_a_number() -> None:
    # rbpmath's __imul__ only multiplied when the other operand was a Vector.
    v = Vector(1.5, -2)
    v *= 2
    assert v == Vector(3, -4)
    v *= 0.5
    assert v == Vector(1.5, -2)
    with pytest.raises(TypeError, match=r"dot"):
        v *= Vector(1, 1)


def test_lesson_fault_vector_times_vector_is_a_type_error_pointing_to_dot() -> None:
    # rbpmath's * between two vectors silently meant the dot product.
    with pytest.raises(TypeError, match=r"v\.dot\(w\)"):
        Vector(1, 2) * Vector(3, 4)
    with pytest.raises(TypeError, match=r"v\.dot\(w\)"):
        Vector(1, 2) * (3, 4)
    with pytest.raises(TypeError, match=r"v\.dot\(w\)"):
        (3, 4) * Vector(1, 2)
    assert Vector(1, 2).dot(Vector(3, 4)) == 11.0


# -- text --------------------------------------------------------------------------------------


def test_str_is_the_lessons_text() -> None:
    assert str(Vector(1, 2)) == "X: 1.0 Y: 2.0"
    assert str(Vector(-0.5, 3)) == "X: -0.5 Y: 3.0"
    assert str(Vector()) == "X: 0.0 Y: 0.0"


@given(vectors)
def test_repr_round_trips_through_eval(a: Vector) -> None:
    back = eval(repr(a), {"Vector": Vector})
    assert back == a
    # bit for bit, including the sign of zero
    assert math.copysign(1, back.x) == math.copysign(1, a.x)
    assert math.copysign(1, back.y) == math.copysign(1, a.y)


# -- tuples, unpacking, components -------------------------------------------------------------


def test_plain_tuples_are_accepted_as_operands() -> None:
    a = Vector(1, 2)
    assert a + (3, 4) == Vector(4, 6)
    assert (3, 4) + a == Vector(4, 6)
    assert a - (3, 5) == Vector(-2, -3)
    assert (3, 5) - a == Vector(2, 3)
    assert a == (1, 2) and (1, 2) == a
    assert a.dot((3, 4)) == 11.0
    assert a.cross((3, 4)) == -2.0
    assert a.distance_to((4, 6)) == 5.0
    assert a.lerp((3, 4), 0.5) == Vector(2, 3)
    a += (1, 1)
    assert a == Vector(2, 3)


def test_unpacking_and_components() -> None:
    x, y = Vector(3, -4)
    assert (x, y) == (3.0, -4.0)
    assert Vector(3, -4).components() == (3.0, -4.0)
    assert isinstance(Vector(3, -4).components(), tuple)
    assert list(Vector(3, -4)) == [3.0, -4.0]


def test_components_are_floats_and_default_to_zero() -> None:
    v = Vector(1, 2)
    assert type(v.x) is float and type(v.y) is float
    assert Vector() == Vector(0, 0)
    assert Vector(x=2) == Vector(2, 0)


def test_numpy_scalars_scale_a_vector_from_both_sides() -> None:
    # A numpy float is a number (np.float64 subclasses float): scaling by it gives a Vector,
    # not a numpy array, whichever side it is on (a dt read back from an array, say).
    s = np.float64(2.0)
    assert type(Vector(1, 2) * s) is Vector and Vector(1, 2) * s == Vector(2, 4)
    assert type(s * Vector(1, 2)) is Vector and s * Vector(1, 2) == Vector(2, 4)


def test_unary_minus_and_division_and_scaling_from_both_sides() -> None:
    assert -Vector(1, -2) == Vector(-1, 2)
    assert Vector(3, 6) / 3 == Vector(1, 2)
    assert 2 * Vector(1, 2) == Vector(1, 2) * 2 == Vector(2, 4)
    with pytest.raises(ZeroDivisionError, match="zero"):
        Vector(1, 2) / 0


# -- the named operations ----------------------------------------------------------------------


def test_dot_cross_length_squared_magnitude() -> None:
    a, b = Vector(3, 4), Vector(-2, 5)
    assert a.dot(b) == 3 * -2 + 4 * 5
    assert a.cross(b) == 3 * 5 - 4 * -2
    assert Vector(1, 0).cross(Vector(0, 1)) == 1.0  # counter-clockwise is positive
    assert a.length_squared() == 25.0
    assert a.magnitude() == 5.0
    assert abs(a) == 5.0


@given(vectors, vectors)
def test_dot_and_cross_identities(a: Vector, b: Vector) -> None:
    # |a|^2 |b|^2 = (a.b)^2 + (a x b)^2  (Lagrange's identity in 2D)
    lhs = a.length_squared() * b.length_squared()
    rhs = a.dot(b) ** 2 + a.cross(b) ** 2
    assert math.isclose(lhs, rhs, rel_tol=1e-9, abs_tol=1e-200)
    assert a.dot(b) == b.dot(a)
    assert a.cross(b) == -b.cross(a)
    assert a.cross(a) == 0.0


def test_normalized_is_a_unit_vector_in_the_same_direction() -> None:
    assert Vector(3, 4).normalized() == Vector(0.6, 0.8)
    assert Vector(0, -7).normalized() == Vector(0, -1)
    with pytest.raises(ValueError, match="zero vector"):
        Vector(0, 0).normalized()


@given(vectors.filter(lambda v: v.magnitude() > 1e-100))
def test_normalized_has_length_one(a: Vector) -> None:
    n = a.normalized()
    assert math.isclose(n.magnitude(), 1.0, rel_tol=4 * EPS)
    assert math.isclose(n.cross(a), 0.0, abs_tol=8 * EPS * a.magnitude())
    assert n.dot(a) > 0


def test_distance_to_and_lerp() -> None:
    assert Vector(1, 1).distance_to(Vector(4, 5)) == 5.0
    assert Vector(4, 5).distance_to(Vector(1, 1)) == 5.0
    a, b = Vector(0, 0), Vector(10, 20)
    assert a.lerp(b, 0) == a
    assert a.lerp(b, 1) == b
    assert a.lerp(b, 0.25) == Vector(2.5, 5)
    # pygame's lerp: t outside [0, 1] is a ValueError (no extrapolation), and the ends are exact.
    with pytest.raises(ValueError, match=r"\[0, 1\]"):
        a.lerp(b, 2)
    with pytest.raises(ValueError, match=r"\[0, 1\]"):
        a.lerp(b, -0.5)
    assert Vector(0.1, 0.7).lerp((0.3, 0.9), 1) == Vector(0.3, 0.9)


# -- refusals ----------------------------------------------------------------------------------


@pytest.mark.parametrize("bad", ["1", None, [1], True, 1j])
def test_non_number_x_component_is_a_type_error_naming_x(bad: object) -> None:
    with pytest.raises(TypeError, match="component x"):
        Vector(bad, 1)  # type: ignore[arg-type]


@pytest.mark.parametrize("bad", ["1", None, (1,), False])
def test_non_number_y_component_is_a_type_error_naming_y(bad: object) -> None:
    with pytest.raises(TypeError, match="component y"):
        Vector(1, bad)  # type: ignore[arg-type]


def test_lerp_refuses_a_non_number_t_and_named_methods_refuse_non_vectors() -> None:
    with pytest.raises(TypeError, match="component t"):
        Vector(0, 0).lerp((1, 1), "half")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="other"):
        Vector(1, 2).dot(3)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="other"):
        Vector(1, 2).distance_to((1, 2, 3))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="value"):
        Vector.coerce("ab")


def test_operators_with_unsupported_operands_raise_type_error() -> None:
    with pytest.raises(TypeError):
        Vector(1, 2) + 1  # type: ignore[operator]
    with pytest.raises(TypeError):
        Vector(1, 2) - "a"  # type: ignore[operator]
    with pytest.raises(TypeError):
        Vector(1, 2) * "a"  # type: ignore[operator]
    with pytest.raises(TypeError):
        Vector(1, 2) / Vector(1, 2)  # type: ignore[operator]
    assert (Vector(1, 2) == "X: 1.0 Y: 2.0") is False
    assert Vector(1, 2) != (1, 2, 3)
