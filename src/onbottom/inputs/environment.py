"""Design environment: water, and load combinations of waves and current (DNV-RP-F109 §3.4).

The sea state and the current themselves are :class:`~onbottom.inputs.storm.SeaState` and
:class:`~onbottom.inputs.storm.Current` (shared with the storm simulations); this module adds
the water column and the load combinations of the design checks.

F109 (2010/2017) §3.4.2: when joint statistics of waves and current are not known, the design
environment is the more severe of

* the 100-year return-period wave with the 10-year current, and
* the 10-year wave with the 100-year current

(:func:`f109_combinations`); users may list any others (installation with 1-year or 10-year
conditions, for instance).
"""

from __future__ import annotations

from dataclasses import dataclass

from onbottom._validate import in_range, one_of, positive
from onbottom.constants import KINEMATIC_VISCOSITY_SEAWATER, RHO_SEAWATER
from onbottom.errors import InputError
from onbottom.inputs.pipe_buildup import CONDITIONS
from onbottom.inputs.storm import Current, SeaState

__all__ = ["Environment", "LoadCombination", "f109_combinations"]


@dataclass(frozen=True, kw_only=True, slots=True)
class Environment:
    """The water column at the pipe.

    Parameters
    ----------
    water_depth : float
        Water depth d [m], in (0, 5000].
    water_density : float
        ρ_w [kg/m³], in [900, 1100].
    kinematic_viscosity : float
        ν [m²/s], > 0 (informative; the F109 checks do not use it).
    """

    water_depth: float
    water_density: float = RHO_SEAWATER
    kinematic_viscosity: float = KINEMATIC_VISCOSITY_SEAWATER

    def __post_init__(self) -> None:
        in_range("Environment.water_depth", self.water_depth, 0.0, 5000.0, low_inclusive=False)
        in_range("Environment.water_density", self.water_density, 900.0, 1100.0)
        positive("Environment.kinematic_viscosity", self.kinematic_viscosity)


@dataclass(frozen=True, kw_only=True, slots=True)
class LoadCombination:
    """One design load combination: a sea state, a current and the pipe condition.

    Parameters
    ----------
    name : str
        Label in reports, non-empty.
    sea_state : SeaState
        Waves (H_s [m], T_p [s], γ, spectrum, direction, spreading).
    current : Current
        Current (V(z_r) [m/s], z_r [m], direction, z_0).
    condition : str
        Pipe condition checked in this combination: one of
        :data:`onbottom.inputs.pipe_buildup.CONDITIONS` (default ``"operation"``).
    """

    name: str
    sea_state: SeaState
    current: Current
    condition: str = "operation"

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.strip():
            raise InputError(f"LoadCombination.name = {self.name!r} is invalid: non-empty text")
        if not isinstance(self.sea_state, SeaState):
            raise InputError(
                f"LoadCombination.sea_state = {self.sea_state!r} is invalid: expected SeaState"
            )
        if not isinstance(self.current, Current):
            raise InputError(
                f"LoadCombination.current = {self.current!r} is invalid: expected Current"
            )
        one_of("LoadCombination.condition", self.condition, CONDITIONS)


def f109_combinations(
    *,
    wave_100: SeaState,
    wave_10: SeaState,
    current_100: Current,
    current_10: Current,
    condition: str = "operation",
) -> tuple[LoadCombination, LoadCombination]:
    """The two F109 §3.4.2 combinations: 100-yr wave + 10-yr current, 10-yr wave + 100-yr
    current (both in ``condition``)."""
    return (
        LoadCombination(
            name="100-yr wave + 10-yr current",
            sea_state=wave_100,
            current=current_10,
            condition=condition,
        ),
        LoadCombination(
            name="10-yr wave + 100-yr current",
            sea_state=wave_10,
            current=current_100,
            condition=condition,
        ),
    )
