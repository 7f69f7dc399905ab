"""Scalar-output functions for parametric sweeps (``onbottom sweep`` built-ins).

Each function takes keyword arguments (the swept and fixed parameters) and returns a mapping
of scalar outputs, the form :func:`onbottom.study.sweep.sweep` expects.
"""

from __future__ import annotations

import math
import warnings

from onbottom.dynamics.centrifuge import run_centrifuge_test
from onbottom.errors import OutOfRangeWarning

__all__ = ["centrifuge_response"]


def centrifuge_response(
    *,
    test: str = "Inclined 1",
    A: float | None = None,
    B: float | None = None,
    C: float | None = None,
    mu: float | None = None,
    gamma: float | None = None,
    dt: float | None = None,
) -> dict[str, float]:
    """Response of one centrifuge test preset to A, B, C, μ, γ' (section solver).

    Parameters
    ----------
    test : str
        Preset name ("Inclined 1" ... "Irregular"); see :mod:`onbottom.dynamics.centrifuge`.
    A, B, C, mu : float or None
        Verley & Sotberg calcareous factors and friction coefficient [-]; None = the test's
        Table 2 value.
    gamma : float or None
        Submerged unit weight γ' [N/m³]; None = the preset default.
    dt : float or None
        Largest time step [s]; None = the preset default.

    Returns
    -------
    dict
        ``initial_penetration``, ``max_penetration``, ``max_abs_displacement`` [m],
        ``final_time`` [s], ``time_to_limit`` [s] and ``cycles_to_limit`` [-] (NaN if the
        limit was not reached), ``success`` (1/0). Out-of-range warnings of the soil
        correlations are counted in ``n_warnings`` rather than raised.
    """
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", OutOfRangeWarning)
        res = run_centrifuge_test(test, A=A, B=B, C=C, mu=mu, gamma=gamma, dt=dt)
    out = {k: float(v) for k, v in res.summary.items()}
    out["time_to_limit"] = math.nan if res.time_to_limit is None else float(res.time_to_limit)
    out["cycles_to_limit"] = math.nan if res.cycles_to_limit is None else float(res.cycles_to_limit)
    out["success"] = float(res.success)
    out["n_warnings"] = float(len(caught))
    return out
