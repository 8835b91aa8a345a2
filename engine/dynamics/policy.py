"""Which method moves a World: the name asked for, or "auto"'s choice, and its stability limit.

"auto" takes the closed form when every force is constant (exact at any dt); otherwise it
tries semi-implicit Euler, velocity Verlet and RK4 in that order (1, 2 and 4 force
evaluations a step) and takes the first that is stable at the step's dt and, with a
``tolerance``, is predicted to meet it (``engine.accuracy``). Explicit Euler is never the best:
it costs what semi-implicit Euler costs, is as accurate on drag and gravity, and is unstable on
every spring.

Whatever the method, the policy knows its limit for the springs and drags held (per body:
omega = sqrt(k / m), rate = c / m; ``engine.stability``) and warns, once per dt, when a step
would pass it.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from typing import Any

from .. import accuracy
from ..accuracy import HORIZON
from ..checks import real
from ..integrators import INTEGRATORS, Integrator, get_integrator
from ..stability import DECAY_LIMITS, OSCILLATION_LIMITS, StabilityWarning, is_stable, max_stable_dt
from .forcefield import ForceModel

__all__ = [
    "MethodPolicy",
    "METHODS",
    "AUTO_ORDER",
    "stability_pairs",
    "limit_text",
    "instability",
]

#: Every name ``World(integrator=...)`` accepts.
METHODS: tuple[str, ...] = (*INTEGRATORS, "exact", "auto")

#: The methods "auto" tries, cheapest first.
AUTO_ORDER = ("semi_implicit_euler", "velocity_verlet", "rk4")


def stability_pairs(omega: Any, rate: Any) -> list[tuple[float, float]]:
    """The distinct (omega rad/s, damping rate 1/s) pairs to check, or an envelope when many."""
    pairs = {(float(w), float(c)) for w, c in zip(omega, rate, strict=True) if w or c}
    if len(pairs) > 32:
        w_max, c_max = float(max(omega)), float(max(rate))
        pairs = {(w_max, 0.0), (0.0, c_max), (w_max, c_max)}
    return sorted(pairs)


def first_unstable(
    step: Integrator, pairs: list[tuple[float, float]], dt: float
) -> tuple[float, float] | None:
    """The first (omega, rate) pair on which ``step`` is unstable at ``dt`` (s), or None."""
    for w, c in pairs:
        if not is_stable(step, w, c, dt):
            return w, c
    return None


def limit_text(step: Integrator, name: str, w: float, c: float, dt: float) -> str:
    """One clause saying why ``name`` fails at ``dt`` on (omega w, rate c) and where it holds."""
    limit = max_stable_dt(step, w, c)
    parts = []
    if w:
        osc = OSCILLATION_LIMITS.get(name)
        parts.append(f"omega={w:.4g} rad/s, omega*dt={w * dt:.4g}")
        if osc is not None:
            parts.append("never stable on a spring" if osc == 0 else f"limit {osc:.4g}")
    if c:
        dec = DECAY_LIMITS.get(name)
        parts.append(f"damping rate={c:.4g} 1/s, rate*dt={c * dt:.4g}")
        if dec is not None:
            parts.append(f"decay limit {dec:.4g}")
    stable = "no dt is stable" if limit == 0.0 else f"stable for dt < {limit:.4g} s"
    return f"{'; '.join(parts)}; {stable}"


def check_tolerance(tolerance: Any, requested: str) -> float | None:
    """``tolerance`` as a positive finite float (m) or None; errors name it and its range."""
    if tolerance is None:
        return None
    try:
        tol = real(tolerance, "tolerance", positive=True)
    except TypeError:
        raise TypeError(
            f"tolerance must be a length in m (e.g. 1e-3) or None, got "
            f"{type(tolerance).__name__} {tolerance!r}"
        ) from None
    except ValueError:
        raise ValueError(
            f"tolerance must be a finite length > 0 m (e.g. 1e-3), got {tolerance!r}"
        ) from None
    if requested != "auto":
        raise ValueError(
            f"tolerance={tolerance!r} only applies to integrator='auto' (which picks a method to "
            f"meet it); integrator={requested!r} was given"
        )
    return tol


class MethodPolicy:
    """The method asked for (a name from METHODS or a function) and how it is applied."""

    def __init__(self, integrator: str | Integrator, tolerance: float | None) -> None:
        if isinstance(integrator, str):
            if integrator not in METHODS:
                raise ValueError(
                    f"unknown integrator {integrator!r}; valid names: {', '.join(METHODS)}"
                )
            self.custom: Integrator | None = None
        elif callable(integrator):
            self.custom = integrator
        else:
            raise TypeError(
                f"integrator must be a name ({', '.join(METHODS)}) or a function "
                f"step(x, v, accel, t, dt) -> (x, v), got {type(integrator).__name__}"
            )
        self.requested = integrator if isinstance(integrator, str) else integrator.__name__
        self.tolerance = check_tolerance(tolerance, self.requested)
        self.choice: tuple[Any, str, str] | None = None  # (key, method, reason)
        self.warned: set[Any] = set()

    def integrator(self, name: str) -> Integrator:
        """The step function behind ``name`` (the custom function, if one was given)."""
        return self.custom if self.custom is not None else get_integrator(name)

    def fixed_choice(self, model: ForceModel) -> tuple[str, str] | None:
        """(method, reason) when the choice does not depend on dt, else None."""
        if self.requested != "auto":
            return self.requested, f"integrator={self.requested!r} was asked for"
        if model.all_constant and model.springs:
            return "exact", (
                "every force is constant and every spring linear (rest length 0, on bodies "
                "that do not turn it), so the closed form is exact at any dt"
            )
        if model.all_constant:
            return "exact", "every force is constant, so the closed form is exact at any dt"
        return None

    def first_unstable(self, name: str, model: ForceModel, dt: float) -> tuple[float, float] | None:
        """The first (omega, rate) on which ``name`` is unstable at ``dt``, or None."""
        return first_unstable(self.integrator(name), stability_pairs(model.omega, model.rate), dt)

    def max_stable_dt(self, name: str, model: ForceModel) -> float:
        """The largest stable dt (s) for ``name`` on ``model``'s springs and drags."""
        if name == "exact" or (name == "auto" and model.all_constant):
            return math.inf
        if name == "auto":
            return max(self.max_stable_dt(n, model) for n in AUTO_ORDER)
        step = self.integrator(name)
        pairs = stability_pairs(model.omega, model.rate)
        return min((max_stable_dt(step, w, c) for w, c in pairs), default=math.inf)

    def predicted_error(
        self, method: str, dt: float, model: ForceModel, state: Callable[[], Any]
    ) -> float:
        """Predicted largest position error (m) over the next 1 s of steps of ``dt`` (s).

        ``state()`` gives (x, v, a) now, or None when there are no bodies.
        """
        if method == "exact":
            return 0.0 if model.all_constant else math.inf
        now = state()
        if now is None:
            return 0.0
        x, v, acc = now
        step = self.integrator(method)
        return accuracy.predicted_error(step, x, v, acc, model.omega, model.rate, dt)

    def choose(self, dt: float, model: ForceModel, state: Callable[[], Any]) -> tuple[str, str]:
        """(method, one-line reason) for a step of ``dt`` seconds."""
        fixed = self.fixed_choice(model)
        if fixed is not None:
            return fixed

        def cheapest(name: str) -> str:
            evals = INTEGRATORS[name].evaluations
            plural = "s" if evals > 1 else ""
            return f"{name} is the cheapest method ({evals} force evaluation{plural} a step)"

        stable = [name for name in AUTO_ORDER if self.first_unstable(name, model, dt) is None]
        if not stable:
            return "rk4", f"no method is stable at dt={dt:g} s; rk4 has the widest limit"
        tol = self.tolerance
        if tol is None:
            return stable[0], f"{cheapest(stable[0])} that is stable at dt={dt:g} s"
        # AUTO_ORDER is cheapest first: the first stable method predicted to meet the
        # tolerance is the cheapest that does.
        errors: dict[str, float] = {}
        for name in stable:
            errors[name] = err = self.predicted_error(name, dt, model, state)
            if err <= tol:
                return name, (
                    f"{cheapest(name)} stable at dt={dt:g} s and predicted within "
                    f"tolerance={tol:g} m over {HORIZON:g} s (error {err:.2g} m)"
                )
        best = min(errors, key=lambda n: errors[n])
        err = errors[best]
        # Global error ~ C dt^p (p the order), so dt (tol / err)^(1/p) would about meet it.
        hint = ""
        if 0.0 < err < math.inf:
            need = dt * (tol / err) ** (1.0 / INTEGRATORS[best].order)
            hint = f"; a dt near {need:.2g} s would meet it"
        return best, (
            f"no stable method meets tolerance={tol:g} m at dt={dt:g} s; {best} is the most "
            f"accurate (predicted error {err:.2g} m over {HORIZON:g} s){hint}"
        )

    def method_for(
        self, dt: float, version: int, model: ForceModel, state: Callable[[], Any]
    ) -> str:
        """The method for a step of ``dt``, chosen once per (dt, version); warns if unstable."""
        key = (dt, version)
        if self.choice is None or self.choice[0] != key:
            name, reason = self.choose(dt, model, state)
            self.choice = (key, name, reason)
            if name != "exact":
                self.warn_if_unstable(name, dt, model)
        return self.choice[1]

    def warn_if_unstable(self, name: str, dt: float, model: ForceModel) -> None:
        """Warn once per (method, dt, springs and drags held) when ``name`` is unstable at dt.

        The key is what the warning is about, not when it was made, so a World restored from
        a snapshot (which carries the keys) does not say it again.
        """
        key = (name, dt, tuple(stability_pairs(model.omega, model.rate)))
        if key in self.warned:
            return
        message = instability(self.integrator, name, model, dt, "this World")
        if message is not None:
            self.warned.add(key)
            warnings.warn(message, StabilityWarning, stacklevel=4)


def instability(
    integrator: Callable[[str], Integrator], name: str, model: ForceModel, dt: float, where: str
) -> str | None:
    """Why ``name`` blows up at ``dt`` (s) on ``model``'s springs and drags, or None if stable.

    The one stability check the World and Particles share: the message names the method, dt,
    the limit and a method that is stable at this dt, if any. ``integrator(name)`` gives the
    step function behind a name; ``where`` names what holds the forces.
    """
    pairs = stability_pairs(model.omega, model.rate)
    step = integrator(name)
    bad = first_unstable(step, pairs, dt)
    if bad is None:
        return None
    stable = [
        other
        for other in INTEGRATORS
        if other != name and first_unstable(integrator(other), pairs, dt) is None
    ]
    hopeless = max_stable_dt(step, *bad) == 0.0
    advice = "a smaller dt will not help" if hopeless else "use a smaller dt"
    if stable:
        joint = "; use" if hopeless else ", or"
        advice += f"{joint} integrator={stable[0]!r}, which is stable at this dt"
    else:
        advice += "; no integrator here is stable at this dt"
    return (
        f"{name} is unstable at dt={dt:g} s for the forces in {where} "
        f"({limit_text(step, name, bad[0], bad[1], dt)}); the run continues and will "
        f"blow up: {advice}"
    )
