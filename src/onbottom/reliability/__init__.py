"""onbottom.reliability — probability that a pipe exceeds a limit.

Uncertain inputs (:mod:`~onbottom.reliability.distributions`) and the estimators of a
failure probability with openturns — Monte Carlo, FORM, importance sampling at the FORM design
point, subset simulation — with their coefficients of variation and FORM importance factors
(:mod:`~onbottom.reliability.estimators`), verified on closed-form limit states, and the storm
climate of a hindcast as standard normal inputs (:mod:`~onbottom.reliability.climate`); the
dynamic limit state of a storm on a pipe section with the seed as an input
(:mod:`~onbottom.reliability.dynamic`, :mod:`~onbottom.reliability.storm_model`), run as a
campaign on Dask streamed to a resumable Zarr store (:mod:`~onbottom.reliability.campaign`),
the response-based design on an environmental contour (:mod:`~onbottom.reliability.design`)
and the run of ``onbottom reliability`` (:mod:`~onbottom.reliability.run`) on a
:class:`~onbottom.reliability.setup.ReliabilitySetup` — a plain value type that
:mod:`onbottom.cases.reliability` builds from a case file, or built by hand. openturns and
zarr are the optional extra ``onbottom[reliability]``, imported only when an estimate or a
store is made. Theory:
``docs/theory/reliability.md``.
"""

from onbottom.reliability.campaign import Campaign, ResultStore
from onbottom.reliability.climate import StormClimate
from onbottom.reliability.distributions import (
    DISTRIBUTIONS,
    UncertainParameter,
    parameter_from_table,
)
from onbottom.reliability.dynamic import (
    DYNAMIC_METHODS,
    ExceedanceEstimate,
    estimate_exceedance,
)
from onbottom.reliability.estimators import (
    METHODS,
    FailureProbability,
    estimate_failure_probability,
    lifetime_probability,
)
from onbottom.reliability.setup import ClimateSettings, ContourDesign, ReliabilitySetup
from onbottom.reliability.storm_model import StormModel

__all__ = [
    "DISTRIBUTIONS",
    "DYNAMIC_METHODS",
    "METHODS",
    "Campaign",
    "ClimateSettings",
    "ContourDesign",
    "ExceedanceEstimate",
    "FailureProbability",
    "ReliabilitySetup",
    "ResultStore",
    "StormClimate",
    "StormModel",
    "UncertainParameter",
    "estimate_exceedance",
    "estimate_failure_probability",
    "lifetime_probability",
    "parameter_from_table",
]
