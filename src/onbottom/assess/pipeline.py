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
  :class:`~onbottom.assess.route.PipelineFESettings` (``[pipeline]`` of the route case) give the
  length, element length, end conditions and
  strain limit (default 0.2 %: a screening value below the yield strain of X65 line pipe,
  448 MPa / 207 GPa = 0.22 %; the DNV-ST-F101 displacement-controlled criterion allows more —
  give the project's design value).

Returned (results.json ``pipeline``): the section, combination, seed and design value, the
max lateral displacement [m] and over D, the max strain and its check, the worst node, the
status, the envelopes along the line (x, max |y|, max strain, max |moment|) and the run time;
the NetCDF (records off: the envelopes and the verdict, :func:`fe_dataset`) is
``pipeline.nc`` in the output folder.

Design (one design that passes every level run). When the FE run fails at the section's
design (max |y| above the route's allowable, or the strain above its limit), the design of that
section rises until the FE passes, by the dynamic level's search
(:func:`onbottom.assess.dynamic.search_dynamic`: bracket [failing, passing], ascent from below in
steps of the dynamic tolerance, one confirming step): the first passing guesses are the
section's heavier passing values already known (the absolute design, the search trials that
passed), then the design + 2, 4, 8, ... tolerances; a failing FE trial stops once |y| passes the
allowable (:data:`~onbottom.assess.dynamic.STOP_MARGIN` × allowable: its verdict is that of the
full run, its max |y| a lower bound). The run at the section's own design is always complete, and
the section solver is run once more on the same storm and seed at that design, to state the
ratio of the two solvers' max |y| (:data:`DISAGREEMENT_FACTOR`). Cost: the FE line has
``length / element_length + 1`` nodes (the route's ``[pipeline]``; default 200 m / 5 m = 41
nodes); one complete FE storm costs about as much as 45 section storms of the same storm.

Every section (``[pipeline] sections = "every"``). The FE then checks each section's design in
that section's own task (:func:`check_section_pipeline`, on its Dask worker: the cost is linear
in sections), on the section's worst storm (the combination and seed of
:func:`section_storm`), started from the section's accepted design — the nearest accepted trial
of the section solver's search — with the search's passing trials as the first guesses above it
(warm start), and every FE storm stopped once |y| passes the allowable (a passing run is
complete by definition; a failing one is decided there). With ``mesh = "rule"`` the line length
and element length follow :func:`fe_mesh`, stated in ``docs/assess.md``. Each section's check is
written by its task as ``pipeline/NN-<section>.nc`` (:func:`fe_dataset`), beside its
``sections/NN-<section>.json``.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

from onbottom.assess.route import Route
from onbottom.results import save_dataset

__all__ = [
    "DISAGREEMENT_FACTOR",
    "MESH_RULE",
    "check_section_pipeline",
    "fe_dataset",
    "fe_mesh",
    "governing_storm",
    "pipeline_trial",
    "run_governing_pipeline",
    "section_fe_nodes",
    "section_storm",
]

DISAGREEMENT_FACTOR = 2.0
"""The two solvers (section, pipeline FE) disagree at the design point when the ratio of their
max |y| on the same storm and seed is above this factor or below its inverse."""


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
    return section_storm(route, sec)


def section_storm(route: Route, sec: dict[str, Any]) -> dict[str, Any]:
    """The FE storm of one section's result ``sec``: its combination with the highest dynamic
    utilisation at the given design and that combination's worst seed, at the section's design
    value (None without a design variable)."""
    given = route.variable == "none"
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


MESH_RULE = (
    "L = max(λ_p, 12/β), h = min(λ_p/16, 1/β), n_e = ceil(L/h): λ_p the linear wavelength at"
    " the peak period and depth (ω² = g k tanh kd), β = (k_s/(4EI))^(1/4) the Winkler"
    " wavenumber (Hetényi 1946) with k_s = μ W_s/(0.02 D), friction mobilised over the"
    " region-1 displacement y1 = 0.02 D of Verley & Sotberg (1994)"
)
"""The stated rule of the FE mesh (``[pipeline] mesh = "rule"``, :func:`fe_mesh`)."""


def fe_mesh(
    pipe: Any, friction_coefficient: float, depth: float, peak_period: float
) -> dict[str, Any]:
    """The FE line's length and element length by :data:`MESH_RULE`.

    Parameters
    ----------
    pipe : Pipe
        The pipe at the design checked: D [m], W_s [N/m], EI [N·m²].
    friction_coefficient : float
        μ [-] of the seabed (lateral friction).
    depth : float
        Water depth d [m].
    peak_period : float
        T_p [s] of the storm's peak sea state.

    Returns
    -------
    dict
        ``length`` [m], ``element_length`` [m], ``n_elements``, ``wavelength`` λ_p [m],
        ``beta`` β [1/m] (0 without bending stiffness), ``rule`` (:data:`MESH_RULE`).

    Notes
    -----
    A fixed or pinned end disturbs a beam on an elastic foundation as e^{-βx} (Hetényi 1946,
    *Beams on Elastic Foundation*, Ch. II): at 6/β from each end the disturbance is below
    0.25 %, so L >= 12/β leaves the middle of the line free of the end conditions; L >= λ_p
    puts one crest and trough of the storm's peak wave along the line (short-crested loads
    vary along it on that scale or longer, the spreading lengthening the crests). An element
    of length h <= 1/β interpolates the deflection mode u = e^{-βx} cos βx by cubic Hermite
    shape functions within h⁴/384 · max|u⁗| = (βh)⁴/96 · max|u| (about 1 % at βh = 1; the
    classical Hermite interpolation bound, |u⁗| = 4β⁴|u|); h <= λ_p/16 resolves the load's
    along-line variation with 16 elements per wavelength. k_s = μ W_s/(0.02 D) counts
    friction only (the passive resistance of the embedment would stiffen it); β ∝ k_s^{1/4}, so a
    soil twice as stiff changes 1/β by 16 %.
    """
    import math

    from onbottom.hydro.kinematics import wave_number

    k = float(wave_number(2.0 * math.pi / peak_period, depth)[0])
    lam = 2.0 * math.pi / k
    d, ws, ei = pipe.outer_diameter, pipe.submerged_weight, pipe.bending_stiffness
    k_s = friction_coefficient * ws / (0.02 * d)
    beta = (k_s / (4.0 * ei)) ** 0.25 if ei > 0.0 and k_s > 0.0 else 0.0
    inv_beta = math.inf if beta == 0.0 else 1.0 / beta
    length = max(lam, 12.0 * inv_beta) if beta > 0.0 else lam
    h_max = min(lam / 16.0, inv_beta)
    n = max(2, math.ceil(length / h_max - 1e-9))
    return {"length": length, "element_length": length / n, "n_elements": n,
            "wavelength": lam, "beta": beta, "rule": MESH_RULE}  # fmt: skip


def _peak_period(setup: Any, sec: Any, combination: str) -> float:
    """T_p [s] of the storm's strongest stage (its load combination's sea state without
    stages)."""
    stages = getattr(setup.storm, "stages", None)
    if stages:
        return float(max(stages, key=lambda st: st.hs).tp)
    for c in sec.combinations:
        if c.name == combination:
            return float(c.sea_state.tp)
    return float(sec.combinations[0].sea_state.tp)


def _mesh_for(route: Route, sec: Any, gov: dict[str, Any], value: float | None) -> dict[str, Any]:
    """The FE mesh of section ``sec`` at design ``value``: the route's ``[pipeline]`` length and
    element length, or :func:`fe_mesh` (``mesh = "rule"``), fixed over the section's trials."""
    p = route.pipeline
    if p.mesh != "rule":
        n = round(p.length / p.element_length)
        return {"length": p.length, "element_length": p.element_length, "n_elements": n,
                "rule": "given"}  # fmt: skip
    k = sec.storm_index(gov["combination"])
    setup = sec.storms[k].setup if value is None else sec.trial_storm(k, value)
    mu = getattr(sec.seabed, "friction_coefficient", None)
    if mu is None:
        from onbottom.errors import InputError

        raise InputError(
            f"[pipeline] mesh = 'rule' is invalid for section {sec.name!r}: its seabed"
            f" ({type(sec.seabed).__name__}) has no friction_coefficient; give the length"
        )
    return fe_mesh(setup.pipe, mu, sec.water_depth, _peak_period(setup, sec, gov["combination"]))


def section_fe_nodes(route: Route, sec: Any) -> int:
    """FE nodes of section ``sec``'s pipeline run, for its cost estimate: the route's
    ``[pipeline]`` line, or with ``mesh = "rule"`` the largest :func:`fe_mesh` over the
    section's load combinations at the given design (the given line where the seabed has no
    friction coefficient: the run itself then refuses the rule)."""
    p = route.pipeline
    given = round(p.length / p.element_length) + 1
    mu = getattr(sec.seabed, "friction_coefficient", None)
    if p.mesh != "rule" or mu is None or not sec.storms:
        return given
    meshes = [
        fe_mesh(c.setup.pipe, mu, sec.water_depth, _peak_period(c.setup, sec, c.name))
        for c in sec.storms
    ]
    return max(m["n_elements"] for m in meshes) + 1


def pipeline_trial(
    route: Route,
    gov: dict[str, Any],
    value: float | None,
    *,
    stop_at_allowable: bool = False,
    section: Any = None,
    mesh: dict[str, Any] | None = None,
) -> tuple[dict[str, Any], Any]:
    """One pipeline FE run of the governing storm ``gov`` (:func:`governing_storm`) at design
    value ``value`` (None: the given design). ``stop_at_allowable``: stop the storm once a
    node's |y| passes :data:`~onbottom.assess.dynamic.STOP_MARGIN` × the allowable (the verdict
    is the full run's; max |y| is then a lower bound). Returns (the row of results.json
    ``pipeline``, without ``envelopes``; the :class:`~onbottom.dynamics.pipeline.PipelineResult`).
    The row's ``pass`` is max |y| <= allowable and the strain within its limit; ``ratio`` is
    max(max |y| / allowable, strain / limit). ``section``: the
    :class:`~onbottom.assess.route.Section` (default ``route.sections[gov["index"]]``);
    ``mesh``: ``length`` and ``element_length`` [m] of the line (default the route's
    ``[pipeline]``)."""
    import warnings

    from onbottom.assess.dynamic import STOP_MARGIN
    from onbottom.dynamics.pipeline import PipelineModel, PipelineSettings, simulate_pipeline
    from onbottom.hydro.short_crested import pipeline_kinematics
    from onbottom.hydro.storm_kinematics import current_normal_to_pipe

    t0, c0 = time.perf_counter(), time.process_time()
    p = route.pipeline
    sec = route.sections[gov["index"]] if section is None else section
    length, element_length = (
        (p.length, p.element_length) if mesh is None else (mesh["length"], mesh["element_length"])
    )
    k = sec.storm_index(gov["combination"])
    setup = sec.storms[k].setup if value is None else sec.trial_storm(k, value)
    pipe = setup.pipe
    d = pipe.outer_diameter
    allow = route.dynamic.allowable_for(d)
    steel = getattr(sec.pipe, "steel_outer_diameter", None)
    model = PipelineModel(
        pipe=pipe,
        length=length,
        element_length=element_length,
        soil=setup.soil,
        end_conditions=p.end_conditions,
        force_model=setup.force_model,
        reductions=setup.reductions,
        current=current_normal_to_pipe(setup.current, d, setup.z0),
        strain_fibre_distance=None if steel is None else 0.5 * steel,
    )
    s = setup.settings
    stop = s.stop_displacement_over_d
    if stop_at_allowable:
        limit = STOP_MARGIN * allow / d
        stop = limit if stop is None else min(stop, limit)
    settings = PipelineSettings(
        dt_max=s.dt_max,
        dt_min=s.dt_min,
        max_displacement_increment_over_d=max(s.max_displacement_increment_over_d, 0.05),
        stop_displacement_over_d=stop,
        record_interval=None,  # envelopes only
        chunk_duration=3600.0,
        strain_limit=p.strain_limit,
    )
    kin = pipeline_kinematics(
        setup.storm.with_seed(gov["seed"]), setup.depth, model.x,
        sample_interval=setup.sample_interval,
    )  # fmt: skip
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = simulate_pipeline(model, kin, duration=p.duration, settings=settings)
    ymax = float(r.max_displacement)
    strain_ok = r.criteria.get("strain")
    ratio = max(ymax / allow, float(r.max_strain) / p.strain_limit)
    row = {
        "design_value": value,
        "diameter_m": d,
        "submerged_weight_n_per_m": float(pipe.submerged_weight),
        "condition": sec.storms[k].condition,
        "allowable_m": allow,
        "max_displacement_m": ymax,
        "max_displacement_over_D": ymax / d,
        "worst_node_x_m": r.worst_node_x,
        "max_strain": float(r.max_strain),
        "strain_check": strain_ok,
        "criteria": {c: v for c, v in r.criteria.items() if c != "strain"},
        "status": int(r.status),
        "success": bool(r.success),
        "message": r.message,
        "stopped_at_allowable": bool(stop_at_allowable and ymax > allow),
        "pass": bool(ymax <= allow and strain_ok is not False),
        "ratio": ratio,
        "cpu_time_s": time.process_time() - c0,
        "wall_time_s": time.perf_counter() - t0,
    }
    return row, r


def _section_solver(
    route: Route, gov: dict[str, Any], value: float | None, section: Any = None
) -> dict[str, Any]:
    """The section solver on the FE's storm and seed at ``value``: max |y| [m]."""
    from onbottom.assess.dynamic import run_seeds

    sec = route.sections[gov["index"]] if section is None else section
    k = sec.storm_index(gov["combination"])
    setup = sec.storms[k].setup if value is None else sec.trial_storm(k, value)
    r = run_seeds(setup, [gov["seed"]])[0]
    return {"max_displacement_m": r["max_displacement"], "status": r["status"]}


CAUSES = (
    "end conditions: the FE stretch is held at its ends ({ends}) over {length:g} m, the section"
    " solver is a rigid unit length; a short fixed stretch stiffens the line, a free one does not",
    "short-crestedness: the FE line sees the storm synthesised short-crested along it (phase"
    " and amplitude vary node to node), the section solver one point's kinematics; where the"
    " crests are long the line moves as a whole and the loads do not average out",
    "axial restraint: the FE line mobilises axial friction and bending, so a node that slides"
    " drags its neighbours (and is dragged back); the section solver has no axial or bending"
    " stiffness",
)
"""Candidate causes stated where the two solvers disagree (:data:`DISAGREEMENT_FACTOR`)."""


def run_governing_pipeline(
    route: Route, sections: list[dict[str, Any]], out: str | Path | None, *, identity: str = ""
) -> dict[str, Any] | None:
    """Run the pipeline FE of the governing section at its design and, where it fails, raise the
    design until it passes (see the module); None when no section qualifies. ``out``: folder of
    ``pipeline.nc`` (:func:`fe_dataset` of the accepted run; None: not written); ``identity``:
    its run identity (the resume key of ``sections/pipeline.json``).

    Returns the results.json ``pipeline`` document: the keys of :func:`governing_storm`, the
    line (length_m, element_length_m, n_nodes, end_conditions, strain_limit, duration_s), the
    accepted run's results (keys of :func:`pipeline_trial`, ``envelopes``), ``section_design``
    (the section's design before the FE), ``at_section_design`` (the complete FE run there, with
    the section solver's max |y| on the same storm and seed, their ratio and ``disagree``),
    ``search`` (the trials and message; None when the section design passes), ``design_value``
    (the accepted design; None: no design in range passes the FE) and ``raised``.
    """
    gov = governing_storm(route, sections)
    if gov is None:
        return None
    result = next(s for s in sections if s["index"] == gov["index"])
    return check_section_pipeline(
        route, route.sections[gov["index"]], result, out, gov=gov, identity=identity
    )


def check_section_pipeline(
    route: Route,
    section: Any,
    result: dict[str, Any],
    out: str | Path | None = None,
    *,
    gov: dict[str, Any] | None = None,
    early_stop: bool = False,
    name: str = "pipeline.nc",
    identity: str = "",
) -> dict[str, Any]:
    """The pipeline FE check of one section's design, raised until it passes (see the module).

    Stages: the FE storm (``gov``, default :func:`section_storm` of ``result``) and mesh → the
    run at the section's design (the nearest accepted trial of the section solver's search),
    with the section solver on the same storm and seed → the design raised where it fails,
    the section's passing trials as the first guesses → the document. ``section``: the
    :class:`~onbottom.assess.route.Section`; ``result``: its result (``design_value``,
    ``levels``, ``dynamic``); ``out``: the output folder of the NetCDF ``name`` (a path
    relative to ``out``: :func:`fe_dataset` of the accepted run, written under a temporary name
    and renamed; None: not written), ``identity`` its run identity; ``early_stop``: stop the run
    at the section's design too once |y| passes the allowable (its verdict is the complete
    run's; its max |y| a lower bound). Returns the keys of :func:`run_governing_pipeline`,
    ``netcdf`` (the file, or None) and ``mesh``.
    """
    t0, c0 = time.perf_counter(), time.process_time()
    gov = section_storm(route, result) if gov is None else gov
    x0 = gov["design_value"]
    mesh = _mesh_for(route, section, gov, x0)
    trial_mesh = mesh if route.pipeline.mesh == "rule" else None
    first, r0 = pipeline_trial(
        route, gov, x0, stop_at_allowable=early_stop, section=section, mesh=trial_mesh
    )
    at_design = _at_design(route, gov, section, first)
    accepted, res, search, value = first, r0, None, x0
    if not first["pass"] and x0 is not None:
        search, accepted, res, value = _raise_design(
            route, gov, section, result, first, r0, trial_mesh
        )
    path = None if out is None or res.envelopes is None else Path(out) / name
    doc = _document(route, gov, mesh, accepted, res, search, value, at_design, path) | {
        "cpu_time_s": time.process_time() - c0,
        "wall_time_s": time.perf_counter() - t0,
    }
    if path is not None:
        save_dataset(fe_dataset(route, doc, res, identity=identity), path)
    return doc


def fe_dataset(route: Route, doc: dict[str, Any], res: Any, *, identity: str = "") -> Any:
    """The NetCDF of a section's FE check (``pipeline.nc``, ``pipeline/NN-<section>.nc``).

    Parameters
    ----------
    route : Route
        The route (its identity, variable and ``[pipeline]``).
    doc : dict
        The check's document (:func:`check_section_pipeline`).
    res : PipelineResult
        The accepted run (:func:`pipeline_trial`).
    identity : str
        The run identity of the check (the section's resume key).

    Returns
    -------
    xarray.Dataset
        The accepted run's envelopes along the line (dim ``node``, coordinate ``x`` [m]:
        ``max_abs_y`` [m], ``max_strain`` [-], ``max_abs_moment`` [N·m], ...) and the verdict
        as scalars: ``max_displacement`` [m] (the max |y| the route reports, the maximum of
        ``max_abs_y``), ``allowable`` [m], ``line_max_strain`` [-], ``strain_limit`` [-],
        ``passed`` (1: the accepted design passes), ``stopped_at_allowable`` (1: a stopped
        run, max |y| a lower bound), ``max_displacement_at_section_design`` [m] and, with a
        design variable, ``design_value`` and ``section_design`` [m or N/m; NaN: none passes].
        Attributes: provenance (:func:`onbottom.results.provenance`: model
        ``onbottom.assess.pipeline_fe``, ``parameters`` the FE line and limits, ``seed``,
        ``case_identity`` the route's, ``run_identity``), the section, combination, condition,
        solver status and message (``assess_section``, ``combination`` as before).
    """
    import numpy as np

    from onbottom.results import annotate, provenance

    unit = {"concrete_thickness": "m", "submerged_weight": "N/m"}.get(route.variable)
    at = doc.get("at_section_design") or doc

    def scalar(v: Any, units: str, long_name: str) -> tuple[tuple, Any, dict[str, str]]:
        value = np.int8(v) if units == "flag" else np.float64(np.nan if v is None else v)
        return (), value, {"long_name": long_name, "units": "1" if units == "flag" else units}

    var = route.variable
    data = {
        "max_displacement": (doc["max_displacement_m"], "m", "largest |lateral displacement|"),
        "allowable": (doc["allowable_m"], "m", "allowable lateral displacement"),
        "line_max_strain": (doc["max_strain"], "1", "largest fibre strain on the line"),
        "strain_limit": (doc["strain_limit"], "1", "strain limit"),
        "max_displacement_at_section_design": (
            at["max_displacement_m"],
            "m",
            "largest |lateral displacement| at the section design",
        ),
        "passed": (bool(doc["pass"]), "flag", "the accepted design passes the pipeline FE"),
        "stopped_at_allowable": (
            bool(doc.get("stopped_at_allowable")),
            "flag",
            "the run stopped at the allowable",
        ),
    }
    if unit is not None:
        data["design_value"] = (doc["design_value"], unit, f"design {var}")
        data["section_design"] = (doc["section_design"], unit, f"section design {var}")
    params = {
        "length_m": doc["length_m"], "element_length_m": doc["element_length_m"],
        "n_nodes": doc["n_nodes"], "end_conditions": doc["end_conditions"],
        "strain_limit": doc["strain_limit"], "duration_s": doc["duration_s"],
        "mesh": route.pipeline.mesh, "sections": route.pipeline.sections,
        "early_stop": route.pipeline.sections == "every",
    }  # fmt: skip
    attrs = provenance(
        "onbottom.assess.pipeline_fe", params, seed=int(doc["seed"]),
        case_identity=route.identity, run_identity=identity, assess_section=doc["section"],
        combination=doc["combination"], condition=str(doc.get("condition")),
        variable=var, status=int(doc["status"]), message=str(doc["message"]),
    )  # fmt: skip
    scalars = {k: scalar(*v) for k, v in data.items()}
    return annotate(res.envelopes.assign(scalars).assign_attrs(attrs))


def _at_design(
    route: Route, gov: dict[str, Any], section: Any, first: dict[str, Any]
) -> dict[str, Any]:
    """The FE run at the section's design with the section solver's max |y| on the same storm
    and seed, their ratio, ``disagree`` and the candidate causes."""
    p = route.pipeline
    sect = _section_solver(route, gov, gov["design_value"], section)
    y_fe, y_sec = first["max_displacement_m"], sect["max_displacement_m"]
    factor = y_fe / y_sec if y_sec > 0 else float("inf")
    return first | {
        "section_solver_max_displacement_m": y_sec,
        "fe_over_section": factor,
        "disagree": bool(factor > DISAGREEMENT_FACTOR or factor < 1.0 / DISAGREEMENT_FACTOR),
        "causes": [c.format(ends=p.end_conditions, length=p.length) for c in CAUSES],
    }


def _raise_design(
    route: Route,
    gov: dict[str, Any],
    section: Any,
    result: dict[str, Any],
    first: dict[str, Any],
    r0: Any,
    mesh: dict[str, Any] | None,
) -> tuple[dict[str, Any], dict[str, Any], Any, float | None]:
    """The design raised from the failing section design x0 until the FE passes
    (:func:`onbottom.assess.dynamic.search_dynamic`, failing trials stopped at the allowable;
    the first guesses: the section's heavier passing values already known, then x0 + 2, 4, 8,
    ... tolerances): (the search, the accepted row, its result, the value; None: none passes)."""
    from onbottom.assess.dynamic import search_dynamic

    x0 = gov["design_value"]
    d, rng = route.dynamic, route.design
    _lo, hi, tol = (
        (rng.thickness_min, rng.thickness_max, d.thickness_tolerance_m)
        if route.variable == "concrete_thickness"
        else (rng.weight_min, rng.weight_max, d.weight_tolerance_n_per_m)
    )
    runs: dict[float, tuple[dict[str, Any], Any]] = {}

    def evaluate(x: float) -> tuple[float, int]:
        row, res = pipeline_trial(route, gov, x, stop_at_allowable=True, section=section, mesh=mesh)
        runs[float(x)] = (row, res)
        return row["ratio"], 1

    levels = result["levels"]
    known_pass = sorted(
        v for v in [(levels.get(k) or {}).get("value") for k in levels]
        + [x for x, g in ((result.get("dynamic") or {}).get("bisection") or {}).get("trials", [])
           if g <= 1.0]
        if v is not None and v > x0
    )  # fmt: skip
    ladder = [x0 + tol * 2**j for j in range(1, 12) if x0 + tol * 2**j < hi]
    guesses = sorted(set(ladder) | set(known_pass))
    search = search_dynamic(evaluate, lo=x0, hi=hi, tol=tol,
                            known=[(x0, first["ratio"])], guesses=guesses)  # fmt: skip
    search = {k: search[k] for k in ("value", "status", "bracket", "trials", "message")}
    value = search["value"]
    if value is not None:
        accepted, res = runs.get(float(value), (first, r0))
    else:
        accepted, res = first, r0
    return search, accepted, res, value


def _document(
    route: Route,
    gov: dict[str, Any],
    mesh: dict[str, Any],
    accepted: dict[str, Any],
    res: Any,
    search: dict[str, Any] | None,
    value: float | None,
    at_design: dict[str, Any],
    path: Path | None,
) -> dict[str, Any]:
    """The results.json ``pipeline`` document of a section's FE check (``path``: its NetCDF)."""
    p = route.pipeline
    x0 = gov["design_value"]
    env = res.envelopes
    ok = accepted["pass"] and (value is not None or x0 is None)
    return (
        gov
        | accepted
        | {
            "design_value": value if ok or x0 is None else None,
            "section_design": x0,
            "raised": bool(ok and x0 is not None and value is not None and value > x0),
            "pass": bool(ok),
            "at_section_design": at_design,
            "search": search,
            "length_m": mesh["length"],
            "element_length_m": mesh["element_length"],
            "n_nodes": int(res.x.size),
            "end_conditions": p.end_conditions,
            "strain_limit": p.strain_limit,
            "duration_s": p.duration,
            "envelopes": None
            if env is None
            else {
                "x": [float(v) for v in env["x"].values],
                "max_abs_y": [float(v) for v in env["max_abs_y"].values],
                "max_strain": [float(v) for v in env["max_strain"].values],
                "max_abs_moment": [float(v) for v in env["max_abs_moment"].values],
            },
            "netcdf": None if path is None else str(path),
        }
        | ({"mesh": mesh} if p.mesh == "rule" else {})
    )
