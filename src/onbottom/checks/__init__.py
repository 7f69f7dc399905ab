"""onbottom.checks — DNV-RP-F109 design checks (closed form, no time integration).

* :func:`absolute_lateral_stability` — F109 (2017) §3.6, Eqs 3.38–3.41;
* :func:`vertical_stability` — F109 §3.3, Eq 3.1;
* :mod:`onbottom.checks.f109_tables` — C*_Y, C*_Z, γ_SC;
* :func:`evaluate_stability` — every check of a section and the design solve
  (``onbottom stability``); :func:`combination_loads` — the cycle peak loads of every load
  combination (``onbottom loads``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from onbottom._lazy import attach

if TYPE_CHECKING:  # the same names, for type checkers, mkdocstrings and the layering test
    from onbottom.checks.absolute import (
        AbsoluteStabilityResult,
        absolute_lateral_stability,
        absolute_stability_of_sea_state,
    )
    from onbottom.checks.evaluation import (
        DesignRequest,
        StabilityEvaluation,
        StabilityInputs,
        evaluate_stability,
    )
    from onbottom.checks.f109_tables import peak_load_coefficients, safety_factor
    from onbottom.checks.loads import LoadsInputs, combination_loads
    from onbottom.checks.vertical import VerticalStabilityResult, vertical_stability

__all__ = [
    "AbsoluteStabilityResult",
    "DesignRequest",
    "LoadsInputs",
    "StabilityEvaluation",
    "StabilityInputs",
    "VerticalStabilityResult",
    "absolute_lateral_stability",
    "absolute_stability_of_sea_state",
    "combination_loads",
    "evaluate_stability",
    "peak_load_coefficients",
    "safety_factor",
    "vertical_stability",
]

__getattr__, __dir__ = attach(
    __name__,
    {
        "onbottom.checks.absolute": (
            "AbsoluteStabilityResult",
            "absolute_lateral_stability",
            "absolute_stability_of_sea_state",
        ),
        "onbottom.checks.evaluation": (
            "DesignRequest",
            "StabilityEvaluation",
            "StabilityInputs",
            "evaluate_stability",
        ),
        "onbottom.checks.loads": (
            "LoadsInputs",
            "combination_loads",
        ),
        "onbottom.checks.f109_tables": (
            "peak_load_coefficients",
            "safety_factor",
        ),
        "onbottom.checks.vertical": (
            "VerticalStabilityResult",
            "vertical_stability",
        ),
    },
)
