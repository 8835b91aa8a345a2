"""The soft step's solver: bodies, contacts and joints solved together in substeps, Box2D v3's way.

A game's scene (a pile of crates, a platformer, a pinball table) holds many contacts that lean
on one another, and joints that hold bodies together. Box2D v3 (Catto, "Solver2D", 2024;
``solver.c``, ``contact_solver.c``, ``revolute_joint.c``, ``weld_joint.c``) solves them all
in one loop: the step of dt is taken in ``substeps`` parts of h = dt / substeps, each part

1. integrating velocities: v += a h, omega += alpha h (the forces' accelerations, held over
   the step);
2. warm starting: every row's impulse of the part before (the last step's, at first) is
   applied again, so a settled pile starts solved (a contact that has none is made one in
   its first part: below);
3. solving with bias: each row pushes its bodies by an impulse so that their relative
   velocity along it meets a target: a contact still open (gap s > 0) may close by s in this
   part, no more (a speculative contact: a box falling on a floor stops on it, whatever its
   speed); one overlapping is pushed apart by a soft spring (below), at most ``PUSH_SPEED``;
4. integrating positions: x += (v - dv_held / 2) h, angle likewise (below);
5. relaxing: the same solve without the spring's push, so that the push moves positions and
   leaves no speed behind; and friction (Coulomb: |lam_t| <= mu lam_n), against the slip less
   the surfaces' own speed along themselves (a conveyor);

then, once, restitution for the contact points that closed faster than ``THRESHOLD`` and
touched: the normal speed they part at is e times the one they met at (below).

**Free flight is exact.** A body in no row (no contact within reach, no joint) is moved by
nothing but its acceleration a, held over the step, and the closed form of that motion is
x0 + v0 dt + a dt^2 / 2, v0 + a dt (and likewise its angle). The parts above give
x0 + v0 dt + a dt^2 (n + 1) / (2 n) for n parts, g dt^2 / (2 n) too far a step (Box2D's; a
ball falling 0.5 s at 60 Hz and 4 parts ends 1 cm low), so such a body takes the closed form
instead: a ball thrown in a game's World flies the lesson's parabola to rounding until a
contact comes within reach.

**Positions exact for held forces.** In a part, v1 = v0 + a h + dv_c, a the forces' held
acceleration and dv_c what the rows' impulses give. Box2D moves the body by v1 h, which for
a held acceleration is x0 + v0 h + a h^2, a h^2 / 2 too far each part: a box sliding to a
stop under friction's held mu g stops v0 h / 2 short (1 cm from 5 m/s: 0.41%), one sliding
down a slope goes a h t / 2 too far (+0.42% after 1 s). The closed form of a held
acceleration is x0 + v0 h + a h^2 / 2 = x0 + (v1 - a h / 2) h, so a body is moved by
(v1 - dv_held / 2) h, dv_held the part of v1 - v0 that is held over the part: a h, and the
impulses of the contacts' warm start (the last part's: a force held, if the contact keeps
it) as far as the solve with bias kept them (a point's normal impulse the lesser of its warm
start and its impulse after that solve, so that an impact's impulse, which the solve takes
back, is not held; its friction while it keeps its sign, the lesser likewise). A body at rest
has dv_held = 0 (its weight and its contacts' push cancel) and moves as Box2D's; a box
sliding to a stop, or down a slope, moves the closed form of its held forces (it stops 0.008%
short; it slides 0.002% long, a h^2 / 2 of its first part, below). The solve's own
corrections (a speculative contact's stop, the soft push) are impulses at the part's start,
moved by a whole h, as Box2D's. Two bodies move by v1 h, as Box2D's: one held by a joint (a
joint's warm start is not held so simply: a pendulum's direction turns), and, in its first
part, one a fresh contact (below) pushed (which of those impulses are held is not known
yet). And a held change whose linear part is faster than ``THRESHOLD`` (m/s in a part:
240 m/s^2 at 1/240 s, an impact's, not a load's) is at most the part's whole change v1 - v0,
and of its sign (each of x, y and the angle): where the rows take back more than such held
impulses give (an impact's warm start taken for a load, beside a fresh push) the half of it
is no motion. Unbounded, a 1 kg polygon struck by a 6 kg disc at 86 m/s against a wall had
the wall's last impulse held (-58.8 m/s a part) and the disc's fresh push not, and was moved
0.12 m into the wall in a step where its rows stopped it at 0.23 m/s (the shapes fuzz; now
1.2 mm). A load's change is left as it is: bounded too, the pyramid of 210 boxes moved
5.08 mm where it moves 4.98, and 50 boxes tumbling at 25 degrees a second went 48 mm into
one another where they go 42.

**A fresh contact.** A contact with no impulse to start from (new in the step, or open in
the last) has its first part solved from nothing, and one relax does not solve a face's two
points together: the first point's friction, at the lever r.n below the centre, turns the
body so that both points stop slipping where the centre does not (a unit box keeps
1 - m_t / m = 0.6 of its slip, m_t = 1 / (w + i (r.n)^2) the point's tangent mass), and the
normal rows take the turn out only in the next part. A box let go on a 20 degree slope
crept 0.17 mm so, and one on a 40 degree slope kept a third too little friction in its
first part (+5 mm after 1 s). So such a contact's rows are relaxed (rigid, no push, with
friction: the relax's sweep) after the warm start of its first part, each sweep leaving the
slip that factor of itself: the warm start it lacked (its creep then 3e-11 m). The sweeps
stop after ``FIRST_SWEEPS``, or at the first that changes no impulse (the next would change
none); a contact whose solve changed none is solved again only once a body of it is pushed;
a contact whose rows do not move each other (one point, and no lever that couples its
normal and friction: K_nt = sum of i (r x n)(r . n) = 0, as a disc's point on the line of
centres) is solved by the first sweep and not swept again (the pit of 1,000 balls forming
took 1.7 ms a step with every sweep over all, 0.94 ms so; what its neighbours' pushes change
is left to the substeps, as Box2D leaves all of it);
and only a contact that may touch in that part is swept (``FIRST_REACH``): the open
neighbours of a settled pile, which never push, and the far ones of a tumbling heap cost the
step nothing.

**Restitution.** Box2D bounces a point that pushed in the step at e times its normal speed
vn0 at the step's start. A box falling onto a floor meets it faster than that, by what
gravity gave it over the gap s it had then: the closed form of held accelerations, vn^2 =
vn0^2 - 2 a_n s (a_n the points' relative normal acceleration, a + alpha x r on each), is
the speed it meets at, and it parts at e times that (a box dropped 2 m at e = 0.5 bounced
to 0.4919 and 0.1104 m against h e^2n = 0.5 and 0.125 m; now 0.49999 and 0.12499). And a
point bounces only where it touched: a push in a solve before the positions move (a
speculative stop on the surface) or on a point closed. The relax's push on a point still
open (it may close only by its gap in the next part) is no touch: it slows the point before
it meets, and the next part's solve with bias stops it on the surface, a touch. In a step's
last part a point that has not touched in the step is given no such push: it is left open
to the next step, whose first part stops it so (its speed then the one it meets at). Given,
the push bounced a box where it hung, 4 mm up (Box2D's rule; its third apex 0.0219 m against
0.03125); counted as no touch and carried as the next step's warm start, it turned the body
it met with no bounce: a box at 10 m/s meeting a disc at -10 m/s 0.1 m above its centre line
from 0.35 m apart (they meet just after a step) ended at -1.46 m/s and 15.3 rad/s against
the closed form's -7.857 m/s and 42.9 rad/s (now to rounding; apexes 0.500009, 0.125007 and
0.031252 m). A point open at the step's start with a warm start (one that touched in the
last step and opened) has that warm start's change of vn taken off vn0 before the closed
form above.

**Rows.** A contact point has anchors r_A, r_B (the point less each body's position) and a
normal n from A to B. Its separation as the bodies move in the step is, the normal held
fixed,

    s = s0 + n.(dp_B - dp_A) + (r_B x n) sin dq_B - (r_A x n) sin dq_A,

dp and dq the moves of position and angle since the step began: each anchor turned with its
body across the normal, not along it. Box2D's "s = s0 + dot(cB + rB - cA - rA, n)" turns the
anchors whole, and so counts (n.r)(1 - cos dq) of each as the surfaces parting; but the
nearest point of a round shape does not turn with it, and a polygon's corner that turns away
gives way to its neighbour. A disc of 0.5 m spinning at 58 rad/s turns a quarter radian a
part: landing so at 15 m/s on a floor it sank 0.10 to 0.12 m into it (the shapes fuzz found
it 0.1003 m in a wall); now it does not sink. The relative normal speed at
the point is vn = n.(v_B + omega_B x r_B - v_A - omega_A x r_A) (in 2D, omega x r =
omega (-r_y, r_x)), and an impulse lam along n changes it by lam / m_n with

    1 / m_n = w_A + w_B + i_A (r_A x n)^2 + i_B (r_B x n)^2        (w = 1/m, i = 1/I).

A disc riding a face that turns (a ball on a bat) slides along the face as it turns, and a box's
corner swings across a face that turns under it (a tumbler's pile), which rows fixed at the
step's start do not follow: such a row's normal, separation, anchors and masses are taken again
after each substep's positions move (engine.dynamics.turning_faces, ``cface``).

**Soft constraints** (Box2D's b2MakeSoft): a spring of frequency f and damping ratio zeta on
the error C, with omega = 2 pi f, a1 = 2 zeta + h omega, a2 = h omega a1, a3 = 1 / (1 + a2),
gives the impulse

    d = -m_n (s_m (vn + bias_rate C)) - s_i lam,   bias_rate = omega / a1,
    s_m = a2 a3 (mass scale),   s_i = a3 (impulse scale),

an implicit (backward Euler) step of the damped spring that stays stable at any stiffness.
Contacts use ``CONTACT_HERTZ`` (at most an eighth of the substep rate; twice as stiff against
what does not move: the floor does not give) and a damping ratio of 10; joints 60 Hz (at most
a quarter of the substep rate) and 2.

**The floor holds its load.** In the steady state of a contact under a held load (lam the
same each part, vn = 0 after the warm start) the solve must add nothing, d = 0, which the
spring meets at C = -s_i lam / (m_n s_m bias_rate) = -lam / (m_n h omega^2): a spring of
stiffness m_n omega^2 that gives under the load W = lam / h by W / (m_n omega^2) (a unit box
on a floor at 60 Hz, 69 um; on a 20 degree slope 64.86 um, which counted as its moving in
its first step). Against what does not move, then, the spring gives only on the change of
its load: the give -s_i lam is -s_i (lam - held), held the point's warm start (the load it
carried through the last part) less what of it only parts the surfaces again, m_n vn where
the warm start left them parting (an impact's impulse re-applied, which the solve must take
back at once, as Box2D's does: held, a box landing on a floor would leave it again at
(1 - s_m) of its speed). The steady state is then C = 0: a box on a floor or a slope keeps
its height to rounding, one dropped on it from 30 m does not rise after it lands, and the
floor under a box hit by another sinks 4 um (it sank 1.1 mm).

**A pile holds its load too, slowly.** Between two bodies that spring gives as Box2D's, by
W / (m_n omega^2) under a load W: a column of N unit boxes sags so by N (N - 1) g / omega^2
in all, 105 mm for 20 (Box2D v3's tower: 133 mm). Held at once as on the floor (``keep`` the
last part's load), the column rang and did not settle: the load a contact holds is then an
integral of its give, and a chain of springs with an integral in each is of third order. In
a column of N bodies of mass m each mode is m s^3 + L c s^2 + L k s + L a k = 0 (k = m_n
omega^2 and c = 2 zeta m_n omega the spring's stiffness and damping, L the mode's eigenvalue
of the chain, a the rate (1/s) at which the held load follows the load), stable
(Routh-Hurwitz) while a < L c / m, and the slowest mode of a column standing on the floor
has L = (pi / 2N)^2. So each point of a face contact holds ``chold``, which closes a share
alpha = a dt of its gap to ``HOLD_PART`` of the point's load a step, the share set by how
deep in a column the point can be, N = r / 2 for its load r = lam / (m_n g h) (lam the
point's impulse a part, g the larger of its two bodies' held accelerations): alpha =
min(``HOLD_SHARE``, zeta omega dt pi^2 / (``HOLD_MARGIN`` r^2)), a an eighth of the slowest
mode's bound or less. The spring gives -s_i (lam - keep) with keep the held load, at most
the last part's (a load taken away is let go at once). What was tried and measured:

* holding all of the load (``HOLD_PART`` 1) leaves a pile's forces free where a body has
  more contacts than it needs, as a rigid pile's are: they wandered, and a pit of 1,000 balls
  slipped in avalanches every few seconds; 95% leaves the spring 5% of its give, which
  decides them;
* a contact of one point (a disc's, a corner's) holds nothing: held, a forming pit of 1,000
  balls (every contact one point, each ball free to roll off its seat) rose 7 cm as its
  contacts took their loads, popped single balls at 0.15 m/s as they did, and slept 0.6 to
  2.3 s later; its settling is Box2D's, the same bits as before;
* a share of 0.05 a step rang at 1 m in a column of 80 unbounded by r, and, bounded, swayed
  the top half of the pyramid of 820 boxes at 7 cm/s for 9 s; 0.02 keeps a column of up to
  62 bodies stable whatever its load, and the pyramid sleeps 16.7 mm from where it was put
  (202 mm before).

A column then settles to 5% of Box2D's sag, 0.05 N (N - 1) g / omega^2: 5.2459 mm for 20
boxes within 20 s, 21.5358 mm for 40 within 60 s, to 1e-7 m (tests/test_soft_solver.py).
Without gravity (g = 0) no load is held: nothing tells a column's depth. A pile rises back
so at a few cm/s, slower than Box2D's sleep speed: a body is still only while its held loads
have at most engine.pipeline.game_sleep's ``RISE`` left to lift it (``brise``, the most of
(``HOLD_PART`` lam - ``chold``) / (m_n h omega^2) over its points). The pyramid of 210 boxes
slept at 0.82 s, 26.9 mm down, and now at 4.3 s, 5.5 mm; that of 820 at 6.4 s (Box2D's soft
contacts: 2.3 s, with their give).

**A hinge** (Box2D's revolute joint) holds the anchors together: C = (c_B + r_B) - (c_A + r_A),
a 2 x 2 system K lam = -(Cdot + bias C) with

    K = [[w_A + w_B + i_A r_Ay^2 + i_B r_By^2,  -i_A r_Ax r_Ay - i_B r_Bx r_By],
         [-i_A r_Ax r_Ay - i_B r_Bx r_By,        w_A + w_B + i_A r_Ax^2 + i_B r_Bx^2]],

solved by Cramer's rule; its angle (angle_B - angle_A less the reference) takes a motor row
(|lam| <= max torque h) and two limit rows (speculative, as contacts). **A weld** adds an
angular row (the angle held) to the hinge's point rows, soft with its own frequency if given.
**A distance** (Box2D's distance joint: a rod, a cable) holds the anchors' distance
L = |d|, d = (c_B + r_B) - (c_A + r_A), along the axis u = d / L taken again at every solve:
a rod's row C = L - length (either sign, soft as a joint), a cable's C = length - L >= 0 (it
only pulls; speculative while slack, as a contact), with the axial mass
1 / (w_A + w_B + i_A (r_A x u)^2 + i_B (r_B x u)^2). A cable that snapped taut faster than
``THRESHOLD`` parts its ends again at its restitution times the speed it met them at, in the
restitution pass, as a contact does.
**Limits** (Box2D's joint limits) are one-sided rows C >= 0: speculative while open (C > 0:
the row may close by C in the substep, bias C / h, no more, as a contact), soft (the joints'
spring) once closed, in the solve with bias, and rigid in the relax; the impulse summed over
the substep is kept >= 0 (``_limit``). A hinge's angle limits, a cable's most length and a
slide joint's least, a groove's ends and a ratchet's notch are such rows.
**A groove** (pymunk's GrooveJoint; Box2D's prismatic joint without its angular row, spring
and motor) keeps B's anchor on A's segment from A's anchor along the unit axis u (turned as A
turns) for ``jupper`` m. With d = (c_B + r_B) - (c_A + r_A) the translation is t = u.d and
the error across C = n.d, n = (-u_y, u_x). As u turns with A (du/dt = omega_A x u),

    dt/dt = u.(v_B - v_A) + (r_B x u) omega_B - ((d + r_A) x u) omega_A,

the relative velocity of B's anchor and the point of A under it, along u: each row acts on A
at the lever d + r_A (B's anchor) and on B at r_B, its mass 1 / (w_A + w_B + i_A ((d + r_A) x
u)^2 + i_B (r_B x u)^2) (n for u across). The ends are limits, t >= 0 and jupper - t >= 0;
across, a soft equality row C = n.d = 0. B turns freely (pymunk's; Box2D's holds the angle).
**A gear** (pymunk's GearJoint) holds C = r angle_B - angle_A - phase (r the ratio): the
Jacobian (-1, r) on (omega_A, omega_B), the mass 1 / (i_A + r^2 i_B), an impulse lam turning
A by -i_A lam and B by r i_B lam; a soft equality row (Chipmunk's jAcc is r lam).
**An angle's rows alone** (ROTARY: pymunk's RotaryLimitJoint, RatchetJoint, SimpleMotor) are
the hinge's motor and limit rows without its point: a rotary limit both limits on angle_B -
angle_A, a ratchet one of them at its notch (moved on notch by notch before each step,
Chipmunk's way: engine.dynamics.constraints), a motor the motor row.
**A spring** (pymunk's DampedSpring, k the stiffness, c the damping) is a force, not a row to
meet: once a substep, before the rows, it gives the impulse -k (L - rest) h along u (explicit,
from the length at the substep's start, as pymunk's), then its damper takes the speed along u
to exp(-c w h) of itself (w the inverse axial mass: the damper's exact flow over h, stable at
any c); a rotary spring the same on the angle angle_B - angle_A (w = i_A + i_B). The stiffness
is explicit, so it holds while omega h < 2 (omega^2 = k w; at 4 substeps of 1/60 s, k w up to
230,000 s^-2).

**pymunk's bounds** (a constraint's rows, engine.dynamics.constraints: ``jmotor``'s bit 2 set).
Chipmunk keeps a row's impulse summed over its step within max_force dt; here a row's impulse
summed over a substep (what it gives in it: the warm start and what each solve adds, the
``jpa`` ... ``jmi`` carried) is kept within max_force h, so that it gives at most max_force
(N, N m) at any time and max_force dt over the step; a groove's rows along it and across it
are bounded as one vector (Chipmunk's ``cpvclamp``), scaled back to max_force h where they
exceed it. The speed a row corrects its error at, the push s_m bias_rate C above (or beta C
below), is at most max_bias (m/s, rad/s; a groove's as one vector again); a speculative row's
"may close by C" is no correction, and is not bounded. Where error_bias (the share of an
error left after 1 s) is set, a row's push in the solve with bias is Chipmunk's, not the
joints' spring: rigid (s_m = 1, s_i = 0) with bias_rate beta = (1 - error_bias^h) / h. Each
substep the push moves the bodies by beta C h and the relax takes its speed away, so an error
left to itself is error_bias^h of itself after a substep, error_bias after 1 s, whatever the
step. (The joints' spring leaves 1 - h^2 omega^2 / (1 + 2 zeta h omega + h^2 omega^2) of it a
substep, so some stiffness would give any error_bias too; but a spring gives under a steady
load, by F / (m omega^2), where pymunk's rows do not. Beta's row is the spring's limit as its
stiffness and damping grow with omega / (2 zeta + h omega) = beta held.)

**One loop, two paths.** ``solve`` is written as the loop it is, over flat arrays. On the fast
path numba compiles it (engine.kernels); on the numpy path it runs as plain Python on lists,
which at a game's size (tens of rows) is faster than numpy's calls a colour; the two give the
same numbers to the last bit (the same operations in the same order on IEEE doubles).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .. import kernels
from ..kernels import floats
from .turning_faces import (
    FACE_A,
    FACE_NUMBERS,
    ROUND,
    STILL,
    face_gap,
    face_start,
    round_gap,
    round_start,
)  # fmt: skip

__all__ = [
    "SUBSTEPS",
    "CONTACT_HERTZ",
    "CONTACT_DAMPING",
    "JOINT_HERTZ",
    "JOINT_DAMPING",
    "PUSH_SPEED",
    "THRESHOLD",
    "HINGE",
    "WELD",
    "MOUSE",
    "DISTANCE",
    "GROOVE",
    "GEAR",
    "ROTARY",
    "SPRING",
    "ROTARY_SPRING",
    "solve",
]

#: Parts a step is taken in (Box2D v3's default: 4).
SUBSTEPS = 4
#: The contacts' stiffness (Hz), at most an eighth of the substep rate (Box2D v3: 30).
CONTACT_HERTZ = 30.0
#: The contacts' damping ratio (Box2D v3: 10, heavily over-damped: no bounce from the push).
CONTACT_DAMPING = 10.0
#: The joints' stiffness (Hz), at most a quarter of the substep rate (Box2D v3: 60).
JOINT_HERTZ = 60.0
#: The joints' damping ratio (Box2D v3: 2).
JOINT_DAMPING = 2.0
#: The fastest an overlap is pushed apart (m/s; Box2D v3's contactSpeed: 3).
PUSH_SPEED = 3.0
#: Contacts closing slower than this (m/s) do not bounce (Box2D v3: 1).
THRESHOLD = 1.0
#: The share of a point's load between bodies that it holds (module doc, "A pile holds its
#: load"): a column gives by the rest, 5% of Box2D's give.
HOLD_PART = 0.95
#: The most of the gap between a point's held load and its target closed in a step (the
#: same): stable so in any column of up to 62 bodies at 60 Hz, whatever its load.
HOLD_SHARE = 0.02
#: How far under the slowest mode's bound the held load follows the load (the same).
HOLD_MARGIN = 8.0
#: Relax sweeps that make a fresh contact's warm start in its first part (module doc): each
#: leaves a unit box on a face 0.6 of its slip, 30 leave 0.6^30 = 2e-7 of it.
FIRST_SWEEPS = 30
#: A fresh contact is swept (``FIRST_SWEEPS``) where a point's gap at the step's start,
#: closed for a substep at the speed it closes at then, is at most this (m, Box2D's linear
#: slop); the others push in no sweep, but where the sweeps turn a body on to them 1.2 m/s
#: faster (this over a substep of 1/240 s).
FIRST_REACH = 0.005
#: Joint kinds, by code: a hinge, a weld, a mouse joint (a point pulled to a target by a
#: spring of its own frequency and damping, its force bounded), a distance between two anchors
#: (a Rod held at its length, a Cable at most its length, a SlideJoint between the two), a
#: groove (pymunk's GrooveJoint), a gear (GearJoint), an angle's limits and motor alone
#: (RotaryLimitJoint, RatchetJoint, SimpleMotor), a spring between two anchors (pymunk's
#: DampedSpring) and one between two angles (DampedRotarySpring). The springs come last: a
#: kind >= SPRING is a force, not a row.
HINGE, WELD, MOUSE, DISTANCE, GROOVE, GEAR, ROTARY, SPRING, ROTARY_SPRING = range(9)


@kernels.helper
def _within(held: float, change: float) -> float:
    """An impact's held part of a substep's change of velocity, at most the change itself and
    of its sign (module doc, "Positions exact for held forces")."""
    if held * change <= 0.0:
        return 0.0
    if held > 0.0:
        return min(held, change)
    return max(held, change)


@kernels.helper
def _point_masses(
    ma: float, ia: float, mb: float, ib: float, rax: float, ray: float, rbx: float, rby: float,
    nx: float, ny: float,
) -> tuple[float, float]:  # fmt: skip
    """A contact point's masses (kg) along the normal (nx, ny) and the tangent t = (-n_y, n_x),
    1 / (w_A + w_B + i_A (r_A x d)^2 + i_B (r_B x d)^2) (0 where nothing moves), of the inverse
    masses and moments ``ma``, ``ia``, ``mb``, ``ib`` and the anchors r_A, r_B (m)."""
    rna = rax * ny - ray * nx
    rnb = rbx * ny - rby * nx
    kn = ma + mb + ia * rna * rna + ib * rnb * rnb
    # r x t = r_x n_x + r_y n_y.
    rta = rax * nx + ray * ny
    rtb = rbx * nx + rby * ny
    kt = ma + mb + ia * rta * rta + ib * rtb * rtb
    return 1.0 / kn if kn > 0.0 else 0.0, 1.0 / kt if kt > 0.0 else 0.0


@kernels.helper
def _block(
    ma: float, ia: float, mb: float, ib: float, nx: float, ny: float, rax1: float, ray1: float,
    rbx1: float, rby1: float, rax2: float, ray2: float, rbx2: float, rby2: float,
) -> tuple[float, float, float, float]:  # fmt: skip
    """A two-point manifold's 2 x 2 normal block (``solve``'s prepare): k11, k12, k22 and 1.0
    where it is well conditioned (k11^2 < 1000 det K), else zeros: inverse masses and moments
    ``ma``, ``ia``, ``mb``, ``ib``, the normal, and each point's anchors on A and on B (m)."""
    a1 = rax1 * ny - ray1 * nx
    a2 = rax2 * ny - ray2 * nx
    b1 = rbx1 * ny - rby1 * nx
    b2 = rbx2 * ny - rby2 * nx
    k11 = ma + mb + ia * a1 * a1 + ib * b1 * b1
    k22 = ma + mb + ia * a2 * a2 + ib * b2 * b2
    k12 = ma + mb + ia * a1 * a2 + ib * b1 * b2
    if k11 > 0.0 and k22 > 0.0 and k11 * k11 < 1000.0 * (k11 * k22 - k12 * k12):
        return k11, k12, k22, 1.0
    return 0.0, 0.0, 0.0, 0.0


@kernels.helper
def _relative(
    bvx: Any, bvy: Any, bw: Any, a: int, b: int, rax: float, ray: float, rbx: float, rby: float
) -> tuple[float, float]:
    """B's point's velocity less A's (m/s), v + omega x r = (v_x - omega r_y, v_y + omega r_x),
    of the bodies' velocities ``bvx``, ``bvy``, ``bw`` (``solve``'s)."""
    return (bvx[b] - bw[b] * rby) - (bvx[a] - bw[a] * ray), (bvy[b] + bw[b] * rbx) - (
        bvy[a] + bw[a] * rax
    )


@kernels.helper
def _apply(
    bvx: Any, bvy: Any, bw: Any, a: int, b: int, ma: float, ia: float, mb: float, ib: float,
    px: float, py: float, rax: float, ray: float, rbx: float, rby: float,
) -> None:  # fmt: skip
    """The impulse (px, py) (N s) at the anchors: -P on A at r_A, +P on B at r_B, in the
    bodies' velocities ``bvx``, ``bvy``, ``bw`` (``solve``'s; ``ma`` ... ``ib`` their inverse
    masses and moments)."""
    bvx[a] -= ma * px
    bvy[a] -= ma * py
    bw[a] -= ia * (rax * py - ray * px)
    bvx[b] += mb * px
    bvy[b] += mb * py
    bw[b] += ib * (rbx * py - rby * px)


@kernels.helper
def _soft(
    jbeta: Any, jsoft: tuple[float, float, float], k: int, bias: bool
) -> tuple[float, float, float]:
    """Joint k's equality row's (bias rate 1/s, mass scale, impulse scale): in the solve with
    bias the joints' spring ``jsoft``, or where its error_bias is set (``jbeta[k]`` >= 0)
    Chipmunk's rigid push (module doc); rigid with no push in the relax."""
    if not bias:
        return 0.0, 1.0, 0.0
    if jbeta[k] >= 0.0:
        return jbeta[k], 1.0, 0.0
    return jsoft


@kernels.helper
def _bounded(rate: float, err: float, mscale: float, top: float) -> float:
    """The bias rate err of a row (m/s or rad/s), kept so that the speed it corrects its error
    at, mscale rate err, is at most ``top`` (max_bias; inf: as it is)."""
    v = rate * err
    most = top / mscale
    if v > most:
        return most
    if v < -most:
        return -most
    return v


@kernels.helper
def _limit(
    jbeta: Any, jsoft: tuple[float, float, float], inv_h: float, k: int, err: float,
    cdot: float, mass: float, old: float, bias: bool, top: float, cap: float,
) -> float:  # fmt: skip
    """Joint k's limit row (module doc) solved once: C = err >= 0, dC/dt = cdot, of
    ``mass``; its impulse of the substep so far ``old`` made new (>= 0: a limit only
    pushes; at most ``cap``, max_force h), its correction at most ``top`` fast (``inv_h``
    1/s the substep's rate; ``jbeta``, ``jsoft``: ``_soft``'s)."""
    rate, mscale, iscale = 0.0, 1.0, 0.0
    v = 0.0
    if err > 0.0:
        v = inv_h * err  # speculative: may close by err in the substep, no more
    elif bias:
        rate, mscale, iscale = _soft(jbeta, jsoft, k, bias)
        v = _bounded(rate, err, mscale, top)
    d = -mscale * mass * (cdot + v) - iscale * old
    return min(max(old + d, 0.0), cap)


@kernels.helper
def _axis(
    dx: Any, dy: Any, cx0: Any, cy0: Any, k: int, a: int, b: int, rax: float, ray: float,
    rbx: float, rby: float,
) -> tuple[float, float, float]:  # fmt: skip
    """Distance k's unit axis u from A's anchor to B's, and its length L (m), now: the
    bodies moved by (``dx``, ``dy``) since the start, the anchors turned to (rax ... rby),
    the axis at the start (``cx0``, ``cy0``) less the anchors then."""
    ex = (dx[b] - dx[a]) + (rbx - rax) + cx0[k]
    ey = (dy[b] - dy[a]) + (rby - ray) + cy0[k]
    length = math.sqrt(ex * ex + ey * ey)
    if length > 0.0:
        return ex / length, ey / length, length
    return 0.0, 0.0, 0.0


@kernels.helper
def _axial_mass(
    bim: Any, bii: Any, a: int, b: int, ux: float, uy: float, rax: float, ray: float,
    rbx: float, rby: float,
) -> float:  # fmt: skip
    """1 / (w_A + w_B + i_A (r_A x u)^2 + i_B (r_B x u)^2) (kg), 0 where nothing can move
    (``bim``, ``bii`` the bodies' inverse masses and moments)."""
    ca_ = rax * uy - ray * ux
    cb_ = rbx * uy - rby * ux
    kk = bim[a] + bim[b] + bii[a] * ca_ * ca_ + bii[b] * cb_ * cb_
    return 1.0 / kk if kk > 0.0 else 0.0


def _sample() -> tuple[Any, ...]:
    """The smallest call of ``solve``: a unit box resting on the static body, held to the
    world by a hinge at its corner."""
    f = np.zeros
    body = [np.array([0.0, 0.0]), np.array([0.5, 0.0]), f(2)]  # x, y, angle
    vel = [f(2), f(2), f(2)]
    mass = [np.array([1.0, 0.0]), np.array([6.0, 0.0])]
    acc = [np.array([0.0, 0.0]), np.array([-9.81, 0.0]), f(2)]
    i1 = np.zeros(1, dtype=np.int64)
    contacts = [
        i1 + 1, i1.copy(), np.array([0.0]), np.array([1.0]), i1 + 2,
        f(2), np.array([-0.5, -0.5]), np.array([0.5, -0.5]), np.array([0.0, 0.0]), f(2),
        np.array([0.6]), f(1), f(1), f(2), f(2), f(2), f(2), f(2),
    ]  # fmt: skip
    joints = [
        i1.copy(), i1 + 1, i1.copy(), np.array([0.5]), np.array([0.5]), np.array([0.5]),
        np.array([0.5]), f(1), f(1), f(1), i1.copy(), f(1), f(1), i1.copy(), f(1), f(1),
        f(1), f(1), f(1), f(1), f(1), f(1),
    ]  # fmt: skip
    faces = [i1.copy(), f(FACE_NUMBERS)]
    return (*body, *vel, *mass, *acc, *contacts, *joints, *faces, 1.0 / 60.0, 4, 30.0, 10.0,
            60.0, 2.0, 3.0, 1.0, FIRST_REACH, f(2))  # fmt: skip


@kernels.loop(sample=_sample)
def solve(
    bx: Any, by: Any, bq: Any,
    bvx: Any, bvy: Any, bw: Any,
    bim: Any, bii: Any,
    bax: Any, bay: Any, balpha: Any,
    ca: Any, cb: Any, cnx: Any, cny: Any, ccount: Any,
    crax: Any, cray: Any, crbx: Any, crby: Any, csep: Any,
    cfric: Any, crest: Any, cspeed: Any,
    cln: Any, clt: Any, chold: Any, ctotal: Any, cmax: Any,
    jkind: Any, ja: Any, jb: Any, jlax: Any, jlay: Any, jlbx: Any, jlby: Any, jref: Any,
    jhertz: Any, jdamp: Any,
    jlimit: Any, jlower: Any, jupper: Any,
    jmotor: Any, jspeed: Any, jmaxtorque: Any,
    jpx: Any, jpy: Any, jpa: Any, jlo: Any, jhi: Any, jmi: Any,
    cface: Any, cround: Any,
    dt: float, substeps: int, contact_hertz: float, contact_damping: float,
    joint_hertz: float, joint_damping: float, push: float, threshold: float, reach: float,
    brise: Any,
) -> None:  # fmt: skip
    """One step of ``dt`` (s) of every body, contact and joint (module doc), in place.

    Bodies (nb each; the last one is the static body, of zero inverse mass at the origin):
    ``bx``, ``by``, ``bq`` position (m) and angle (rad), at the step's start in and its end
    out; ``bvx``, ``bvy``, ``bw`` velocity (m/s, rad/s), likewise; ``bim``, ``bii`` inverse
    mass (1/kg) and inverse moment (1/(kg m^2)), 0 for what does not move or turn; ``bax``,
    ``bay``, ``balpha`` the acceleration held over the step (m/s^2, rad/s^2).

    Contacts (nc manifolds of 1 or 2 points; a point's arrays are 2 nc long, point j of
    manifold k at 2 k + j): bodies ``ca``, ``cb``, the unit normal ``cnx``, ``cny`` from A to
    B, ``ccount`` points, anchors ``crax``, ``cray``, ``crbx``, ``crby`` (m, the point less
    each body's position at the step's start), ``csep`` the separation then (m, < 0
    overlapping); friction ``cfric``, restitution ``crest``, ``cspeed`` the speed (m/s) the
    surfaces move along the tangent (-n_y, n_x) of themselves, B's less A's (a conveyor);
    ``cln``, ``clt`` the normal and tangent impulses (N s a substep): the last step's in
    (warm start), this step's out; ``chold`` the normal load a point holds (N s a substep,
    in and out; module doc, "A pile holds its load"); ``ctotal`` out: the normal impulse
    over the whole step; ``cmax`` out: the largest a substep applied at a touch
    (``contact``).

    Joints (nj): ``jkind`` (HINGE ... ROTARY_SPRING), bodies ``ja``, ``jb`` and their local
    anchors (m, in each body's frame about its position; the static body's in world
    coordinates: a mouse joint's target), ``jref`` angle_B - angle_A at rest (rad); a weld's
    or mouse joint's ``jhertz`` and ``jdamp`` (a weld's 0 Hz: rigid); which limits are on
    (``jlimit``: 1 the lower, 2 the upper, 3 both) and where (``jlower``, ``jupper``): a
    hinge's or ROTARY's on angle_B - angle_A - jref (rad), a distance's on its length (m:
    equal, a rod, held both ways), a groove's on B's anchor along it (m: 0 and its length; A's
    anchor its start, ``jref`` its direction in A's frame, rad); a motor (``jmotor``'s bit 1
    on, ``jspeed`` rad/s, ``jmaxtorque`` N m); pymunk's bounds on a constraint's rows
    (``jmotor``'s bit 2 on; module doc): its largest force ``jmaxtorque`` (N, N m; a motor's
    torque is its force), its largest bias speed ``jdamp`` (m/s, rad/s) and its error_bias
    ``jhertz`` (the share of an error left after 1 s; < 0: the joints' spring); a mouse
    joint's angular damping (``jspeed``, 1/s) and largest force (``jmaxtorque``, N); a
    cable's restitution (``jspeed``); a gear's phase (``jref``, rad) and ratio (``jspeed``);
    impulses (N s, N m s a substep) in and out: ``jpx``, ``jpy`` the point's, ``jpa`` a weld's
    angle's (a rod's along u, a groove's across it, a gear's), ``jlo``, ``jhi`` the limits' (a
    cable's, pulling, in ``jhi``), ``jmi`` the motor's. A spring's rest length or angle is
    ``jlower`` (m, rad), its stiffness ``jhertz`` (N/m, N m/rad), its damping ``jdamp`` (N s/m,
    N m s/rad); its ``jpa`` out is the impulse it gave over the whole step (along u, or on B's
    angle), and is not warm started.

    ``cface``, ``cround`` (nc; FACE_NUMBERS nc): each contact's face that turns (engine.dynamics.
    turning_faces' ``face_rows``: 0, which body's face its normal turns with, or ROUND or
    SEGMENT: the line from a disc to a static shape's core) and its numbers (that module's
    FACE_NUMBERS: the rounding radius (m) of the body whose point meets it, the static shape's,
    and a SEGMENT's ends): such a row is taken again as its bodies move (that module's
    doc), and given back as it was at the end.

    The step's rates and lengths: ``contact_hertz``, ``contact_damping``, ``joint_hertz``,
    ``joint_damping`` the springs' (Hz, ratios); ``push`` (m/s, ``PUSH_SPEED``) the fastest an
    overlap is pushed apart; ``threshold`` (m/s, ``THRESHOLD``) the speed past which a point
    bounces; ``reach`` (m, ``FIRST_REACH``) the gap within which a fresh contact is swept: each
    in the World's length units (engine.world.World's ``length_units_per_meter``).

    ``brise`` (nb) out: how far each body's held loads have yet to lift it (m), the most of
    the give still left under its face contacts' loads (module doc, "A pile holds its load"):
    what engine.pipeline.game_sleep's stillness reads.
    """
    nb = len(bx)
    nc = len(ca)
    nj = len(ja)

    h = dt / substeps
    inv_h = 1.0 / h
    # Box2D's softness: contacts at most an eighth of the substep rate, joints a quarter.
    # (b2MakeSoft written out: numba compiles this one function.)
    hz = min(contact_hertz, 0.125 * inv_h)
    omega = 2.0 * math.pi * hz
    a1 = 2.0 * contact_damping + h * omega
    a2 = h * omega * a1
    c_rate, c_mass, c_imp = omega / a1, a2 / (1.0 + a2), 1.0 / (1.0 + a2)
    omega = 2.0 * math.pi * 2.0 * hz
    a1 = 2.0 * contact_damping + h * omega
    a2 = h * omega * a1
    s_rate, s_mass, s_imp = omega / a1, a2 / (1.0 + a2), 1.0 / (1.0 + a2)
    omega = 2.0 * math.pi * min(joint_hertz, 0.25 * inv_h)
    a1 = 2.0 * joint_damping + h * omega
    a2 = h * omega * a1
    j_rate, j_mass, j_imp = omega / a1, a2 / (1.0 + a2), 1.0 / (1.0 + a2)
    # pymunk's bounds on each joint's rows (module doc): the most impulse a row's substep may
    # sum to (max_force h), the fastest it corrects its error (max_bias), its error_bias's
    # bias rate beta (< 0: the joints' spring); no bound, and the spring, but for a
    # constraint's rows (jmotor's bit 2).
    jmost = floats(nj, math.inf)
    jfast = floats(nj, math.inf)
    jbeta = floats(nj, -1.0)
    jsoft = (j_rate, j_mass, j_imp)  # the joints' spring (``_soft``)

    def press(
        p: int, d: float, a: int, b: int, ma: float, ia: float, mb: float, ib: float,
        nx: float, ny: float, rax: float, ray: float, rbx: float, rby: float, touch: bool,
    ) -> bool:  # fmt: skip
        """Point p's normal impulse grown by d, kept >= 0 (a contact only pushes), applied;
        counted in ``cmax`` where it is a ``touch`` (``contact``). Whether it changed."""
        new = max(cln[p] + d, 0.0)
        d = new - cln[p]
        cln[p] = new
        ctotal[p] += d
        if touch and new > cmax[p]:
            cmax[p] = new
        _apply(bvx, bvy, bw, a, b, ma, ia, mb, ib, d * nx, d * ny, rax, ray, rbx, rby)
        return d != 0.0

    # The start of the step: positions and angles kept, the moves counted from them.
    x0 = floats(nb, 0.0)
    y0 = floats(nb, 0.0)
    q0 = floats(nb, 0.0)
    dx = floats(nb, 0.0)
    dy = floats(nb, 0.0)
    dq = floats(nb, 0.0)
    cq = floats(nb, 1.0)  # cos and sin of each body's turn since the start (dq)
    sq = floats(nb, 0.0)
    for i in range(nb):
        x0[i] = bx[i]
        y0[i] = by[i]
        q0[i] = bq[i]
    # The bodies in no row fly the closed form at the step's end (module doc); the parts
    # leave them as they were.
    free = floats(nb, 1.0)  # 1.0: in no row (floats: the kernels' quick scratch)
    for k in range(nc):
        free[ca[k]] = 0.0
        free[cb[k]] = 0.0
    for k in range(nj):
        free[ja[k]] = 0.0
        free[jb[k]] = 0.0

    # -- prepare the contacts: masses along the normal and tangent, the relative normal speed
    # at the start (for restitution).
    nmass = floats(2 * nc, 0.0)
    tmass = floats(2 * nc, 0.0)
    rel = floats(2 * nc, 0.0)
    # A two-point manifold's normal rows as one 2 x 2 system, K = J M^-1 J^T:
    # k_ij = w_A + w_B + i_A (r_Ai x n)(r_Aj x n) + i_B (r_Bi x n)(r_Bj x n), solved as a block
    # where it is well conditioned (k11^2 < 1000 det K, Box2D v2.4's bound; kblock 1).
    kn1 = floats(nc, 0.0)
    kn12 = floats(nc, 0.0)
    kn2 = floats(nc, 0.0)
    kblock = floats(nc, 0.0)
    for k in range(nc):
        a = ca[k]
        b = cb[k]
        ma, ia, mb, ib = bim[a], bii[a], bim[b], bii[b]
        nx, ny = cnx[k], cny[k]
        if ccount[k] == 2:
            p = 2 * k
            kn1[k], kn12[k], kn2[k], kblock[k] = _block(
                ma, ia, mb, ib, nx, ny, crax[p], cray[p], crbx[p], crby[p], crax[p + 1],
                cray[p + 1], crbx[p + 1], crby[p + 1],
            )  # fmt: skip
        for j in range(ccount[k]):
            p = 2 * k + j
            rax, ray, rbx, rby = crax[p], cray[p], crbx[p], crby[p]
            nmass[p], tmass[p] = _point_masses(ma, ia, mb, ib, rax, ray, rbx, rby, nx, ny)
            # v + omega x r = (v_x - omega r_y, v_y + omega r_x).
            dvx, dvy = _relative(bvx, bvy, bw, a, b, rax, ray, rbx, rby)
            rel[p] = dvx * nx + dvy * ny
            ctotal[p] = 0.0
            cmax[p] = 0.0
        for j in range(ccount[k] if crest[k] != 0.0 else 0):  # (restitution's alone)
            p = 2 * k + j
            if csep[p] <= 0.0:
                continue
            # Open at the start: the speed it meets at (module doc, "Restitution"), (1) before
            # a push the last relax gave it open, the warm start: the manifold's impulses
            # P_i = lam_n n + lam_t t at r_i changed it by n.((w_A + w_B) P_i
            # + i_B (r_Bi x P_i) perp(r_B) + i_A (r_Ai x P_i) perp(r_A)), perp(r) = (-r_y, r_x);
            # (2) at the touch, s further on: vn^2 = vn0^2 - 2 a_n s.
            rax, ray, rbx, rby = crax[p], cray[p], crbx[p], crby[p]
            for i in range(ccount[k]):
                q = 2 * k + i
                px = cln[q] * nx - clt[q] * ny
                py = cln[q] * ny + clt[q] * nx
                if px == 0.0 and py == 0.0:
                    continue
                tb = ib * (crbx[q] * py - crby[q] * px)
                ta = ia * (crax[q] * py - cray[q] * px)
                gx = (mb + ma) * px - tb * rby - ta * ray
                gy = (mb + ma) * py + tb * rbx + ta * rax
                rel[p] -= gx * nx + gy * ny
            if rel[p] < 0.0:
                anx = (bax[b] - balpha[b] * rby) - (bax[a] - balpha[a] * ray)
                any_ = (bay[b] + balpha[b] * rbx) - (bay[a] + balpha[a] * rax)
                meet = rel[p] * rel[p] - 2.0 * (anx * nx + any_ * ny) * csep[p]
                if meet > 0.0:
                    rel[p] = -math.sqrt(meet)

    # -- the rows on a face that turns (engine.dynamics.turning_faces) where the point rides the
    # face (``live``: 0 not, 1 rides it, 2 rides it and is taken again from the first substep
    # its bodies have turned ``STILL``): its points' normal speed at the start closes at no
    # more than the threshold (one that strikes the face is an impact, whose rows stay where
    # it met); each one's normal at the start, its core point less that body's position then
    # (world axes) and the face's offset f0, per point; and its rows as they came, given back
    # at the end.
    faced = 0
    for k in range(nc):
        if cface[k] != 0:
            faced += 1
    turning = 0
    live = floats(nc if faced else 0, 0.0)
    for k in range(nc if faced else 0):
        if cface[k] == 0:
            continue
        live[k] = 1.0
        if cface[k] >= ROUND:
            # (A disc and a static shape's core: the line between them turns as the disc
            # passes, whatever its speed; an impact's line is the one where they meet, which
            # the rows taken again follow.)
            turning += 1
            continue
        for j in range(ccount[k]):
            p = 2 * k + j
            dvx, dvy = _relative(
                bvx, bvy, bw, ca[k], cb[k], crax[p], cray[p], crbx[p], crby[p]
            )  # fmt: skip
            if dvx * cnx[k] + dvy * cny[k] < -threshold:
                live[k] = 0.0
        if live[k] != 0.0:
            turning += 1
    tn0x = floats(nc if turning else 0, 0.0)
    tn0y = floats(nc if turning else 0, 0.0)
    te0x = floats(2 * nc if turning else 0, 0.0)
    te0y = floats(2 * nc if turning else 0, 0.0)
    tf0 = floats(2 * nc if turning else 0, 0.0)
    # (A round row's static core: its segment's ends, less B's position; a point twice.)
    te1x = floats(2 * nc if turning else 0, 0.0)
    te1y = floats(2 * nc if turning else 0, 0.0)
    te2x = floats(2 * nc if turning else 0, 0.0)
    te2y = floats(2 * nc if turning else 0, 0.0)
    kept = floats(8 * nc if turning else 0, 0.0)  # (each point's four anchors, as they came)
    for k in range(nc if turning else 0):
        if live[k] == 0.0:
            continue
        nx, ny = cnx[k], cny[k]
        tn0x[k], tn0y[k] = nx, ny
        f = FACE_NUMBERS * k
        r = cround[f]
        for j in range(ccount[k]):
            p = 2 * k + j
            kept[4 * p], kept[4 * p + 1] = crax[p], cray[p]
            kept[4 * p + 2], kept[4 * p + 3] = crbx[p], crby[p]
            if cface[k] >= ROUND:
                sbx, sby = x0[cb[k]], y0[cb[k]]  # (the static body's: the origin)
                te0x[p], te0y[p], te1x[p], te1y[p], te2x[p], te2y[p] = round_start(
                    cface[k], nx, ny, crax[p], cray[p], crbx[p], crby[p], csep[p], r,
                    cround[f + 1], cround[f + 2] - sbx, cround[f + 3] - sby, cround[f + 4] - sbx,
                    cround[f + 5] - sby,
                )  # fmt: skip
                continue
            te0x[p], te0y[p], tf0[p] = face_start(
                cface[k], nx, ny, crax[p], cray[p], crbx[p], crby[p], csep[p], r
            )

    def turned(p: int, k: int, a: int, b: int) -> tuple[float, float, float, float, float]:
        """Point p of contact k on a face that turns, at the bodies' poses now
        (engine.dynamics.turning_faces.face_gap): its separation, normal and disc centre."""
        ox = (x0[b] + dx[b]) - (x0[a] + dx[a])
        oy = (y0[b] + dy[b]) - (y0[a] + dy[a])
        if cface[k] >= ROUND:
            return round_gap(
                tn0x[k], tn0y[k], ox, oy, cq[a], sq[a], cq[b], sq[b], te0x[p], te0y[p],
                te1x[p], te1y[p], te2x[p], te2y[p], cround[FACE_NUMBERS * k],
                cround[FACE_NUMBERS * k + 1],
            )  # fmt: skip
        f, d = (a, b) if cface[k] == FACE_A else (b, a)
        return face_gap(
            cface[k], tn0x[k], tn0y[k], ox, oy, cq[f], sq[f], cq[d], sq[d], te0x[p], te0y[p],
            cround[FACE_NUMBERS * k], tf0[p],
        )  # fmt: skip

    def retake(k: int) -> None:
        """Contact k's rows on a face that turns taken again where its bodies are now
        (engine.dynamics.turning_faces): the normal, the anchors at the point midway between
        the disc and the face, and the masses along the normal and the tangent."""
        a = ca[k]
        b = cb[k]
        ma, ia, mb, ib = bim[a], bii[a], bim[b], bii[b]
        ox = (x0[b] + dx[b]) - (x0[a] + dx[a])
        oy = (y0[b] + dy[b]) - (y0[a] + dy[a])
        r = cround[FACE_NUMBERS * k]
        for j in range(ccount[k]):
            p = 2 * k + j
            s, nx, ny, wx, wy = turned(p, k, a, b)
            if cface[k] == FACE_A:
                rbx = wx - (r + 0.5 * s) * nx
                rby = wy - (r + 0.5 * s) * ny
                rax, ray = rbx + ox, rby + oy
            else:
                rax = wx + (r + 0.5 * s) * nx
                ray = wy + (r + 0.5 * s) * ny
                rbx, rby = rax - ox, ray - oy
            cnx[k], cny[k] = nx, ny
            crax[p], cray[p], crbx[p], crby[p] = rax, ray, rbx, rby
            nmass[p], tmass[p] = _point_masses(ma, ia, mb, ib, rax, ray, rbx, rby, nx, ny)
        if ccount[k] == 2:
            p = 2 * k
            kn1[k], kn12[k], kn2[k], kblock[k] = _block(
                ma, ia, mb, ib, cnx[k], cny[k], crax[p], cray[p], crbx[p], crby[p],
                crax[p + 1], cray[p + 1], crbx[p + 1], crby[p + 1],
            )  # fmt: skip

    def press2(
        k: int, r1: float, r2: float, l1: float, l2: float, a: int, b: int, ma: float,
        ia: float, mb: float, ib: float, nx: float, ny: float, touch1: bool, touch2: bool,
    ) -> bool:  # fmt: skip
        """Manifold k's two normal impulses at once: the new x >= 0 with w = K (x - l) + r >= 0
        and x w = 0 (a linear complementarity problem of two rows, Box2D v2.4's block solver:
        both pushing, the first alone, the second alone, or neither), applied; each counted in
        ``cmax`` where it is a touch (``contact``). Whether they changed."""
        p = 2 * k
        k11, k12, k22 = kn1[k], kn12[k], kn2[k]
        det = 1.0 / (k11 * k22 - k12 * k12)
        x1 = l1 - det * (k22 * r1 - k12 * r2)
        x2 = l2 - det * (k11 * r2 - k12 * r1)
        if not (x1 >= 0.0 and x2 >= 0.0):
            x1 = l1 - (r1 - k12 * l2) / k11
            x2 = 0.0
            w2 = k12 * (x1 - l1) - k22 * l2 + r2
            if not (x1 >= 0.0 and w2 >= 0.0):
                x1 = 0.0
                x2 = l2 - (r2 - k12 * l1) / k22
                w1 = -k11 * l1 + k12 * (x2 - l2) + r1
                if not (x2 >= 0.0 and w1 >= 0.0):
                    x1 = 0.0
                    x2 = 0.0
        d1 = x1 - cln[p]
        d2 = x2 - cln[p + 1]
        cln[p] = x1
        cln[p + 1] = x2
        ctotal[p] += d1
        ctotal[p + 1] += d2
        if touch1 and x1 > cmax[p]:
            cmax[p] = x1
        if touch2 and x2 > cmax[p + 1]:
            cmax[p + 1] = x2
        px, py = (d1 + d2) * nx, (d1 + d2) * ny
        bvx[a] -= ma * px
        bvy[a] -= ma * py
        bw[a] -= ia * (
            (crax[p] * ny - cray[p] * nx) * d1 + (crax[p + 1] * ny - cray[p + 1] * nx) * d2
        )
        bvx[b] += mb * px
        bvy[b] += mb * py
        bw[b] += ib * (
            (crbx[p] * ny - crby[p] * nx) * d1 + (crbx[p + 1] * ny - crby[p + 1] * nx) * d2
        )
        return d1 != 0.0 or d2 != 0.0

    # -- prepare the joints: each anchor turned into the world's axes at the start, the
    # bodies' offset then, and the axial mass.
    fax = floats(nj, 0.0)
    fay = floats(nj, 0.0)
    fbx = floats(nj, 0.0)
    fby = floats(nj, 0.0)
    cx0 = floats(nj, 0.0)
    cy0 = floats(nj, 0.0)
    amass = floats(nj, 0.0)
    # A soft weld's own spring (its hertz and damping ratio), for each joint.
    w_rate = floats(nj, 0.0)
    w_mass = floats(nj, 1.0)
    w_imp = floats(nj, 0.0)
    # A distance's parting speed at the start (m/s), and whether its cable pulled in the step.
    drel = floats(nj, 0.0)
    dhit = floats(nj, 0.0)
    # A groove's unit axis at the start, in the world's axes.
    gux = floats(nj, 0.0)
    guy = floats(nj, 0.0)

    def slide(
        k: int, bias: bool, ux: float, uy: float, t: float, lax: float, lay: float, rbx: float,
        rby: float, across: float,
    ) -> None:  # fmt: skip
        """Joint k's rows along the unit axis u (a distance's or a groove's: module doc) solved
        once, each acting on A at the lever (lax, lay) and on B at r_B, t the translation along
        u: a rod's length (C = t - jupper, either sign), else t's limits (t >= jlower where
        ``jlimit``'s bit 1 asks, t <= jupper where its bit 2 does), then a groove's point
        across u (C = ``across`` = n.d, n = (-u_y, u_x))."""
        a = ja[k]
        b = jb[k]
        ma, ia, mb, ib = bim[a], bii[a], bim[b], bii[b]
        rod = jkind[k] == DISTANCE and jlower[k] == jupper[k]
        groove = jkind[k] == GROOVE
        # Each row's largest correction speed: max_bias, a groove's shared by its rows as one
        # vector's (each row's part of it as its error's part of the error across and past
        # the ends, so that the correction keeps its direction).
        tops = (jfast[k], jfast[k], jfast[k])
        cap = math.inf if groove else jmost[k]  # (a groove's, as a vector, below)
        if groove and jfast[k] < math.inf:
            past = min(t - jlower[k], 0.0) + min(jupper[k] - t, 0.0)
            size = math.sqrt(past * past + across * across)
            if size > 0.0:
                f = jfast[k] / size
                lo_top = f * -min(t - jlower[k], 0.0)
                hi_top = f * -min(jupper[k] - t, 0.0)
                tops = (lo_top, hi_top, f * abs(across))
        for row in range(3):
            nx, ny = ux, uy
            if row == 2:
                if not rod and jkind[k] != GROOVE:
                    break
                if not rod:
                    nx, ny = -uy, ux
            elif rod or ((jlimit[k] >> row) & 1) == 0:
                continue
            mass = _axial_mass(bim, bii, a, b, nx, ny, lax, lay, rbx, rby)
            dvx, dvy = _relative(bvx, bvy, bw, a, b, lax, lay, rbx, rby)
            cdot = dvx * nx + dvy * ny  # (along u: > 0, the anchors part)
            if row < 2:
                # The least: C = t - jlower >= 0, pushing B along u; the most: C = jupper - t
                # >= 0, pulling B back along -u (a cable's pull).
                sign = 1.0 if row == 0 else -1.0
                old = jlo[k] if row == 0 else jhi[k]
                err = t - jlower[k] if row == 0 else jupper[k] - t
                new = _limit(
                    jbeta, jsoft, inv_h, k, err, sign * cdot, mass, old, bias, tops[row], cap
                )
                d = sign * (new - old)
                if row == 0:
                    jlo[k] = new
                else:
                    jhi[k] = new
                    if new > 0.0:
                        dhit[k] = 1.0
            else:
                # A rod's length, or a groove's point across: a soft equality row, its
                # impulse within max_force h (a groove's, with its ends', below).
                rate, mscale, iscale = _soft(jbeta, jsoft, k, bias)
                err = t - jupper[k] if rod else across
                v = _bounded(rate, err, mscale, tops[2])
                d = -mscale * mass * (cdot + v) - iscale * jpa[k]
                old = jpa[k]
                new = old + d
                if not groove and (new > jmost[k] or new < -jmost[k]):
                    new = min(max(new, -jmost[k]), jmost[k])
                    d = new - old
                jpa[k] = new
            _apply(bvx, bvy, bw, a, b, ma, ia, mb, ib, d * nx, d * ny, lax, lay, rbx, rby)
        if groove:
            # The ends' push along u and the point's across it as one impulse on B, at most
            # max_force h: scaled back to it where it exceeds it (Chipmunk's cpvclamp).
            along = jlo[k] - jhi[k]
            size = math.sqrt(along * along + jpa[k] * jpa[k])
            if size > jmost[k]:
                f = jmost[k] / size
                da = (jlo[k] * f - jhi[k] * f) - along
                dn = jpa[k] * f - jpa[k]
                jlo[k] *= f
                jhi[k] *= f
                jpa[k] *= f
                _apply(
                    bvx, bvy, bw, a, b, ma, ia, mb, ib, da * ux - dn * uy, da * uy + dn * ux, lax,
                    lay, rbx, rby,
                )  # fmt: skip

    def spring(k: int, rax: float, ray: float, rbx: float, rby: float) -> None:
        """Spring k's impulses over a substep (module doc): its stiffness', explicit, then its
        damper's, which takes the speed along it to exp(-c w h) of itself."""
        a = ja[k]
        b = jb[k]
        ma, ia, mb, ib = bim[a], bii[a], bim[b], bii[b]
        if jkind[k] == SPRING:
            ux, uy, length = _axis(dx, dy, cx0, cy0, k, a, b, rax, ray, rbx, rby)
            mass = _axial_mass(bim, bii, a, b, ux, uy, rax, ray, rbx, rby)
            if mass == 0.0:
                return
            d = -jhertz[k] * (length - jlower[k]) * h
            dvx, dvy = _relative(bvx, bvy, bw, a, b, rax, ray, rbx, rby)
            vn = dvx * ux + dvy * uy + d / mass  # the parting speed after the stiffness' kick
            d -= vn * (1.0 - math.exp(-jdamp[k] * h / mass)) * mass
            jpa[k] += d
            _apply(bvx, bvy, bw, a, b, ma, ia, mb, ib, d * ux, d * uy, rax, ray, rbx, rby)
            return
        if amass[k] == 0.0:
            return
        twist = (q0[b] + dq[b]) - (q0[a] + dq[a]) - jlower[k]
        d = -jhertz[k] * twist * h
        spin = bw[b] - bw[a] + d / amass[k]
        d -= spin * (1.0 - math.exp(-jdamp[k] * h / amass[k])) * amass[k]
        jpa[k] += d
        bw[a] -= ia * d
        bw[b] += ib * d

    for k in range(nj):
        a = ja[k]
        b = jb[k]
        c, s = math.cos(q0[a]), math.sin(q0[a])
        fax[k] = c * jlax[k] - s * jlay[k]
        fay[k] = s * jlax[k] + c * jlay[k]
        c, s = math.cos(q0[b]), math.sin(q0[b])
        fbx[k] = c * jlbx[k] - s * jlby[k]
        fby[k] = s * jlbx[k] + c * jlby[k]
        cx0[k] = x0[b] - x0[a]
        cy0[k] = y0[b] - y0[a]
        ki = bii[a] + bii[b]
        if jkind[k] == GEAR:
            ki = bii[a] + jspeed[k] * jspeed[k] * bii[b]  # J = (-1, r): i_A + r^2 i_B
        amass[k] = 1.0 / ki if ki > 0.0 else 0.0
        if jkind[k] == GROOVE:
            c, s = math.cos(q0[a]), math.sin(q0[a])
            gx, gy = math.cos(jref[k]), math.sin(jref[k])
            gux[k] = c * gx - s * gy
            guy[k] = s * gx + c * gy
        if jkind[k] >= SPRING:
            jpa[k] = 0.0  # (a force: what it gives is summed over the step, not carried)
        elif (jmotor[k] & 2) != 0:
            # A constraint's bounds (module doc): its jhertz an error_bias, not a frequency.
            jmost[k] = h * jmaxtorque[k]
            jfast[k] = jdamp[k]
            if jhertz[k] >= 0.0:
                jbeta[k] = (1.0 - jhertz[k] ** h) * inv_h
        elif jhertz[k] > 0.0:
            omega = 2.0 * math.pi * jhertz[k]
            a1 = 2.0 * jdamp[k] + h * omega
            a2 = h * omega * a1
            w_rate[k], w_mass[k], w_imp[k] = omega / a1, a2 / (1.0 + a2), 1.0 / (1.0 + a2)
        if jkind[k] == DISTANCE:
            # The anchors' parting speed along the link at the start (for a cable's bounce).
            ux, uy, _ = _axis(dx, dy, cx0, cy0, k, a, b, fax[k], fay[k], fbx[k], fby[k])
            dvx, dvy = _relative(bvx, bvy, bw, a, b, fax[k], fay[k], fbx[k], fby[k])
            drel[k] = dvx * ux + dvy * uy

    # The held part of each substep's change of velocity (module doc, "Positions exact for
    # held forces"), dv_held: the forces' a h and the contacts' warm start as far as the
    # solve with bias kept it, a normal's the lesser of the two, a friction's whole (friction
    # is solved in the relax alone). It is v1 - v0 less what that solve pushed past the warm
    # start (the rest of the substep's change up to then), so each body keeps v0 plus that
    # push, uvx, uvy, uw (v1 - dv_held), pushed where a point's impulse grows past its warm
    # start (wsn, each point's). A body held by a joint moves by v h (wheld 0). ``v0x``,
    # ``v0y``, ``v0w``: v0, which bounds an impact's dv_held (``_within``).
    uvx = floats(nb, 0.0)
    uvy = floats(nb, 0.0)
    uw = floats(nb, 0.0)
    v0x = floats(nb, 0.0)
    v0y = floats(nb, 0.0)
    v0w = floats(nb, 0.0)
    wsn = floats(2 * nc, 0.0)
    wheld = floats(nb, 1.0)
    unheld = floats(nb, 0.0)  # 1.0: moves by v h in this substep (a fresh contact pushed it)
    for k in range(nj):
        wheld[ja[k]] = 0.0
        wheld[jb[k]] = 0.0

    def gap(p: int, a: int, b: int, mx: float, my: float, nx: float, ny: float) -> float:
        """Point p's separation now (m): the bodies moved apart by (mx, my) since the start,
        the anchors turned across the normal as their bodies have (module doc, "Rows")."""
        if turning and live[p // 2] == 2.0:
            return turned(p, p // 2, a, b)[0]  # (a face that turns: exact, module doc)
        rna = crax[p] * ny - cray[p] * nx
        rnb = crbx[p] * ny - crby[p] * nx
        return csep[p] + mx * nx + my * ny + rnb * sq[b] - rna * sq[a]

    def contact(k: int, stage: int, late: bool) -> bool:
        """Contact k's rows solved once (module doc), in a ``stage``: 0 a fresh contact's
        sweep (a relax before the substep's positions move), 1 the solve with bias, 2 the
        relax, 3 restitution. Its normal rows (with the soft push in the solve with bias, the
        two points as a block where the block is well conditioned), then in a relax its
        friction, in the solve with bias the impulses held (``uvx``, ``uvy``, ``uw``). A push
        is a touch (``cmax``, which a bounce asks for) where the point is closed, or where the
        solve is ahead of the positions (stages 0 and 1): a speculative push then stops it on
        the surface as the positions move. After them, a point still open that pushes only
        slows to what its gap allows in the next substep (Box2D's relax): it has not touched
        yet; and where ``late`` (the step's last relax) such a point that has not touched in
        the step is not pushed at all (module doc, "Restitution"). Restitution pushes a point
        that met faster than the threshold and touched to part at e times the speed it met
        at, -e rel (both as a block where both do). Whether an impulse changed."""
        bias = stage == 1
        bounce = stage == 3
        ahead = stage < 2 or bounce
        e = crest[k]
        a = ca[k]
        b = cb[k]
        ma, ia, mb, ib = bim[a], bii[a], bim[b], bii[b]
        nx, ny = cnx[k], cny[k]
        # Stiffer against what does not move (Box2D: the floor does not give).
        rigid = (ma == 0.0 and ia == 0.0) or (mb == 0.0 and ib == 0.0)
        if rigid:
            rate, mscale, iscale = s_rate, s_mass, s_imp
        else:
            rate, mscale, iscale = c_rate, c_mass, c_imp
        mx = dx[b] - dx[a]
        my = dy[b] - dy[a]
        changed = False
        # Both points at once where the block is well conditioned (press2): a box that lands
        # flat stays flat, where one point after the other would tip it; but a point left
        # open (``late``) leaves the other solved alone.
        block = ccount[k] == 2 and kblock[k] != 0.0
        s1 = 0.0
        s2 = 0.0
        for j in range(ccount[k]):
            q = 2 * k + j
            sep = gap(q, a, b, mx, my, nx, ny)
            if j == 0:
                s1 = sep
            else:
                s2 = sep
            if late and sep > 0.0 and cmax[q] == 0.0:
                block = False
            if bounce and (rel[q] > -threshold or cmax[q] == 0.0):
                block = False
        r1 = 0.0
        r2 = 0.0
        l1 = 0.0
        l2 = 0.0
        t1 = True
        t2 = True
        for j in range(ccount[k]):
            p = 2 * k + j
            sep = s1 if j == 0 else s2
            if late and sep > 0.0 and cmax[p] == 0.0:
                continue  # (left open to the next step: above)
            if bounce and (rel[p] > -threshold or cmax[p] == 0.0):
                continue  # (no bounce: above)
            rax, ray, rbx, rby = crax[p], cray[p], crbx[p], crby[p]
            vbias, ms, im = 0.0, 1.0, 0.0
            if bounce:
                vbias = e * rel[p]  # (the target vn = -e rel)
            elif sep > 0.0:
                vbias = sep * inv_h  # speculative: may close by sep, no more
            elif bias:
                vbias = max(mscale * rate * sep, -push)
                ms, im = mscale, iscale
            dvx, dvy = _relative(bvx, bvy, bw, a, b, rax, ray, rbx, rby)
            vn = dvx * nx + dvy * ny
            keep = 0.0  # the load held (module doc, "The floor holds its load")
            if im != 0.0:
                keep = max(wsn[p] - nmass[p] * max(vn, 0.0), 0.0)
                if not rigid:
                    keep = min(keep, chold[p])  # (module doc, "A pile holds its load")
            touch = ahead or sep <= 0.0
            if not block:
                d = -nmass[p] * (ms * vn + vbias) - im * (cln[p] - keep)
                if press(p, d, a, b, ma, ia, mb, ib, nx, ny, rax, ray, rbx, rby, touch):
                    changed = True
            elif j == 0:
                r1 = ms * vn + vbias
                l1 = (1.0 - im) * cln[p] + im * keep
                t1 = touch
            else:
                r2 = ms * vn + vbias
                l2 = (1.0 - im) * cln[p] + im * keep
                t2 = touch
        if block:
            changed = press2(k, r1, r2, l1, l2, a, b, ma, ia, mb, ib, nx, ny, t1, t2)
        if stage == 0 or stage == 2:
            # Friction, in the relax only (Box2D v3), against the slip less the
            # surfaces' own speed: vt = (v_B - v_A).t - speed, t = (-n_y, n_x).
            tx, ty = -ny, nx
            for j in range(ccount[k]):
                p = 2 * k + j
                rax, ray, rbx, rby = crax[p], cray[p], crbx[p], crby[p]
                dvx, dvy = _relative(bvx, bvy, bw, a, b, rax, ray, rbx, rby)
                vt = dvx * tx + dvy * ty - cspeed[k]
                d = -tmass[p] * vt
                most = cfric[k] * cln[p]
                new = min(max(clt[p] + d, -most), most)
                d = new - clt[p]
                clt[p] = new
                px, py = d * tx, d * ty
                _apply(bvx, bvy, bw, a, b, ma, ia, mb, ib, px, py, rax, ray, rbx, rby)
                if d != 0.0:
                    changed = True
        for j in range(ccount[k] if bias else 0):
            # What this solve pushed past the warm start, not held (above: uvx).
            p = 2 * k + j
            more = cln[p] - wsn[p]
            if more <= 0.0:
                continue
            px, py = more * nx, more * ny
            uvx[a] -= ma * px
            uvy[a] -= ma * py
            uw[a] -= ia * (crax[p] * py - cray[p] * px)
            uvx[b] += mb * px
            uvy[b] += mb * py
            uw[b] += ib * (crbx[p] * py - crby[p] * px)
        return changed

    # The contacts with no impulse to start from (module doc, "A fresh contact") that may
    # touch in the first substep (``FIRST_REACH``; rel: a point's normal speed at the start,
    # or the faster one it meets at where it bounces): their indices, the first nfresh of
    # ``fresh`` (floats: the kernels' quick scratch).
    fresh = floats(nc, 0.0)
    alone = floats(nc, 0.0)
    nfresh = 0
    for k in range(nc):
        unset = True
        near = False
        for j in range(ccount[k]):
            p = 2 * k + j
            if cln[p] != 0.0 or clt[p] != 0.0:
                unset = False
            if csep[p] + rel[p] * h <= reach:
                near = True
        if unset and near:
            fresh[nfresh] = k
            # Rows that one relax solves (module doc, "A fresh contact"): one point whose
            # normal and friction do not move each other, K_nt = sum of i (r x n)(r . n) = 0
            # (a disc's point lies on the line of centres); swept once.
            if ccount[k] == 1:
                p = 2 * k
                nx, ny = cnx[k], cny[k]
                ka = crax[p] * ny - cray[p] * nx
                kb = crbx[p] * ny - crby[p] * nx
                knt = bii[ca[k]] * ka * (crax[p] * nx + cray[p] * ny) + bii[cb[k]] * kb * (
                    crbx[p] * nx + crby[p] * ny
                )
                knn = bim[ca[k]] + bim[cb[k]] + bii[ca[k]] * ka * ka + bii[cb[k]] * kb * kb
                if abs(knt) <= 1e-9 * knn:
                    alone[nfresh] = 1.0
            nfresh += 1
    # A fresh contact's sweep that changed no impulse changes none again until a body of it
    # is pushed (its solve reads nothing else that the sweeps change), and is skipped till
    # then: ``calm`` the count of solves at the one that changed nothing (0: it changed),
    # ``moved`` at the last that pushed the body (module doc, "A fresh contact").
    calm = floats(nc, 0.0)
    moved = floats(nb, 0.0)
    solves = 0.0

    # The substeps, then (sub == substeps) the restitution pass after the loads held (module
    # doc, "Restitution"): one loop, so that ``contact`` is called in one place (numba
    # compiles an inner function again at each of its calls: a second call cost 3 s of a
    # cold compile).
    for sub in range(substeps + 1):
        last = sub == substeps
        if last:
            # -- the loads held between bodies (module doc, "A pile holds its load"): each
            # point of a face contact (two points) has a held load that closes alpha =
            # min(HOLD_SHARE, zeta omega dt pi^2 / (HOLD_MARGIN r^2)) of its gap to HOLD_PART
            # of the last part's load lam, r = lam / (m_n g h) (in squares: no root, which
            # numba and Python could round apart).
            depth = contact_damping * 2.0 * math.pi * hz * dt * math.pi * math.pi / HOLD_MARGIN
            # A point's spring gives under a load W = lam / h by W / (m_n omega^2): what it has yet
            # to give back as it holds its load is (HOLD_PART lam - chold) / (m_n h omega^2), and
            # each end of it is lifted so by at most that (``brise``).
            stiff = h * (2.0 * math.pi * hz) ** 2  # (times m_n: the spring's stiffness times h)
            for i in range(nb):
                brise[i] = 0.0
            for k in range(nc):
                a = ca[k]
                b = cb[k]
                g2 = max(bax[a] * bax[a] + bay[a] * bay[a], bax[b] * bax[b] + bay[b] * bay[b])
                # (Against what does not move the contact holds its whole load at once: ``keep``.)
                moves = (bim[a] != 0.0 or bii[a] != 0.0) and (bim[b] != 0.0 or bii[b] != 0.0)
                for j in range(ccount[k]):
                    p = 2 * k + j
                    lam = cln[p]
                    if not moves or ccount[k] != 2 or g2 == 0.0 or lam <= 0.0 or nmass[p] == 0.0:
                        chold[p] = 0.0
                        continue
                    load = nmass[p] * h
                    # (Compared before dividing: a load of 1e-170 N s squares to 0, the share then
                    # HOLD_SHARE; found by the shapes fuzz, a division by zero.)
                    share = HOLD_SHARE
                    deep = depth * load * load * g2
                    if deep < HOLD_SHARE * lam * lam:
                        share = deep / (lam * lam)
                    chold[p] += share * (HOLD_PART * lam - chold[p])
                    firm = nmass[p] * stiff
                    rise = 0.0 if firm == 0.0 else (HOLD_PART * lam - chold[p]) / firm
                    if rise > brise[a]:
                        brise[a] = rise
                    if rise > brise[b]:
                        brise[b] = rise
        else:
            for p in range(2 * nc):
                wsn[p] = cln[p]
            # -- integrate velocities (only what moves: the static body and kinematic bodies
            # have no acceleration; a free body flies the closed form at the end).
            for i in range(nb):
                uvx[i] = bvx[i]
                uvy[i] = bvy[i]
                uw[i] = bw[i]
                v0x[i] = bvx[i]
                v0y[i] = bvy[i]
                v0w[i] = bw[i]
                if free[i] != 0.0:
                    continue
                bvx[i] += bax[i] * h
                bvy[i] += bay[i] * h
                bw[i] += balpha[i] * h

            # -- warm start: joints, then contacts.
            for k in range(nj):
                if jkind[k] >= SPRING:
                    continue
                a = ja[k]
                b = jb[k]
                ma, ia, mb, ib = bim[a], bii[a], bim[b], bii[b]
                rax = cq[a] * fax[k] - sq[a] * fay[k]
                ray = sq[a] * fax[k] + cq[a] * fay[k]
                rbx = cq[b] * fbx[k] - sq[b] * fby[k]
                rby = sq[b] * fbx[k] + cq[b] * fby[k]
                px, py = jpx[k], jpy[k]
                axial = jpa[k] + jmi[k] + jlo[k] - jhi[k]
                if jkind[k] == DISTANCE:
                    # Along the axis now: lam u, lam = the rod's or least's push less the pull.
                    ux, uy, _ = _axis(dx, dy, cx0, cy0, k, a, b, rax, ray, rbx, rby)
                    px, py, axial = axial * ux, axial * uy, 0.0
                elif jkind[k] == GROOVE:
                    # The ends' push along the axis now and the point's across it (jpa), at B's
                    # anchor (on A at d + r_A).
                    ux = cq[a] * gux[k] - sq[a] * guy[k]
                    uy = sq[a] * gux[k] + cq[a] * guy[k]
                    rax += (dx[b] - dx[a]) + (rbx - rax) + cx0[k]
                    ray += (dy[b] - dy[a]) + (rby - ray) + cy0[k]
                    along = jlo[k] - jhi[k]
                    px, py = along * ux - jpa[k] * uy, along * uy + jpa[k] * ux
                    axial = 0.0
                elif jkind[k] == GEAR:
                    bw[a] -= ia * axial
                    bw[b] += jspeed[k] * ib * axial
                    continue
                bvx[a] -= ma * px
                bvy[a] -= ma * py
                bw[a] -= ia * (rax * py - ray * px + axial)
                bvx[b] += mb * px
                bvy[b] += mb * py
                bw[b] += ib * (rbx * py - rby * px + axial)
            for k in range(nc):
                a = ca[k]
                b = cb[k]
                ma, ia, mb, ib = bim[a], bii[a], bim[b], bii[b]
                nx, ny = cnx[k], cny[k]
                for j in range(ccount[k]):
                    p = 2 * k + j
                    px = cln[p] * nx - clt[p] * ny
                    py = cln[p] * ny + clt[p] * nx
                    ctotal[p] += cln[p]
                    _apply(
                        bvx, bvy, bw, a, b, ma, ia, mb, ib, px, py, crax[p], cray[p], crbx[p],
                        crby[p],
                    )  # fmt: skip

        # -- the fresh contacts' warm start, made (above): their relax's sweep, FIRST_SWEEPS
        # times or until one changes no impulse (the next would change none), in the first
        # substep; then the solve with the soft push, positions integrated, the relax without
        # it. (One call of ``contact`` for the three: numba compiles an inner function again
        # at each of its calls.)
        # (After the substeps, stage 3 alone: restitution. A point that met faster than the
        # threshold, and touched in the step (pushed there: ``contact``), parts at e times
        # the speed it met at (module doc).)
        for stage in range(3 if last else 0, 4 if last else 3):
            sweep = stage == 0
            bias = stage == 1
            if sweep and (sub != 0 or nfresh == 0):
                continue
            for k in range(nj if stage == 1 or stage == 2 else 0):
                a = ja[k]
                b = jb[k]
                if jkind[k] >= SPRING:
                    if bias:
                        spring(
                            k,
                            cq[a] * fax[k] - sq[a] * fay[k], sq[a] * fax[k] + cq[a] * fay[k],
                            cq[b] * fbx[k] - sq[b] * fby[k], sq[b] * fbx[k] + cq[b] * fby[k],
                        )  # fmt: skip
                    continue
                if jkind[k] == DISTANCE or jkind[k] == GROOVE:
                    rax = cq[a] * fax[k] - sq[a] * fay[k]
                    ray = sq[a] * fax[k] + cq[a] * fay[k]
                    rbx = cq[b] * fbx[k] - sq[b] * fby[k]
                    rby = sq[b] * fbx[k] + cq[b] * fby[k]
                    if jkind[k] == DISTANCE:
                        # Along the anchors' line: t its length, the levers the anchors.
                        ux, uy, t = _axis(dx, dy, cx0, cy0, k, a, b, rax, ray, rbx, rby)
                        lax, lay, across = rax, ray, 0.0
                    else:
                        # A groove: the axis turned as A has since the start, d from A's
                        # anchor to B's; on A the rows act at B's anchor, d + r_A.
                        ux = cq[a] * gux[k] - sq[a] * guy[k]
                        uy = sq[a] * gux[k] + cq[a] * guy[k]
                        ex = (dx[b] - dx[a]) + (rbx - rax) + cx0[k]
                        ey = (dy[b] - dy[a]) + (rby - ray) + cy0[k]
                        t = ux * ex + uy * ey
                        lax, lay, across = ex + rax, ey + ray, ux * ey - uy * ex
                    slide(k, bias, ux, uy, t, lax, lay, rbx, rby, across)
                    continue
                ma, ia, mb, ib = bim[a], bii[a], bim[b], bii[b]
                fixed = ia + ib == 0.0
                if jkind[k] == GEAR:
                    # C = r angle_B - angle_A - phase (r = jspeed, phase = jref).
                    if amass[k] != 0.0:
                        r = jspeed[k]
                        rate, mscale, iscale = _soft(jbeta, jsoft, k, bias)
                        err = r * (q0[b] + dq[b]) - (q0[a] + dq[a]) - jref[k]
                        cdot = r * bw[b] - bw[a]
                        v = _bounded(rate, err, mscale, jfast[k])
                        d = -amass[k] * mscale * (cdot + v) - iscale * jpa[k]
                        old = jpa[k]
                        new = old + d
                        if new > jmost[k] or new < -jmost[k]:
                            new = min(max(new, -jmost[k]), jmost[k])
                            d = new - old
                        jpa[k] = new
                        bw[a] -= ia * d
                        bw[b] += r * ib * d
                    continue
                if jkind[k] == WELD:
                    # The angle held: C = angle_B - angle_A - ref.
                    rate, mscale, iscale = 0.0, 1.0, 0.0
                    if jhertz[k] > 0.0:
                        rate, mscale, iscale = w_rate[k], w_mass[k], w_imp[k]
                    elif bias:
                        rate, mscale, iscale = j_rate, j_mass, j_imp
                    if not fixed:
                        err = (q0[b] + dq[b]) - (q0[a] + dq[a]) - jref[k]
                        cdot = bw[b] - bw[a]
                        d = -amass[k] * mscale * (cdot + rate * err) - iscale * jpa[k]
                        jpa[k] += d
                        bw[a] -= ia * d
                        bw[b] += ib * d
                elif jkind[k] == MOUSE:
                    # The grip calms the body's spin: omega / (1 + k h) a substep (the
                    # implicit step of omega' = -k omega; jspeed holds k, 1/s).
                    if bias and jspeed[k] > 0.0 and ib > 0.0:
                        bw[b] = bw[b] / (1.0 + jspeed[k] * h)
                else:
                    if (jmotor[k] & 1) != 0 and not fixed:
                        cdot = bw[b] - bw[a] - jspeed[k]
                        d = -amass[k] * cdot
                        old = jmi[k]
                        most = h * jmaxtorque[k]
                        jmi[k] = min(max(old + d, -most), most)
                        d = jmi[k] - old
                        bw[a] -= ia * d
                        bw[b] += ib * d
                    if jlimit[k] != 0 and not fixed:
                        angle = (q0[b] + dq[b]) - (q0[a] + dq[a]) - jref[k]
                        mass = amass[k]
                        for side in range(2):
                            if ((jlimit[k] >> side) & 1) == 0:
                                continue
                            # Lower: C = angle - lower >= 0, turning B up; upper: C = upper -
                            # angle >= 0, turning B down.
                            sign = 1.0 if side == 0 else -1.0
                            old = jlo[k] if side == 0 else jhi[k]
                            err = angle - jlower[k] if side == 0 else jupper[k] - angle
                            turn = sign * (bw[b] - bw[a])
                            new = _limit(
                                jbeta, jsoft, inv_h, k, err, turn, mass, old, bias, jfast[k],
                                jmost[k],
                            )  # fmt: skip
                            d = sign * (new - old)
                            if side == 0:
                                jlo[k] = new
                            else:
                                jhi[k] = new
                            bw[a] -= ia * d
                            bw[b] += ib * d
                    if jkind[k] == ROTARY:
                        continue  # (the angle's rows alone)
                # The point: C = (c_B + r_B) - (c_A + r_A), both anchors turned as their
                # bodies have since the start.
                rax = cq[a] * fax[k] - sq[a] * fay[k]
                ray = sq[a] * fax[k] + cq[a] * fay[k]
                rbx = cq[b] * fbx[k] - sq[b] * fby[k]
                rby = sq[b] * fbx[k] + cq[b] * fby[k]
                cdx = (bvx[b] - bw[b] * rby) - (bvx[a] - bw[a] * ray)
                cdy = (bvy[b] + bw[b] * rbx) - (bvy[a] + bw[a] * rax)
                rate, mscale, iscale = 0.0, 1.0, 0.0
                if (jkind[k] == WELD and jhertz[k] > 0.0) or jkind[k] == MOUSE:
                    rate, mscale, iscale = w_rate[k], w_mass[k], w_imp[k]
                elif bias:
                    rate, mscale, iscale = j_rate, j_mass, j_imp
                if rate != 0.0:
                    ex = (dx[b] - dx[a]) + (rbx - rax) + cx0[k]
                    ey = (dy[b] - dy[a]) + (rby - ray) + cy0[k]
                    cdx += rate * ex
                    cdy += rate * ey
                k11 = ma + mb + ray * ray * ia + rby * rby * ib
                k12 = -ray * rax * ia - rby * rbx * ib
                k22 = ma + mb + rax * rax * ia + rbx * rbx * ib
                det = k11 * k22 - k12 * k12
                if det != 0.0:
                    det = 1.0 / det
                sx = det * (k22 * cdx - k12 * cdy)
                sy = det * (k11 * cdy - k12 * cdx)
                px = -mscale * sx - iscale * jpx[k]
                py = -mscale * sy - iscale * jpy[k]
                if jkind[k] == MOUSE:
                    # A mouse joint's force is at most jmaxtorque (N): its impulse in a
                    # substep at most that times h, the push scaled back to it.
                    tx, ty = jpx[k] + px, jpy[k] + py
                    most = h * jmaxtorque[k]
                    if tx * tx + ty * ty > most * most:
                        scale = most / math.sqrt(tx * tx + ty * ty)
                        px, py = tx * scale - jpx[k], ty * scale - jpy[k]
                jpx[k] += px
                jpy[k] += py
                _apply(bvx, bvy, bw, a, b, ma, ia, mb, ib, px, py, rax, ray, rbx, rby)

            # (The step's last relax: a point open that has not touched is left to the next
            # step, module doc "Restitution".)
            late = stage == 2 and sub == substeps - 1
            for again in range(FIRST_SWEEPS if sweep else 1):
                changed = False
                for i in range(nfresh if sweep else nc):
                    k = int(fresh[i]) if sweep else i
                    if stage == 3 and crest[k] == 0.0:
                        continue  # (no bounce asked)
                    a = ca[k]
                    b = cb[k]
                    if sweep:
                        if again != 0 and alone[i] != 0.0:
                            continue  # (solved by the first sweep: above)
                        if calm[i] != 0.0 and moved[a] < calm[i] and moved[b] < calm[i]:
                            continue  # (it would change nothing: above)
                        solves += 1.0
                        calm[i] = solves
                    if contact(k, stage, late) and sweep:
                        changed = True
                        calm[i] = 0.0
                        if bim[a] != 0.0 or bii[a] != 0.0:  # (what does not move is not pushed)
                            moved[a] = solves
                        if bim[b] != 0.0 or bii[b] != 0.0:
                            moved[b] = solves
                if not changed:
                    break
            if sweep:
                # Which of their impulses are held forces and which an impact's is not known
                # yet: the bodies they pushed move by v h in this first substep (Box2D's).
                for i in range(nfresh):
                    k = int(fresh[i])
                    for j in range(ccount[k]):
                        if cln[2 * k + j] != 0.0 or clt[2 * k + j] != 0.0:
                            unheld[ca[k]] = 1.0
                            unheld[cb[k]] = 1.0

            if bias:
                # -- integrate positions (the moves since the start, and their rotations):
                # by the velocity less half the held change, exact for a held force.
                for i in range(nb):
                    if free[i] != 0.0:
                        continue
                    half = 0.5 * wheld[i] * (1.0 - unheld[i])
                    unheld[i] = 0.0
                    turn = bw[i]
                    if half == 0.0:
                        dx[i] += bvx[i] * h
                        dy[i] += bvy[i] * h
                    else:
                        hx = bvx[i] - uvx[i]
                        hy = bvy[i] - uvy[i]
                        hw = bw[i] - uw[i]
                        if hx * hx + hy * hy > threshold * threshold:  # (an impact's)
                            hx = _within(hx, bvx[i] - v0x[i])
                            hy = _within(hy, bvy[i] - v0y[i])
                            hw = _within(hw, bw[i] - v0w[i])
                        dx[i] += (bvx[i] - half * hx) * h
                        dy[i] += (bvy[i] - half * hy) * h
                        turn -= half * hw
                    if turn != 0.0:
                        dq[i] += turn * h
                        cq[i] = math.cos(dq[i])
                        sq[i] = math.sin(dq[i])
                # The rows on a face that turns, taken again where the bodies are now (for
                # the relax, the next substep and the restitution), from the first substep
                # after which they have turned (live 2): till then the rows fixed at the
                # start are right to the turn squared (a pile at rest keeps them, at their
                # cost: engine.dynamics.turning_faces, ``STILL``).
                for k in range(nc if turning else 0):
                    if live[k] == 1.0:
                        if cface[k] >= ROUND:
                            # (A disc and a static core: from the first substep after which
                            # the line between them has turned by STILL.)
                            _, nx, ny, _, _ = turned(2 * k, k, ca[k], cb[k])
                            if abs(nx * tn0y[k] - ny * tn0x[k]) >= STILL:
                                live[k] = 2.0
                        elif abs(dq[ca[k]]) + abs(dq[cb[k]]) >= STILL:
                            live[k] = 2.0
                    if live[k] == 2.0:
                        retake(k)

    # -- a cable that snapped taut faster than the threshold, and pulled in the step, brings
    # its ends back together at e times the speed they parted at (jspeed holds e).
    for k in range(nj):
        e = jspeed[k]
        if jkind[k] != DISTANCE or e == 0.0 or dhit[k] == 0.0 or drel[k] < threshold:
            continue
        a = ja[k]
        b = jb[k]
        rax = cq[a] * fax[k] - sq[a] * fay[k]
        ray = sq[a] * fax[k] + cq[a] * fay[k]
        rbx = cq[b] * fbx[k] - sq[b] * fby[k]
        rby = sq[b] * fbx[k] + cq[b] * fby[k]
        ux, uy, _ = _axis(dx, dy, cx0, cy0, k, a, b, rax, ray, rbx, rby)
        dvx, dvy = _relative(bvx, bvy, bw, a, b, rax, ray, rbx, rby)
        # Target: the anchors close at e drel, cdot = -e drel; a pull lam changes cdot by
        # -lam / m (the axial mass m).
        lam = _axial_mass(bim, bii, a, b, ux, uy, rax, ray, rbx, rby) * (
            dvx * ux + dvy * uy + e * drel[k]
        )
        new = max(jhi[k] + lam, 0.0)
        d = -(new - jhi[k])
        jhi[k] = new
        _apply(
            bvx, bvy, bw, a, b, bim[a], bii[a], bim[b], bii[b], d * ux, d * uy, rax, ray, rbx, rby
        )

    # -- the step's end: positions and angles from the moves; a free body's from the closed
    # form of its motion (module doc).
    for i in range(nb - 1):
        if free[i] != 0.0:
            dx[i] = bvx[i] * dt + 0.5 * bax[i] * dt * dt
            dy[i] = bvy[i] * dt + 0.5 * bay[i] * dt * dt
            dq[i] = bw[i] * dt + 0.5 * balpha[i] * dt * dt
            bvx[i] += bax[i] * dt
            bvy[i] += bay[i] * dt
            bw[i] += balpha[i] * dt
        bx[i] = x0[i] + dx[i]
        by[i] = y0[i] + dy[i]
        bq[i] = q0[i] + dq[i]
    # The rows on a face that turns given back as they came (their events report them so).
    for k in range(nc if turning else 0):
        if live[k] != 2.0:
            continue
        cnx[k], cny[k] = tn0x[k], tn0y[k]
        for j in range(ccount[k]):
            p = 2 * k + j
            crax[p], cray[p] = kept[4 * p], kept[4 * p + 1]
            crbx[p], crby[p] = kept[4 * p + 2], kept[4 * p + 3]
