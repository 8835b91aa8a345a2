"""A joint's impulses of its last step, put on it when first read.

A joint reports what it did in the last step (``Hinge.linear_impulse`` in N s, a rod's
``impulse``, ...). The exact models write those values as they solve. The soft step solves a
game's joints sixty times a second, and a game reads them seldom (a rope's tension to break it,
once in a while), so it leaves them pending: one ``Pending`` a step holds the solver's
impulses for all its joints, and the first read or write of any of their reported values puts
every one of them on its joint (``Pending.fill``). What a read returns is the same either way.

A reported value is a ``Reported`` descriptor on the joint's class, kept in a slot of the same
name with a leading underscore; the joint's ``_pending`` slot holds the step's ``Pending``
(None once filled). A joint copied or pickled takes its values filled, and no ``Pending``
(``reported_state``, its class's ``__getstate__``): a copy is no joint of the step's.
"""

from __future__ import annotations

from typing import Any, Generic, TypeVar, overload

__all__ = ["Pending", "Reported", "reported_state"]

T = TypeVar("T")


class Pending:
    """A step's impulses not yet put on its joints: ``fill`` puts them."""

    __slots__ = ()

    def fill(self) -> None:
        """Put every joint's values on it and clear each one's ``_pending``."""
        raise NotImplementedError


class Reported(Generic[T]):
    """A joint's value of its last step (its class's slot ``_<name>``), read after any
    pending step's values are put on the joint (module doc)."""

    def __init__(self, doc: str) -> None:
        """``doc``: what the value is, in its units."""
        self.__doc__ = doc
        self._slot: Any = None

    def __set_name__(self, owner: type, name: str) -> None:
        # The slot's member descriptor, read and written directly (no getattr by name).
        self._slot = owner.__dict__["_" + name]

    @overload
    def __get__(self, obj: None, owner: type | None = None) -> Reported[T]: ...

    @overload
    def __get__(self, obj: object, owner: type | None = None) -> T: ...

    def __get__(self, obj: object | None, owner: type | None = None) -> T | Reported[T]:
        if obj is None:
            return self
        pending = obj._pending  # type: ignore[attr-defined]
        if pending is not None:
            pending.fill()
        value: T = self._slot.__get__(obj, owner)
        return value

    def __set__(self, obj: object, value: T) -> None:
        pending = obj._pending  # type: ignore[attr-defined]
        if pending is not None:
            pending.fill()  # (the step's other values stay as it reported them)
        self._slot.__set__(obj, value)


def reported_state(obj: Any) -> tuple[None, dict[str, Any]]:
    """A joint's state for ``copy`` and ``pickle`` (its class's ``__getstate__``): every slot's
    value, the pending step's values put on it first, and no ``Pending`` kept (a copy is not
    one of the step's joints, so a ``Pending`` would never fill it)."""
    pending = obj._pending
    if pending is not None:
        pending.fill()
    state: dict[str, Any] = {}
    for cls in type(obj).__mro__:
        slots = cls.__dict__.get("__slots__", ())
        for name in (slots,) if isinstance(slots, str) else slots:
            try:
                state[name] = cls.__dict__[name].__get__(obj, cls)
            except AttributeError:
                continue  # a slot never set
    state["_pending"] = None
    return None, state
