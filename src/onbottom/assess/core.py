"""``assess(route) -> Assessment``: every F109 level on every KP section of a route.

The route is a built :class:`~onbottom.assess.route.Route`
(:func:`onbottom.cases.assess.load_route` builds it from a route case file).

For each section (one task on Dask, :mod:`onbottom.study.engine`), in every load combination
(each in its pipe condition):

* **vertical** — F109 (2017) §3.3 Eq 3.1 (flotation, γ_W) in every ``design.vertical_conditions``;
* **absolute** — F109 §3.6 Eqs 3.38 (lateral) and 3.39 (vertical), with the minimum concrete
  thickness (or submerged weight) that passes every static check
  (:func:`onbottom.checks.design.design_concrete_thickness`), as ``onbottom stability`` does;
* **generalized** — F109 §3.5 from F109's own tables (:mod:`onbottom.checks.f109_generalized`
  through :mod:`onbottom.assess.generalized`), else "not covered" with the reason;
* **dynamic curves** (``[levels] dynamic_curves``) — the tool's own curve sweeps, read in the
  same groups: shown beside the others, never presented as F109's and never governing;
* **dynamic** — storms on the section over seeds at the given weight (as ``onbottom storm
  --seeds N``) and the minimum weight for which every seed stays within the allowable
  displacement (:mod:`onbottom.assess.dynamic`), never below the flotation minimum (Eq 3.1).

The governing (design) value per section is the smallest weight among the levels run that
passes (absolute, generalized, dynamic) — each a complete F109 design method on its own — with
a **design floor**: it is never below F109's generalized requirement for the same allowable
displacement (0.5D ↔ L_stable, 10D ↔ L_10) unless ``[levels] allow_below_generalized`` gives
the reason; where F109's tables leave a current-dominated combination (M >= 0.8) uncovered,
the dynamic design is bounded below by the same storms on Coulomb friction (no penetration
benefit) unless ``[levels] allow_below_coulomb`` gives the reason. Each section's
``design_floor`` states the rule in words (:data:`FLOOR_RULES`) and the dynamic/generalized
submerged-weight ratio. The dynamic and generalized values are raised to the flotation minimum.
The report states the weight the dynamic level saves against the absolute one.

Resumable: each finished section writes ``sections/NN-<slug>.json`` in the output folder
(atomic rename) holding the run identity: the section's inputs, the levels and options
(:attr:`Section.identity <onbottom.assess.route.Section>`), the package's content hash
(:func:`onbottom._version.content_hash`) and the content hash of every data file the section
reads (the curve sweeps of the generalized level), and a checksum of the whole file. A rerun
reuses a section whose identity matches; a section whose identity differs is run again, and
:attr:`Assessment.recomputed` says why (inputs, package or which data file changed); a file
whose checksum does not match its content (edited by hand) is refused by name
(:class:`~onbottom.errors.ResultFileError`).
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import re
import time
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

from onbottom._version import __version__, content_hash, file_hash
from onbottom.assess.route import Route, Section
from onbottom.errors import ResultFileError
from onbottom.results import (
    annotate,
    checksum_json,
    provenance,
    verify_json_checksum,
    write_text_atomic,
)

__all__ = ["Assessment", "assess"]

SECTION_FOLDER = "sections"
PIPELINE_FOLDER = "pipeline"
"""Folder of the sections' pipeline FE results (``[pipeline] sections = "every"``)."""


def _slug(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9]+", "-", name).strip("-").lower() or "section"


def section_file(out: Path, i: int, name: str) -> Path:
    return out / SECTION_FOLDER / f"{i:02d}-{_slug(name)}.json"


def pipeline_file(out: Path, i: int, name: str) -> Path:
    """The pipeline FE results of section ``i`` (``[pipeline] sections = "every"``): the
    NetCDF of :func:`onbottom.assess.pipeline.fe_dataset`, named as its ``sections/`` file."""
    return out / PIPELINE_FOLDER / f"{i:02d}-{_slug(name)}.nc"


@dataclass(frozen=True)
class _SectionJob:
    """A picklable section task: the route's settings (no sections), the section, its index,
    the output folder."""

    route: Route
    section: Section
    index: int
    out: str | None
    curve_files: tuple[str, ...] = ()
    identity: dict[str, Any] = field(default_factory=dict)

    def __call__(self, _: Any = None) -> dict[str, Any]:
        t0, c0 = time.perf_counter(), time.process_time()
        ident = _digest(self.identity) if self.identity else self.section.identity
        result = _run_section(self.route, self.section, self.index, self.curve_files)
        if _fe_every_section(self.route):
            result = _section_pipeline(
                self.route, self.section, result, self.out, self.index, identity=ident
            )
        result["wall_time_s"] = time.perf_counter() - t0
        result["cpu_time_s"] = time.process_time() - c0  # this worker's CPU (load-free cost)
        result["identity"] = ident
        result["identity_parts"] = self.identity
        if self.out is not None:
            path = section_file(Path(self.out), self.index, self.section.name)
            write_text_atomic(path, checksum_json(result, default=_jsonable))
        return result


def _fe_every_section(route: Route) -> bool:
    """The pipeline FE checks every section's design, in the section's task."""
    return route.levels.pipeline_fe and route.pipeline.sections == "every"


def _section_pipeline(
    route: Route,
    sec: Section,
    result: dict[str, Any],
    out: str | None = None,
    index: int = 0,
    *,
    identity: str = "",
) -> dict[str, Any]:
    """The section's result with the pipeline FE check of its design (``pipeline_fe``: the
    document of :func:`onbottom.assess.pipeline.check_section_pipeline`, every FE storm stopped
    at the allowable) and its ``pipeline_fe`` level (:func:`_apply_pipeline`); unchanged where
    the section has no design or no dynamic run. ``out``: the output folder of its NetCDF
    (:func:`pipeline_file` of section ``index``, run identity ``identity``; None: not
    written)."""
    from onbottom.assess.pipeline import check_section_pipeline

    if not (result.get("dynamic") or {}).get("base") or (
        route.variable != "none" and result.get("design_value") is None
    ):
        return result
    name = pipeline_file(Path(), index, sec.name).as_posix()
    doc = _clean(check_section_pipeline(route, sec, result, out, early_stop=True, name=name,
                                        identity=identity))  # fmt: skip
    return _apply_pipeline(route, [result], doc)[0] | {"pipeline_fe": doc}


def _digest(parts: dict[str, Any]) -> str:
    return hashlib.sha256(json.dumps(parts, sort_keys=True).encode()).hexdigest()


def data_hashes(route: Route, files: tuple[str, ...]) -> dict[str, str]:
    """Content hashes (SHA-256) of the data files a section's results depend on, by path:
    the curve sweeps when the generalized level runs. A file that cannot be read counts as
    ``"unreadable"`` (the level reports it)."""
    if not route.levels.generalized:
        return {}
    out = {}
    for f in files:
        try:
            out[str(f)] = file_hash(f)
        except OSError:
            out[str(f)] = "unreadable"
    return out


def section_identity_parts(section: Section, data: dict[str, str]) -> dict[str, Any]:
    """What a section's saved result is keyed on: its inputs (:attr:`Section.identity`), the
    package's content hash and the data files' hashes (:func:`data_hashes`)."""
    return {"inputs": section.identity, "package": content_hash(), "data": dict(data)}


def stale_reason(old: dict[str, Any] | None, new: dict[str, Any]) -> str:
    """Why a saved result keyed on ``old`` (its ``identity_parts``) is not the result of
    ``new``: which inputs, package or data file differ ("" when none)."""
    if not old:
        return "written by an earlier onbottom without a package or data hash"
    why = []
    if old.get("inputs") != new["inputs"]:
        why.append("the section's inputs changed")
    if old.get("package") != new["package"]:
        why.append(
            f"the onbottom package changed (content {str(old.get('package'))[:12]}… →"
            f" {new['package'][:12]}…)"
        )
    od, nd = old.get("data") or {}, new["data"]
    for f in sorted(set(od) | set(nd)):
        if od.get(f) != nd.get(f):
            what = "added" if f not in od else "no longer read" if f not in nd else "changed"
            why.append(f"data file {f} {what}")
    return "; ".join(why)


def read_saved(path: Path, what: str) -> dict[str, Any] | None:
    """The saved JSON result ``path`` (None when unreadable: it is recomputed); a file whose
    checksum does not match its content is refused by name."""
    try:
        old = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(old, dict):
        return None
    if verify_json_checksum(old) is False:
        raise ResultFileError(
            f"{what} {str(path)!r} was changed after onbottom wrote it (its checksum does"
            " not match its content): a result edited by hand is not reused; delete the"
            " file to recompute it, or give another --out folder",
            field="--out",
        )
    return old


def _jsonable(x: Any) -> Any:
    if isinstance(x, (np.floating, np.integer)):
        return x.item()
    if isinstance(x, np.ndarray):
        return x.tolist()
    return str(x)


def _clean(x: Any) -> Any:
    """JSON-safe numbers (inf/nan → None)."""
    if isinstance(x, dict):
        return {str(k): _clean(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_clean(v) for v in x]
    if isinstance(x, (np.floating, np.integer)):
        x = x.item()
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, (str, int, float, bool)) or x is None:
        return x
    return str(x)


def _design(variable, section, seabed, env, combos, options, d, evaluate=None) -> dict:
    """Minimum of ``variable`` passing the rows of ``evaluate`` (default every static check)."""
    from onbottom.checks import design as dz
    from onbottom.checks.evaluation import solve_design
    from onbottom.inputs.pipe_buildup import PipeBuildUp

    try:
        if evaluate is None:
            res = solve_design(variable, section, seabed, env, combos, options, d)
        else:
            from dataclasses import replace

            if isinstance(section, PipeBuildUp):
                build = lambda t: section.with_layer_thickness(d.layer, t)  # noqa: E731
                lo, hi, tol, unit = d.thickness_min, d.thickness_max, 1.0e-5, "m"
            else:
                build = lambda w: replace(section, submerged_weight=w, mass=None)  # noqa: E731
                lo, hi, tol, unit = d.weight_min, d.weight_max, 0.1, "N/m"
            res = dz.minimum_passing(build, evaluate, lo, hi, 51, tol, variable, unit)
        return {"success": True, "value": res.value, "utilisation": res.utilisation,
                "governing_check": res.governing_check, "message": res.message}  # fmt: skip
    except dz.NoFeasibleDesignError as exc:
        return {"success": False, "value": None, "utilisation": exc.best_utilisation,
                "governing_check": None, "message": str(exc)}  # fmt: skip


def _generalized_design(variable, sec: Section, files, route: Route, levels) -> dict:
    """Minimum of the design variable with every combination's generalized utilisation <= 1
    (the same scan + brentq as the static design), raised to the flotation minimum; a trial
    whose point leaves the tables counts as failing (nothing is extrapolated). ``files``:
    curve sweeps — empty for F109's tables (level ``generalized``), the sweeps for the level
    ``dynamic_curves``."""
    import math as _m

    from onbottom.assess.generalized import dynamic_curve_rows, generalized_rows
    from onbottom.checks.design import CheckRow, run_checks

    seabed, env, combos, options = sec.seabed, sec.environment, sec.combinations, sec.options

    def evaluate(s: Any) -> list:
        rows = run_checks(s, seabed, env, combos, options)
        kw = {"seabed_model": sec.seabed_model, "water_density": env.water_density}
        gen = (
            dynamic_curve_rows(rows, list(files), route.dynamic.allowable, **kw)
            if files
            else generalized_rows(rows, route.dynamic.allowable, **kw)
        )
        return [
            CheckRow(g["name"], g["combination"], g["condition"],
                     g["utilisation"] if g["covered"] else _m.inf,
                     bool(g["covered"] and g["pass"]), {})
            for g in gen
        ]  # fmt: skip

    res = _design(variable, sec.pipe, seabed, env, combos, options, route.design, evaluate)
    vert = levels.get("vertical", {}).get("value")
    if res["success"] and vert is not None and vert > res["value"]:
        res |= {"value": vert, "governing_check": "flotation (F109 Eq 3.1)"}
    return res


def _table_level(gen: list[dict[str, Any]], what: str) -> dict[str, Any]:
    covered = [g for g in gen if g["covered"]]
    return {
        "success": False,
        "value": None,
        "covered": len(covered),
        "points": len(gen),
        "message": f"not covered by {what}: " + gen[0]["message"]
        if not covered and gen
        else f"{len(covered)} of {len(gen)} combinations covered by {what}; a minimum needs"
        " every combination covered",
    }


CURRENT_DOMINATED_M = 0.8
"""M = V/U_s from which a point not covered by F109's tables is treated as current-dominated:
the dynamic level is then bounded below by the same storms on Coulomb friction."""


def _coulomb_trial(trial: Any) -> Any:
    """``trial(k, x)`` with the soil replaced by Coulomb friction at the seabed's μ (no
    penetration, no passive resistance: no benefit from embedment gained in the storm)."""
    from onbottom.soil.coulomb import CoulombFriction

    def coulomb(k: int, x: float) -> Any:
        setup = trial(k, x)
        return replace(setup, soil=CoulombFriction.from_seabed(setup.seabed))

    return coulomb


def _run_section(
    route: Route, sec: Section, i: int, curve_files: tuple[str, ...]
) -> dict[str, Any]:
    """Every level of one section, in named stages: the static levels (vertical, absolute)
    → the table levels (generalized, dynamic curves) → the dynamic level at the given design
    → the dynamic design search → the governing design → the section's result."""
    rows, levels, checks, notes = _static_levels(route, sec)
    gen, floor_requirement = _table_levels(route, sec, rows, levels, checks, curve_files)
    dynamic: dict[str, Any] = {}
    if route.levels.dynamic:
        dynamic = _dynamic_at_given(route, sec, checks)
        if route.variable != "none":
            _dynamic_design(route, sec, dynamic, levels, gen)
    return _section_result(route, sec, i, levels, gen, floor_requirement, checks, dynamic, notes)


def _static_levels(
    route: Route, sec: Section
) -> tuple[list[Any], dict[str, Any], list[dict[str, Any]], list[str]]:
    """The F109 checks at the given design, the vertical (flotation) and absolute designs:
    (check rows, levels, check rows as dicts, notes)."""
    from onbottom.checks.design import penetration_outside_validity, run_checks
    from onbottom.errors import OutOfRangeWarning
    from onbottom.inputs.consistency import warnings_reported_by_case

    section, seabed, env = sec.pipe, sec.seabed, sec.environment
    combos, options, variable = sec.combinations, sec.options, route.variable
    notes: list[str] = []
    with warnings.catch_warnings(record=True) as caught, warnings_reported_by_case():
        warnings.simplefilter("always", OutOfRangeWarning)
        rows = run_checks(section, seabed, env, combos, options)
        levels: dict[str, Any] = {}
        vertical_rows = lambda s: [  # noqa: E731
            r for r in run_checks(s, seabed, env, combos, options) if r.name == "vertical_stability"
        ]
        if variable != "none":
            levels["vertical"] = _design(
                variable, section, seabed, env, combos, options, route.design, vertical_rows
            )
            if route.levels.absolute:
                levels["absolute"] = _design(
                    variable, section, seabed, env, combos, options, route.design
                )
    notes += sorted({str(w.message) for w in caught if issubclass(w.category, Warning)})
    notes += penetration_outside_validity(rows)
    if sec.gap:
        notes.insert(0, sec.gap)
    checks = [
        _clean({k: v for k, v in r.as_dict().items() if k != "details"} | {"level": "absolute"
               if r.name.startswith("absolute") else "vertical", "details": r.details})
        for r in rows
    ]  # fmt: skip
    return rows, levels, checks, notes


def _table_levels(
    route: Route,
    sec: Section,
    rows: list[Any],
    levels: dict[str, Any],
    checks: list[dict[str, Any]],
    curve_files: tuple[str, ...],
) -> tuple[list[dict[str, Any]], dict[str, Any] | None]:
    """The generalized level (F109 §3.5 tables) and the dynamic curves (the tool's own
    sweeps), added to ``levels`` and ``checks``: (the generalized rows, F109's generalized
    requirement computed for the design floor alone, or None)."""
    from onbottom.assess.generalized import dynamic_curve_rows, generalized_rows

    env, variable = sec.environment, route.variable
    gen: list[dict[str, Any]] = []
    floor_requirement: dict[str, Any] | None = None
    if route.levels.generalized or route.levels.dynamic:
        # F109's requirement is the dynamic level's floor even where the generalized level is
        # not run as a level of its own: turning it off is no way below the standard
        gen = generalized_rows(rows, route.dynamic.allowable, seabed_model=sec.seabed_model,
                               water_density=env.water_density)  # fmt: skip
    if route.levels.generalized:
        checks += [_clean(g) for g in gen]
        levels["generalized"] = _table_level(gen, "F109's generalized tables")
        if gen and all(g["covered"] for g in gen) and variable != "none":
            levels["generalized"] |= _generalized_design(variable, sec, (), route, levels)
    elif gen and all(g["covered"] for g in gen) and variable != "none":
        floor_requirement = _table_level(gen, "F109's generalized tables") | _generalized_design(
            variable, sec, (), route, levels
        )
    if curve_files:
        dcr = dynamic_curve_rows(rows, list(curve_files), route.dynamic.allowable,
                                 seabed_model=sec.seabed_model,
                                 water_density=env.water_density)  # fmt: skip
        checks += [_clean(g) for g in dcr]
        levels["dynamic_curves"] = _table_level(dcr, "the dynamic curves") | {
            "files": [Path(f).name for f in curve_files]
        }
        if dcr and all(g["covered"] for g in dcr) and variable != "none":
            levels["dynamic_curves"] |= _generalized_design(
                variable, sec, curve_files, route, levels
            )
    return gen, floor_requirement


def _dynamic_at_given(route: Route, sec: Section, checks: list[dict[str, Any]]) -> dict[str, Any]:
    """The storms of every load combination over the seeds at the given design, the worst
    seed's history (for the report) and one ``dynamic_lateral`` check row per combination
    (added to ``checks``): the ``dynamic`` document with its ``base``."""
    from onbottom.assess import dynamic as dyn

    d = route.dynamic
    seeds = d.seed_list
    names = [c.name for c in sec.storms]
    base = {}
    for c in sec.storms:
        base[c.name] = dyn.run_seeds(c.setup, seeds)
    allow = {
        n: d.allowable_for(base[n][0]["diameter"]) for n in names if base[n]
    }  # D of the given design
    dynamic: dict[str, Any] = {}
    dynamic["base"] = {
        n: {
            "seeds": [r["seed"] for r in base[n]],
            "max_displacement": [r["max_displacement"] for r in base[n]],
            "final_displacement": [r["final_displacement"] for r in base[n]],
            "status": [r["status"] for r in base[n]],
            "diameter": base[n][0]["diameter"],
            "submerged_weight": base[n][0]["submerged_weight"],
            "allowable": allow[n],
            "utilisation": max(r["max_displacement"] for r in base[n]) / allow[n],
            "condition": c.condition,
        }
        for n, c in zip(names, sec.storms, strict=True)
    }
    for (n, b), c in zip(dynamic["base"].items(), sec.storms, strict=True):
        # the worst seed's history, for the report
        worst = b["seeds"][int(np.argmax(b["max_displacement"]))]
        b["history"] = {"seed": worst} | dyn.history(c.setup, worst, duration=d.duration_s)
        checks.append(
            _clean({
                "name": "dynamic_lateral", "combination": n, "condition": b["condition"],
                "utilisation": b["utilisation"], "pass": b["utilisation"] <= 1.0,
                "level": "dynamic",
                "details": {"allowable": b["allowable"], "seeds": len(b["seeds"]),
                            "max_over_seeds": max(b["max_displacement"]),
                            "mean_over_seeds": float(np.mean(b["max_displacement"]))},
            })
        )  # fmt: skip
    return dynamic


def _search_range(route: Route) -> tuple[float, float, float]:
    """(lower bound, upper bound, tolerance) of the design variable's search [m or N/m]."""
    d, rng = route.dynamic, route.design
    if route.variable == "concrete_thickness":
        return rng.thickness_min, rng.thickness_max, d.thickness_tolerance_m
    return rng.weight_min, rng.weight_max, d.weight_tolerance_n_per_m


def _dynamic_design(
    route: Route,
    sec: Section,
    dynamic: dict[str, Any],
    levels: dict[str, Any],
    gen: list[dict[str, Any]],
) -> None:
    """The minimum design of the dynamic level (:func:`onbottom.assess.dynamic.search_dynamic`
    from the runs at the given design, the absolute and generalized designs as guesses, the
    flotation minimum as lower bound) and, where F109's tables leave a current-dominated point
    uncovered, the Coulomb-friction lower bound: ``levels["dynamic"]`` and
    ``dynamic["bisection"]`` (and ``dynamic["coulomb_bound"]``)."""
    from onbottom.assess import dynamic as dyn

    d = route.dynamic
    seeds = d.seed_list
    names = [c.name for c in sec.storms]
    evaluate = dyn.DynamicTrials(sec.trial_storm, len(names), seeds, d.allowable_for)
    evaluate.prime({
        (k, sd): y / dynamic["base"][n]["allowable"]
        for k, n in enumerate(names)
        for sd, y in zip(dynamic["base"][n]["seeds"],
                         dynamic["base"][n]["max_displacement"], strict=True)
    })  # fmt: skip
    lo, hi, tol = _search_range(route)
    vert = levels.get("vertical", {}).get("value")
    if vert is not None and vert > lo:
        lo = min(vert, hi)  # the design is raised to the flotation minimum anyway
    given = sec.given_value
    known = []
    if given is not None and all(len(b["seeds"]) == len(seeds) for b in
                                 dynamic["base"].values()):  # fmt: skip
        known.append((given, max(b["utilisation"] for b in dynamic["base"].values())))
    guesses = [
        levels[k]["value"]
        for k in ("generalized", "absolute")
        if (levels.get(k) or {}).get("success") and levels[k].get("value") is not None
    ]
    b = dyn.search_dynamic(evaluate, lo, hi, tol, known=known, guesses=guesses)
    dynamic["bisection"] = b
    value = b["value"]
    governed = "dynamic lateral (every seed <= allowable)"
    if value is not None and vert is not None and vert > value:
        value, governed = vert, "flotation (F109 Eq 3.1)"
    levels["dynamic"] = {
        "success": value is not None,
        "value": value,
        "utilisation": None,
        "governing_check": governed if value is not None else None,
        "message": b["message"],
        "storms": b["storms"],
    }
    # Coulomb-friction lower bound where F109's tables leave a current-dominated point
    uncovered = [
        g["combination"] for g in gen
        if not g["covered"] and g["details"].get("M", 0.0) >= CURRENT_DOMINATED_M
    ]  # fmt: skip
    if value is None or not uncovered:
        return
    cb_eval = dyn.DynamicTrials(_coulomb_trial(sec.trial_storm), len(names), seeds, d.allowable_for)
    cb = dyn.search_dynamic(cb_eval, lo, hi, tol, known=[], guesses=guesses)
    cbv = cb["value"]
    if cbv is not None and vert is not None and vert > cbv:
        cbv = vert
    dynamic["coulomb_bound"] = {
        "combinations": uncovered, "value": cbv, "message": cb["message"],
        "storms": cb["storms"],
    }  # fmt: skip
    levels["dynamic"]["coulomb_bound"] = cbv
    below = cbv is None or value < cbv
    if below and route.levels.allow_below_coulomb is None:
        levels["dynamic"] |= {
            "value": cbv, "success": cbv is not None, "unbounded_value": value,
            "governing_check": "Coulomb-friction lower bound (same storms, no"
            " penetration benefit)" if cbv is not None else None,
        }  # fmt: skip


def _section_result(
    route: Route,
    sec: Section,
    i: int,
    levels: dict[str, Any],
    gen: list[dict[str, Any]],
    floor_requirement: dict[str, Any] | None,
    checks: list[dict[str, Any]],
    dynamic: dict[str, Any],
    notes: list[str],
) -> dict[str, Any]:
    """The governing level and design (the lightest passing level, raised to the design
    floor), the worst check and the weight saved: the section's result document."""
    candidates = {
        k: v["value"]
        for k, v in levels.items()
        if k in ("absolute", "generalized", "dynamic")
        and v.get("success")
        and v.get("value") is not None
    }
    gov_level = min(candidates, key=candidates.get) if candidates else None
    design_value = candidates.get(gov_level) if gov_level else None
    floor = _design_floor(route, sec, levels, gen, gov_level, design_value, floor_requirement)
    if floor["rule"] == "generalized_floor":
        gov_level, design_value = "generalized", floor["generalized_value"]
    worst = max(
        (c for c in checks if c.get("utilisation") is not None), key=lambda c: c["utilisation"]
    )
    saved = None
    if "absolute" in candidates and "dynamic" in candidates:
        saved = _weight_saved(route, sec, candidates["absolute"], candidates["dynamic"])
    return _clean({
        "index": i, "name": sec.name, "kp_start_m": sec.kp_start, "kp_end_m": sec.kp_end,
        "water_depth": sec.water_depth, "seabed_model": sec.seabed_model,
        "variable": route.variable, "checks": checks, "levels": levels, "dynamic": dynamic,
        "governing_level": gov_level,
        "design_value": design_value,
        "design_floor": floor,
        "governing_check": f"{worst['name']} / {worst['combination']}",
        "max_utilisation": worst["utilisation"],
        "weight_saved": saved, "notes": notes,
        "stability_document": sec.document,
        "sea_states": [{"combination": c.name, "condition": c.condition,
                        "hs": c.sea_state.hs, "tp": c.sea_state.tp,
                        "gamma": c.sea_state.gamma,
                        "wave_direction_deg": c.sea_state.direction_deg,
                        "spreading_s": c.sea_state.spreading_s,
                        "current_velocity": c.current.velocity,
                        "current_reference_height": c.current.reference_height,
                        "current_direction_deg": c.current.direction_deg}
                       for c in sec.combinations],
    })  # fmt: skip


def _submerged_weight(route: Route, sec: Section, x: float) -> float:
    """Submerged weight [N/m] (operation condition of the pipe) at design value ``x``."""
    from dataclasses import replace

    from onbottom.inputs.pipe_buildup import PipeBuildUp

    section = sec.pipe
    if isinstance(section, PipeBuildUp):
        designed = section.with_layer_thickness(route.design.layer, x)
        return designed.properties(sec.condition).submerged_weight
    return replace(section, submerged_weight=x, mass=None).submerged_weight


def _weight_saved(route: Route, sec: Section, x_abs: float, x_dyn: float) -> dict[str, Any]:
    """Submerged weight [N/m] (operation condition of the pipe) at both designs, and the
    difference absolute − dynamic (positive: the dynamic level saves weight)."""
    wa, wd = _submerged_weight(route, sec, x_abs), _submerged_weight(route, sec, x_dyn)
    return {"condition": sec.condition, "absolute_submerged_weight": wa,
            "dynamic_submerged_weight": wd, "saved_submerged_weight": wa - wd,
            "saved_fraction": (wa - wd) / wa, "absolute_value": x_abs,
            "dynamic_value": x_dyn}  # fmt: skip


FLOOR_RULES: dict[str, str] = {
    "at_or_above_generalized": "the design is at or above F109's generalized requirement",
    "generalized_floor": "raised to F109's generalized requirement: the lighter design of the"
    " governing level is not accepted below the standard",
    "allowed_below_generalized": "below F109's generalized requirement, accepted by [levels]"
    " allow_below_generalized",
    "coulomb_floor": "F109's tables do not cover a current-dominated point (M >= 0.8): the"
    " dynamic design is raised to the same storms on Coulomb friction (no penetration benefit)",
    "at_or_above_coulomb": "F109's tables do not cover a current-dominated point (M >= 0.8):"
    " the dynamic design is at or above the same storms on Coulomb friction",
    "allowed_below_coulomb": "F109's tables do not cover a current-dominated point (M >= 0.8);"
    " the dynamic design is below the Coulomb-friction bound, accepted by [levels]"
    " allow_below_coulomb",
    "not_covered": "F109's tables do not cover every combination and no point is"
    " current-dominated (M < 0.8): no floor applies",
    "not_checked": "neither the generalized nor the dynamic level is run, or there is no design"
    " variable: no floor checked",
}
"""Design-floor rules of a section, in words (``design_floor.rule`` of each section)."""


def _design_floor(
    route: Route,
    sec: Section,
    levels: dict[str, Any],
    gen: list[dict[str, Any]],
    gov_level: str | None,
    design_value: float | None,
    requirement: dict[str, Any] | None = None,
) -> dict[str, Any]:
    """Which rule set the design against F109's generalized requirement, and the
    dynamic/generalized submerged-weight ratio (see :data:`FLOOR_RULES`). ``requirement``: F109's
    generalized minimum computed for the floor alone, where the generalized level is not run."""
    g = levels.get("generalized") or requirement or {}
    dyn = levels.get("dynamic") or {}
    out: dict[str, Any] = {"generalized_value": g.get("value"), "dynamic_value": dyn.get("value")}
    gv = g.get("value") if g.get("success") else None
    if gv is not None and dyn.get("success") and dyn.get("value") is not None:
        wg = _submerged_weight(route, sec, gv)
        wd = _submerged_weight(route, sec, dyn["value"])
        out |= {"generalized_submerged_weight": wg, "dynamic_submerged_weight": wd,
                "dynamic_over_generalized_weight": wd / wg if wg > 0 else None}  # fmt: skip
        if dyn.get("unbounded_value") is not None:
            wu = _submerged_weight(route, sec, dyn["unbounded_value"])
            out["unbounded_dynamic_over_generalized_weight"] = wu / wg if wg > 0 else None
    if "coulomb_bound" in dyn:
        out["coulomb_value"] = dyn["coulomb_bound"]
    if route.levels.allow_below_generalized is not None:
        out["allow_below_generalized"] = route.levels.allow_below_generalized
    if route.levels.allow_below_coulomb is not None:
        out["allow_below_coulomb"] = route.levels.allow_below_coulomb
    if not gen or design_value is None:
        rule = "not_checked"
    elif gv is not None:
        if design_value >= gv - 1e-12:
            rule = "at_or_above_generalized"
        elif route.levels.allow_below_generalized is not None:
            rule = "allowed_below_generalized"
        else:
            rule = "generalized_floor"
    elif "coulomb_bound" in dyn:
        cb = dyn["coulomb_bound"]
        unbounded = dyn.get("unbounded_value")
        allowed = route.levels.allow_below_coulomb is not None
        if unbounded is not None:
            rule = "coulomb_floor"
        elif allowed and (cb is None or (dyn.get("value") or 0.0) < cb):
            rule = "allowed_below_coulomb"
        else:
            rule = "at_or_above_coulomb"
    else:
        rule = "not_covered"
    words = FLOOR_RULES[rule]
    if rule in ("allowed_below_generalized",):
        words += f" (reason given: {route.levels.allow_below_generalized!r})"
    if rule == "allowed_below_coulomb":
        words += f" (reason given: {route.levels.allow_below_coulomb!r})"
    return out | {"rule": rule, "words": words, "lightest_level": gov_level}


# ---- the study ----------------------------------------------------------------------------------
@dataclass(frozen=True)
class Assessment:
    """Results of :func:`assess`.

    Attributes
    ----------
    route : Route
        The route assessed.
    sections : list of dict
        Per section: name, KP range [m], checks (rows), levels (per level: success, value,
        governing check, message), dynamic (per-seed results at the given design and the
        bisection), governing_level, design_value, weight_saved, notes.
    identity : str
        The route's identity (:attr:`Route.identity <onbottom.assess.route.Route>`: the
        SHA-256 of the validated case file).
    wall_time_s : float
        Wall time of the study [s]; ``reused`` lists the sections taken from a previous run,
        ``recomputed`` the saved sections run again, as (name, reason).
    pipeline : dict or None
        The pipeline FE run of the governing section (``[levels] pipeline_fe``; keys of
        :func:`onbottom.assess.pipeline.run_governing_pipeline`), None when not run.
    """

    route: Route
    sections: list[dict[str, Any]]
    identity: str
    wall_time_s: float
    reused: list[str] = field(default_factory=list)
    source: str = ""
    pipeline: dict[str, Any] | None = None
    recomputed: list[tuple[str, str]] = field(default_factory=list)

    @property
    def summary(self) -> pd.DataFrame:
        """One row per KP section: governing check and utilisation at the given design,
        required value per level, the governing level and value, the weight saved."""
        rows = []
        for s in self.sections:
            lv = s["levels"]
            ws = s.get("weight_saved") or {}
            rows.append({
                "section": s["name"], "kp_start_m": s["kp_start_m"], "kp_end_m": s["kp_end_m"],
                "water_depth_m": s["water_depth"], "seabed": s["seabed_model"],
                "governing_check": s["governing_check"], "max_utilisation": s["max_utilisation"],
                "variable": s["variable"],
                **{f"{k}_value": (lv.get(k) or {}).get("value")
                   for k in ("vertical", "absolute", "generalized", "dynamic",
                             "dynamic_curves", "pipeline_fe")},
                "governing_level": s["governing_level"], "design_value": s["design_value"],
                "floor_rule": (s.get("design_floor") or {}).get("rule"),
                "dynamic_over_generalized_weight": (s.get("design_floor") or {}).get(
                    "dynamic_over_generalized_weight"),
                "saved_submerged_weight_n_per_m": ws.get("saved_submerged_weight"),
            })  # fmt: skip
        return pd.DataFrame(rows)

    @property
    def checks(self) -> pd.DataFrame:
        """Every check row of every section (level, name, combination, condition,
        utilisation, pass)."""
        rows = [
            {"section": s["name"], **{k: v for k, v in c.items() if k != "details"}}
            for s in self.sections
            for c in s["checks"]
        ]
        return pd.DataFrame(rows)

    def dynamic_dataset(self) -> xr.Dataset:
        """Per-seed results of the dynamic runs at the given design: dims (section,
        combination, seed); max/final displacement [m], status, allowable [m]."""
        secs = [s for s in self.sections if s.get("dynamic", {}).get("base")]
        if not secs:
            return xr.Dataset(attrs=provenance("onbottom.assess", None))
        combos = sorted({n for s in secs for n in s["dynamic"]["base"]})
        seeds = sorted(
            {sd for s in secs for b in s["dynamic"]["base"].values() for sd in b["seeds"]}
        )
        shape = (len(secs), len(combos), len(seeds))
        ymax, yfin = np.full(shape, np.nan), np.full(shape, np.nan)
        status = np.full(shape, -99, dtype=np.int64)
        allow = np.full(shape[:2], np.nan)
        for a, s in enumerate(secs):
            for b, n in enumerate(combos):
                base = s["dynamic"]["base"].get(n)
                if not base:
                    continue
                allow[a, b] = base["allowable"]
                for sd, y, f, st in zip(
                    base["seeds"],
                    base["max_displacement"],
                    base["final_displacement"],
                    base["status"],
                    strict=True,
                ):
                    c = seeds.index(sd)
                    ymax[a, b, c], yfin[a, b, c], status[a, b, c] = y, f, st  # fmt: skip
        ds = xr.Dataset(
            {
                "max_displacement": (("section", "combination", "seed"), ymax),
                "final_displacement": (("section", "combination", "seed"), yfin),
                "status": (("section", "combination", "seed"), status),
                "allowable": (("section", "combination"), allow),
            },
            coords={"section": [s["name"] for s in secs], "combination": combos, "seed": seeds},
            attrs=provenance("onbottom.assess", None, case_identity=self.identity,
                             source=self.source),
        )  # fmt: skip
        for k, u in (("max_displacement", "m"), ("final_displacement", "m"),
                     ("allowable", "m"), ("status", "1")):  # fmt: skip
            ds[k].attrs.setdefault("units", u)
        return annotate(ds)


def assess(
    route: Route,
    *,
    out: str | Path | None = None,
    n_workers: int | None = None,
    scheduler: str | None = None,
    progress: bool = False,
    curve_files: list[str] | None = None,
    source: str = "",
) -> Assessment:
    """Run every level of every section of a route (see the module docstring).

    Parameters
    ----------
    route : Route
        The built route (:func:`onbottom.cases.assess.load_route` reads one from a route case
        file).
    out : path or None
        Output folder of the per-section JSON files (resume); None: nothing written.
    n_workers : int or None
        Local Dask workers (None: one per core; 0: in this process, no Dask).
    scheduler : str or None
        Address of a Dask scheduler.
    progress : bool
        A progress bar over the sections.
    curve_files : list of str or None
        NetCDF curve sweeps of the ``dynamic_curves`` level (None: the route's
        ``levels.dynamic_curves``; empty: the level is not run).
    source : str
        Where the route came from (a path, or "embedded example").
    """
    t0 = time.perf_counter()
    files = tuple(route.levels.dynamic_curves if curve_files is None else curve_files)
    settings = replace(route, sections=())  # each job carries its own section only
    outp = None if out is None else Path(out)
    results: dict[int, dict[str, Any]] = {}
    jobs = []
    reused = []
    recomputed = []
    data = data_hashes(route, files)
    for i, s in enumerate(route.sections):
        parts = section_identity_parts(s, data) if s.identity else {}
        if parts and _fe_every_section(route):  # the section's result holds its FE check
            parts["pipeline"] = dataclasses.asdict(route.pipeline)
        if outp is not None and parts:  # a section without an identity is always run
            f = section_file(outp, i, s.name)
            if f.is_file():
                old = read_saved(f, "saved section result")
                lost = _lost_pipeline_file(outp, i, s.name, old)
                if old and old.get("identity") == _digest(parts) and not lost:
                    results[i] = old
                    reused.append(s.name)
                    continue
                why = lost or (
                    stale_reason(old.get("identity_parts"), parts) if old else "unreadable"
                )
                recomputed.append((s.name, why or "its run identity differs"))
        out_s = None if outp is None else str(outp)
        jobs.append(_SectionJob(settings, s, i, out_s, files, parts))
    if jobs:
        if n_workers == 0 and scheduler is None:
            from tqdm.auto import tqdm

            done = [job() for job in tqdm(jobs, disable=not progress, unit="section")]
        else:
            from onbottom.study.engine import ParallelMap, dask_client

            workers = n_workers if n_workers is None else max(1, min(n_workers, len(jobs)))
            with dask_client(None, scheduler_address=scheduler, n_workers=workers) as c:
                done = ParallelMap(c, batch_size=1, progress=progress)(_call, jobs)
        for r in done:
            results[r["index"]] = r
    sections = [results[i] for i in range(len(route.sections))]
    if _fe_every_section(route):
        pipe = _governing_section_pipeline(route, sections)
    else:
        pipe = _pipeline(route, sections, outp) if route.levels.pipeline_fe else None
        if pipe is not None:
            sections = _apply_pipeline(route, sections, pipe)
    return Assessment(route=route, sections=sections, identity=route.identity,
                      wall_time_s=time.perf_counter() - t0, reused=reused,
                      source=source, pipeline=pipe, recomputed=recomputed)  # fmt: skip


def _lost_pipeline_file(out: Path, i: int, name: str, old: dict[str, Any] | None) -> str:
    """Why saved section ``i`` cannot be reused for its FE check's NetCDF (:func:`pipeline_file`):
    gone or not a complete result; empty: it is there (its path in ``old`` made that of
    ``out``), or the section wrote none."""
    from onbottom.results import check_result_file

    doc = (old or {}).get("pipeline_fe") or {}
    if not doc.get("netcdf"):
        return ""
    f = pipeline_file(out, i, name)
    try:
        check_result_file(f)
    except (ResultFileError, OSError):
        return f"its pipeline FE results {f.relative_to(out).as_posix()} are missing or partial"
    doc["netcdf"] = str(f)
    return ""


def _governing_file_kept(out: Path, old: dict[str, Any]) -> bool:
    """Whether the saved governing-section run's NetCDF (``pipeline.nc``) is still there and
    complete (its path in ``old`` made that of ``out``); True when the run wrote none."""
    from onbottom.results import check_result_file

    if not old.get("netcdf"):
        return True
    f = out / "pipeline.nc"
    try:
        check_result_file(f)
    except (ResultFileError, OSError):
        return False
    old["netcdf"] = str(f)
    return True


def _governing_section_pipeline(route: Route, sections: list[dict[str, Any]]) -> dict | None:
    """Where the FE checked every section: the check of the governing section (the heaviest
    design after the FE; ties: the highest dynamic utilisation), None when none ran."""
    from onbottom.assess.pipeline import governing_storm

    checked = [s for s in sections if s.get("pipeline_fe")]
    gov = governing_storm(route, checked) if checked else None
    if gov is None:
        return None
    return next(s["pipeline_fe"] for s in checked if s["index"] == gov["index"])


def _pipeline(route: Route, sections: list[dict[str, Any]], out: Path | None) -> dict | None:
    """The pipeline FE run of the governing section, reused from ``sections/pipeline.json``
    when its identity (the section results it depends on and the pipeline settings) matches."""
    from onbottom.assess.pipeline import governing_storm, run_governing_pipeline

    gov = governing_storm(route, sections)
    if gov is None:
        return None
    ident = hashlib.sha256(
        json.dumps(
            {"governing": gov, "pipeline": dataclasses.asdict(route.pipeline), "design": 2,
             "section": next(s["identity"] for s in sections if s["index"] == gov["index"]),
             "version": __version__, "package": content_hash()},
            sort_keys=True,
        ).encode()
    ).hexdigest()  # fmt: skip
    f = None if out is None else out / SECTION_FOLDER / "pipeline.json"
    if f is not None and f.is_file():
        old = read_saved(f, "saved pipeline result")
        if old and old.get("identity") == ident and _governing_file_kept(out, old):
            return old | {"reused": True}
    res = run_governing_pipeline(route, sections, out, identity=ident)
    res = _clean(res | {"identity": ident})
    if f is not None:
        write_text_atomic(f, checksum_json(res))
    return res


def _apply_pipeline(
    route: Route, sections: list[dict[str, Any]], pipe: dict[str, Any]
) -> list[dict[str, Any]]:
    """The governing section with its ``pipeline_fe`` level: its design rises to the value that
    passes the pipeline FE (governing level ``pipeline_fe``), or it has no design (the reason in
    ``no_design_reason``) when none in range passes. The other sections are unchanged (the FE
    runs on the governing section only)."""
    out = []
    for s in sections:
        if s["index"] != pipe.get("index"):
            out.append(s)
            continue
        s = dict(s)
        levels = dict(s["levels"])
        at = pipe.get("at_section_design") or {}
        if route.variable == "none":
            levels["pipeline_fe"] = {
                "success": bool(pipe["pass"]), "value": None,
                "governing_check": "pipeline FE: max |y| <= allowable, strain <= limit",
                "message": "at the given design: " + ("pass" if pipe["pass"] else "FAIL"),
            }  # fmt: skip
        elif pipe["pass"]:
            raised = bool(pipe.get("raised"))
            levels["pipeline_fe"] = {
                "success": True, "value": pipe["design_value"],
                "governing_check": "pipeline FE: max |y| <= allowable, strain <= limit",
                "message": (
                    f"the section design fails the pipeline FE (max |y| "
                    f"{at.get('max_displacement_m', float('nan')):.3g} m = "
                    f"{at.get('max_displacement_over_D', float('nan')):.3g} D): raised until "
                    f"it passes. {(pipe.get('search') or {}).get('message', '')}"
                    if raised else "passes at the section design"
                ),
            }  # fmt: skip
            if raised:
                s["design_value"] = pipe["design_value"]
                s["governing_level"] = "pipeline_fe"
        else:
            reason = "no design in range passes the pipeline FE of the governing storm: " + str(
                (pipe.get("search") or {}).get("message", pipe.get("message", ""))
            )
            levels["pipeline_fe"] = {"success": False, "value": None,
                                     "governing_check": None, "message": reason}  # fmt: skip
            s["design_value"] = None
            s["governing_level"] = None
            s["no_design_reason"] = reason
        s["levels"] = levels
        out.append(s)
    return out


def _call(job: _SectionJob) -> dict[str, Any]:
    return job()
