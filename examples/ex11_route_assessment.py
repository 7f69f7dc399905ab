"""A whole route through every F109 level: the minimum concrete per KP section.

Loads the embedded example route (shore approach, mid-route, deep end; ``onbottom assess
--example`` prints it), shortens its storms and seeds so that the example runs in about a
minute in one process, and runs :func:`onbottom.assess.assess`: per section the flotation,
absolute and dynamic levels and their minimum concrete thickness, the governing design and
the weight the dynamic level saves, and the pipeline FE run of the governing section with its
strain check. The full study with its report is
``onbottom assess --out assess_results``.
Run: ``python examples/ex11_route_assessment.py``.
"""

from __future__ import annotations

import tomllib

from onbottom.assess import assess
from onbottom.cases.assess import build_route, example_path, parse_route_case

doc = tomllib.loads(example_path().read_text(encoding="utf-8"))
doc["dynamic"].update(seeds=2, build_up_hours=0.1, peak_hours=0.5)  # short, for the gallery
route = build_route(parse_route_case(doc))  # the case validated, then built
a = assess(route, n_workers=0)
table = a.summary[
    ["section", "water_depth_m", "max_utilisation", "absolute_value", "dynamic_value",
     "governing_level", "saved_submerged_weight_n_per_m"]
]  # fmt: skip
print(table.to_string(index=False, float_format=lambda x: f"{x:.4g}"))
for s in a.sections:
    b = s["dynamic"]["bisection"]
    print(f"{s['name']}: dynamic search {len(b['trials'])} trials, {b['storms']} storms")
p = a.pipeline  # the pipeline FE of the governing section ([levels] pipeline_fe)
print(
    f"pipeline FE of {p['section']} ({p['combination']}, seed {p['seed']}): max |y|"
    f" {p['max_displacement_over_D']:.3g}D, max strain {100 * p['max_strain']:.3g} %"
    f" (limit {100 * p['strain_limit']:.3g} %)"
)
