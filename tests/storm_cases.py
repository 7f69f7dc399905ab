"""Small storm case texts (a 0.4 m pipe on sand in 13 m of water; a regular or measured flow;
a short pipeline) for the ``[storm] kind = "regular"`` / ``"measured"`` tests."""

from __future__ import annotations

from case_helpers import write_file

COMMON = """
[pipe]
outer_diameter = 0.4
submerged_weight = 1500.0

[seabed]
model = "sand"
submerged_unit_weight = 10.0e3
friction_coefficient = 0.6
d50 = 0.25e-3

[environment]
water_depth = 13.0

[current]
velocity = 0.3
reference_height = 1.0
z0 = 1e-5

[solver]
record_interval = 1.0
"""

REGULAR = """
[storm]
kind = "regular"
height = 3.0
period = 10.0
direction_deg = 90.0
build_up_hours = 0.0028
peak_hours = 0.0139
"""

MEASURED = """
[storm]
kind = "measured"
series = "data/flow.csv"
"""

PIPELINE = """
[pipeline]
length = 40.0
element_length = 10.0
bending_stiffness = 1.0e8
axial_stiffness = 1.0e10
end_conditions = "free"
record_interval = 5.0
"""


def write_case(folder, storm, extra=""):
    """``folder/case.toml``: :data:`COMMON` + ``storm`` (a ``[storm]`` table) + ``extra``."""
    folder.mkdir(parents=True, exist_ok=True)
    return write_file(folder, COMMON + storm + extra)
