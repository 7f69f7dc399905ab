"""Model parameters to calibrate: value, bounds, whether it varies, units."""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

from onbottom._validate import finite
from onbottom.errors import InputError

__all__ = [
    "CALCAREOUS_BOUNDS",
    "CALCAREOUS_START",
    "Parameter",
    "calcareous_parameters",
    "check_vary",
    "parameters_from_mapping",
]

CALCAREOUS_START: Mapping[str, float] = {"A": 0.25, "B": 0.35, "C": 0.98, "mu": 0.6}
"""Start values of the calcareous Verley & Sotberg fit: Youssef & Cassidy (2014) Table 3
(μ: middle of the tests' 0.48–0.85)."""

CALCAREOUS_BOUNDS: Mapping[str, tuple[float, float]] = {
    "A": (0.05, 1.0),
    "B": (0.05, 1.0),
    "C": (0.5, 1.5),
    "mu": (0.4, 1.2),
    "gamma": (4.0e3, 10.0e3),
}
"""Search bounds: μ as searched by Youssef & Cassidy (2014) (0.4–1.2); A, B, C around their
Table 2's spread; γ' [N/m³] 4–10 kN/m³."""


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


def check_vary(names: Sequence[str], *, option: str = "vary", given: object = None) -> None:
    """Raise :class:`~onbottom.errors.InputError` unless ``names`` are distinct names of
    :data:`CALCAREOUS_BOUNDS`, at least one; messages name ``option`` and show ``given`` (the
    text the names came from; default ``names``)."""
    known = sorted(CALCAREOUS_BOUNDS)
    shown = list(names) if given is None else given
    bad = [n for n in names if n not in CALCAREOUS_BOUNDS]
    if bad:
        raise InputError(f"{option} names {bad} are invalid: must be among {known}")
    if not names:
        raise InputError(f"{option} = {shown!r} is invalid: name at least one of {known}")
    if len(set(names)) != len(names):
        raise InputError(f"{option} = {shown!r} is invalid: a name is repeated")


def calcareous_parameters(
    vary: Sequence[str],
    *,
    bounds: Mapping[str, Sequence[float]] | None = None,
    start: Mapping[str, float] | None = None,
    gamma: float | None = None,
) -> tuple[Parameter, ...]:
    """The parameters of a calcareous Verley & Sotberg fit (``onbottom calibrate``).

    Parameters
    ----------
    vary : sequence of str
        Names to fit, among ``A``, ``B``, ``C``, ``mu`` [-] and ``gamma`` (γ' [N/m³]); the
        others are fixed at their start values.
    bounds : mapping or None
        ``{name: (lower, upper)}`` over :data:`CALCAREOUS_BOUNDS`.
    start : mapping or None
        Start (or fixed) values over :data:`CALCAREOUS_START`; a start value of a varied
        parameter outside its bounds is moved onto the nearer bound, and a fixed one widens
        its bounds to include it.
    gamma : float or None
        γ' [N/m³]: the start (or fixed) value of ``gamma`` unless ``start`` names it; without
        either, ``gamma`` is a parameter only when varied (start: middle of its bounds).

    Returns
    -------
    tuple of Parameter
        ``A``, ``B``, ``C``, ``mu`` (and ``gamma``), units ``"1"`` (``gamma``: ``"N/m3"``).
    """
    known = set(CALCAREOUS_BOUNDS)
    names = list(vary)
    check_vary(names)
    for what, given in (("bounds", bounds or {}), ("start", start or {})):
        for k in given:
            if k not in known:
                raise InputError(f"{what} {k!r} is invalid: must be among {sorted(known)}")
    b = {k: (float(v[0]), float(v[1])) for k, v in CALCAREOUS_BOUNDS.items()}
    for k, (lo, hi) in (bounds or {}).items():
        if not lo < hi:
            raise InputError(f"bounds {k} = ({lo:g}, {hi:g}) is invalid: lower must be below upper")
        b[k] = (lo, hi)
    s = dict(CALCAREOUS_START)
    if gamma is not None:
        s["gamma"] = gamma
    s.update(start or {})
    if "gamma" in names and "gamma" not in s:
        s["gamma"] = 0.5 * (b["gamma"][0] + b["gamma"][1])
    params = []
    for name, value in s.items():
        lo, hi = b.get(name, (value - abs(value), value + abs(value)))
        if name in names:
            value = min(max(value, lo), hi)
        params.append(
            Parameter(
                name=name,
                value=value,
                lower=min(lo, value),
                upper=max(hi, value),
                vary=name in names,
                units="N/m3" if name == "gamma" else "1",
            )
        )
    return tuple(params)
