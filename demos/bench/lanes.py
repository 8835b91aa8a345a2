"""Would the soft step's contacts gain from being solved side by side? A model of its rows.

Run with ``python -m demos.bench lanes`` (``--quick``: the smaller scene only; needs the
``fast`` extra). The big scenes' step on the fast path is mostly the contacts' solve
(engine.dynamics.solver; the speed guide, "What is left"), Gauss-Seidel: each row reads the
velocities of its two bodies, pushes them, and writes them back before the next row starts.
Box2D v3 colours its contacts (no two rows of a colour share a moving body) and solves the
rows of a colour four or eight at a time in SIMD lanes. This measures what that layout is
worth to numba, on a model of the rows, not the engine's solve:

* **the rows**: Box2D's soft contact (``b2SolveContact``): per point, the separation from the
  bodies' moves, a speculative stop where it is open or a soft push where it overlaps, the
  normal impulse kept >= 0; then each point's friction, kept within mu times its normal
  impulse; manifolds of one point (a pit of discs) or two (a pile of boxes);
* **scalar**: the rows one after another, each reading and writing its bodies in place, in
  colour order (a one-point manifold skips its second point by a branch);
* **lanes**: each colour's rows in three loops: the bodies' velocities gathered into the rows
  of one table, the rows solved over that table alone (no body read there, so no row waits on
  another's writes; the two-point manifolds, then the one-point ones, in a loop of their own
  that has no second point), the velocities put back. In the same order, the two ways give
  the same bits.

LLVM vectorises the middle loop only if it may: numba indexes with signed integers and wraps
a negative index, so the loop's index is unsigned; and LLVM's vectoriser gives up on a loop
that needs more than 8 run-time checks that its arrays do not overlap ("too many memory
checks needed": every array written against every array read). ``raised`` compiles the
kernels with those limits raised (``llvmlite.binding.set_option``, in a process of its own:
the options hold for the rest of a process). Reported: each way's time per call (four
sweeps over every row, the least of three rounds), how many packed multiplies the lanes'
machine code holds (``vmulpd``: zero where LLVM did not vectorise), and whether the two ways
ended with the same bits.
"""

from __future__ import annotations

import json
import subprocess
import sys
import time
from typing import Any

import numpy as np

try:
    import numba
except ImportError:  # (the fast extra not installed: the model is plain Python, unmeasured)
    numba = None  # type: ignore[assignment]

__all__ = ["report", "measure", "scene", "colour_order", "table", "scalar", "lanes"]

#: The rows' numbers: the substep's 1/h (1/s); the soft push's bias rate (1/s), mass and
#: impulse scales (Box2D's b2MakeSoft at its contacts' 30 Hz, damping ratio 10, h = 1/240 s,
#: rounded); its largest push speed (m/s, Box2D's contactPushMaxVelocity).
INV_H, RATE, MASS_SCALE, IMPULSE_SCALE, PUSH = 240.0, 9.07, 0.942, 0.0577, 3.0
SWEEPS = 4  # solves over every row a call (a step's four substeps)
# The table's rows (one column a contact): the bodies' velocities (vax vay wa vbx vby wb: 0 to
# 5, gathered each colour), their moves and inverse masses (6 to 13, gathered too), the
# normal, whether a second point, friction (14 to 17), then each point's anchors, separation
# at the start, normal and tangent masses and impulses (POINT + 9 j to POINT + 9 j + 8).
POINT, ROWS = 18, 36


def _jit(**options: Any) -> Any:
    """numba.njit with ``options``, or the function as it is where numba is not installed."""
    return (lambda fn: fn) if numba is None else numba.njit(**options)


# (Each helper inlined in numba's own code: a call left to LLVM is one it cannot vectorise.)
_inline = _jit(inline="always")


def scene(side: int, points: int, seed: int = 0) -> dict[str, np.ndarray]:
    """A side x side grid of bodies, each in contact with its right, upper and diagonal
    neighbours and the bottom row with the static body (the last), with random normals,
    anchors (m) and separations: the rows' arithmetic and memory traffic, not a pile."""
    rng = np.random.default_rng(seed)
    n = side * side
    ca: list[int] = []
    cb: list[int] = []
    for i in range(side):
        for j in range(side):
            k = i * side + j
            for other, on in ((k + 1, j + 1 < side), (k + side, i + 1 < side),
                              (k + side + 1, i + 1 < side and j + 1 < side)):  # fmt: skip
                if on:
                    ca.append(k)
                    cb.append(other)
            if i == 0:
                ca.append(n)  # the static body is A
                cb.append(k)
    nc = len(ca)
    turn = rng.uniform(0.0, 2.0 * np.pi, nc)
    im = np.ones(n + 1)
    ii = np.full(n + 1, 2.0)
    im[n] = ii[n] = 0.0
    moving = np.ones(n + 1)
    moving[n] = 0.0
    return {
        "ca": np.array(ca, dtype=np.int64), "cb": np.array(cb, dtype=np.int64),
        "nx": np.cos(turn), "ny": np.sin(turn), "two": np.full(nc, float(points == 2)),
        "fric": np.full(nc, 0.6), "anchors": rng.uniform(-0.5, 0.5, (2, 4, nc)),
        "sep": rng.uniform(-0.01, 0.01, (2, nc)), "mass": rng.uniform(0.1, 1.0, (2, 2, nc)),
        "v": rng.normal(size=(3, n + 1)) * moving, "moves": rng.normal(size=(3, n + 1)) * 1e-3
        * moving, "im": im, "ii": ii,
    }  # fmt: skip


def colour_order(
    ca: np.ndarray, cb: np.ndarray, two: np.ndarray, static: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Greedy colours (the static body shared by any number of a colour's rows): the rows'
    order by colour, in each colour the two-point manifolds (``two`` 1.0) first; each colour's
    first row (and the end), and each colour's first one-point row."""
    taken: list[set[int]] = [set() for _ in range(static + 1)]
    colour = np.zeros(len(ca), dtype=np.int64)
    for k, (a, b) in enumerate(zip(ca.tolist(), cb.tolist(), strict=True)):
        c = 0
        while (a != static and c in taken[a]) or (b != static and c in taken[b]):
            c += 1
        colour[k] = c
        for body in (a, b):
            if body != static:
                taken[body].add(c)
    key = 2 * colour + (two == 0.0)
    order = np.argsort(key, kind="stable")
    starts = np.searchsorted(key[order], 2 * np.arange(colour.max() + 2))
    mids = np.searchsorted(key[order], 2 * np.arange(colour.max() + 1) + 1)
    return order, starts.astype(np.int64), mids.astype(np.int64)


def table(s: dict[str, np.ndarray], order: np.ndarray) -> np.ndarray:
    """The contacts' rows (ROWS x nc) in ``order``; the gathered rows 0 to 13 left empty."""
    t = np.zeros((ROWS, len(order)))
    t[14], t[15], t[16], t[17] = s["nx"][order], s["ny"][order], s["two"][order], s["fric"][order]
    for j in range(2):
        q = POINT + 9 * j
        t[q : q + 4] = s["anchors"][j][:, order]
        t[q + 4] = s["sep"][j][order]
        t[q + 5 : q + 7] = s["mass"][j][:, order]
    return t


@_inline
def _point(
    vax: float, vay: float, wa: float, vbx: float, vby: float, wb: float, dpx: float,
    dpy: float, dqa: float, dqb: float, ma: float, ia: float, mb: float, ib: float, nx: float,
    ny: float, r1x: float, r1y: float, r2x: float, r2y: float, s0: float, mass: float,
    old: float,
) -> tuple[float, float, float, float, float, float, float]:  # fmt: skip
    """A point's normal row (anchors r1, r2 from A's and B's positions, m; separation s0 at
    the step's start, m; normal mass, kg; impulse so far, N s): the velocities after it and
    its impulse."""
    # The separation now: s0 + n.(dp_B + dq_B x r_B - dp_A - dq_A x r_A).
    s = (dpx - dqb * r2y + dqa * r1y) * nx + (dpy + dqb * r2x - dqa * r1x) * ny + s0
    # Open: close by s this substep, no more (speculative); overlapping: the soft push.
    bias = s * INV_H if s > 0.0 else max(RATE * s, -PUSH)
    scale = 1.0 if s > 0.0 else MASS_SCALE
    keep = 0.0 if s > 0.0 else IMPULSE_SCALE
    vn = (vbx - wb * r2y - vax + wa * r1y) * nx + (vby + wb * r2x - vay - wa * r1x) * ny
    new = max(old - mass * scale * (vn + bias) - keep * old, 0.0)  # (a contact only pushes)
    v = (vax, vay, wa, vbx, vby, wb)
    return _push(v, ma, ia, mb, ib, r1x, r1y, r2x, r2y, (new - old) * nx, (new - old) * ny, new)


@_inline
def _rub(
    vax: float, vay: float, wa: float, vbx: float, vby: float, wb: float, ma: float,
    ia: float, mb: float, ib: float, nx: float, ny: float, r1x: float, r1y: float, r2x: float,
    r2y: float, mass: float, most: float, old: float,
) -> tuple[float, float, float, float, float, float, float]:  # fmt: skip
    """A point's friction row (tangent mass, kg; at most ``most`` N s either way): the
    velocities after it and its impulse."""
    vt = -(vbx - wb * r2y - vax + wa * r1y) * ny + (vby + wb * r2x - vay - wa * r1x) * nx
    new = min(max(old - mass * vt, -most), most)
    v = (vax, vay, wa, vbx, vby, wb)
    return _push(v, ma, ia, mb, ib, r1x, r1y, r2x, r2y, -(new - old) * ny, (new - old) * nx, new)


@_inline
def _push(
    v: tuple[float, float, float, float, float, float], ma: float, ia: float, mb: float,
    ib: float, r1x: float, r1y: float, r2x: float, r2y: float, px: float, py: float,
    impulse: float,
) -> tuple[float, float, float, float, float, float, float]:  # fmt: skip
    """The velocities ``v`` after an impulse (px, py) (N s) at the anchors r1, r2, -P on A and
    P on B (w = 1/m, i = 1/I: dv = w P, d omega = i r x P), and ``impulse`` passed on."""
    vax, vay, wa, vbx, vby, wb = v
    return (vax - ma * px, vay - ma * py, wa - ia * (r1x * py - r1y * px),
            vbx + mb * px, vby + mb * py, wb + ib * (r2x * py - r2y * px), impulse)  # fmt: skip


@_inline
def _contact(
    vax: float, vay: float, wa: float, vbx: float, vby: float, wb: float, dpx: float,
    dpy: float, dqa: float, dqb: float, ma: float, ia: float, mb: float, ib: float, nx: float,
    ny: float, two: float, mu: float, first: tuple[float, ...], other: tuple[float, ...],
) -> tuple[float, float, float, float, float, float, float, float, float, float]:  # fmt: skip
    """One contact: its bodies' velocities (m/s, rad/s), their moves since the step began
    (dp_B - dp_A, m; dq_A, dq_B, rad), inverse masses, the normal, whether a second point, the
    friction coefficient, and each point's anchors, separation, masses and impulses (``first``,
    ``other``: the table's rows POINT + 9 j to POINT + 9 j + 8): its points' normal rows, then
    their friction (Box2D's order). The velocities after them, and the four impulses.

    (Scalars in and out, no array: an array handed to an inlined function is counted in and
    out by numba's runtime, a call in the loop that LLVM cannot vectorise; and at most 30
    arguments a call, past which Python passes them as one tuple, which numba does not take.)"""
    a0x, a0y, b0x, b0y, s0, mn0, mt0, n0, f0 = first
    a1x, a1y, b1x, b1y, s1, mn1, mt1, n1, f1 = other
    vax, vay, wa, vbx, vby, wb, n0 = _point(
        vax, vay, wa, vbx, vby, wb, dpx, dpy, dqa, dqb, ma, ia, mb, ib, nx, ny, a0x, a0y, b0x,
        b0y, s0, mn0, n0,
    )  # fmt: skip
    # (A one-point manifold skips its second point; no store here, so where the rows run side
    # by side LLVM computes both ways and selects.)
    if two != 0.0:
        vax, vay, wa, vbx, vby, wb, n1 = _point(
            vax, vay, wa, vbx, vby, wb, dpx, dpy, dqa, dqb, ma, ia, mb, ib, nx, ny, a1x, a1y,
            b1x, b1y, s1, mn1, n1,
        )  # fmt: skip
    vax, vay, wa, vbx, vby, wb, f0 = _rub(
        vax, vay, wa, vbx, vby, wb, ma, ia, mb, ib, nx, ny, a0x, a0y, b0x, b0y, mt0, mu * n0, f0
    )
    if two != 0.0:
        vax, vay, wa, vbx, vby, wb, f1 = _rub(
            vax, vay, wa, vbx, vby, wb, ma, ia, mb, ib, nx, ny, a1x, a1y, b1x, b1y, mt1,
            mu * n1, f1,
        )  # fmt: skip
    return vax, vay, wa, vbx, vby, wb, n0, n1, f0, f1


@_inline
def _point_rows(t: Any, k: Any, q: int) -> tuple[float, ...]:
    """Column k's rows q to q + 8 of ``t``: a point's anchors, separation, masses, impulses."""
    return (t[q, k], t[q + 1, k], t[q + 2, k], t[q + 3, k], t[q + 4, k], t[q + 5, k],
            t[q + 6, k], t[q + 7, k], t[q + 8, k])  # fmt: skip


@_jit()
def scalar(ca: Any, cb: Any, t: Any, v: Any, moves: Any, im: Any, ii: Any) -> None:
    """SWEEPS sweeps over the contacts of ``t`` in its order, each reading its bodies'
    velocities ``v`` (3, nb) and writing them back (Gauss-Seidel)."""
    for _ in range(SWEEPS):
        for k in range(len(ca)):
            a, b = ca[k], cb[k]
            out = _contact(
                v[0, a], v[1, a], v[2, a], v[0, b], v[1, b], v[2, b],
                moves[0, b] - moves[0, a], moves[1, b] - moves[1, a], moves[2, a],
                moves[2, b], im[a], ii[a], im[b], ii[b], t[14, k], t[15, k], t[16, k],
                t[17, k], _point_rows(t, k, POINT), _point_rows(t, k, POINT + 9),
            )  # fmt: skip
            v[0, a], v[1, a], v[2, a], v[0, b], v[1, b], v[2, b] = out[:6]
            t[25, k], t[34, k], t[26, k], t[35, k] = out[6:]


@_inline
def _rows(t: Any, lo: int, hi: int, points: int) -> None:
    """Contacts lo to hi of ``t``, each on its own column: one loop, side by side where LLVM
    vectorises it (``points``: 2, their manifolds of two points; 1, of one)."""
    for i in range(hi - lo):
        u = np.uint64(lo + i)  # (unsigned: numba then wraps no negative index)
        two = t[16, u] if points == 2 else 0.0  # (a constant where one point: no second)
        out = _contact(
            t[0, u], t[1, u], t[2, u], t[3, u], t[4, u], t[5, u], t[6, u], t[7, u], t[8, u],
            t[9, u], t[10, u], t[11, u], t[12, u], t[13, u], t[14, u], t[15, u], two, t[17, u],
            (t[18, u], t[19, u], t[20, u], t[21, u], t[22, u], t[23, u], t[24, u], t[25, u],
             t[26, u]), (t[27, u], t[28, u], t[29, u], t[30, u], t[31, u], t[32, u], t[33, u],
             t[34, u], t[35, u]),
        )  # fmt: skip
        t[0, u], t[1, u], t[2, u], t[3, u], t[4, u], t[5, u] = out[:6]
        t[25, u], t[34, u], t[26, u], t[35, u] = out[6:]


@_jit()
def lanes(
    ca: Any, cb: Any, starts: Any, mids: Any, t: Any, v: Any, moves: Any, im: Any, ii: Any
) -> None:
    """SWEEPS sweeps as ``scalar``, a colour at a time: its contacts' bodies gathered into
    ``t``'s rows 0 to 13, its contacts solved over ``t`` alone (``_rows``: the two-point
    manifolds, then from ``mids`` on the one-point ones), the velocities put back."""
    for _ in range(SWEEPS):
        for c in range(len(starts) - 1):
            lo, hi = starts[c], starts[c + 1]
            for k in range(lo, hi):
                a, b = ca[k], cb[k]
                t[0, k], t[1, k], t[2, k] = v[0, a], v[1, a], v[2, a]
                t[3, k], t[4, k], t[5, k] = v[0, b], v[1, b], v[2, b]
                t[6, k], t[7, k] = moves[0, b] - moves[0, a], moves[1, b] - moves[1, a]
                t[8, k], t[9, k] = moves[2, a], moves[2, b]
                t[10, k], t[11, k], t[12, k], t[13, k] = im[a], ii[a], im[b], ii[b]
            _rows(t, lo, mids[c], 2)
            _rows(t, mids[c], hi, 1)
            for k in range(lo, hi):
                a, b = ca[k], cb[k]
                v[0, a], v[1, a], v[2, a] = t[0, k], t[1, k], t[2, k]
                v[0, b], v[1, b], v[2, b] = t[3, k], t[4, k], t[5, k]


def run(side: int, points: int, rounds: int) -> dict[str, Any]:
    """Time ``scalar`` and ``lanes`` on one scene (``scene``), in turn, ``rounds`` times: the
    least time a call of each (s), and whether both ended with the same bits."""
    s = scene(side, points)
    static = len(s["im"]) - 1
    order, starts, mids = colour_order(s["ca"], s["cb"], s["two"], static)
    ca, cb = s["ca"][order], s["cb"][order]
    ts, tl = table(s, order), table(s, order)
    vs, vl = s["v"].copy(), s["v"].copy()
    ways = {
        "scalar": lambda: scalar(ca, cb, ts, vs, s["moves"], s["im"], s["ii"]),
        "lanes": lambda: lanes(ca, cb, starts, mids, tl, vl, s["moves"], s["im"], s["ii"]),
    }
    for call in ways.values():
        call()  # (compiled here)
    best = {"scalar": np.inf, "lanes": np.inf}
    calls = max(1, 20_000 // len(ca))
    for _ in range(rounds):
        for name, call in ways.items():
            t0 = time.perf_counter()
            for _ in range(calls):
                call()
            best[name] = min(best[name], (time.perf_counter() - t0) / calls)
    # (Each way called as often: the same sweeps over the same rows.)
    same = bool(np.array_equal(vs, vl) and np.array_equal(ts[14:], tl[14:]))
    return {"contacts": len(ca), "colours": len(starts) - 1, "same": same, **best}


def measure(quick: bool, raised: bool) -> dict[str, Any]:
    """In this process: the functions compiled by numba (LLVM's memory-check limits raised
    first where ``raised``), each scene run; and the packed multiplies in the lanes' code."""
    import llvmlite.binding as llvm

    if raised:
        llvm.set_option("", "-runtime-memory-check-threshold=2000")
        llvm.set_option("", "-vectorize-memory-check-threshold=5000")
    out: dict[str, Any] = {"runs": []}
    for side in (32,) if quick else (32, 100):
        for points in (1, 2):
            made = run(side, points, rounds=3)
            out["runs"].append({"side": side, "points": points, **made})
    code = lanes.inspect_asm(lanes.signatures[0])
    out["packed"] = code.count("vmulpd")
    return out


def report(quick: bool = False) -> str:
    """The table: each scene's times by both ways, with LLVM's limits as they are and raised."""
    if numba is None:
        return "lanes: needs numba (the fast extra: pip install -e '.[fast]')"
    found = {}
    for raised in (False, True):
        probe = (
            "import json, sys; from demos.bench import lanes; "
            f"print(json.dumps(lanes.measure({quick}, {raised})))"
        )
        done = subprocess.run(
            [sys.executable, "-c", probe], capture_output=True, text=True, check=True
        )
        found[raised] = json.loads(done.stdout.strip().splitlines()[-1])
    lines = [
        f"lanes: a model of the soft step's contact rows (Box2D's soft contact, {SWEEPS} sweeps "
        "a call), in colour order one row at a time (scalar) and a colour's rows gathered into "
        "a table and solved side by side (lanes); time a call, the least of three rounds",
        "  contacts  points  colours    scalar    lanes (LLVM's limits / raised)    "
        "scalar / lanes   same bits",
    ]
    for plain, wide in zip(found[False]["runs"], found[True]["runs"], strict=True):
        lines.append(
            f"  {plain['contacts']:8,d}  {plain['points']:6d}  {plain['colours']:7d}  "
            f"{1e6 * plain['scalar']:7.0f} us  {1e6 * plain['lanes']:7.0f} us / "
            f"{1e6 * wide['lanes']:6.0f} us        {plain['scalar'] / plain['lanes']:5.2f}x / "
            f"{wide['scalar'] / wide['lanes']:5.2f}x   {plain['same'] and wide['same']}"
        )
    lines.append(
        f"  packed multiplies (vmulpd) in the rows' loop: {found[False]['packed']} with LLVM's "
        f"limits, {found[True]['packed']} raised (0: not vectorised)"
    )
    return "\n".join(lines)
