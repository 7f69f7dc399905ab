"""Peak hydrodynamic loads per wave cycle of every load combination (``onbottom loads``).

For each load combination of :class:`~onbottom.checks.evaluation.StabilityInputs` the absolute
check (:func:`~onbottom.checks.design.run_checks`, F109 §3.6) gives the pipe's outer diameter,
submerged weight, the mean current over D (V*, F109 Eq 3.3) and the load reductions r_y, r_z
(F109 Eqs 3.17–3.22); :func:`~onbottom.hydro.load_envelope.load_envelope` then gives the peak
Morison drag + inertia and lift loads of every wave cycle of a random-phase record of the
combination's sea state, in V–H space (Youssef & Cassidy 2014, Fig. 4).
:mod:`onbottom.cases.stability` builds the inputs from a case file.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from onbottom.checks.design import run_checks
from onbottom.checks.evaluation import StabilityInputs, penetration_outside_validity
from onbottom.errors import InputError
from onbottom.hydro.forces import MorisonCoefficients
from onbottom.hydro.load_envelope import LoadEnvelope, load_envelope

__all__ = ["CombinationLoads", "LoadsInputs", "LoadsResult", "combination_loads"]


@dataclass(frozen=True, kw_only=True)
class LoadsInputs:
    """Built inputs of :func:`combination_loads`: the section, seabed, water and combinations
    (``checks``; their options must run the ``absolute`` check), the Morison ``coefficients``,
    whether the F109 load ``reductions`` apply (else r_y = r_z = 1) and the default random-phase
    ``seed`` [-]."""

    checks: StabilityInputs
    coefficients: MorisonCoefficients
    reductions: bool = True
    seed: int = 0


@dataclass(frozen=True)
class CombinationLoads:
    """The cycle peaks of one load combination: its ``combination`` and ``condition`` names,
    H_s ``hs`` [m], T_p ``tp`` [s], the ``envelope`` and the reductions ``r_y``, ``r_z`` [-]."""

    combination: str
    condition: str
    hs: float
    tp: float
    envelope: LoadEnvelope
    r_y: float
    r_z: float

    def as_dict(self) -> dict[str, Any]:
        """Cycles, the fraction between 20° and 45°, max H, min V [N/m], max angle [deg]."""
        e = self.envelope
        return {
            "combination": self.combination,
            "condition": self.condition,
            "hs": self.hs,
            "tp": self.tp,
            "n_cycles": e.n_cycles,
            "fraction_20_45": e.fraction_between(20.0, 45.0),
            "max_horizontal": float(e.horizontal.max()) if e.n_cycles else None,
            "min_vertical": float(e.vertical.min()) if e.n_cycles else None,
            "max_angle_deg": float(e.angle_deg.max()) if e.n_cycles else None,
            "submerged_weight": e.submerged_weight,
            "r_y": self.r_y,
            "r_z": self.r_z,
        }


@dataclass(frozen=True)
class LoadsResult:
    """Result of :func:`combination_loads`: one :class:`CombinationLoads` per combination, the
    ``seed`` used and the ``invalid`` notes (embedment outside F109's validity)."""

    combinations: tuple[CombinationLoads, ...]
    seed: int
    invalid: tuple[str, ...] = ()

    @property
    def envelopes(self) -> list[LoadEnvelope]:
        return [c.envelope for c in self.combinations]

    @property
    def success(self) -> bool:
        return not self.invalid

    @property
    def message(self) -> str:
        return "; ".join(self.invalid)


def combination_loads(
    inputs: LoadsInputs, *, duration: float, seed: int | None = None
) -> LoadsResult:
    """Cycle peak loads of every load combination in a ``duration`` [s] record.

    ``seed``: the random-phase seed (None → ``inputs.seed``). A pipe that floats in a
    combination's condition (w_s <= 0) is an :class:`~onbottom.errors.InputError` on ``pipe``.
    """
    c = inputs.checks
    seed = inputs.seed if seed is None else seed
    rows = run_checks(c.section, c.seabed, c.environment, c.combinations, c.options)
    invalid = penetration_outside_validity(rows)
    by_combo = {r.combination: r.details for r in rows if r.name == "absolute_lateral"}
    env = c.environment
    out = []
    for combo in c.combinations:
        det = by_combo[combo.name]
        if "diameter" not in det:
            err = InputError(
                f"pipe = (condition {combo.condition!r}) is invalid for combination"
                f" {combo.name!r}: the pipe floats (submerged weight"
                f" {det.get('submerged_weight', float('nan')):.4g} N/m <= 0); check the densities"
                " and the contents of that condition"
            )
            err.field = "pipe"  # type: ignore[attr-defined]
            raise err
        r_y, r_z = (det["r_y"], det["r_z"]) if inputs.reductions else (1.0, 1.0)
        ss = combo.sea_state
        e = load_envelope(
            hs=ss.hs,
            tp=ss.tp,
            depth=env.water_depth,
            diameter=det["diameter"],
            submerged_weight=det["submerged_weight"],
            current=det["v_star"],
            gamma=ss.gamma,
            spectrum=ss.spectrum,
            wave_direction_deg=ss.direction_deg,
            spreading_s=ss.spreading_s or None,
            coefficients=inputs.coefficients,
            r_y=r_y,
            r_z=r_z,
            density=env.water_density,
            duration=duration,
            seed=seed,
        )
        out.append(CombinationLoads(combo.name, combo.condition, ss.hs, ss.tp, e, r_y, r_z))
    return LoadsResult(tuple(out), seed, tuple(invalid))
