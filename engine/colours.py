"""A body's or a collider's colour for drawing (``body.colour``, ``peg.colour``): checked here,
resolved by the renderer.

A colour is what pygame takes: an (r, g, b) or (r, g, b, a) tuple of ints 0 to 255 (a
``pygame.Color`` is one), a colour name pygame knows (``"red"``, ``"gold"``) or a hex string
(``"#ff8800"``); None (the default) keeps ``draw_world``'s own colours (a body in blue, asleep
in grey, moved by the game in vermillion; a collider in ink). A tuple is checked when it is
set; a name is kept as written, and ``draw_world`` says which body or collider holds a name
pygame does not know (this module imports no pygame, as the engine's core does not).

The spelling is British, as every colour in the engine's drawing code (pymunk's ``color``
points here). A colour is the game's, not the physics': a snapshot does not keep it.

>>> as_colour((255, 0, 0))
(255, 0, 0)
>>> as_colour("red"), as_colour(None)
('red', None)
"""

from __future__ import annotations

from typing import Any

__all__ = ["Colour", "as_colour", "COLOR_ADVICE"]

#: A colour as kept: a tuple of 3 or 4 ints 0 to 255, a pygame colour name or hex string, or
#: None for draw_world's own.
Colour = tuple[int, ...] | str | None

#: What pymunk's spelling ``color`` is told.
COLOR_ADVICE = (
    "the engine spells it colour (British, as all its drawing names): write .colour = "
    "(255, 0, 0) or .colour = 'red' (None: draw_world's own colours)"
)


def as_colour(value: Any, name: str = "colour") -> Colour:
    """``value`` as a colour to keep (module doc); a TypeError or ValueError naming ``name``
    and what would be valid otherwise."""
    if value is None or isinstance(value, str):
        if isinstance(value, str) and not value.strip():
            raise ValueError(
                f"{name} must be a colour: a pygame colour name such as 'red', a hex string "
                f"such as '#ff8800', or an (r, g, b) tuple of ints 0 to 255, got {value!r}"
            )
        return value
    try:
        parts = tuple(value)
    except TypeError:
        parts = None
    ok = parts is not None and len(parts) in (3, 4)
    ok = ok and all(isinstance(c, int) and not isinstance(c, bool) for c in parts or ())
    if not ok or not all(0 <= c <= 255 for c in parts or ()):
        raise (ValueError if parts is not None and ok else TypeError)(
            f"{name} must be an (r, g, b) or (r, g, b, a) tuple of ints 0 to 255, a pygame "
            f"colour name such as 'red' or a hex string such as '#ff8800' (None: draw_world's "
            f"own), got {type(value).__name__} {value!r}"
        )
    return tuple(int(c) for c in parts)  # type: ignore[union-attr]
