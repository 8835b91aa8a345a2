"""The World's StabilityWarning on a demo's frame, not on stderr.

A scene that records frames for a lesson is watched in its frames, not in the terminal: when
the World warns that a step is past what its solver holds (a pile deeper than its contact
iterations, a dt past a method's limit), the scene keeps the first warning, with the time it
came, and draws it. Other warnings go on to stderr as usual.
"""

from __future__ import annotations

import warnings

from engine import StabilityWarning, World

__all__ = ["Warned", "step_noting", "headline"]

#: The first StabilityWarning of a run: (World time s, the message).
Warned = tuple[float, str]


def step_noting(world: World, dt: float, first: Warned | None) -> Warned | None:
    """Step ``world`` by ``dt`` (s), keeping its StabilityWarning instead of printing it: the
    earliest of ``first`` and this step's (as (time s, message)); other warnings are shown."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", StabilityWarning)
        world.step(dt)
    for w in caught:
        if not issubclass(w.category, StabilityWarning):
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
        elif first is None or world.t < first[0]:
            first = (world.t, str(w.message))
    return first


def headline(warned: Warned) -> str:
    """A warning as one line for a frame: when, and what it says past its measured numbers
    ("the World warned at 1.37 s: this pile is past what 4 contact iterations a step can
    hold")."""
    t, message = warned
    what = message.split(": ", 1)[-1].split(";", 1)[0].strip()
    return f"the World warned at {t:.2f} s: {what}"
