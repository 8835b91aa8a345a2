"""Bodies found inside a solid collider: pushed out to its surface, with an OverlapWarning.

A body gets inside a collider when it starts there (added, or a collider added over it), is
put there (its ``pos`` written), or is freed there (the link that held it taken out). The
World moves it to the nearest place outside every solid collider (engine.exact.push_out) and says
so, naming both, so that a scene built wrong is not silently changed.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from ..body import Body

if TYPE_CHECKING:
    from ..dynamics.links import Link
    from ..dynamics.store import BodyStore
    from .contacts import Contacts

__all__ = ["OverlapWarning", "PushState", "push_out", "freed"]


class OverlapWarning(UserWarning):
    """A body started inside a collider and was pushed out to its surface."""


class PushState(Protocol):
    """What pushing bodies out reads and writes of a World's state (``WorldState``)."""

    # engine.pipeline.world_state imports this module (a body put inside a collider is pushed out as
    # it is written), so the state is named by these members of it, not by its class.

    @property
    def store(self) -> BodyStore | None:
        """The body arrays (engine.dynamics.store), or None before the first body."""
        ...

    @property
    def contacts(self) -> Contacts | None:
        """The static contacts (engine.exact.contacts), or None before the first collider."""
        ...

    @property
    def bodies(self) -> list[Body]:
        """The bodies, in the order of the arrays' rows."""
        ...

    @property
    def links(self) -> list[Link]:
        """The links and joints held."""
        ...

    @property
    def world(self) -> Any:
        """The World this is the state of (what ``Body.world`` answers)."""
        ...

    def state_written(self, row: int | None = None, moved: bool = False) -> None:
        """A position or velocity was set by hand (of ``row``, or of the World as a whole)."""
        ...


def push_out(
    state: PushState, rows: Iterable[int], how: str = "started", stacklevel: int = 3
) -> None:
    """Push the bodies in ``rows`` out of every solid collider, to the nearest place
    outside all of them, warning for each (``how`` it got inside: "started", "was put").
    A body pushed out rests on nothing until it lands again. ``stacklevel`` counts from the
    caller of this function, as ``warnings.warn``'s does."""
    contacts, store = state.contacts, state.store
    assert contacts is not None and store is not None
    idx = np.fromiter(rows, dtype=np.intp)
    idx = idx[~store.kinematic[idx]]  # walls do not hold what the game moves
    # (A body with a shape other than a disc is held out by its contacts: engine.geometry.shaped.)
    idx = idx[store.round(idx)]
    if not len(idx):
        return
    x, v = store.x[idx], store.v[idx]
    contacts.set_body_filters(store.group, store.categories, store.mask)
    moved = contacts.push_out(x, v, store.radius[idx], idx)
    if not moved:
        return
    store.x[idx], store.v[idx], store.prev_x[idx] = x, v, x
    contacts.rest[idx[[i for i, _ in moved]]] = -1
    state.state_written()
    # Those still inside (no place near them is outside every collider: three faces at once):
    # pushed again, on copies, they would move again.
    stuck = {i for i, _ in contacts.push_out(x.copy(), v.copy(), store.radius[idx], idx)}
    for i, k in moved[:10]:
        body = state.bodies[int(idx[i])]
        warnings.warn(
            f"{body!r} {how} inside {contacts.colliders[k]!r}; "
            + (
                "no place near it is outside every solid collider: it was left overlapping, "
                "for the steps to push it out; move it to a free place"
                if i in stuck
                else "it was pushed out to the nearest place outside every solid collider"
            ),
            OverlapWarning,
            stacklevel=stacklevel,
        )


def freed(state: PushState, bodies: list[Body], stacklevel: int = 4) -> None:
    """Bodies whose links were taken out: one no longer linked to anything that a link
    held inside a collider (links act after the contacts; a pin holds a body where a
    collider is added) is pushed out, as a teleport is."""
    store = state.store
    if state.contacts is None or store is None:
        return
    linked = {id(b) for k in state.links for b in k.bodies}
    rows = [
        store.row(b.slot)
        for b in bodies
        if b.world is state.world and not b.kinematic and id(b) not in linked
    ]
    if rows:
        push_out(state, rows, "was freed", stacklevel=stacklevel)
