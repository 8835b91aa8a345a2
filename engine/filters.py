"""Which pairs of bodies may collide: pymunk's shape filter (a group and category bits).

Two bodies collide unless a :class:`Filter` turns the pair off:

* the same nonzero ``group``: never (the parts of one thing, the balls of one pour);
* ``a.categories & b.mask == 0`` or ``b.categories & a.mask == 0``: never (a body can say
  which categories it is in and which it meets, 32 bits each).

Bodies of radius 0 (points) never collide with each other, whatever their filters: the
fireworks' sparks stay free particles.

>>> Filter(group=1).collides(Filter(group=1))
False
>>> Filter(categories=0b01, mask=0b10).collides(Filter(categories=0b10, mask=0b01))
True
>>> Filter(categories=0b01, mask=0b01).collides(Filter(categories=0b10))
False
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

__all__ = ["Filter", "ALL_CATEGORIES", "ALL_MASKS", "as_filter"]

#: Every category bit (pymunk's ``ShapeFilter.ALL_CATEGORIES()``, 32 bits).
ALL_CATEGORIES = 0xFFFFFFFF
#: A mask that meets every category (pymunk's ``ShapeFilter.ALL_MASKS()``).
ALL_MASKS = ALL_CATEGORIES


def _bits(value: Any, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise TypeError(f"Filter {name} must be an int, got {type(value).__name__} {value!r}")
    if not 0 <= value <= ALL_CATEGORIES:
        raise ValueError(f"Filter {name} must be in [0, 0xFFFFFFFF] (32 bits), got {value!r}")
    return value


@dataclass(frozen=True)
class Filter:
    """A body's collision filter: ``group`` (0: none), ``categories`` and ``mask`` (32 bits)."""

    group: int = 0
    categories: int = ALL_CATEGORIES
    mask: int = ALL_CATEGORIES

    def __post_init__(self) -> None:
        if isinstance(self.group, bool) or not isinstance(self.group, int):
            raise TypeError(
                f"Filter group must be an int (0: no group), got "
                f"{type(self.group).__name__} {self.group!r}"
            )
        if self.group < 0:
            raise ValueError(f"Filter group must be >= 0 (0: no group), got {self.group!r}")
        _bits(self.categories, "categories")
        _bits(self.mask, "mask")

    def collides(self, other: Filter) -> bool:
        """True if a body with this filter may collide with one with ``other``."""
        if self.group and self.group == other.group:
            return False
        return bool(self.categories & other.mask) and bool(other.categories & self.mask)


#: The filter of a body given none: no group, every category, meets every category.
DEFAULT = Filter()


def as_filter(value: Any) -> Filter:
    """``value`` if it is a Filter; else a TypeError that says what a ``filter`` must be."""
    if not isinstance(value, Filter):
        raise TypeError(
            f"filter must be an engine.Filter (group, categories, mask), got "
            f"{type(value).__name__} {value!r}"
        )
    return value
