"""One storm on a pipe section as a campaign model: inputs → maximum lateral displacement.

:class:`StormModel` maps a row of inputs and a seed to one run of
:func:`onbottom.dynamics.storm_section.simulate_storm_section` (summary only). The row holds,
in :attr:`StormModel.input_names` order:

* the sea state: with a storm climate (:class:`~onbottom.reliability.climate.StormClimate`),
  its standard normal ``u_hs``, ``u_tp`` (and ``u_direction``: the sector, whose centre minus
  ``pipe_heading_deg`` is the wave direction to the pipe axis, the convention of
  ``onbottom metocean``'s case tables; and ``u_current`` when the climate carries the
  hindcast's current model: the current speed at the case's reference height — the hindcast's
  current must be given at that height — and, with sectors, the current's direction set to the
  waves' (co-linear, pushing the pipe the same way, as F109 §3.4.2's combinations assume));
  without a climate, ``hs`` [m] and ``tp`` [s] themselves;
* any of :data:`PHYSICAL_INPUTS`: ``direction_deg`` (waves to the pipe axis [deg]),
  ``current_velocity`` [m/s] (at the case's reference height), ``current_direction_deg``
  [deg], ``friction_coefficient`` [-], ``submerged_unit_weight`` [N/m³] (sand and clay: the
  soil model is rebuilt from the seabed with the drawn values).

Everything else comes from the storm case (``StormSetup``): pipe, soil model kind, water depth,
roughness, force model, reductions, solver settings, and the storm's shape (build-up, peak and
decay durations, spectrum, γ, spreading). The peak sea state is the drawn one.

Outputs: ``max_displacement``, ``final_displacement`` [m], the sea state used (``hs`` [m],
``tp`` [s], ``direction_deg`` [deg], ``current_velocity`` [m/s]), ``max_penetration`` [m],
``n_steps``, ``stopped_early`` (1 when the storm stopped at :attr:`StormModel.stop_at`, before
the case's own runaway stop; its ``max_displacement`` is then the displacement at the stop, a
lower bound of the whole storm's); status as the solver's (1 end, 2 runaway stop, 3 lift-off
stop, < 0 numerical).

Early stop: a campaign that only asks whether a storm exceeds some limits sets ``stop_at``
just above the largest of them. A storm that reaches it exceeds every limit whatever it does
afterwards, and a storm that does not runs exactly as without the stop (the solver checks the
stop after each committed step), so every exceedance verdict equals the full run's.
"""

from __future__ import annotations

import hashlib
import math
import pickle
from dataclasses import dataclass, replace
from functools import cached_property
from typing import Any

import numpy as np

from onbottom._version import __version__, short_hash
from onbottom.errors import InputError
from onbottom.reliability.climate import StormClimate

__all__ = ["PHYSICAL_INPUTS", "StormModel"]

PHYSICAL_INPUTS: dict[str, str] = {
    "hs": "m",
    "tp": "s",
    "direction_deg": "deg",
    "current_velocity": "m/s",
    "current_direction_deg": "deg",
    "friction_coefficient": "1",
    "submerged_unit_weight": "N/m3",
}
"""Inputs a row may set (name → unit)."""

OUTPUTS = (
    "max_displacement",
    "final_displacement",
    "hs",
    "tp",
    "direction_deg",
    "current_velocity",
    "max_penetration",
    "n_steps",
    "stopped_early",
)


@dataclass(frozen=True)
class StormModel:
    """A storm section run as a function of its uncertain inputs (module docstring).

    Parameters
    ----------
    setup : onbottom.dynamics.storm_setup.StormSetup
        The storm case (a spectral storm: ``setup.storm`` is a ``Storm``).
    inputs : tuple of str
        Names of the non-climate inputs, each in :data:`PHYSICAL_INPUTS`.
    climate : StormClimate or None
        The long-term sea-state model; None: ``hs`` and ``tp`` must be among ``inputs``.
    pipe_heading_deg : float
        Pipe axis heading [deg from north] (sectors only).
    soil_kind : str or None
        ``[seabed].model`` of the case (sand, calcareous, clay, rock, coulomb) to rebuild the
        soil model with drawn soil inputs; None: sand for Verley & Sotberg, clay for Verley &
        Lund, else Coulomb.
    stop_at : float or None
        Lateral displacement [m] at which a storm stops (module docstring, early stop), > 0;
        None: only the case's own runaway stop (``max_displacement_over_d``).
    """

    setup: Any
    inputs: tuple[str, ...] = ()
    climate: StormClimate | None = None
    pipe_heading_deg: float = 0.0
    soil_kind: str | None = None
    stop_at: float | None = None

    def __post_init__(self) -> None:
        from onbottom.inputs.storm import Storm

        if self.stop_at is not None and not (math.isfinite(self.stop_at) and self.stop_at > 0):
            raise InputError(f"StormModel.stop_at = {self.stop_at!r} is invalid: give a > 0 [m]")

        if not isinstance(self.setup.storm, Storm):
            raise InputError(
                "storm.kind is invalid for a reliability campaign: a spectral storm is needed"
                " (its sea state is drawn)"
            )
        for n in self.inputs:
            if n not in PHYSICAL_INPUTS:
                raise InputError(
                    f"reliability input {n!r} is invalid: one of {', '.join(PHYSICAL_INPUTS)}"
                )
        if len(set(self.inputs)) != len(self.inputs):
            raise InputError(f"reliability inputs = {self.inputs!r} is invalid: repeated names")
        if self.climate is None and not {"hs", "tp"} <= set(self.inputs):
            raise InputError(
                "reliability inputs are invalid: without a climate (hindcast) hs and tp must be"
                " given as distributions"
            )
        if self.climate is not None and {"hs", "tp"} & set(self.inputs):
            raise InputError(
                "reliability inputs are invalid: hs/tp come from the climate (hindcast); remove"
                " them from [reliability.inputs]"
            )
        if self.climate is not None and self.climate.sectors and "direction_deg" in self.inputs:
            raise InputError(
                "reliability inputs are invalid: direction_deg comes from the climate's sectors"
            )
        if (
            self.climate is not None
            and self.climate.current is not None
            and "current_velocity" in self.inputs
        ):
            raise InputError(
                "reliability inputs are invalid: current_velocity comes from the hindcast's"
                " current model (reliability.climate.current = true); remove it from"
                " [reliability.inputs]"
            )

    @cached_property
    def _climate_names(self) -> tuple[str, ...]:
        """Names of the climate's standard normal inputs (made once: every run reads them)."""
        return tuple(p.name for p in self.climate.parameters()) if self.climate else ()

    @property
    def input_names(self) -> tuple[str, ...]:
        """Columns of a row: the climate's standard normals first, then :attr:`inputs`."""
        return self._climate_names + tuple(self.inputs)

    @property
    def output_names(self) -> tuple[str, ...]:
        return OUTPUTS

    @property
    def diameter(self) -> float:
        """Pipe outer diameter D [m]."""
        return float(self.setup.pipe.outer_diameter)

    def identity(self) -> str:
        """onbottom's version and content hash, the input names and a hash of the pickled
        case objects (the climate fitted to the hindcast included)."""
        s = self.setup
        blob = pickle.dumps(
            (
                s.pipe,
                s.seabed,
                type(s.soil).__name__,
                s.storm.with_seed(0),
                s.depth,
                s.current,
                s.z0,
                s.force_model,
                s.reductions,
                s.settings,
                s.sample_interval,
                self.climate,
                self.pipe_heading_deg,
                self.soil_kind,
                self.stop_at,
            )
        )
        digest = hashlib.blake2b(blob, digest_size=16).hexdigest()
        return (
            f"onbottom {__version__} (content {short_hash()}); StormModel {self.input_names};"
            f" case {digest}"
        )

    def sea_state(self, x: np.ndarray) -> dict[str, float]:
        """hs [m], tp [s], direction_deg [deg] of a row, and ``current_velocity`` [m/s] and
        ``current_direction_deg`` [deg] when the climate draws the current."""
        row = dict(zip(self.input_names, np.asarray(x, dtype=float).tolist(), strict=True))
        peak = self.setup.storm.stages[0] if self.setup.storm.stages else None
        direction = row.get("direction_deg", peak.direction_deg if peak else 90.0)
        if self.climate is not None:
            c = self.climate
            u = np.array([[row[name] for name in self._climate_names]])
            ss = c.sea_state(u)
            hs, tp = float(ss["hs"][0]), float(ss["tp"][0])
            k = int(ss["sector"][0])
            if k >= 0:
                direction = (c.sector_centres_deg[k] - self.pipe_heading_deg) % 360.0
            if c.current is not None:
                cur_dir = float(direction) if k >= 0 else self.setup.current.direction_deg
                return {
                    "hs": hs,
                    "tp": tp,
                    "direction_deg": float(direction),
                    "current_velocity": float(ss["current"][0]),
                    "current_direction_deg": float(cur_dir),
                }
        else:
            hs, tp = row["hs"], row["tp"]
        return {"hs": hs, "tp": tp, "direction_deg": float(direction)}

    def build(self, x: np.ndarray, seed: int):
        """(soil, storm, current) of a row."""
        from onbottom.inputs.storm import Storm
        from onbottom.soil.registry import soil_model_for_seabed

        s = self.setup
        row = dict(zip(self.input_names, np.asarray(x, dtype=float).tolist(), strict=True))
        ss = self.sea_state(x)
        seabed = s.seabed
        soil_changes = {
            k: row[k] for k in ("friction_coefficient", "submerged_unit_weight") if k in row
        }
        if soil_changes:
            seabed = replace(seabed, **soil_changes)
            kind = self.soil_kind or {"VerleySotberg": "sand", "VerleyLund": "clay"}.get(
                type(s.soil).__name__, "coulomb"
            )
            soil = soil_model_for_seabed(kind, s.pipe, seabed)
        else:
            soil = s.soil
        storm: Storm = s.storm
        peak = replace(storm.stages[0], hs=ss["hs"], tp=ss["tp"], direction_deg=ss["direction_deg"])
        storm = replace(storm, stages=(peak,), seed=int(seed))
        current = s.current
        cur = {}
        if "current_velocity" in ss:
            cur["velocity"] = min(10.0, max(0.0, ss["current_velocity"]))
            cur["direction_deg"] = ss["current_direction_deg"]
        if "current_velocity" in row:
            cur["velocity"] = max(0.0, row["current_velocity"])
        if "current_direction_deg" in row:
            cur["direction_deg"] = row["current_direction_deg"] % 360.0
        if cur:
            current = replace(current, **cur)
        return soil, storm, current

    @cached_property
    def _run_settings(self) -> tuple[Any, bool]:
        """The solver settings of every run (no records; the early stop when it comes before
        the case's own runaway stop) and whether the early stop applies (made once)."""
        settings = replace(self.setup.settings, record_interval=None)
        own = settings.stop_displacement_over_d
        early = self.stop_at is not None and self.stop_at / self.diameter < own
        if early:
            settings = replace(settings, stop_displacement_over_d=self.stop_at / self.diameter)
        return settings, early

    def __call__(self, x: np.ndarray, seed: int) -> dict[str, float]:
        from onbottom.dynamics.storm_section import simulate_storm_section

        s = self.setup
        soil, storm, current = self.build(x, seed)
        kw = s.kwargs()
        kw["current"] = current
        settings, early = self._run_settings
        kw["settings"] = settings
        r = simulate_storm_section(s.pipe, soil, storm, **kw)
        peak = storm.stages[0]
        return {
            "max_displacement": r.max_displacement,
            "final_displacement": r.final_displacement,
            "hs": peak.hs,
            "tp": peak.tp,
            "direction_deg": peak.direction_deg,
            "current_velocity": current.velocity,
            "max_penetration": r.summary.get("max_penetration", math.nan),
            "n_steps": r.summary.get("n_steps", math.nan),
            "stopped_early": float(early and r.max_displacement >= self.stop_at),
            "status": r.status,
            "message": r.message,
        }
