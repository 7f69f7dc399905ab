"""A closed-form campaign model for verification: a pipe held by friction alone.

Inputs ``friction_coefficient`` μ [-] and ``load`` F [N/m] (a static lateral load) on a pipe of
submerged weight W [N/m]; the "displacement" output is the utilisation Y = F(1 + s ε)/(μ W),
with ε ~ N(0, 1) drawn from the run's seed (``numpy.random.default_rng(seed)``): s = 0 is the
friction-only pipe of ``docs/theory/reliability.md`` (P[Y > 1] in closed form), s > 0 adds a
seed-borne scatter like a storm's random phases, with P[Y > 1] = E_ε[Φ(−β(ε))] by quadrature
(:meth:`FrictionModel.exact_probability`). ``delay`` [s] makes each run sleep (kill/resume
tests and benchmarks of the campaign's overhead).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from scipy import integrate, special

__all__ = ["FrictionModel"]


@dataclass(frozen=True)
class FrictionModel:
    """Friction-only pipe with an optional seed-borne scatter (module docstring).

    Parameters
    ----------
    weight : float
        W [N/m], > 0.
    scatter : float
        s [-], ≥ 0.
    delay : float
        Sleep per run [s], ≥ 0.
    """

    weight: float = 1500.0
    scatter: float = 0.0
    delay: float = 0.0

    input_names = ("friction_coefficient", "load")
    output_names = ("max_displacement",)

    def identity(self) -> str:
        return f"FrictionModel(weight={self.weight!r}, scatter={self.scatter!r})"

    def __call__(self, x: np.ndarray, seed: int) -> dict[str, float]:
        if self.delay:
            time.sleep(self.delay)
        mu, f = float(x[0]), float(x[1])
        eps = float(np.random.default_rng(int(seed)).standard_normal()) if self.scatter else 0.0
        return {"max_displacement": f * (1.0 + self.scatter * eps) / (mu * self.weight)}

    def exact_probability(self, mu: tuple[float, float], load: tuple[float, float]) -> float:
        """P[Y > 1] for μ ~ N(mean, std) and F ~ N(mean, std) (independent)."""
        (mm, ms), (fm, fs) = mu, load
        w = self.weight

        def p(eps: float) -> float:
            k = 1.0 + self.scatter * eps
            beta = (mm * w - fm * k) / math.hypot(ms * w, fs * k)
            return float(special.ndtr(-beta))

        if not self.scatter:
            return p(0.0)
        val, _ = integrate.quad(
            lambda e: p(e) * math.exp(-0.5 * e * e) / math.sqrt(2.0 * math.pi),
            -9.0,
            9.0,
            epsabs=1e-14,
            epsrel=1e-10,
        )
        return float(val)
