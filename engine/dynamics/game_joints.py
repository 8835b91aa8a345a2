"""The soft step's joints: each joint a row of the solver's joint arrays, and each row's
impulses reported back on its joint after the step.

The joints of a World's soft step (engine.pipeline.game_step's stage 5) are its mouse joints, links
(rods, cables, pins), joints (hinges, welds), springs and pymunk's constraints
(engine.dynamics.constraints), in that order, each one row of ``solver.solve``'s joint arrays: 16
inputs (its kind, the rows of its two bodies, its anchors, its settings) and 6 impulses, the
last step's, which warm start it. What a step costs here is kept small for a game, which
steps the same joints 60 times a second: a joint's inputs are made again only when the
World's bodies or the joint's settings change (``_row_token``), the arrays only when a row's
inputs do (the solver leaves each joint's impulses in them, the next step's warm start), and
the impulses are reported on the joints by a kind read once (``_Kind``), not a chain of
class tests a joint a step.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..vector import Vector
from . import solver
from .constraints import (
    GearJoint,
    GrooveJoint,
    RatchetJoint,
    RotaryLimitJoint,
    SimpleMotor,
    SlideJoint,
    SoftJoint,
)
from .joints import Hinge, Joint, Weld
from .links import Link, Pin, edits
from .mouse_joint import MouseJoint
from .reported import Pending
from .springs import BodySpring, DampedRotarySpring, DampedSpring

#: The World's state (engine.pipeline.world_state.WorldState), named by what is read of it.
WorldState = Any

__all__ = ["GameJoints", "IMPULSES_AT", "INT_ROWS"]

#: Where a joint's six impulses start in the solver's arrays: after the bodies' 11 and the
#: contacts' 18, the joints' 16 inputs (solver.solve's order).
IMPULSES_AT = 11 + 18 + 16
#: Which of the 22 joint arrays are ints (jkind, ja, jb, jlimit, jmotor: solver.solve's order).
INT_ROWS = (0, 1, 2, 10, 13)

# How a row's impulses are reported on its joint (``GameJoints.report``), read once a joint.
_CONSTRAINT, _MOUSE, _SPRING, _ROTARY_SPRING, _ROD, _PIN, _WELD, _HINGE = range(8)


def _kind(j: Any) -> int:
    """How ``j``'s impulses are reported (the kinds above)."""
    if isinstance(j, SoftJoint):
        return _CONSTRAINT
    if isinstance(j, MouseJoint):
        return _MOUSE
    if isinstance(j, DampedSpring):
        return _SPRING
    if isinstance(j, DampedRotarySpring):
        return _ROTARY_SPRING
    if not isinstance(j, Joint):
        return _PIN if isinstance(j, Pin) else _ROD
    return _HINGE if isinstance(j, Hinge) else _WELD


class GameJoints:
    """A soft step's joints (module doc): their rows kept from step to step, their impulses
    (the warm start) by joint."""

    def __init__(self, fast: bool) -> None:
        self.fast = fast  # the compiled step (it leaves the impulses in the arrays it took)
        # The last step's impulses (``_StepReport``), or those set (``impulses``) by id(joint).
        self._last: _StepReport | None = None
        self._impulses: dict[int, tuple[float, ...]] | None = {}
        # What the fast path's arrays hold the impulses of: the last report, or a token made
        # when ``impulses`` was set (no arrays hold those).
        self._token: object = self._impulses
        # The fast path's joint arrays: (each row's inputs, the arrays, the impulses kept
        # from them after the kernel's step, or None before it): ``arrays``.
        self._arrays: tuple[list[Any], list[np.ndarray], Any] | None = None
        # (the fast path's joint arrays, and their six impulse arrays as one table's rows)
        self._impulse_rows: tuple[list[np.ndarray], np.ndarray] | None = None
        #: The fast path's joint arrays as two tables, whose rows they are (``arrays``).
        self.packed: tuple[np.ndarray, np.ndarray] = (
            np.zeros((len(INT_ROWS), 0), dtype=np.int64),
            np.zeros((22, 0)),
        )
        # Each joint's row inputs, by id(joint): (joint, _row_token, row), while the World's
        # bodies are the same (the key: its version, the bodies' count, the store).
        self._rows: tuple[Any, dict[int, tuple[Any, Any, list[Any]]]] = (None, {})
        # The last step's rows as a whole: (the World's key and engine.dynamics.links.edits()
        # then, the joints, their inputs), where no row's inputs change every step.
        self._inputs: tuple[Any, list[Any], list[list[Any]]] | None = None
        # The rows' owners (``arrays``): the World's links, springs and mouse joints lists and
        # their lengths as last read, and the owners made of them.
        self._owners: tuple[list[Any], list[Any], list[Any], tuple[int, ...], list[Any]] | None
        self._owners = None
        # The numpy path's 16 input arrays and their lists (``_plain``): (the rows' inputs and
        # owners they were made of, the arrays, their lists, which owners are springs, whether
        # no owner is there twice).
        self._inputs_made: tuple[Any, ...] | None = None
        # The numpy path's last arrays and the solver's lists of them (``lists``).
        self._lists: tuple[list[np.ndarray], list[list[Any]]] | None = None
        # The joints last reported, each one's kind, and whether any is a pymunk constraint.
        self._kinds: tuple[list[Any], list[int], bool] = ([], [], False)

    @property
    def impulses(self) -> dict[int, tuple[float, ...]]:
        """Each joint's six impulses of the last step (the warm start), by id(joint)."""
        if self._impulses is None:
            last = self._last
            assert last is not None
            rows = list(zip(*last.table.tolist(), strict=True))
            self._impulses = dict(zip(map(id, last.joints), rows, strict=True))
        return self._impulses

    @impulses.setter
    def impulses(self, value: dict[int, tuple[float, ...]]) -> None:
        self._last, self._impulses = None, value
        self._token = object()

    def arrays(self, state: WorldState, store: Any, n: int) -> tuple[list[np.ndarray], list[Any]]:
        """The joints as the solver's joint arrays (solver.solve's order: each row's 16
        inputs, then the 6 impulses kept from the last step, the warm start): mouse joints,
        links and joints, springs."""
        # A Pin that holds its body still makes it kinematic (WorldState.links_changed): the
        # solver's static body in all but name. Every other link is a row. Kept while the
        # World's three lists are the same objects of the same lengths (each grows in place
        # or is made anew: engine.pipeline.membership; a pin's ``holds`` is fixed when made).
        links, springs, drags = state.links, state.springs.items, state.drags.items
        sizes = (len(links), len(springs), len(drags))
        owners = self._owners
        if (
            owners is not None
            and owners[0] is links
            and owners[1] is springs
            and owners[2] is drags
            and owners[3] == sizes
        ):
            ends = owners[4]
        else:
            joints = [j for j in links if not (isinstance(j, Pin) and j.holds)]
            ends = [*drags, *joints, *springs]
            self._owners = (links, springs, drags, sizes, ends)
        # Each row's inputs change only where the World's bodies or the joint's settings do
        # (_row_token): kept by joint while the bodies' rows are the same.
        key = (state.version, n, id(store))
        if self._rows[0] != key:
            self._rows = (key, {})
        made = self._rows[1]
        # No setting of any joint set since (``edits``), the same joints: the same rows (a
        # game's plain step, where reading each joint's token was most of this call's cost).
        stamp = (key, edits())
        kept = self._inputs
        if kept is not None and kept[0] == stamp and kept[1] == ends:
            inputs = kept[2]
        else:
            inputs = []
            every = True  # (every row kept by its token: none changes every step)
            for j in ends:
                token = _row_token(j)
                entry = made.get(id(j))
                if token is not None and entry is not None and entry[0] is j and entry[1] == token:
                    inputs.append(entry[2])
                    continue
                row = self._row(j, store, n)
                if token is not None:
                    made[id(j)] = (j, token, row)
                else:
                    every = False
                inputs.append(row)
            self._inputs = (stamp, ends, inputs) if every else None
        if not self.fast:
            return self._plain(ends, inputs), ends
        # The kernel leaves each joint's impulses in place in the last six arrays, which
        # ``report`` keeps as ``impulses``: where every row's inputs are the last step's and
        # those impulses are still the ones kept, the arrays are this step's.
        kept_arrays = self._arrays
        if kept_arrays is not None and kept_arrays[2] is self._token:
            if kept_arrays[0] == inputs:
                return kept_arrays[1], ends
        rows = [[*row, *warm] for row, warm in zip(inputs, self._warm(ends), strict=True)]
        ints, table, arrays = _columns(rows, 22)
        # The compiled step takes the two tables (two arguments where the 22 arrays were 22:
        # each array a kernel takes costs its call about 0.1 us) and reads the arrays as their
        # rows.
        self.packed = (ints, table)
        self._arrays = (inputs, arrays, None)
        # The six impulse arrays are rows of one table: ``report`` copies them at once.
        self._impulse_rows = (arrays, table[16:])
        return arrays, ends

    def _warm(self, ends: list[Any]) -> list[tuple[float, ...]]:
        """Each joint's six impulses to start from (``impulses``; a spring's none: it is
        not warm started)."""
        none = (0.0,) * 6
        kept = self.impulses
        return [none if isinstance(j, BodySpring) else kept.get(id(j), none) for j in ends]

    def _plain(self, ends: list[Any], inputs: list[list[Any]]) -> list[np.ndarray]:
        """``arrays`` on the numpy path: the 16 input arrays (and the solver's lists of them,
        ``lists``) kept while the rows' inputs are the same list (``_inputs``: no joint's
        setting changed), and the six impulse arrays the last step's report's table where it
        is of these joints (the impulses it keeps are that table's columns by joint), else
        read from ``impulses`` as the fast path's are."""
        made = self._inputs_made
        if made is None or made[0] is not inputs or made[1] is not ends:
            head = _columns(inputs, 16)[2]
            spring = np.array([isinstance(j, BodySpring) for j in ends], dtype=bool)
            once = len({id(j) for j in ends}) == len(ends)
            made = (inputs, ends, head, [a.tolist() for a in head], spring, once)
            self._inputs_made = made
        _, _, head, head_lists, spring, once = made
        last = self._last
        if last is not None and last.joints is ends and once:
            # (A spring's impulses are not kept: its warm start is none.)
            impulses = np.where(spring, 0.0, last.table) if spring.any() else last.table
        else:
            impulses = np.array(self._warm(ends), dtype=float).reshape(-1, 6).T.copy()
        arrays = [*head, *impulses]
        # (solve only reads the 16 inputs' lists, and writes the impulses' in place: those are
        # new lists each step, the inputs' the kept ones.)
        self._lists = (arrays, [*head_lists, *impulses.tolist()])
        return arrays

    def lists(self, arrays: list[np.ndarray]) -> list[list[Any]]:
        """The joints' ``arrays`` (``arrays``'s) as the solver's lists (solver.solve.py's
        plain Python takes lists): on the numpy path the inputs' lists kept with them."""
        kept = self._lists
        if kept is not None and kept[0] is arrays:
            return kept[1]
        return [a.tolist() for a in arrays]

    def constrained(self, joints: list[Any]) -> bool:
        """Whether any of ``joints`` is a pymunk constraint (its report reads the bodies'
        positions at the step's end)."""
        return self._kinds_of(joints)[2]

    def report(
        self, joints: list[Any], out: list[Any], k: int, arrays: list[np.ndarray] | None = None
    ) -> None:
        """Each joint's impulses kept (warm start) and reported on it: over the step of ``k``
        substeps, on body_a (N s, N m s); ``out`` the solver's arrays after it. ``arrays``:
        the fast path's joint arrays the kernel took (``arrays``), which now hold these
        impulses: kept for the next step while no row's inputs change."""
        base = IMPULSES_AT
        # The six impulse columns, a row a joint, copied (the fast path's arrays are the next
        # step's warm start, solved in place); put on the joints when one is read.
        rows = self._impulse_rows
        if arrays is not None and rows is not None and rows[0] is arrays:
            table = rows[1].copy()  # (the kernel solved them in place: the same numbers)
        else:
            table = np.array(out[base : base + 6], dtype=float)
        last = self._last = _StepReport(joints, self._kinds_of(joints)[1], table, k, out)
        self._impulses = None
        self._token = last
        if arrays is not None and self._arrays is not None and self._arrays[1] is arrays:
            self._arrays = (self._arrays[0], arrays, last)
        for j in joints:
            j._pending = last

    def _kinds_of(self, joints: list[Any]) -> tuple[list[Any], list[int], bool]:
        """Each joint's kind, read again only when the joints are not the last ones."""
        kept = self._kinds
        if kept[0] != joints:
            kinds = [_kind(j) for j in joints]
            kept = self._kinds = (list(joints), kinds, _CONSTRAINT in kinds)
        return kept

    def _row(self, j: Any, store: Any, n: int) -> list[Any]:
        """A mouse joint's, link's, joint's or spring's row: its 16 inputs (solver.solve's
        jkind ... jmaxtorque). A hinge's and a weld's: the solver's body A is the joint's
        body_b (or the static body), its B the joint's body_a, so that the solver's
        angle_B - angle_A is the joint's angle."""
        if isinstance(j, MouseJoint):
            # A mouse joint: the static body's anchor is the target (world coordinates).
            target, anchor = j.target, j.anchor
            return [
                solver.MOUSE, n, store.row(j.body.slot), target.x, target.y, anchor.x,
                anchor.y, 0.0, j.hertz, j.damping_ratio, 0, 0.0, 0.0, 0,
                j.angular_damping, min(j.max_force, 1e300),
            ]  # fmt: skip
        if isinstance(j, SoftJoint):
            return _constraint_row(j, store, n)
        if isinstance(j, BodySpring):
            return _spring_row(j, store, n)
        if not isinstance(j, Joint):
            return self._link_row(j, store, n)
        b, a, anchor_b = self._ends(j, store, n)
        hertz = j.hertz if isinstance(j, Weld) and j.hertz is not None else 0.0
        zeta = j.damping_ratio if isinstance(j, Weld) else 0.0
        lim = j.limits if isinstance(j, Hinge) else None
        speed = j.motor_speed if isinstance(j, Hinge) else None
        most = j.max_torque if isinstance(j, Hinge) else 0.0
        return [
            solver.WELD if isinstance(j, Weld) else solver.HINGE,
            b,
            a,
            anchor_b.x,
            anchor_b.y,
            j.anchor_a.x,
            j.anchor_a.y,
            j.reference_angle,
            hertz,
            zeta,
            0 if lim is None else 3,  # both limits
            0.0 if lim is None else lim[0],
            0.0 if lim is None else lim[1],
            0 if speed is None else 1,
            0.0 if speed is None else speed,
            min(most, 1e300),
        ]

    @staticmethod
    def _ends(link: Link, store: Any, n: int) -> tuple[int, int, Vector]:
        """A link's or joint's ends as the solver takes them: its body A's row (the link's
        other end, or the static body ``n`` for a fixed point), B's (the link's own body), and
        A's anchor (in its own frame; a fixed point's in world coordinates)."""
        other = link._other
        a = n if other is None else store.row(other.slot)
        anchor = link.anchor_b if other is not None else link._point
        assert anchor is not None
        return a, store.row(link.body.slot), anchor

    def _link_row(self, link: Link, store: Any, n: int) -> list[Any]:
        """A rod's or cable's distance row, or a pin's hinge to the world at its point (the
        solver's body A the other end, B the link's body: ``_ends``)."""
        a, b, anchor_b = self._ends(link, store, n)
        ax, ay = link.anchor_a.x, link.anchor_a.y
        if isinstance(link, Pin):
            return [solver.HINGE, a, b, anchor_b.x, anchor_b.y, ax, ay, 0.0, 0.0, 0.0, 0, 0.0,
                    0.0, 0, 0.0, 0.0]  # fmt: skip
        # A rod holds its length both ways (least = most); a cable at most (the upper limit).
        least = link.length if link.rigid else 0.0
        return [solver.DISTANCE, a, b, anchor_b.x, anchor_b.y, ax, ay, 0.0, 0.0, 0.0, 2, least,
                link.length, 0, link.restitution, 0.0]  # fmt: skip


class _StepReport(Pending):
    """A soft step's joint impulses (``GameJoints.report``), put on each joint (``fill``) when
    one of its reported values is first read or written (engine.dynamics.reported)."""

    __slots__ = ("joints", "kinds", "table", "k", "out")

    def __init__(
        self, joints: list[Any], kinds: list[int], table: np.ndarray, k: int, out: list[Any]
    ) -> None:
        """``table`` (6, m): the joints' six impulses of the last substep, a column a joint;
        ``k`` the substeps; ``out`` the solver's arrays after the step (a pymunk constraint's
        report reads its bodies' places there, and its ends' rows)."""
        self.joints, self.kinds, self.table, self.k, self.out = joints, kinds, table, k, out

    def fill(self) -> None:
        """Each joint's impulses over the step, on body_a (N s, N m s): its last substep's
        times the ``k`` substeps."""
        k, out, base = self.k, self.out, IMPULSES_AT
        # Only the joints whose last report this is (a joint stepped again since, in
        # another World, has a later one).
        mine = [j._pending is self for j in self.joints]
        for j, own in zip(self.joints, mine, strict=True):
            if own:
                j._pending = None
        rows = zip(*self.table.tolist(), strict=True)
        for i, (j, kind, impulses) in enumerate(zip(self.joints, self.kinds, rows, strict=True)):
            if not mine[i]:
                continue
            px, py, pa, lo, hi, mi = impulses
            if kind == _HINGE or kind == _WELD:
                j.linear_impulse = Vector(px * k, py * k)
                j.impulse = math.hypot(px * k, py * k)  # its size, as the exact solver's
                j.angular_impulse = (pa + mi + lo - hi) * k
                if kind == _HINGE:
                    j.motor_impulse = mi * k
            elif kind == _ROD:
                j.impulse = (hi - lo - pa) * k  # along it, > 0 pulling its ends together
            elif kind == _PIN:
                j.impulse = math.hypot(px, py) * k  # |P|
            elif kind == _MOUSE:
                j.impulse = Vector(px * k, py * k)  # on the body, over the step
            elif kind == _SPRING:
                j.impulse = -pa  # over the step (not a substep's), > 0 pulling
            elif kind == _ROTARY_SPRING:
                j.impulse = pa  # the angular impulse on a over the step
            else:
                ends = (int(out[base - 15][i]), int(out[base - 14][i]))  # (ja, jb)
                _report_constraint(j, ends, impulses, k, out)


def _spring_row(spring: BodySpring, store: Any, n: int) -> list[Any]:
    """A spring's row (solver.SPRING or ROTARY_SPRING): the solver's body A its ``b`` (the
    static body for the world, its anchor then in world coordinates), B its ``a``, so that
    angle_B - angle_A is its twist's angle; rest, stiffness and damping in the row."""
    a = n if spring.second is None else store.row(spring.second.slot)
    b = store.row(spring.a.slot)
    if isinstance(spring, DampedSpring):
        kind, rest = solver.SPRING, spring.rest_length
        pa, pb = spring.anchor_b, spring.anchor_a
    else:
        assert isinstance(spring, DampedRotarySpring)
        kind, rest = solver.ROTARY_SPRING, spring.rest_angle
        pa = pb = Vector(0.0, 0.0)
    return [kind, a, b, pa.x, pa.y, pb.x, pb.y, 0.0, spring.stiffness, spring.damping, 0, rest,
            0.0, 0, 0.0, 0.0]  # fmt: skip


def _constraint_row(j: SoftJoint, store: Any, n: int) -> list[Any]:
    """A pymunk constraint's row (engine.dynamics.constraints; engine.dynamics.solver's kinds): the
    solver's A its body_a, B its body_b (the static body ``n`` for the world, its anchors then in
    world coordinates), so that angle_B - angle_A is pymunk's b.angle - a.angle."""
    a = n if j._a is None else store.row(j._a.slot)
    b = n if j._b is None else store.row(j._b.slot)
    kind, ref, lower, upper, speed = solver.ROTARY, 0.0, 0.0, 0.0, 0.0
    limit, motor = 0, 0
    pa, pb = j.anchor_a, j.anchor_b
    if isinstance(j, SlideJoint):
        # A distance: at most max apart, at least min (the least's row on where min > 0).
        kind, lower, upper, limit = solver.DISTANCE, j.min, j.max, 3 if j.min > 0.0 else 2
    elif isinstance(j, GrooveJoint):
        # A's anchor the groove's start, its direction the axis, its length the upper limit.
        kind, limit = solver.GROOVE, 3
        ref, upper = j.axis
    elif isinstance(j, GearJoint):
        kind, ref, speed = solver.GEAR, j.phase, j.ratio
    elif isinstance(j, RotaryLimitJoint):
        limit, lower, upper = 3, j.min, j.max
    elif isinstance(j, RatchetJoint):
        # One limit at the notch, moved on from the angles the step starts at: the lower for
        # a ratchet that turns up freely, the upper for one that turns down.
        delta = (0.0 if j._b is None else float(store.angle[b])) - (
            0.0 if j._a is None else float(store.angle[a])
        )
        lower = upper = j._advance(delta)
        limit = 1 if j.ratchet > 0.0 else 2
    else:
        assert isinstance(j, SimpleMotor)
        # The hinge's motor row drives omega_B - omega_A: pymunk's rate is omega_a - omega_b.
        motor, speed = 1, -j.rate
    # pymunk's bounds (jmotor's bit 2): the largest force (a motor's torque) in jmaxtorque,
    # the largest bias speed in jdamp, the error_bias in jhertz (-1: the joints' spring).
    error = -1.0 if j.error_bias is None else j.error_bias
    most, fastest = min(j.max_force, 1e300), min(j.max_bias, 1e300)
    return [kind, a, b, pa.x, pa.y, pb.x, pb.y, ref, error, fastest, limit, lower, upper,
            motor | 2, speed, most]  # fmt: skip


def _row_token(j: Any) -> tuple[Any, ...] | None:
    """What a joint's row inputs follow besides the bodies' rows: every setting that changes
    them bumps ``revision`` (a hinge's motor and limits, set without remaking a solver, are
    read as they are); None where they change every step (a ratchet's notch follows the
    angles, a mouse joint's target the mouse)."""
    if isinstance(j, (MouseJoint, RatchetJoint)):
        return None
    if isinstance(j, Hinge):
        return (j.revision, j._limits, j._speed, j._max_torque)
    return (j.revision,)


def _report_constraint(
    j: SoftJoint, rows: tuple[int, int], impulses: tuple[float, ...], k: int, out: list[Any]
) -> None:
    """A pymunk constraint's impulses over the step, given body_a (engine.dynamics.constraints),
    from the solver's last substep's (``impulses``: jpx, jpy, jpa, jlo, jhi, jmi) times its ``k``
    substeps; ``rows`` its ends' rows in ``out``, the solver's arrays after the step."""
    _, _, pa, lo, hi, mi = impulses
    j.linear_impulse, j.angular_impulse = Vector(0.0, 0.0), 0.0
    a, b = rows
    n = len(out[0]) - 1  # (the static body's row)
    if isinstance(j, SlideJoint):
        # Along the joint as it is at the step's end, > 0 pulling, as a rod's.
        j.impulse = (hi - lo - pa) * k
        d = _at_end(out, b, n, j.anchor_b) - _at_end(out, a, n, j.anchor_a)
        length = d.length()
        j.linear_impulse = d * (j.impulse / length) if length > 0.0 else Vector(0.0, 0.0)
        return
    if isinstance(j, GrooveJoint):
        # Along the groove and across it, as it is at the step's end.
        angle, _ = j.axis
        turn = 0.0 if a == n else float(out[2][a])
        u = Vector(math.cos(angle + turn), math.sin(angle + turn))
        # On body_b: the ends' push along u, the point's across (n = (-u_y, u_x)).
        on_b = u * ((lo - hi) * k) + Vector(-u.y, u.x) * (pa * k)
        j.linear_impulse = -on_b
        j.impulse = on_b.length()
        return
    if isinstance(j, GearJoint):
        j.angular_impulse = -pa * k  # body_b took ratio times its opposite
    else:
        j.angular_impulse = -(mi + lo - hi) * k
    j.impulse = abs(j.angular_impulse)


def _at_end(out: list[Any], row: int, n: int, local: Vector) -> Vector:
    """The point ``local`` of the body in ``row`` (its own frame; the static body's, world
    coordinates) where the solver's step left it (``out``: its x, y and angle arrays first)."""
    if row == n:
        return local
    q = float(out[2][row])
    c, s = math.cos(q), math.sin(q)
    x, y = float(out[0][row]), float(out[1][row])
    return Vector(x + c * local.x - s * local.y, y + s * local.x + c * local.y)


def _columns(rows: list[Any], width: int) -> tuple[np.ndarray, np.ndarray, list[np.ndarray]]:
    """The joints' ``rows`` (``width`` numbers each) as one float table whose rows are the
    columns (each C-contiguous, as the kernel takes them), the five of ints (``INT_ROWS``) in
    an int table of their own, and the columns as solve's arrays, in order."""
    table = np.array(rows, dtype=float).reshape(-1, width).T.copy()
    ints = table[list(INT_ROWS)].astype(np.int64)
    at = {row: i for i, row in enumerate(INT_ROWS)}
    return ints, table, [ints[at[i]] if i in at else table[i] for i in range(width)]
