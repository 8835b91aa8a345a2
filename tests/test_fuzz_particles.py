"""Fuzzing engine.particles.Particles: constructor, emit, step, kill and run.

Examples per test: constructor 300, emit/step/kill sequences 600. This file: 900.
"""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np
from fuzzing import anything, attempt, check_message, fuzz, junk, numbers, pairs
from hypothesis import example, given
from hypothesis import strategies as st

from engine.forces import Drag, Gravity, Wind
from engine.particles import Particles

small_counts = st.one_of(st.integers(-3, 40), numbers, junk)


@fuzz(300)
@given(
    capacity=st.one_of(
        st.integers(-3, 200), st.sampled_from([10**8 + 1, 10**15, 2**64]), numbers, junk
    ).filter(lambda c: not (isinstance(c, (int, np.integer)) and 10**4 < c <= 10**8)),
    dt=st.one_of(st.floats(1e-4, 0.1), numbers, junk),
    mass=st.one_of(st.just(1.0), numbers, junk),
    integrator=st.one_of(st.sampled_from(["semi_implicit_euler", "rk4", "nope"]), junk),
    forces=st.one_of(st.just(()), st.just([Gravity((0, -9.8))]), junk, numbers),
)
def test_constructor_names_a_bad_argument(
    capacity: Any, dt: Any, mass: Any, integrator: Any, forces: Any
) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # StabilityWarning for extreme dt or mass
        ok, p = attempt(
            lambda: Particles(capacity, dt, forces, integrator, mass),
            "capacity",
            "dt",
            "mass",
            "integrator",
            "force",
        )
    if ok:
        assert p is not None
        assert p.capacity == capacity and len(p) == 0 and p.t == 0.0
        assert 0 < p.dt < math.inf and 0 < p.mass < math.inf


OPS = ("emit", "emit_many", "step", "kill", "kill_mask", "run")


@fuzz(600)
@given(
    ops=st.lists(
        st.tuples(
            st.sampled_from(OPS),
            small_counts,
            st.one_of(st.tuples(st.floats(-1e3, 1e3), st.floats(-1e3, 1e3)), pairs, anything),
            st.one_of(st.floats(0.0, 2.0), numbers, junk, st.just(math.inf)),
            st.one_of(st.integers(0, 12), st.integers(-(2**40), 2**40), numbers, junk),
        ),
        min_size=1,
        max_size=12,
    ),
    general=st.booleans(),
)
# Found exploring: an array of two lifetimes, one a particle (the oracle took one number).
@example(ops=[("emit", 2, (-110.7, 623.6), np.array([1.0, 2.0]), 0)], general=False)
# ... and of kinds, with a count past the capacity (the first ``placed`` of them went in).
@example(ops=[("emit", 70, (0.0, 0.0), np.full(70, 0.5), np.arange(70))], general=True)
def test_emit_step_kill_keep_counts_consistent_and_state_finite(
    ops: list[tuple[str, Any, Any, Any, Any]], general: bool
) -> None:
    p = Particles(
        64,
        dt=1 / 60,
        forces=[Gravity((0.0, -9.81)), Drag(0.1), Wind(lambda t: (math.sin(t), 0.0), 0.2)],
        fast_path=not general,
    )
    for op, count, position, lifetime, kind in ops:
        n, emitted, dropped = len(p), p.emitted, p.dropped
        if op in ("emit", "emit_many"):
            if op == "emit_many" and not (type(count) is int and 0 <= count <= 100):
                continue
            velocity = (1.0, 2.0) if op == "emit" else np.ones((count, 2))
            ok, placed = attempt(
                lambda c=count, x=position, life=lifetime, k=kind, v=velocity: p.emit(
                    c, x, v, life, k
                ),
                "count",
                "position",
                "velocity",
                "lifetime",
                "kind",
            )
            if not ok:
                assert (len(p), p.emitted, p.dropped) == (n, emitted, dropped)
                continue
            assert isinstance(placed, int) and 0 <= placed <= count
            assert len(p) == n + placed and p.emitted == emitted + placed
            assert p.dropped == dropped + count - placed
            if placed:
                # A kind and a lifetime are one for all or one a particle (an array of
                # ``count``, of which the first ``placed`` went in).
                kinds, lives = np.asarray(kind), np.asarray(lifetime, dtype=float)
                kinds = kinds if kinds.ndim == 0 else kinds[:placed]
                lives = lives if lives.ndim == 0 else lives[:placed]
                assert (p.kinds[n:] == kinds).all(), (kind, p.kinds[n:])
                assert (p.lifetimes[n:] == lives).all(), (lifetime, p.lifetimes[n:])
        elif op == "step":
            gone = p.step()
            assert gone == len(p.expired.ids) and len(p) == n - gone
        elif op == "run":
            if isinstance(count, (int, np.integer)) and count > 40:
                continue  # a valid but long run: not what this test is about
            ok, gone = attempt(lambda c=count: p.run(c), "steps")
            if ok:
                assert 0 <= count <= 40 and len(p) == n - gone
        elif op == "kill":
            if isinstance(count, int) and not 0 <= count <= 100:
                continue
            which = count if not isinstance(count, int) else [i % max(n, 1) for i in range(count)]
            ok, killed = attempt(lambda w=which: p.kill(w), "which")
            if ok:
                assert len(p) == n - killed
        else:
            mask = p.positions[:, 1] < float(np.median(p.positions[:, 1])) if n else []
            killed = p.kill(np.asarray(mask, dtype=bool))
            assert len(p) == n - killed
        # The invariants of the structure after any call.
        assert 0 <= len(p) <= p.capacity
        assert len(set(p.ids.tolist())) == len(p)
        assert np.isfinite(p.positions).all() and np.isfinite(p.velocities).all()
        assert (p.ages >= 0).all() and (p.lifetimes > 0).all()


def test_a_kind_beyond_int32_is_refused_not_wrapped() -> None:
    p = Particles(4)
    try:
        p.emit(1, (0.0, 0.0), kind=2**40)
    except (TypeError, ValueError) as exc:
        check_message(exc, ("kind",))
    else:
        assert p.kinds.tolist() == [2**40]
