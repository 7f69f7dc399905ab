"""Uncertain inputs of a reliability analysis: a name, a distribution and its parameters.

Each :class:`UncertainParameter` is what a case file's table such as
``friction_coefficient = {distribution = "normal", mean = 0.6, std = 0.06}`` describes
(:func:`parameter_from_table`), and becomes an openturns distribution
(:meth:`UncertainParameter.openturns`). Distributions and their parameters (SI units of the
variable):

* ``normal``: ``mean``, ``std`` (> 0);
* ``lognormal``: ``mean``, ``std`` of the variable itself (> 0; not of its logarithm);
* ``uniform``: ``low`` < ``high``;
* ``gumbel``: ``mean``, ``std`` (> 0), maxima;
* ``weibull``: ``scale`` (> 0), ``shape`` (> 0), ``location``;
* ``fixed``: ``value`` (a deterministic input kept in the list for the record).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

from onbottom._validate import (
    FRICTION_COEFFICIENT,
    SOIL_UNIT_WEIGHT_N_M3,
    finite,
    one_of,
    positive,
)
from onbottom.errors import InputError

__all__ = ["DISTRIBUTIONS", "UncertainParameter", "parameter_from_table"]

DISTRIBUTIONS: dict[str, tuple[str, ...]] = {
    "normal": ("mean", "std"),
    "lognormal": ("mean", "std"),
    "uniform": ("low", "high"),
    "gumbel": ("mean", "std"),
    "weibull": ("scale", "shape", "location"),
    "fixed": ("value",),
}
"""Supported distributions and the names of their parameters."""

PLAUSIBLE_RANGES: dict[str, tuple[tuple[float, float], str]] = {
    "submerged_unit_weight": (SOIL_UNIT_WEIGHT_N_M3[0], "N/m³"),
    "friction_coefficient": (FRICTION_COEFFICIENT[0], "-"),
}
"""Inputs whose mean must lie in the engineering plausibility range of the deterministic input
(:mod:`onbottom._validate`): a γ' typed in kN/m³ (10 for 10 000 N/m³) is refused by name."""


@dataclass(frozen=True, slots=True)
class UncertainParameter:
    """One uncertain input.

    Parameters
    ----------
    name : str
        Name of the input (a field of the model, e.g. ``"friction_coefficient"``).
    distribution : str
        One of :data:`DISTRIBUTIONS`.
    parameters : mapping of str to float
        The distribution's parameters (see the module docstring), in the variable's SI unit.
    """

    name: str
    distribution: str
    parameters: Mapping[str, float] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.strip():
            raise InputError(f"UncertainParameter.name = {self.name!r} is invalid: non-empty text")
        one_of(f"{self.name}.distribution", self.distribution, DISTRIBUTIONS)
        need = DISTRIBUTIONS[self.distribution]
        given = dict(self.parameters)
        if self.distribution == "weibull":
            given.setdefault("location", 0.0)
        if set(given) != set(need):
            raise InputError(
                f"{self.name} = {dict(self.parameters)!r} is invalid: a {self.distribution}"
                f" distribution takes {', '.join(need)}"
            )
        for k, v in given.items():
            finite(f"{self.name}.{k}", v)
        d = self.distribution
        if d in ("normal", "lognormal", "gumbel"):
            positive(f"{self.name}.std", given["std"])
        if d == "lognormal":
            positive(f"{self.name}.mean", given["mean"])
        if d == "uniform" and not given["low"] < given["high"]:
            raise InputError(
                f"{self.name}.low, high = {given['low']!r}, {given['high']!r} is invalid:"
                " low < high"
            )
        if d == "weibull":
            positive(f"{self.name}.scale", given["scale"])
            positive(f"{self.name}.shape", given["shape"])
        object.__setattr__(self, "parameters", {k: float(v) for k, v in given.items()})
        if self.name in PLAUSIBLE_RANGES:
            (lo, hi), unit = PLAUSIBLE_RANGES[self.name]
            m = self.mean()
            if not lo <= m <= hi:
                key = "value" if d == "fixed" else "mean"
                raise InputError(
                    f"{self.name} {key} = {m:g} {unit} is invalid: must lie in the plausible"
                    f" range [{lo:g}, {hi:g}] {unit} (check the unit: the inputs are in SI)"
                )

    @property
    def is_random(self) -> bool:
        """False for ``fixed``."""
        return self.distribution != "fixed"

    def openturns(self):
        """The openturns distribution (``fixed``: a Dirac)."""
        import openturns as ot

        p = self.parameters
        d = self.distribution
        if d == "normal":
            dist = ot.Normal(p["mean"], p["std"])
        elif d == "lognormal":
            dist = ot.LogNormalMuSigma(p["mean"], p["std"], 0.0).getDistribution()
        elif d == "uniform":
            dist = ot.Uniform(p["low"], p["high"])
        elif d == "gumbel":
            dist = ot.GumbelMuSigma(p["mean"], p["std"]).getDistribution()
        elif d == "weibull":
            dist = ot.WeibullMin(p["scale"], p["shape"], p["location"])
        else:
            dist = ot.Dirac(p["value"])
        dist.setDescription([self.name])
        return dist

    def mean(self) -> float:
        """Mean of the input (SI)."""
        p = self.parameters
        if self.distribution in ("normal", "lognormal", "gumbel"):
            return p["mean"]
        if self.distribution == "uniform":
            return 0.5 * (p["low"] + p["high"])
        if self.distribution == "weibull":
            return p["location"] + p["scale"] * math.gamma(1.0 + 1.0 / p["shape"])
        return p["value"]


def parameter_from_table(name: str, table: Mapping[str, object] | float) -> UncertainParameter:
    """An :class:`UncertainParameter` from a case-file value: a number (``fixed``) or a table
    ``{distribution = "...", <parameters>}``."""
    if isinstance(table, (int, float)) and not isinstance(table, bool):
        return UncertainParameter(name, "fixed", {"value": float(table)})
    if not isinstance(table, Mapping) or "distribution" not in table:
        raise InputError(
            f"{name} = {table!r} is invalid: a number or a table with 'distribution' and its"
            ' parameters, e.g. {distribution = "normal", mean = 0.6, std = 0.06}'
        )
    params = {k: v for k, v in table.items() if k != "distribution"}
    for k, v in params.items():
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise InputError(f"{name}.{k} = {v!r} is invalid: expected a number")
    return UncertainParameter(name, str(table["distribution"]), params)
