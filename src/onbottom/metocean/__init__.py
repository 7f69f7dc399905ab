"""onbottom.metocean — from a hindcast to the design sea states and currents per direction.

Strict hindcast reader (:mod:`~onbottom.metocean.hindcast`), declustered storms
(:mod:`~onbottom.metocean.storms`), return values with confidence intervals by pyextremes
(:mod:`~onbottom.metocean.extremes`), the DNV-RP-C205 H_s–T_p model and IFORM contours by
virocon (:mod:`~onbottom.metocean.joint`), the analysis (:mod:`~onbottom.metocean.analysis`),
the DNV-RP-F109 design table (:mod:`~onbottom.metocean.table`) and the run of ``onbottom
metocean`` with its notes, case fragments and files (:mod:`~onbottom.metocean.run`).
pyextremes and virocon are the optional extra ``onbottom[metocean]``, imported only when a fit
runs. Theory: ``docs/theory/metocean.md``. Depends on ``inputs`` and the base modules.
"""

from onbottom.metocean.analysis import MetoceanOptions, MetoceanResult, analyse_hindcast
from onbottom.metocean.current import CurrentModel, fit_current_model
from onbottom.metocean.extremes import ReturnLevels, fit_return_levels, gpd_return_level
from onbottom.metocean.hindcast import Hindcast, read_hindcast, write_hindcast_csv
from onbottom.metocean.joint import JointModel, fit_joint_model, iform_contour
from onbottom.metocean.run import MetoceanRun, run_metocean_analysis, write_metocean_outputs
from onbottom.metocean.storms import Storms, storm_peaks, threshold_for_rate
from onbottom.metocean.synthetic import EXAMPLE_MODEL, SyntheticModel, synthetic_hindcast
from onbottom.metocean.table import DesignRow, design_rows, design_table_csv, sector_toml

__all__ = [
    "EXAMPLE_MODEL",
    "CurrentModel",
    "DesignRow",
    "Hindcast",
    "JointModel",
    "MetoceanOptions",
    "MetoceanResult",
    "MetoceanRun",
    "ReturnLevels",
    "Storms",
    "SyntheticModel",
    "analyse_hindcast",
    "design_rows",
    "design_table_csv",
    "fit_current_model",
    "fit_joint_model",
    "fit_return_levels",
    "gpd_return_level",
    "iform_contour",
    "read_hindcast",
    "run_metocean_analysis",
    "sector_toml",
    "storm_peaks",
    "synthetic_hindcast",
    "threshold_for_rate",
    "write_hindcast_csv",
    "write_metocean_outputs",
]
