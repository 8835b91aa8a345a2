"""What a frame holds: the pixel rectangles of the text, arrowheads and markers drawn on it.

The drawing helpers (``draw_text``, ``draw_arrow``, the plots' and charts' lettering) note
each label's rectangle (its ink, not the blank padding of the font's box) and each
arrowhead's, with the panel it belongs to, for the surface they draw on. The recorder clears a
surface's notes before each frame is drawn, so :func:`marks` then lists what that one frame
shows, and a test can ask of any frame: does a label cover another label or a marker, and does
a label or an arrowhead leave the frame or its panel (cut off at an edge)? See
:func:`problems`.

A panel is a rectangle that frames part of a picture (a plot, a chart, the paper Alfred walks
on): what is drawn inside ``with panel(rect):`` belongs to it and must stay within it.
Noting costs a list append per label; the notes of a surface never cleared (a game's own loop)
are capped at :data:`KEEP`.
"""

from __future__ import annotations

import weakref
from collections import deque
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass

import pygame

__all__ = ["KEEP", "MARGIN", "Mark", "clear", "copy_marks", "marks", "note", "panel", "problems"]

#: The most notes kept per surface (a surface no recorder clears keeps its latest ones).
KEEP = 4096


@dataclass(frozen=True)
class Mark:
    """One thing drawn: its ``kind`` ("text", "arrowhead", "marker" or "panel": a plot's or a
    chart's box), pixel ``rect``, the ``text`` of a label ("" otherwise) and the ``panel`` it
    was drawn in (None: the frame)."""

    kind: str
    rect: pygame.Rect
    text: str = ""
    panel: pygame.Rect | None = None

    def __str__(self) -> str:
        what = f"{self.kind} {self.text!r}" if self.text else self.kind
        r = self.rect
        return f"{what} at ({r.x}, {r.y}, {r.w}, {r.h})"


_notes: weakref.WeakKeyDictionary[pygame.Surface, deque[Mark]] = weakref.WeakKeyDictionary()
_panels: list[pygame.Rect] = []


def note(surface: pygame.Surface, kind: str, rect: pygame.Rect, text: str = "") -> None:
    """Note that ``kind`` ("text", "arrowhead", "marker") was drawn on ``surface`` at ``rect``."""
    if rect.w <= 0 or rect.h <= 0:
        return
    kept = _notes.get(surface)
    if kept is None:
        kept = _notes[surface] = deque(maxlen=KEEP)
    kept.append(Mark(kind, pygame.Rect(rect), text, _panels[-1] if _panels else None))


def marks(surface: pygame.Surface) -> list[Mark]:
    """What was noted on ``surface`` since it was last cleared, in drawing order."""
    return list(_notes.get(surface, ()))


def clear(surface: pygame.Surface) -> None:
    """Forget the notes of ``surface`` (the recorder does so before each frame)."""
    _notes.pop(surface, None)


def copy_marks(source: pygame.Surface, target: pygame.Surface, offset: tuple[int, int]) -> None:
    """Note on ``target`` what ``source`` holds, moved by ``offset`` (after blitting it there)."""
    dx, dy = offset
    for m in marks(source):
        moved = m.panel.move(dx, dy) if m.panel is not None else None
        kept = _notes.get(target)
        if kept is None:
            kept = _notes[target] = deque(maxlen=KEEP)
        kept.append(Mark(m.kind, m.rect.move(dx, dy), m.text, moved))


@contextmanager
def panel(rect: pygame.Rect | Sequence[int]) -> Iterator[pygame.Rect]:
    """What is drawn inside the ``with`` block belongs to the panel ``rect`` (px)."""
    box = pygame.Rect(rect)
    _panels.append(box)
    try:
        yield box
    finally:
        _panels.pop()


#: The margin (px) a label or an arrowhead keeps from the frame's and its panel's edges: one
#: that touches the edge looks cut.
MARGIN = 2


def problems(
    surface: pygame.Surface, found: Sequence[Mark] | None = None, overlap_ok: Sequence[str] = ()
) -> list[str]:
    """What is wrong with a frame's marks, in words (empty when nothing is).

    A label that overlaps another label or a marker, or is drawn over an arrowhead, or lies on
    (or under) a panel it is not part of; a label or
    an arrowhead that is not wholly inside the frame, or inside its panel, :data:`MARGIN` px
    from the edge. (An arrow drawn over a label, as a moving arrow crosses an axis's numbers,
    is motion, not layout: allowed.) Labels whose text contains one of ``overlap_ok`` may
    overlap (where overlap is the point, e.g. a strobe's trail of labels).
    """
    found = marks(surface) if found is None else found
    frame = surface.get_rect().inflate(-2 * MARGIN, -2 * MARGIN)
    out: list[str] = []
    for m in found:
        if m.kind in ("marker", "panel"):
            continue
        if not frame.contains(m.rect):
            out.append(f"{m} leaves the frame {tuple(surface.get_rect())}")
        elif m.panel is not None and not m.panel.inflate(-2, -2).contains(m.rect):
            out.append(f"{m} leaves its panel {tuple(m.panel)}")
    panels = [(j, m.rect) for j, m in enumerate(found) if m.kind == "panel"]
    for i, a in enumerate(found):
        if a.kind != "text" or any(word in a.text for word in overlap_ok):
            continue
        for j, box in panels:
            # Words drawn on a panel after it, wholly inside it, are its own (a plot's notes);
            # words under a panel (drawn before it), or across its edge, are not.
            if a.panel == box or not a.rect.colliderect(box):
                continue
            if j > i:
                out.append(f"{a} is covered by the panel {tuple(box)} drawn after it")
            elif not box.inflate(-2, -2).contains(a.rect):
                out.append(f"{a} crosses the edge of the panel {tuple(box)}")
        for j, b in enumerate(found):
            if j == i or not a.rect.colliderect(b.rect):
                continue
            if b.kind == "text" and j > i and not any(word in b.text for word in overlap_ok):
                out.append(f"{a} overlaps {b}")
            elif b.kind == "marker" or (b.kind == "arrowhead" and j < i):
                out.append(f"{a} overlaps {b}")
    return out
