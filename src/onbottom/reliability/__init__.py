"""onbottom.reliability — probability that a pipe exceeds a limit (issue 34, items 3 and 6).

So far: uncertain inputs (:mod:`~onbottom.reliability.distributions`) and the estimators of a
failure probability with openturns — Monte Carlo, FORM, importance sampling at the FORM design
point, subset simulation — with their coefficients of variation and FORM importance factors
(:mod:`~onbottom.reliability.estimators`), verified on closed-form limit states, and the storm
climate of a hindcast as standard normal inputs (:mod:`~onbottom.reliability.climate`). The campaign
over storms (Dask, Zarr, resume) is still to come. openturns is the optional extra
``onbottom[reliability]``, imported only when an estimate runs. Theory:
``docs/theory/reliability.md``.
"""

from onbottom.reliability.climate import StormClimate
from onbottom.reliability.distributions import (
    DISTRIBUTIONS,
    UncertainParameter,
    parameter_from_table,
)
from onbottom.reliability.estimators import (
    METHODS,
    FailureProbability,
    estimate_failure_probability,
    lifetime_probability,
)

__all__ = [
    "DISTRIBUTIONS",
    "METHODS",
    "FailureProbability",
    "StormClimate",
    "UncertainParameter",
    "estimate_failure_probability",
    "lifetime_probability",
    "parameter_from_table",
]
