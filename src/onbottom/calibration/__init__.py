"""onbottom.calibration — fit model parameters to test records (measured, simulated or DEM).

Records (:mod:`.records`), misfit (:mod:`.objective`), parameters (:mod:`.parameters`),
grid / global / local fitting with uncertainty (:mod:`.fit`), simulators (:mod:`.simulators`),
multi-test summaries (:mod:`.summary`) and the Youssef & Cassidy (2014) workflow
(:mod:`.paper`). Guide: docs/calibration.md.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from onbottom._lazy import attach

if TYPE_CHECKING:  # the same names, for type checkers, mkdocstrings and the layering test
    from onbottom.calibration.fit import CalibrationResult, calibrate, grid_search, misfit_slices
    from onbottom.calibration.objective import HISTORY_ONLY, Misfit, MisfitWeights, evaluate_misfit
    from onbottom.calibration.parameters import Parameter, calcareous_parameters
    from onbottom.calibration.records import (
        TestRecord,
        load_record,
        record_from_result,
        save_record,
    )
    from onbottom.calibration.simulators import CentrifugeSimulator, RecordedLoadSimulator
    from onbottom.calibration.summary import fit_each, parameter_table, recommend, write_fits

__all__ = [
    "HISTORY_ONLY",
    "CalibrationResult",
    "CentrifugeSimulator",
    "Misfit",
    "MisfitWeights",
    "Parameter",
    "RecordedLoadSimulator",
    "TestRecord",
    "calcareous_parameters",
    "calibrate",
    "evaluate_misfit",
    "fit_each",
    "grid_search",
    "load_record",
    "misfit_slices",
    "parameter_table",
    "recommend",
    "record_from_result",
    "save_record",
    "write_fits",
]

__getattr__, __dir__ = attach(
    __name__,
    {
        "onbottom.calibration.fit": (
            "CalibrationResult",
            "calibrate",
            "grid_search",
            "misfit_slices",
        ),
        "onbottom.calibration.objective": (
            "HISTORY_ONLY",
            "Misfit",
            "MisfitWeights",
            "evaluate_misfit",
        ),
        "onbottom.calibration.parameters": ("Parameter", "calcareous_parameters"),
        "onbottom.calibration.records": (
            "TestRecord",
            "load_record",
            "record_from_result",
            "save_record",
        ),
        "onbottom.calibration.simulators": (
            "CentrifugeSimulator",
            "RecordedLoadSimulator",
        ),
        "onbottom.calibration.summary": (
            "fit_each",
            "parameter_table",
            "recommend",
            "write_fits",
        ),
    },
)
