"""Model parameters to calibrate: value, bounds, whether it varies, units."""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

from onbottom._validate import finite
from onbottom.errors import InputError

__all__ = ["Parameter", "parameters_from_mapping"]


@dataclass(frozen=True, kw_only=True, slots=True)
class Parameter:
    """One model parameter of a calibration.

    Parameters
    ----------
    name : str
        Keyword the simulator understands (``"A"``, ``"B"``, ``"C"``, ``"mu"``, ``"gamma"``).
    value : float
        Start value of the search, or the fixed value when ``vary`` is False [units].
    lower, upper : float
        Search bounds [units], ``lower < upper``; ``value`` must lie within them.
    vary : bool
        Whether the fit adjusts this parameter.
    units : str
        Units of value and bounds (``"1"`` for dimensionless; SI otherwise, e.g. ``"N/m3"``).
    """

    name: str
    value: float
    lower: float
    upper: float
    vary: bool = True
    units: str = "1"

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.isidentifier():
            raise InputError(f"Parameter.name = {self.name!r} is invalid: expected an identifier")
        v = finite(f"Parameter {self.name}.value", self.value)
        lo = finite(f"Parameter {self.name}.lower", self.lower)
        hi = finite(f"Parameter {self.name}.upper", self.upper)
        if not lo < hi:
            raise InputError(
                f"Parameter {self.name}: bounds [{lo:g}, {hi:g}] are invalid: need lower < upper"
            )
        if not lo <= v <= hi:
            raise InputError(
                f"Parameter {self.name}.value = {v:g} is invalid: must lie in [{lo:g}, {hi:g}]"
            )
        object.__setattr__(self, "value", v)
        object.__setattr__(self, "lower", lo)
        object.__setattr__(self, "upper", hi)

    @property
    def span(self) -> float:
        """upper − lower [units]."""
        return self.upper - self.lower


def parameters_from_mapping(
    values: Mapping[str, float],
    bounds: Mapping[str, Sequence[float]],
    vary: Iterable[str],
    units: Mapping[str, str] | None = None,
) -> tuple[Parameter, ...]:
    """Build parameters from start values, ``{name: (lower, upper)}`` and the names to vary.

    A fixed parameter without bounds gets the degenerate-free bounds ``value ± |value|``
    (or ±1 around 0); its bounds are not used.
    """
    vary = set(vary)
    unknown = vary - set(values)
    if unknown:
        raise InputError(f"vary names {sorted(unknown)} have no value; known: {sorted(values)}")
    units = dict(units or {})
    out = []
    for name, value in values.items():
        if name in bounds:
            lo, hi = (float(b) for b in bounds[name])
        elif name in vary:
            raise InputError(f"parameter {name!r} varies but has no bounds")
        else:
            pad = abs(float(value)) or 1.0
            lo, hi = float(value) - pad, float(value) + pad
        out.append(
            Parameter(
                name=name,
                value=float(value),
                lower=lo,
                upper=hi,
                vary=name in vary,
                units=units.get(name, "1"),
            )
        )
    return tuple(out)
