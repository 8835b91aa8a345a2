"""A headless 2D physics engine for particles, balls and crates, grown from lesson 1.

>>> from engine import Vector, Body, World
>>> from engine.forces import Gravity
>>> world = World()
>>> ball = world.add(Body(Vector(0, 0), Vector(3, 4), Vector(0, 0), mass=0.5))
>>> _ = world.add_force(Gravity((0, -9.81)))
>>> world.step(1 / 60)
>>> round(world.t, 6)
0.016667

``import engine`` never imports pygame; drawing lives in ``engine.render``.
"""

from . import filters, forces, integrators, kernels, kinematics, stability
from .body import Body
from .dynamics import events, joints, links
from .dynamics.constraints import (
    GearJoint,
    GrooveJoint,
    RatchetJoint,
    RotaryLimitJoint,
    SimpleMotor,
    SlideJoint,
)
from .dynamics.events import ContactEvent
from .dynamics.joints import Hinge, Weld
from .dynamics.links import Cable, Link, Pin, Rod
from .dynamics.mouse_joint import MouseJoint
from .dynamics.springs import DampedRotarySpring, DampedSpring
from .exact import contacts
from .filters import Filter
from .geometry import colliders
from .geometry.colliders import Box, Circle, Collider, Plane, Polygon, Segment
from .loop import FixedStep, RealClock, Steppable, VirtualClock
from .pipeline.solver_choice import SolverWarning
from .stability import SimulationDiverged, StabilityWarning
from .vector import Vector
from .world import OverlapWarning, QueryHit, World

__all__ = [
    "Vector",
    "Body",
    "World",
    "Plane",
    "Segment",
    "Circle",
    "Box",
    "Polygon",
    "Collider",
    "ContactEvent",
    "Filter",
    "Rod",
    "Cable",
    "Pin",
    "Link",
    "Hinge",
    "Weld",
    "SlideJoint",
    "GrooveJoint",
    "GearJoint",
    "RatchetJoint",
    "RotaryLimitJoint",
    "SimpleMotor",
    "DampedSpring",
    "DampedRotarySpring",
    "MouseJoint",
    "QueryHit",
    "OverlapWarning",
    "FixedStep",
    "VirtualClock",
    "RealClock",
    "Steppable",
    "SolverWarning",
    "StabilityWarning",
    "SimulationDiverged",
    "colliders",
    "kernels",
    "contacts",
    "events",
    "filters",
    "forces",
    "integrators",
    "joints",
    "kinematics",
    "links",
    "stability",
]

__version__ = "0.1.0"
