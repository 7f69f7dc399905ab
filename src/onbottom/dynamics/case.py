"""Section-simulation case files (TOML): a preset centrifuge test or a user's own case.

Schema (loads in kN/m, unit weights in kN/m³, lengths in m, times in s; see
``examples/section_case.toml`` and ``examples/section_preset.toml``)::

    [preset]                      # EITHER a preset test ...
    test = "Inclined 1"           # Table 1 name
    parameters = "table2"         # or "recommended" (Table 3)
    # optional: A, B, C, mu, gamma_kn, alpha_deg, time_basis, shape, after_limit, dt

    [pipe]                        # ... OR pipe + soil + programme (+ solver)
    outer_diameter = 1.0
    submerged_weight_kn = 10.52
    # mass = 1878.0               # kg/m, optional (default from W_s and buoyancy)
    # added_mass_coefficient = 2.29

    [soil]
    model = "verley_sotberg_calcareous"   # or "verley_sotberg_silica", "coulomb"
    friction_coefficient = 0.48
    submerged_unit_weight_kn = 7.5        # not for coulomb
    # A = 0.25, B = 0.35, C = 0.98        # calcareous defaults (Table 3)

    [programme]                   # see onbottom.dynamics.programmes.from_toml
    kind = "inclined_cyclic"
    ...

    [solver]                      # all optional
    displacement_limit = 3.0
    after_limit = "stop"          # or "runaway_end", "continue"
    integrator = "backward_euler" # or "newmark"
    dt_max = 0.2
    max_displacement_increment = 0.002
"""

from __future__ import annotations

import os
import tomllib
from collections.abc import Mapping
from typing import Any

from onbottom._validate import one_of
from onbottom.dynamics import centrifuge
from onbottom.dynamics.programmes import from_toml as programme_from_toml
from onbottom.dynamics.section import (
    SectionResult,
    SolverSettings,
    section_mass,
    simulate_section,
)
from onbottom.errors import InputError
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.soil.coulomb import CoulombFriction

__all__ = ["load_case", "run_case"]

_KN = 1.0e3
_SOIL_MODELS = ("verley_sotberg_calcareous", "verley_sotberg_silica", "coulomb")


def load_case(source: str | os.PathLike | Mapping[str, Any]) -> dict[str, Any]:
    """Read a case file (or mapping) into a dict; relative CSV paths resolve beside the file."""
    if isinstance(source, Mapping):
        return {"doc": dict(source), "path": None}
    with open(source, "rb") as fh:
        return {"doc": tomllib.load(fh), "path": os.fspath(source)}


def _check_keys(table: Mapping[str, Any], allowed: tuple[str, ...], where: str) -> None:
    extra = sorted(set(table) - set(allowed))
    if extra:
        raise InputError(f"[{where}] has unknown keys {extra}; allowed: {sorted(allowed)}")


def run_case(
    source: str | os.PathLike | Mapping[str, Any], *, progress: bool = False
) -> SectionResult:
    """Run the case of a TOML file or mapping (schema in the module docstring)."""
    loaded = load_case(source)
    doc = loaded["doc"]
    if "preset" in doc:
        p = dict(doc["preset"])
        allowed = (
            "test",
            "parameters",
            "A",
            "B",
            "C",
            "mu",
            "gamma_kn",
            "alpha_deg",
            "time_basis",
            "shape",
            "after_limit",
            "dt",
        )
        _check_keys(p, allowed, "preset")
        if "test" not in p:
            raise InputError("[preset] test is missing: give a Table 1 test name")
        gamma = p.get("gamma_kn")
        return centrifuge.run_centrifuge_test(
            str(p["test"]),
            parameters=str(p.get("parameters", "table2")),
            A=p.get("A"),
            B=p.get("B"),
            C=p.get("C"),
            mu=p.get("mu"),
            gamma=None if gamma is None else float(gamma) * _KN,
            alpha_deg=p.get("alpha_deg"),
            time_basis=str(p.get("time_basis", "paper")),
            shape=str(p.get("shape", "sine")),
            after_limit=str(p.get("after_limit", "stop")),
            dt=p.get("dt"),
            progress=progress,
        )
    for key in ("pipe", "soil", "programme"):
        if key not in doc:
            raise InputError(f"case has no [{key}] table (and no [preset])")
    pt = dict(doc["pipe"])
    _check_keys(
        pt,
        ("outer_diameter", "submerged_weight_kn", "mass", "added_mass_coefficient"),
        "pipe",
    )
    ca = float(pt.pop("added_mass_coefficient", centrifuge.ADDED_MASS_COEFFICIENT))
    pipe = Pipe(
        outer_diameter=float(pt["outer_diameter"]),
        submerged_weight=float(pt["submerged_weight_kn"]) * _KN,
        mass=None if pt.get("mass") is None else float(pt["mass"]),
    )
    prog = programme_from_toml(
        {"programme": doc["programme"]} if loaded["path"] is None else loaded["path"]
    )
    st = dict(doc["soil"])
    model = one_of("soil.model", st.pop("model", None), _SOIL_MODELS)
    mu = float(st.pop("friction_coefficient", 0.6))
    if model == "coulomb":
        _check_keys(st, ("mobilisation_displacement",), "soil")
        soil = CoulombFriction(friction_coefficient=mu, **st)
    else:
        from onbottom.soil.verley_sotberg import VerleySotberg

        if "submerged_unit_weight_kn" not in st:
            raise InputError("soil.submerged_unit_weight_kn is missing (required for V&S)")
        sand = Sand(
            submerged_unit_weight=float(st.pop("submerged_unit_weight_kn")) * _KN,
            friction_coefficient=mu,
        )
        options = dict(st)
        if model == "verley_sotberg_calcareous":
            soil = VerleySotberg.calcareous(
                pipe, sand, installation_load=prog.peak_vertical_load, **options
            )
        else:
            soil = VerleySotberg.silica(
                pipe, sand, installation_load=prog.peak_vertical_load, **options
            )
    sv = dict(doc.get("solver", {}))
    _check_keys(
        sv,
        (
            "displacement_limit",
            "after_limit",
            "integrator",
            "dt_max",
            "dt_min",
            "max_displacement_increment",
            "force_tolerance",
            "max_iterations",
            "chunks",
        ),
        "solver",
    )
    limit = sv.pop("displacement_limit", None)
    after = str(sv.pop("after_limit", "stop"))
    settings = SolverSettings(**sv)
    return simulate_section(
        prog,
        soil,
        mass=section_mass(pipe, ca),
        displacement_limit=None if limit is None else float(limit),
        after_limit=after,
        settings=settings,
        progress=progress,
        attrs={"case_file": loaded["path"] or "<mapping>"},
    )
