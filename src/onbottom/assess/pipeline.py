"""Pipeline FE run of the governing section of a route (``[levels] pipeline_fe = true``).

The section solver of the dynamic level treats a rigid unit length; a real line bends between
points held by the soil, and where it moves it strains. F109 (2017) §3.4 (dynamic lateral
stability) lets the pipe move beyond 0.5D only when the strain is checked, with the
displacement-controlled criteria of DNV-ST-F101 (§5.4.12). This module runs the pipeline FE
(:func:`onbottom.dynamics.pipeline.simulate_pipeline`, docs/theory/pipeline_fe.md) on a
straight stretch of the governing section:

* **governing section**: the section with the heaviest design (the largest design value of
  the route; ties: the highest dynamic utilisation at the given design), at its design value
  (the concrete thickness or submerged weight the assessment chose);
* **governing storm**: the load combination and seed with the largest displacement of the
  dynamic level at the given design (the same storm: the section's ``onbottom storm``
  document, its seed), synthesised short-crested along the line
  (:func:`onbottom.hydro.short_crested.pipeline_kinematics`);
* the pipe, soil model, force model, F109 load reductions and current of that storm (the
  section's :data:`~onbottom.assess.route.TrialStorm` at the design value);
  :class:`~onbottom.assess.route.PipelineSettings` (``[pipeline]`` of the route case) give the
  length, element length, end conditions and
  strain limit (default 0.2 %: a screening value below the yield strain of X65 line pipe,
  448 MPa / 207 GPa = 0.22 %; the DNV-ST-F101 displacement-controlled criterion allows more —
  give the project's design value).

Returned (results.json ``pipeline``): the section, combination, seed and design value, the
max lateral displacement [m] and over D, the max strain and its check, the worst node, the
status, the envelopes along the line (x, max |y|, max strain, max |moment|) and the run time;
the NetCDF (records off: envelopes only) is ``pipeline.nc`` in the output folder.
"""

from __future__ import annotations

import logging
import time
from pathlib import Path
from typing import Any

from onbottom.assess.route import Route

__all__ = ["governing_storm", "run_governing_pipeline"]


def governing_storm(route: Route, sections: list[dict[str, Any]]) -> dict[str, Any] | None:
    """The governing section, its design value, combination and seed (None: no candidate —
    no section has a design value and a dynamic run at the given design). Without a design
    variable (``solve_for = "none"``) the section with the highest dynamic utilisation, at the
    given design (design value None)."""
    given = route.variable == "none"  # no design variable: the given design is the design
    cands = [
        s
        for s in sections
        if (given or s.get("design_value") is not None) and (s.get("dynamic") or {}).get("base")
    ]
    if not cands:
        return None

    def dyn_util(s: dict[str, Any]) -> float:
        return max(b["utilisation"] for b in s["dynamic"]["base"].values())

    sec = max(cands, key=lambda s: (0.0 if given else s["design_value"], dyn_util(s)))
    name, base = max(sec["dynamic"]["base"].items(), key=lambda kv: kv[1]["utilisation"])
    seed = base["seeds"][max(range(len(base["seeds"])), key=lambda k: base["max_displacement"][k])]
    return {
        "section": sec["name"],
        "index": sec["index"],
        "design_value": None if given else sec["design_value"],
        "variable": route.variable,
        "combination": name,
        "seed": int(seed),
    }


def run_governing_pipeline(
    route: Route, sections: list[dict[str, Any]], out: str | Path | None
) -> dict[str, Any] | None:
    """Run the pipeline FE of the governing section (see the module); None when no section
    qualifies. ``out``: folder of ``pipeline.nc`` (None: kept in memory)."""
    import warnings

    from onbottom.dynamics.pipeline import PipelineModel, PipelineSettings, simulate_pipeline
    from onbottom.hydro.short_crested import pipeline_kinematics
    from onbottom.hydro.storm_kinematics import current_normal_to_pipe

    gov = governing_storm(route, sections)
    if gov is None:
        return None
    t0 = time.perf_counter()
    p = route.pipeline
    sec = route.sections[gov["index"]]
    k = sec.storm_index(gov["combination"])
    setup = (
        sec.storms[k].setup if route.variable == "none" else sec.trial_storm(k, gov["design_value"])
    )
    pipe = setup.pipe
    d = pipe.outer_diameter
    steel = getattr(sec.pipe, "steel_outer_diameter", None)
    model = PipelineModel(
        pipe=pipe,
        length=p.length,
        element_length=p.element_length,
        soil=setup.soil,
        end_conditions=p.end_conditions,
        force_model=setup.force_model,
        reductions=setup.reductions,
        current=current_normal_to_pipe(setup.current, d, setup.z0),
        strain_fibre_distance=None if steel is None else 0.5 * steel,
    )
    s = setup.settings
    settings = PipelineSettings(
        dt_max=s.dt_max,
        dt_min=s.dt_min,
        max_displacement_increment_over_d=max(s.max_displacement_increment_over_d, 0.05),
        stop_displacement_over_d=s.stop_displacement_over_d,
        record_interval=None,  # envelopes only
        chunk_duration=3600.0,
        strain_limit=p.strain_limit,
    )
    kin = pipeline_kinematics(
        setup.storm.with_seed(gov["seed"]),
        setup.depth,
        model.x,
        sample_interval=setup.sample_interval,
    )
    output = None if out is None else Path(out) / "pipeline.nc"
    from onbottom.errors import ResultFileError

    def run(resume: str) -> Any:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return simulate_pipeline(
                model,
                kin,
                duration=p.duration,
                settings=settings,
                output=output,
                attrs={"assess_section": gov["section"], "combination": gov["combination"]},
                identity_extra={"assess": gov},
                resume=resume,
            )

    try:
        r = run("auto")
    except ResultFileError as exc:
        # a checkpoint or partial pipeline.nc of other inputs (an edited [pipeline], another
        # governing storm): assess owns the folder and has no --restart; start this run afresh
        logging.getLogger(__name__).warning("pipeline FE started afresh: %s", exc)
        r = run("never")
    env = r.envelopes
    return gov | {
        "length_m": p.length,
        "element_length_m": p.element_length,
        "n_nodes": int(model.x.size),
        "end_conditions": p.end_conditions,
        "diameter_m": d,
        "submerged_weight_n_per_m": float(pipe.submerged_weight),
        "condition": sec.storms[k].condition,
        "max_displacement_m": float(r.max_displacement),
        "max_displacement_over_D": float(r.max_displacement) / d,
        "worst_node_x_m": r.worst_node_x,
        "max_strain": float(r.max_strain),
        "strain_limit": p.strain_limit,
        "strain_check": r.criteria.get("strain"),
        "criteria": {k: v for k, v in r.criteria.items() if k != "strain"},
        "status": int(r.status),
        "success": bool(r.success),
        "message": r.message,
        "duration_s": p.duration,
        "envelopes": {
            "x": [float(v) for v in env["x"].values],
            "max_abs_y": [float(v) for v in env["max_abs_y"].values],
            "max_strain": [float(v) for v in env["max_strain"].values],
            "max_abs_moment": [float(v) for v in env["max_abs_moment"].values],
        },
        "netcdf": None if r.netcdf is None else str(r.netcdf),
        "wall_time_s": time.perf_counter() - t0,
    }
