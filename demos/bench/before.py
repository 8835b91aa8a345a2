"""The World with no colliders against the same World before the soft step, side by side.

Run with ``python -m demos.bench before``. The soft step for piles (commit dc40160) added work
to every step of a World with bodies; a World with no colliders, whose bodies do not collide
with each other, should not pay for it (target: as fast as before, within 5%).
This topic times the same scene on the engine of this checkout and on the engine of the
commit before the rework (``a097264``, taken out with ``git archive`` into a temporary
folder), each in a fresh Python process, the two alternating round by round so that a burst
of load hits both alike; each process reports the median CPU time of a step over 15 batches
of 200 steps. The scene: 1,000 balls of radius 0.1 m in one filter group (they never meet)
under gravity, integrator "auto" (the closed form), dt = 1/120 s, no colliders: the balls
of ``demos.bench contacts`` without their box.

Needs git and the commit in the repository (a shallow clone may lack it: then it says so).
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

__all__ = ["BEFORE", "SCRIPT", "step_time", "report"]

#: The commit before the soft step (dc40160): the engine "before".
BEFORE = "a097264"
ROOT = Path(__file__).resolve().parents[2]

#: What each process runs: only the engine's public API, the same at both commits.
SCRIPT = """
import statistics, time, timeit
import numpy as np
from engine import Body, Filter, Vector, World
from engine.forces import Gravity
rng = np.random.default_rng(1)
pos = rng.uniform((1.0, 1.0), (39.0, 29.0), (1000, 2))
vel = rng.uniform(-10.0, 10.0, (1000, 2))
world = World(integrator="auto")
world.add_force(Gravity((0.0, -9.81)))
world.add_all(
    Body(Vector(*p), Vector(*v), Vector(0, 0), radius=0.1, filter=Filter(group=1))
    for p, v in zip(pos.tolist(), vel.tolist())
)
world.step(1 / 120)
runs = [
    timeit.timeit(lambda: world.step(1 / 120), number=200, timer=time.process_time) / 200
    for _ in range(15)
]
print(statistics.median(runs))
"""


def step_time(folder: Path) -> float:
    """Seconds of CPU a step, measured in a fresh process on the engine under ``folder``."""
    done = subprocess.run(
        [sys.executable, "-c", SCRIPT],
        cwd=folder,
        env={**os.environ, "PYTHONPATH": str(folder)},
        capture_output=True,
        text=True,
        check=True,
    )
    return float(done.stdout.strip())


def _export(commit: str, folder: Path, repo: Path) -> str | None:
    """Write ``commit``'s engine/ from the git repository ``repo`` into ``folder``; None, or
    why it could not."""
    try:
        archive = subprocess.run(
            ["git", "-C", str(repo), "archive", "--format=tar", commit, "engine"],
            capture_output=True,
            check=False,
        )
    except OSError as error:
        return f"git could not run ({error})"
    if archive.returncode != 0:
        return f"git archive {commit} failed: {archive.stderr.decode(errors='replace').strip()}"
    path = folder / "engine.tar"
    path.write_bytes(archive.stdout)
    with tarfile.open(path) as tar:
        tar.extractall(folder, filter="data")
    return None


def report(quick: bool = False, before: str = BEFORE, repo: Path = ROOT) -> str:
    """Time the no-collider World here and at ``before`` (a commit of ``repo``), alternating;
    return the text."""
    rounds = 2 if quick else 6
    with tempfile.TemporaryDirectory(prefix="bench-before-") as tmp:
        why = _export(before, Path(tmp), repo)
        if why is not None:
            return f"before: not measured: {why}"
        now: list[float] = []
        then: list[float] = []
        for _ in range(rounds):
            then.append(step_time(Path(tmp)))
            now.append(step_time(ROOT))
    a, b = statistics.median(now), statistics.median(then)
    ratio = a / b
    verdict = "met" if ratio <= 1.05 else "NOT met"
    return "\n".join(
        [
            "before: 1,000 balls, no colliders, dt = 1/120 s: CPU time a step, medians of "
            f"{rounds} alternating processes",
            f"  this checkout {a * 1e6:.2f} us, {before} (before the soft step) {b * 1e6:.2f} us:"
            f" {ratio:.2f}x (target: within 5%: {verdict}); rounds: "
            + ", ".join(f"{x / y:.2f}" for x, y in zip(now, then, strict=True)),
        ]
    )
