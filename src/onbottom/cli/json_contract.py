"""The JSON contract of ``onbottom … --json``: one registry of keys and their meaning.

Every ``--json`` output is a JSON object carrying ``schema_version`` (:data:`SCHEMA_VERSION`,
added by :func:`onbottom.cli._common.emit_json` and the error object); its other keys are
listed here per command, with nested tables where they have fixed keys. ``docs/json.md`` is
generated from this registry (``python -m onbottom.cli.json_contract > docs/json.md``) and
``tests/unit/test_json_contract.py`` checks that the page is current and that the commands'
actual keys are the documented ones.

One meaning per key across commands: ``max_displacement_m`` is always the worst seed's
maximum lateral displacement and ``mean_max_displacement_m`` the seed mean beside it (equal for
one seed), for the pipe section and the pipeline alike.
"""

from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["CONTRACT", "SCHEMA_VERSION", "Output", "documented_keys", "render_markdown"]

SCHEMA_VERSION = 1
"""Version of the JSON contract; incremented when a key changes meaning or disappears."""

SCHEMA_KEY = {
    "schema_version": "version of this JSON contract (an integer; see the top of this page)"
}


@dataclass(frozen=True)
class Output:
    """One kind of ``--json`` output: the command line that gives it, its top-level keys and
    the keys of its nested tables (``"checks[]"``: the keys of each item of a list)."""

    command: str
    title: str
    keys: dict[str, str]
    nested: dict[str, dict[str, str]] = field(default_factory=dict)
    open_keys: str = ""
    """Where a table's keys are open-ended, what they are (then only listed keys are checked)."""


_STORM_COMMON = {
    "max_displacement_m": "largest lateral displacement |y| of the worst seed [m]",
    "mean_max_displacement_m": "mean over the seeds of each seed's largest |y| [m] (one seed:"
    " equal to max_displacement_m)",
    "criteria": 'F109 dynamic criteria {"0.5D": bool, "10D": bool}',
    "status": "solver status (1: ran to the end, 2: stopped at the runaway limit, 3: lift-off"
    " stop; -3: ran to the end but the penetration left the soil model's range (z > D/2);"
    " other < 0: failed; -9: some seeds failed or left the range)",
    "success": "true if the run (every seed) produced a valid result",
    "message": "one line: how the run ended",
    "seeds": "number of storms run",
    "diameter_m": "outer diameter D of the pipe [m]",
    "netcdf": "result file(s) written",
    "warnings": "unusual-input warnings (file, line, key, value, range)",
}

CONTRACT: dict[str, Output] = {
    "error": Output(
        "onbottom stability missing.toml --json",
        "Any command that fails (exit status 1, 2, 3 or 70)",
        {"error": "the error: {type, message, field}"},
        {
            "error": {
                "type": "exception class (InputError, CaseFileError, BudgetError, UsageError, …)",
                "message": "what is wrong: the key or option, its value and the allowed range",
                "field": "the option or case-file key at fault (dotted), or null",
            }
        },
    ),
    "stability": Output(
        "onbottom stability examples/stability_case.toml --json",
        "DNV-RP-F109 design checks",
        {
            "case": "the case file",
            "section": "the pipe section in its condition (D, w_s, s_g, EI, EA, masses)",
            "checks": "one item per check and load combination",
            "success": "false where the design solve has no solution or z_p/D > 0.5",
            "message": "why success is false, else empty",
            "all_pass": "true if every check passes",
            "design": "the design solve ([design] solve_for): value, utilisation, status (a"
            " solver status, docs/conventions.md: 6 converged, 7 the lower bound already passes,"
            " -6 no value in the range passes), …",
            "generalized": "F109 §3.5 from F109's tables per lateral combination: point {K, M,"
            " N, L_actual}, L_stable and L_10 (null where not covered, with *_reason) and"
            " utilisation_0.5D / utilisation_10D at the given design",
            "warnings": "unusual-input warnings",
        },
        {
            "checks[]": {
                "name": "flotation, absolute_lateral, …",
                "combination": "load combination name",
                "condition": "pipe condition",
                "utilisation": "utilisation (<= 1 passes), or null",
                "pass": "verdict",
                "details": "the numbers of the check (F109 equation inputs and outputs)",
            }
        },
    ),
    "loads": Output(
        "onbottom loads examples/stability_case.toml --json",
        "Morison + lift peak loads of a 3-h record per combination",
        {
            "case": "the case file",
            "seed": "random-phase seed of the records",
            "duration": "record duration [s]",
            "coefficients": "{cd, cm, cl} used",
            "combinations": "one item per load combination",
            "success": "false where an embedment lies outside F109 validity",
            "message": "why success is false, else empty",
            "warnings": "unusual-input warnings",
        },
        {
            "combinations[]": {
                "combination": "name",
                "condition": "pipe condition",
                "hs": "H_s [m]",
                "tp": "T_p [s]",
                "submerged_weight": "w_s [N/m]",
                "r_y": "lateral load reduction [-]",
                "r_z": "vertical load reduction [-]",
                "max_horizontal": "largest horizontal load [N/m]",
                "min_vertical": "smallest vertical (downward +) load [N/m]",
                "max_angle_deg": "largest load inclination [deg]",
                "fraction_20_45": "fraction of cycles inclined 20–45° [-]",
                "n_cycles": "load cycles in the record",
            }
        },
    ),
    "storm_section": Output(
        "onbottom storm examples/storm_case.toml --json",
        "Pipe section in one storm",
        {
            **_STORM_COMMON,
            "final_displacement_m": "lateral displacement at the end [m]",
            "max_displacement_over_D": "max_displacement_m / D [-]",
            "summary": "solver counters: steps, rejected steps, time of the maximum, …",
            "seed": "the storm's seed",
            "plot": "figure written, or null",
        },
    ),
    "storm_seeds": Output(
        "onbottom storm examples/storm_case.toml --seeds 3 --json",
        "Pipe section in several storms (seeds)",
        {
            **_STORM_COMMON,
            "final_displacement_m": "mean |y| at the end over the seeds [m]",
            "statistics": "of each seed's max |y| [m]: mean, std, min, max, fractile, …",
            "failures": "seeds that failed: {seed, status, message}",
        },
        {
            "statistics": {
                "mean": "[m]",
                "std": "[m]",
                "min": "[m]",
                "max": "[m] (= max_displacement_m)",
                "fractile": "[m] at fractile_level",
                "fractile_level": "[-] ([run] fractile)",
                "n_seeds": "seeds run",
                "n_failed": "seeds failed",
                "n_out_of_range": "seeds whose penetration left the soil model's range (z > D/2;"
                " status -3, counted in the statistics, listed with the failures)",
                "mean_over_D": "mean / D [-]",
            }
        },
    ),
    "storm_pipeline": Output(
        "onbottom storm examples/pipeline_case.toml --json",
        "Whole pipeline FE in a storm ([pipeline] table)",
        {
            **_STORM_COMMON,
            "max_displacement_over_D": "max_displacement_m / D [-]",
            "max_strain": "largest bending + axial strain of any seed [-]",
            "worst_node_x_m": "position along the line of the worst node [m]",
            "strain_limit": "[pipeline] strain_limit, or null",
            "strain_check": "strain verdict of every seed, or null",
            "n_nodes": "FE nodes",
            "plot": "figure written, or null",
            "animation": "GIF written, or null",
            "failures": "seeds that failed",
            "per_seed": "one summary per seed",
            "model": '"pipeline_fe"',
        },
    ),
    "assess": Output(
        "onbottom assess --json",
        "A route through every F109 level: design per KP section (results.json)",
        {
            "schema": "document schema of results.json (onbottom.assess/1)",
            "provenance": "version, git commit, date, machine, case source and SHA-256, run"
            " identity, the package's content hash, wall time, sections reused from a previous"
            " run and sections recomputed (with the reason)",
            "route": "{name, sections, variable, allowable}",
            "summary": "one item per KP section",
            "sections": "everything per section: checks with details, levels, per-seed dynamic"
            " results and the search trials (key bisection: its status a solver status,"
            " docs/conventions.md: 6 a design found, 7 the lower bound already passes, -6 no"
            " value in the range passes), notes, the section's stability case document; with"
            ' [pipeline] sections = "every", the section\'s own pipeline FE check (key'
            ' pipeline_fe: the keys of `pipeline`, mesh with [pipeline] mesh = "rule", and'
            " netcdf, the section's FE results pipeline/NN-<section>.nc in --out)",
            "comparison": "per section: absolute and dynamic designs, which is heavier, why",
            "validity": "assumptions and reconstructed models",
            "clauses": "check name -> F109 clause and equation",
            "pipeline": "pipeline FE run of the governing section ([levels] pipeline_fe; with"
            ' [pipeline] sections = "every", the governing section\'s own check):'
            " section, combination, seed, design_value, max_displacement_m, max_strain,"
            " strain_limit, strain_check, envelopes {x, max_abs_y, max_strain, max_abs_moment};"
            " null when not run",
            "files": "files written in --out (with [levels] pipeline_fe: pipeline.nc; with"
            ' [pipeline] sections = "every": pipeline/NN-<section>.nc per section)',
            "pdf": "why report.pdf was not written, or null",
        },
        {
            "summary[]": {
                "section": "section name",
                "kp_start_m": "KP start [m]",
                "kp_end_m": "KP end [m]",
                "water_depth_m": "[m]",
                "seabed": "soil model",
                "governing_check": "check / combination of the largest utilisation at the"
                " given design",
                "max_utilisation": "largest utilisation at the given design [-]",
                "variable": "concrete_thickness [m] or submerged_weight [N/m]",
                "vertical_value": "flotation minimum of the variable, or null",
                "absolute_value": "absolute-method minimum, or null (no solution / not run)",
                "generalized_value": "F109 generalized minimum (§3.5 tables) where they cover"
                " every combination, else null",
                "dynamic_value": "dynamic minimum (every seed within the allowable), or null",
                "dynamic_curves_value": "minimum from the tool's own curve sweeps ([levels]"
                " dynamic_curves), or null (not run / not covered)",
                "pipeline_fe_value": "the design passing the pipeline FE (the governing"
                ' section, or every section with [pipeline] sections = "every"; null elsewhere,'
                " or where no design in range passes it)",
                "governing_level": "the level of the design value (the lightest passing, raised"
                " to the generalized one by the design floor; pipeline_fe where the pipeline FE"
                " raised it)",
                "design_value": "the design value of the variable, or null",
                "floor_rule": "design-floor rule applied (onbottom.assess.core.FLOOR_RULES)",
                "dynamic_over_generalized_weight": "submerged weight at the dynamic design over"
                " that at the generalized design [-], or null",
                "saved_submerged_weight_n_per_m": "submerged weight saved by the dynamic level"
                " against the absolute one [N/m] (negative: it needs more), or null",
            }
        },
    ),
    "curves": Output(
        "onbottom curves examples/curves_case.toml --json",
        "Generalized-stability curves L_stable, L_10 from dynamic storms",
        {
            "points": "one item per soil, N, M, K",
            "statistic": "curve statistic: 'fractile' (each seed's own L; L is the fractile,"
            " the median beside it) or 'mean_of_maxima' (the former seed-averaged maximum)",
            "statistic_description": "the statistic in words (seeds, fractile, early stop)",
            "seeds": "seeds per point",
            "fractile": "fractile of the per-seed L reported as L [-], or null",
            "stopped_early": "storms stopped once |y| reached their criterion (verdict known)",
            "total_storms": "storms run",
            "wall_time_s": "[s]",
            "workers": "Dask workers",
            "failures": "points whose runs failed",
            "no_crossing": "points with no L in the bracket (message says why)",
            "netcdf": "NetCDF written",
            "csv": "CSV written (the points)",
            "figure": "PNG written",
            "warnings": "unusual-input warnings",
        },
        {
            "points[]": {
                "soil": "sand or clay",
                "N": "[-]",
                "M": "[-]",
                "K": "[-]",
                "statistic": "the curve statistic (as the top-level key)",
                "seeds": "seeds per point",
                "{c}": "L at the criterion c (L_stable, L_10): the fractile of the per-seed L"
                " (statistic 'fractile') or the geometric mean of the final bracket of the"
                " mean of maxima; NaN (null) where not converged",
                "{c}_median": "median of the per-seed L [-] (null for 'mean_of_maxima')",
                "{c}_per_seed": "each seed's own L [-] (null: no crossing; empty for"
                " 'mean_of_maxima')",
                "{c}_stopped_early": "storms of the point stopped once their verdict was known",
                "{c}_seeds_no_crossing": "seeds without a crossing in the L tried",
                "{c}/(2+M)^2": "L/(2 + M)² (the form of F109 Tables 3-9/3-10) [-]",
                "{c}_L_low": "low end of the final bisection bracket [-] (statistic"
                " 'fractile': the fractile of the seeds' low ends)",
                "{c}_L_high": "high end of the final bisection bracket [-] (statistic"
                " 'fractile': the fractile of the seeds' high ends)",
                "{c}_bracket_width": "L_high/L_low - 1 [-]",
                "{c}_converged": "true if the bracket is within the tolerance asked for",
                "{c}_out_of_range": "1 if storms deciding the point buried the pipe beyond the"
                " soil model's range (z > D/2): the point is marked, not trusted",
                "{c}_seed_mean_low": "mean over the seeds of max |y|/D at L_low [-] ('fractile':"
                " at each seed's own L_low; a storm stopped early counts with the criterion)",
                "{c}_seed_min_low": "smallest seed max |y|/D at L_low [-]",
                "{c}_seed_max_low": "largest seed max |y|/D at L_low [-]",
                "{c}_seed_mean_high": "mean over the seeds of max |y|/D at L_high [-]",
                "{c}_seed_min_high": "smallest seed max |y|/D at L_high [-]",
                "{c}_seed_max_high": "largest seed max |y|/D at L_high [-]",
                "{c}_evaluations": "bisection evaluations",
                "{c}_storms": "storms run for the point",
                "{c}_runtime_s": "[s]",
            }
        },
    ),
    "report": Output(
        "onbottom report --only f114_reference --out DIR --json",
        "Validation report",
        {
            "index": "index.html written",
            "json": "report.json written",
            "n_pass": "checks that pass",
            "n_fail": "checks that fail",
            "run_time": "[s]",
            "sections": "one item per section: {name, state, n_pass, n_fail, run_time, reason}",
        },
    ),
    "report_list": Output(
        "onbottom report --list --json",
        "Sections of the validation report",
        {"sections": "one item per section: {name, title, slow, available}"},
    ),
    "sweep": Output(
        "onbottom sweep examples/sweep_grid.toml -o sweep.nc --json",
        "Parametric sweep of a registered function",
        {
            "success": "true if no run failed",
            "output": "NetCDF written",
            "dims": "grid dimensions and their sizes",
            "variables": "variables of the result",
            "n_points": "grid points",
            "n_failed": "points whose run failed",
            "errors": "up to 10 distinct error messages",
            "wall_time": "[s]",
        },
    ),
    "backbone": Output(
        "onbottom backbone --diameter 1 --weight-kn 10.52 --gamma-kn 7.5 --json",
        "Verley & Sotberg backbone",
        {
            "model": "soil model",
            "parameters": "model parameters",
            "vertical_load": "V [N/m]",
            "backbone": "region limits and forces (SI)",
            "success": "false where the embedment leaves the model's validity",
            "message": "why success is false, else empty",
            "warnings": "unusual-input warnings",
        },
    ),
    "penetration": Output(
        "onbottom penetration --diameter 0.5 --gamma-kn 16.7 --phi-deg 35 --json",
        "DNVGL-RP-F114 vertical penetration",
        {
            "model": "F114 model",
            "parameters": "model parameters",
            "units": "units of the table's columns",
            "table": "z, B, Q_v per embedment",
            "embedment": "embedment under the given load, or null; its status is a solver status"
            " (docs/conventions.md: 6 converged, -5 the lay-factor iteration did not converge,"
            " -3 outside the model's validity)",
            "bounds": "lower/upper bound parameters (where computed)",
            "warnings": "unusual-input warnings",
        },
    ),
    "simulate": Output(
        "onbottom simulate examples/section_preset.toml --json",
        "Pipe section under a load programme",
        {
            "success": "valid result",
            "status": "solver status (docs/conventions.md: 1 end of the programme, 2 stopped at"
            " the displacement limit, 5 ran on after the limit until the pipe stopped; -3 outside"
            " the model's validity; other < 0: failed)",
            "message": "how the run ended",
            "n_steps": "solver steps",
            "cycles_to_limit": "load cycles to the displacement limit, or null",
            "time_to_limit_s": "[s], or null",
            "netcdf": "NetCDF written",
            "plot": "figure written, or null",
            "warnings": "unusual-input warnings",
        },
        open_keys="plus the solver summary (initial_penetration, max_penetration,"
        " final_displacement, … [SI])",
    ),
    "calibrate": Output(
        "onbottom calibrate RECORD --json",
        "Calibration of the Verley & Sotberg factors",
        {
            "fits": "one fit per record (or one joint fit): success, parameters, misfit, …",
            "recommended": "recommended values over the fits",
        },
    ),
    "reproduce": Output(
        "onbottom reproduce --json",
        "Youssef & Cassidy (2014) centrifuge tests",
        {"rows": "one row per test", "files": "files written", "wall_time_s": "[s]"},
    ),
    "reproduce_bands": Output(
        "onbottom reproduce --bands --json",
        "Sensitivity bands of the centrifuge cycle counts",
        {
            "bands": "one summary per test",
            "n_runs": "runs",
            "files": "files written",
            "wall_time_s": "[s]",
        },
    ),
    "metocean": Output(
        "onbottom metocean examples/hindcast_synthetic.csv --out DIR --json",
        "Metocean statistics of a hindcast: return values per sector, joint model, F109 table",
        {
            "success": "false when the omnidirectional H_s has no return values (exit status 3)",
            "hindcast": "the hindcast file",
            "years": "length of the record [years]",
            "step_hours": "sampling step [h]",
            "sectors": "sector labels (waves coming from)",
            "return_periods": "R [years]",
            "ci_method": "profile or bootstrap",
            "confidence": "level of the intervals",
            "table": "one row per sector, omni first (design_table.csv)",
            "joint_model": "DNV-RP-C205 H_s-T_p model parameters",
            "current_model": "current speed given H_s (Weibull, Gaussian copula), or null"
            " without current",
            "contour_max_hs": "highest H_s of each IFORM contour, per return period [m]",
            "tail": "omni H_s tail guard: warnings, exponential (xi = 0) values, censored"
            " storms and the censored fit; null without a fit",
            "contour_check": "H_s marginal's tail against the data at the longest return period:"
            " levels [{hs, empirical, fitted, mle}], contour_max_hs, pot_value, ratio, alpha,"
            " mle_contour_max_hs, mle, tp_at_peaks {n, mean_z, std_z, ks, ks_p} (T_p | H_s"
            " checked on the storm peaks); null without a POT value",
            "files": "files written in --out (report.html among them)",
            "notes": "extrapolation, sectors without values and why",
        },
        {
            "table[]": {
                "sector": "label (omni, N, ...)",
                "centre_deg": "sector centre, coming from [deg], or null (omni)",
                "hs": "H_s per return period [m] (POT/GPD)",
                "hs_lower": "lower bound of the interval [m]",
                "hs_upper": "upper bound of the interval [m]",
                "tp": "median T_p given that H_s [s]",
                "tp_low": "5 % T_p given that H_s [s]",
                "tp_high": "95 % T_p given that H_s [s]",
                "current": "current speed per return period [m/s] (POT/GPD), or null",
                "current_lower": "lower bound [m/s], or null",
                "current_upper": "upper bound [m/s], or null",
                "current_with_hs": "median current given the row's H_s [m/s] (joint model),"
                " or null",
                "current_with_hs_p90": "90 % current given the row's H_s [m/s], or null",
            },
            "joint_model": {
                "model": "name of the model",
                "hs_scale": "Weibull alpha of H_s [m]",
                "hs_shape": "Weibull beta of H_s",
                "hs_location": "Weibull gamma of H_s [m]",
                "mu": "a0, a1, a2 of the mean of ln T_p",
                "sigma": "b0, b1, b2 of the standard deviation of ln T_p",
                "n_states": "sea states fitted",
            },
        },
    ),
    "reliability": Output(
        "onbottom reliability examples/reliability_case.toml --out DIR --json",
        "Long-term reliability of a pipe section's lateral stability",
        {
            "success": "false when a storm run failed numerically (exit status 3)",
            "case": "the case file",
            "out": "output folder",
            "diameter": "pipe outer diameter D [m]",
            "storms_per_year": "storm rate lambda [1/year]",
            "inputs": "names of the random inputs, the storm seed last",
            "climate": "hindcast, rate, threshold, gpd_scale, gpd_shape, sectors,"
            " sector_frequencies, current_model (null: the current is a case input),"
            " joint_model; empty without a hindcast",
            "estimates": "one item per displacement limit",
            "design": "response-based design on the IFORM contour (return_period, fractile,"
            " points, governing, design_displacement [m], f109), or null",
            "campaign": "counters of the storm runs",
            "target": "annual probability per limit against DNV-OS-F101's target for the"
            " safety class: source, safety_class, annual_target, limits [{label, annual, upper,"
            " verdict pass|fail|undecided}]",
            "plan": "per limit: the storms and CPU time its estimator needs for the case's"
            " target_cv at the measured rate (label, target_cv, method, storms, storms_used,"
            " lower_bound, cpu_seconds_per_storm [s], cpu_seconds [s])",
            "files": "files written in --out (stores, figures, reliability.json, report.html)",
            "notes": "CV above target, failed runs",
        },
        {
            "estimates[]": {
                "label": "the limit as given (0.5D, 10D, metres)",
                "limit": "y_lim [m]",
                "probability": "P[max lateral displacement > limit] per storm",
                "cv": "coefficient of variation of probability, or null",
                "method": "subset, importance or monte_carlo",
                "storms": "storm runs the estimate asked for",
                "computed": "of which run in this call (the rest read back from the store)",
                "failed_runs": "runs that failed numerically (counted as exceedances)",
                "annual": "1 - exp(-lambda p)",
                "lifetime": "1 - (1 - annual)^design life",
                "reliability_index": "-Phi^-1(p), or null",
                "history": "[storms, probability, cv] per block or subset level",
                "curve": "[displacement m, probability per storm] of the subset levels",
                "importance": "input -> SRRC^2 over all storms (the bulk of the response)",
                "importance_kind": "which measure (SRRC^2 over the first unbiased block)",
                "design_point": "importance sampling's centre [input units], else empty",
                "upper_bound": "true when probability is only an upper bound (no CV)",
                "stopped_early": (
                    "storms stopped just above the largest limit (verdict known; their"
                    " displacement a lower bound)"
                ),
                "interval": "[low, high] confidence interval of probability (per storm)",
                "annual_interval": "[low, high] of annual",
                "lifetime_interval": "[low, high] of lifetime",
                "interval_kind": "how the interval was made (Clopper-Pearson, weights, bound)",
                "confidence": "level of the intervals (0.95)",
                "failures": "failing storms of the estimate",
                "failure_mean": "input -> E[u | failure]: mean standardized input of failures",
                "failure_mean_kind": "what failure_mean is (words)",
                "pilot_storms": "storms of importance sampling's pilot (in storms)",
                "notes": "fallbacks and warnings of this estimate",
            },
            "campaign": {
                "requested": "storm runs asked for",
                "computed": "run in this call",
                "reused": "read back from the store",
                "failed": "raised (recorded, not fatal)",
                "seconds_per_storm": "compute seconds per storm run [s], or null",
            },
        },
    ),
    "warmup": Output(
        "onbottom warmup --json",
        "One-time compile of the numba kernels into numba's cache",
        {
            "targets": "one item per kernel group, in the order finished",
            "wall_s": "wall time of the whole warm-up [s]",
            "cpu_s": "CPU time of all kernel groups together [s]",
            "compiled": "numba compiles in all (0: everything was already cached)",
            "processes": "worker processes used (1: in this process)",
        },
        {
            "targets[]": {
                "name": "kernel group (the names --only takes)",
                "title": "what it compiles",
                "wall_s": "wall time of the group [s]",
                "cpu_s": "CPU time of the group [s]",
                "compiled": "numba compiles of the group (0: loaded from the cache)",
            },
        },
    ),
}
"""Every ``--json`` output (the DEM commands print the run summaries of
``onbottom.dem.summary``; see docs/theory/dem.md)."""


def documented_keys(output: str, table: str = "", criteria: tuple[str, ...] = ()) -> set[str]:
    """The documented keys of ``output`` (top level, or the nested ``table``), with
    ``schema_version`` at the top level and ``{c}`` expanded for ``criteria``."""
    o = CONTRACT[output]
    keys = o.nested[table] if table else {**SCHEMA_KEY, **o.keys}
    out: set[str] = set()
    for k in keys:
        if "{c}" in k:
            out.update(k.replace("{c}", c) for c in criteria)
        else:
            out.add(k)
    return out


def render_markdown() -> str:
    """``docs/json.md``."""
    lines = [
        "# JSON output",
        "",
        "<!-- generated by `python -m onbottom.cli.json_contract > docs/json.md`; do not edit:"
        " the registry is src/onbottom/cli/json_contract.py -->",
        "",
        "Every command takes `--json` and then prints one JSON object on stdout (errors"
        " included: the `error` object below, with a non-zero exit status). Every object"
        f" carries `schema_version` (now {SCHEMA_VERSION}), incremented when a key changes"
        " meaning or disappears. NaN and infinity are written as `null`. Units are SI unless"
        " a key carries a suffix (`_m`, `_s`, `_deg`).",
        "",
        "One meaning per key: `max_displacement_m` is always the worst seed's largest lateral"
        " displacement, with `mean_max_displacement_m` (the seed mean) beside it, for the pipe"
        " section and the pipeline alike.",
        "",
        "`tests/unit/test_json_contract.py` checks this page against the registry and the"
        " commands' actual keys against the page. The DEM commands (`onbottom dem …`,"
        " `onbottom dem-lammps …`) print the run summaries of `onbottom.dem.summary`"
        " ([DEM theory](theory/dem.md)), with `schema_version` too.",
        "",
    ]
    for name, o in CONTRACT.items():
        lines += [f"## {o.title}", "", f"`{o.command}` ({name})", ""]
        lines += ["| key | meaning |", "|---|---|"]
        for k, v in {**SCHEMA_KEY, **o.keys}.items():
            lines.append(f"| `{k}` | {v} |")
        if o.open_keys:
            lines += ["", f"Other keys: {o.open_keys}."]
        for table, keys in o.nested.items():
            lines += ["", f"`{table}`:", "", "| key | meaning |", "|---|---|"]
            for k, v in keys.items():
                shown = k.replace("|", "\\|")
                lines.append(f"| `{shown}` | {v.replace('|', chr(92) + '|')} |")
        lines.append("")
    return "\n".join(lines)


if __name__ == "__main__":  # pragma: no cover
    print(render_markdown(), end="")
