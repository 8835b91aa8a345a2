"""A scene whose snapshot is its World's plus a few read-outs of its own (``kept``)."""

from __future__ import annotations

from typing import Any


class KeptReadouts:
    """Mixin for a scene with a ``world``: ``snapshot`` and ``restore`` carry the World's state
    and the attributes named in ``kept`` (read-outs the scene measures beside its World)."""

    world: Any
    #: The scene's own read-outs (beside its World) that a snapshot keeps.
    kept: tuple[str, ...] = ()

    def snapshot(self) -> tuple[Any, ...]:
        return self.world.snapshot(), tuple(getattr(self, name) for name in self.kept)

    def restore(self, snapshot: tuple[Any, ...]) -> None:
        world, kept = snapshot
        self.world.restore(world)
        for name, value in zip(self.kept, kept, strict=True):
            setattr(self, name, value)
