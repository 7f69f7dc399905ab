"""The design report of ``onbottom assess`` as data, rendered by the shared report templates.

:func:`report_context` turns an :class:`~onbottom.assess.core.Assessment` into the page: the
cards, the contents, and sections made of paragraphs, tables and figures; :func:`render` fills
``assess.html.j2`` (the header band, contents, cards, tables and print rules of the metocean,
reliability and validation reports: ``onbottom/report/templates``, read as files — the
``report`` package sits above ``assess``). Every table is also written as CSV
(``tables/assess_<id>.csv``, linked from its caption).

The summary table is built from :data:`SUMMARY_COLUMNS` (key, header, cell function): a column
is one entry; validity marks (:data:`MARKS`) are attached to the design cell of each row.
"""

from __future__ import annotations

import csv
import io
import json
import math
import statistics as st
from collections.abc import Callable
from pathlib import Path
from typing import Any

from onbottom.assess._figures import figure_part, history_svg, png, strip_svg, vh_part
from onbottom.assess._wording import (
    CLAUSES,
    VALIDITY,
    WHY_LIGHTER,
    format_value,
    level_name,
    section_validity,
)
from onbottom.assess.core import PIPELINE_FOLDER, Assessment
from onbottom.assess.pipeline import DISAGREEMENT_FACTOR

__all__ = ["MARKS", "SUMMARY_COLUMNS", "render", "report_context", "section_marks"]

MARKS: dict[str, str] = {
    "E": "extrapolated correlation: an input lies outside a correlation's calibration range"
    " (e.g. K_s outside Verley & Sotberg's [0.1, 30]); the result rests on an extrapolation",
    "R": "reconstructed model: the dynamic level rests on a reconstructed soil or force model"
    " (see Assumptions and validity)",
    "S": "solver disagreement: the section solver and the pipeline FE differ by more than the"
    " stated factor at the design point (see Pipeline FE)",
    "P": "raised by the pipeline FE: the section design failed the pipeline FE of the governing"
    " storm and was raised until it passed",
    "N": "not covered: F109's generalized tables (§3.5) do not cover the section's point",
    "F": "raised by the design floor: the lightest passing level was below F109's generalized"
    " requirement (or, where the tables do not cover a current-dominated point, below the same"
    " storms on Coulomb friction) and the design was raised to it",
}
"""Validity marks of a section's design (key: legend)."""


def _fmt(x: Any, digits: int = 3, unit: str = "") -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "—"
    if isinstance(x, bool):
        return "pass" if x else "FAIL"
    if isinstance(x, (int, float)):
        return f"{x:.{digits}g}" + (f" {unit}" if unit else "")
    return str(x)


def cell(t: Any, c: str = "", marks: list[dict[str, str]] | tuple = (), text: bool = False):
    """A table cell: text ``t``, CSS class ``c`` (pass / fail / na), validity marks."""
    return {"t": t if isinstance(t, str) else _fmt(t), "c": c, "marks": list(marks), "text": text}


def verdict_cell(ok: bool | None, none: str = "not covered") -> dict[str, Any]:
    """pass (green) / FAIL (red) / not assessed (grey: never green)."""
    if ok is None:
        return cell(none, "na", text=True)
    return cell("pass" if ok else "FAIL", "pass" if ok else "fail", text=True)


class Tables:
    """The report's tables, each with an id, a caption and its CSV."""

    def __init__(self) -> None:
        self.items: list[dict[str, Any]] = []

    def add(self, tid: str, caption: str, columns: list[str], rows: list[list[Any]],
            *, wide: bool = False) -> dict[str, Any]:  # fmt: skip
        rows = [[r if isinstance(r, dict) else cell(r) for r in row] for row in rows]
        buf = io.StringIO(newline="")
        w = csv.writer(buf)
        w.writerow(columns)
        for row in rows:
            w.writerow([r["t"] + "".join(f" [{m['key']}]" for m in r["marks"]) for r in row])
        n = sum(1 for x in self.items if x["id"].startswith(tid))
        tid = tid if n == 0 else f"{tid}-{n + 1}"
        tb = {"id": tid, "caption": caption, "columns": columns, "rows": rows, "wide": wide,
              "csv": f"tables/assess_{tid}.csv", "csv_text": buf.getvalue()}  # fmt: skip
        self.items.append(tb)
        return {"kind": "table", "table": tb}


def section_marks(s: dict[str, Any], a: Assessment) -> list[dict[str, str]]:
    """The validity marks (:data:`MARKS`) of a section's design."""
    keys = []
    if any("calibration range" in n or "extrapolat" in n for n in s.get("notes", [])):
        keys.append("E")
    # reconstructed: V&S sand (its Eqs 6 and 8) and the wake force model (public structure,
    # constants fitted by onbottom); constant Morison coefficients are not a reconstruction
    if "dynamic" in s["levels"] and (s["seabed_model"] == "sand" or a.route.force_model == "wake"):
        keys.append("R")
    p = s.get("pipeline_fe") or a.pipeline or {}  # the section's own check, or the route's
    if p.get("index") == s["index"] and (p.get("at_section_design") or {}).get("disagree"):
        keys.append("S")
    if s.get("governing_level") == "pipeline_fe":
        keys.append("P")
    floor = s.get("design_floor") or {}
    lightest = floor.get("lightest_level")
    if lightest and s.get("governing_level") and lightest != s["governing_level"]:
        keys.append("F")
    gen = s["levels"].get("generalized")
    if gen is not None and not gen.get("covered"):
        keys.append("N")
    return [{"key": k, "title": MARKS[k]} for k in keys]


def _level_cell(s: dict[str, Any], key: str, var: str) -> dict[str, Any]:
    lv = s["levels"].get(key)
    if lv is None:
        return cell("not run", "na", text=True)
    if key == "generalized" and lv.get("value") is None:
        return cell("not covered" if not lv.get("covered") else "partly covered", "na", text=True)
    if lv.get("value") is None:
        return cell("no design" if var != "none" else ("pass" if lv.get("success") else "FAIL"),
                    "fail" if not lv.get("success") else "", text=True)  # fmt: skip
    return cell(format_value(lv["value"], var))


def _design_cell(s: dict[str, Any], a: Assessment) -> dict[str, Any]:
    var = a.route.variable
    marks = section_marks(s, a)
    if s["governing_level"] is None:
        return cell("NO DESIGN", "fail", marks, text=True)
    return cell(f"{format_value(s['design_value'], var)} ({level_name(s['governing_level'])})",
                "pass", marks, text=True)  # fmt: skip


def _saved(s: dict[str, Any], a: Assessment) -> dict[str, Any]:
    ws = s.get("weight_saved") or {}
    if ws.get("saved_submerged_weight") is not None:
        return cell(f"{ws['saved_submerged_weight']:.0f} ({100 * ws['saved_fraction']:.0f} %)")
    lv = s["levels"]
    if "dynamic" not in lv or "absolute" not in lv:
        return cell("levels not run", "na", text=True)
    if (lv["dynamic"] or {}).get("value") is not None:
        return cell("absolute: no design in range", "na", text=True)
    return cell("dynamic: no design", "na", text=True)


def _floor_cell(s: dict[str, Any], a: Assessment) -> dict[str, Any]:
    fl = s.get("design_floor") or {}
    if not fl:
        return cell("not applied", "na", text=True)
    ratio = fl.get("dynamic_over_generalized_weight")
    txt = str(fl.get("rule", "")).replace("_", " ")
    if ratio is not None:
        txt += f" ({ratio:.2f})"
    return cell(txt, text=True)


SUMMARY_COLUMNS: list[tuple[str, str, Callable[[dict[str, Any], Assessment], Any]]] = [
    ("section", "Section", lambda s, a: cell(s["name"], text=True)),
    ("kp", "KP [km]", lambda s, a: cell(f"{s['kp_start_m'] / 1e3:g}–{s['kp_end_m'] / 1e3:g}")),
    ("depth", "Depth [m]", lambda s, a: cell(f"{s['water_depth']:g}")),
    ("seabed", "Seabed", lambda s, a: cell(s["seabed_model"], text=True)),
    ("check", "Governing check (given design)",
     lambda s, a: cell(s["governing_check"].replace("_", " "), text=True)),
    ("util", "Utilisation (given design)",
     lambda s, a: cell(_fmt(s["max_utilisation"]),
                       "fail" if (s["max_utilisation"] or 0) > 1 else "pass")),
    ("vertical", "Flotation min.", lambda s, a: _level_cell(s, "vertical", a.route.variable)),
    ("absolute", "Absolute min.", lambda s, a: _level_cell(s, "absolute", a.route.variable)),
    ("generalized", "Generalized min.",
     lambda s, a: _level_cell(s, "generalized", a.route.variable)),
    ("dynamic", "Dynamic min.", lambda s, a: _level_cell(s, "dynamic", a.route.variable)),
    ("dynamic_curves", "Dynamic curves (tool's own)",
     lambda s, a: _level_cell(s, "dynamic_curves", a.route.variable)),
    ("floor", "Design floor (dynamic ÷ generalized weight)", _floor_cell),
    ("pipeline_fe", "Pipeline FE",
     lambda s, a: _level_cell(s, "pipeline_fe", a.route.variable)
     if "pipeline_fe" in s["levels"]
     else cell("not run" if not a.route.levels.pipeline_fe else "governing section only",
               "na", text=True)),
    ("design", "Design (level) + marks", _design_cell),
    ("saved", "Weight saved by dynamic vs absolute [N/m]", _saved),
]  # fmt: skip
"""Columns of the summary table: (key, header, cell of a section). Add a column here."""


# ---- inputs ---------------------------------------------------------------------------------
def _pipe_tables(a: Assessment, T: Tables) -> list[dict[str, Any]]:
    """The pipe build-up (steel, coatings, contents per condition) and, per condition, the
    computed D, w_s and specific gravity at the given design and at each section's design."""
    from onbottom.inputs.pipe_buildup import PipeBuildUp

    sec0 = a.route.sections[0]
    pipe = sec0.pipe
    parts: list[dict[str, Any]] = []
    if isinstance(pipe, PipeBuildUp):
        rows = [
            ["steel", "outer diameter", f"{1e3 * pipe.steel_outer_diameter:.1f}", "mm"],
            ["steel", "wall thickness", f"{1e3 * pipe.wall_thickness:.1f}", "mm"],
            ["steel", "density", f"{pipe.steel_density:g}", "kg/m³"],
            ["steel", "Young's modulus", f"{pipe.youngs_modulus / 1e9:g}", "GPa"],
        ]
        for layer in pipe.layers:
            sized = (
                " (design variable)"
                if a.route.variable == "concrete_thickness" and layer.name == a.route.design.layer
                else ""
            )
            rows.append([f"coating: {layer.name}", f"thickness{sized}",
                         f"{1e3 * layer.thickness:.1f}", "mm"])  # fmt: skip
            rows.append([f"coating: {layer.name}", "density", f"{layer.density:g}", "kg/m³"])
        conds = ("installation", "flooded", "hydrotest", "operation")
        for c in conds:
            rows.append([f"contents: {c}", "density", f"{getattr(pipe.contents, c):g}", "kg/m³"])
        rows.append(["sea water", "density", f"{pipe.seawater_density:g}", "kg/m³"])
        parts.append(T.add("pipe", "Pipe build-up (as given; every section)",
                           ["Part", "Quantity", "Value", "Unit"],
                           [[cell(x, text=True) for x in r] for r in rows]))  # fmt: skip
        designs = [("given design", None)] + [
            (f"design of {s['name']}", s["design_value"]) for s in a.sections
            if s.get("design_value") is not None and a.route.variable == "concrete_thickness"
        ]  # fmt: skip
        prow = []
        for label, x in designs:
            built = pipe if x is None else pipe.with_layer_thickness(a.route.design.layer, x)
            for c in conds:
                pr = built.properties(c)
                prow.append([cell(label, text=True), cell(c, text=True),
                             f"{1e3 * pr.outer_diameter:.1f}", f"{pr.mass:.1f}",
                             f"{pr.submerged_weight:.1f}",
                             f"{pr.specific_gravity:.3f}"])  # fmt: skip
        parts.append(T.add("pipe-properties",
                           "Computed per condition: outer diameter D, mass, submerged weight w_s,"
                           " specific gravity (pipe condition of the lateral checks: "
                           f"{sec0.condition})",
                           ["Design", "Condition", "D [mm]", "mass [kg/m]", "w_s [N/m]",
                            "specific gravity [-]"], prow))  # fmt: skip
    else:
        rows = [
            ["outer diameter D", _fmt(getattr(pipe, "outer_diameter", None), 4), "m"],
            ["submerged weight w_s", _fmt(getattr(pipe, "submerged_weight", None), 4), "N/m"],
        ]
        parts.append(T.add("pipe", "Pipe (as given)", ["Quantity", "Value", "Unit"], rows))
    return parts


def _basis_tables(a: Assessment, T: Tables) -> list[dict[str, Any]]:
    """Safety class and factors, levels and criteria, solver settings."""
    r = a.route
    doc = (a.sections[0].get("stability_document") or {}).get("design", {})
    gsc = sorted({c["details"].get("gamma_sc") for s in a.sections for c in s["checks"]
                  if c["name"] == "absolute_lateral" and c.get("details")} - {None})  # fmt: skip
    allow = (f"{r.dynamic.allowable_displacement_m:g} m" if r.dynamic.allowable == "user"
             else r.dynamic.allowable)  # fmt: skip
    rows = [
        ["safety class", doc.get("safety_class", "—"), "DNV-RP-F109 (2017) Table 3-5"],
        ["region", doc.get("region", "—"), "DNV-RP-F109 (2017) Tables 3-6 to 3-8"],
        ["γ_SC (absolute, as used)", ", ".join(f"{g:g}" for g in gsc) or "—",
         "DNV-RP-F109 (2017) Tables 3-5 to 3-8"],
        ["γ_W (flotation)", f"{doc.get('vertical_safety_factor', 1.1):g}",
         "DNV-RP-F109 (2017) Eq 3.1"],
        ["design variable", r.variable.replace("_", " ") + (f" of layer '{r.design.layer}'"
         if r.variable == "concrete_thickness" else ""), ""],
        ["search range", f"{1e3 * r.design.thickness_min:g}–{1e3 * r.design.thickness_max:g} mm"
         if r.variable == "concrete_thickness"
         else f"{r.design.weight_min:g}–{r.design.weight_max:g} N/m", ""],
    ]  # fmt: skip
    basis = T.add(
        "basis",
        "Design basis: safety class and factors",
        ["Item", "Value", "Source"],
        [[cell(x, text=True) for x in rw] for rw in rows],
    )
    lv = r.levels
    crit = [
        ["flotation", "run", "γ_W · b / (w_s + b) ≤ 1 in every condition", "F109 Eq 3.1"],
        ["absolute", "run" if lv.absolute else "not run",
         "γ_SC (F*_Y + μF*_Z)/(μ w_s + F_R) ≤ 1 and γ_SC F*_Z / w_s ≤ 1", "F109 Eqs 3.38, 3.39"],
        ["generalized", "run" if lv.generalized else "not run",
         f"lateral displacement ≤ {allow} from F109's generalized tables (L_stable for 0.5D,"
         " L_10 for 10D; no extrapolation); the design is never below it unless opted in",
         "F109 §3.5, Tables 3-2 to 3-4"],
        ["dynamic curves", "run" if getattr(lv, "dynamic_curves", None) else "not run",
         f"lateral displacement ≤ {allow} from the tool's own curve sweeps (shown, never"
         " governing; not F109's tables)", "onbottom curves"],
        ["dynamic", "run" if lv.dynamic else "not run",
         f"every seed's max |y| ≤ {allow}, {r.dynamic.seeds} seeds per trial", "F109 §3.4"],
        ["pipeline FE", f"run ({r.pipeline.sections} section)" if lv.pipeline_fe else "not run",
         f"max |y| ≤ {allow} on the line, fibre strain ≤ {100 * r.pipeline.strain_limit:g} %",
         "F109 §3.4.1; DNV-ST-F101 §5.4.12"],
    ]  # fmt: skip
    levels = T.add(
        "levels",
        "Levels and criteria",
        ["Level", "Status", "Criterion", "Clause"],
        [[cell(x, text=True) for x in rw] for rw in crit],
    )
    st0 = a.route.sections[0].storms[0].setup.settings if a.route.sections[0].storms else None
    tol = (f"{1e3 * r.dynamic.thickness_tolerance_m:g} mm" if r.variable == "concrete_thickness"
           else f"{r.dynamic.weight_tolerance_n_per_m:g} N/m")  # fmt: skip
    srows = [
        ["force model (dynamic, pipeline FE)", r.force_model, ""],
        ["storm", f"{r.dynamic.build_up_hours:g} h build-up + {r.dynamic.peak_hours:g} h peak", ""],
        ["seeds per trial", f"{r.dynamic.seeds} (from {r.dynamic.first_seed})", ""],
        ["time step (largest)", _fmt(getattr(st0, "dt_max", None)), "s"],
        ["design search tolerance", tol, ""],
        ["pipeline FE line", f"{r.pipeline.length:g} m, elements {r.pipeline.element_length:g} m"
         f" ({round(r.pipeline.length / r.pipeline.element_length) + 1} nodes), ends"
         f" {r.pipeline.end_conditions}", ""],
        ["pipeline FE storm", "whole storm" if r.pipeline.duration is None
         else f"first {r.pipeline.duration:g} s", ""],
    ]  # fmt: skip
    solver = T.add(
        "solver",
        "Solver settings",
        ["Setting", "Value", "Unit"],
        [[cell(x, text=True) for x in rw] for rw in srows],
    )
    return [basis, levels, solver]


def _soil_table(s: dict[str, Any], T: Tables) -> dict[str, Any]:
    sb = (s.get("stability_document") or {}).get("seabed", {})
    units = {"submerged_unit_weight": "N/m³", "unit_weight": "N/m³", "d50": "m",
             "undrained_shear_strength": "Pa", "trench_depth": "m", "trench_angle_deg": "deg",
             "friction_coefficient": "-"}  # fmt: skip
    rows = [[cell(k.replace("_", " "), text=True), cell(v if isinstance(v, str) else _fmt(v, 4)),
             cell(units.get(k, ""), text=True)]
            for k, v in sb.items() if v is not None]  # fmt: skip
    return T.add(f"s{s['index']}-soil", f"Soil of {s['name']}", ["Quantity", "Value", "Unit"], rows)


SEA_COLUMNS = [
    ("combination", "Combination", ""), ("condition", "Condition", ""), ("hs", "H_s", "m"),
    ("tp", "T_p", "s"), ("gamma", "γ", "-"), ("wave_direction_deg", "Wave dir.", "deg"),
    ("spreading_s", "Spreading s", "-"), ("current_velocity", "Current", "m/s"),
    ("current_reference_height", "at z_r", "m"), ("current_direction_deg", "Current dir.", "deg"),
]  # fmt: skip


def _absolute_worked(s: dict[str, Any], T: Tables) -> dict[str, Any] | None:
    """The figures of Eq 3.38 of the section's highest absolute lateral utilisation (the check
    can be redone by hand from them)."""
    rows = [c for c in s["checks"] if c["name"] == "absolute_lateral" and c.get("details")]
    if not rows:
        return None
    c = max(rows, key=lambda r: r.get("utilisation") or 0)
    d = c["details"]
    items = [
        ("gamma_sc", "γ_SC", "-"), ("f_y", "F*_Y", "N/m"), ("f_z", "F*_Z", "N/m"),
        ("friction_coefficient", "μ", "-"), ("submerged_weight", "w_s", "N/m"),
        ("passive_resistance", "F_R", "N/m"), ("diameter", "D", "m"), ("u_star", "U*", "m/s"),
        ("v_star", "V*", "m/s"), ("t_star", "T*", "s"), ("k_star", "K*", "-"),
        ("c_y", "C*_Y", "-"), ("c_z", "C*_Z", "-"), ("r_y", "r_y", "-"), ("r_z", "r_z", "-"),
        ("penetration", "z_p", "m"),
    ]  # fmt: skip
    rw = [[cell(sym, text=True), cell(_fmt(d.get(k), 6)), cell(u, text=True)]
          for k, sym, u in items if d.get(k) is not None]  # fmt: skip
    rw.append([cell("utilisation γ_SC (F*_Y + μF*_Z)/(μ w_s + F_R)", text=True),
               cell(_fmt(c["utilisation"], 6)), cell("-", text=True)])  # fmt: skip
    return T.add(f"s{s['index']}-eq338", f"Absolute lateral check by hand (Eq 3.38): {s['name']},"
                 f" {c['combination']}, condition {c['condition']}",
                 ["Symbol", "Value", "Unit"], rw)  # fmt: skip


# ---- pipeline FE --------------------------------------------------------------------------------
def _fe_file(p: dict[str, Any]) -> str:
    """The check's NetCDF as a path from the output folder (``pipeline/NN-<section>.nc``)."""
    f = Path(p["netcdf"])
    return f"{f.parent.name}/{f.name}" if f.parent.name == PIPELINE_FOLDER else f.name


def _pipeline_parts(
    p: dict[str, Any], a: Assessment, T: Tables, tid: str = "pipeline"
) -> list[dict[str, Any]]:
    """The pipeline FE check ``p`` of the governing section (or of its own section, table
    ``tid``): lead, table with its NetCDF, agreement, envelopes."""
    var = a.route.variable
    parts: list[dict[str, Any]] = []
    at = p.get("at_section_design") or {}
    x0 = p.get("section_design")
    if p.get("raised"):
        lead = (f"The section design {format_value(x0, var)} of {p['section']} failed the"
                f" pipeline FE (max |y| {at.get('max_displacement_m', math.nan):.3g} m ="
                f" {at.get('max_displacement_over_D', math.nan):.3g} D against the allowable"
                f" {at.get('allowable_m', math.nan):.3g} m); the design was raised to"
                f" {format_value(p['design_value'], var)}, which passes.")  # fmt: skip
    elif p.get("pass"):
        lead = f"The design of {p['section']} passes the pipeline FE."
    else:
        lead = (f"NO DESIGN: no design of {p['section']} in the range passes the pipeline FE."
                f" {(p.get('search') or {}).get('message', '')}")  # fmt: skip
    parts.append({"kind": "p", "text": lead, "c": "" if p.get("pass") else "fail"})
    rows = [
        ("Governing storm", f"{p['combination']} (seed {p['seed']}), condition {p['condition']}"),
        ("Line", f"{p['length_m']:g} m, {p['n_nodes']} nodes, ends {p['end_conditions']}"),
    ]
    for label, r in (("at the section design", at), ("at the accepted design", p)):
        if not r:
            continue
        rows += [
            (f"Design value {label}", "the given design" if r.get("design_value") is None
             else format_value(r["design_value"], var)),
            (f"D, w_s {label}",
             f"{r['diameter_m']:.4g} m, {r['submerged_weight_n_per_m']:.4g} N/m"),
            (f"Max |y| {label}", f"{r['max_displacement_m']:.3g} m = "
             f"{r['max_displacement_over_D']:.3g} D at x = {r['worst_node_x_m']:.0f} m"
             f" (allowable {r['allowable_m']:.3g} m): {'pass' if r['pass'] else 'FAIL'}"),
            (f"Max strain {label}", f"{100 * r['max_strain']:.3g} % (limit"
             f" {100 * p['strain_limit']:.3g} %)"),
        ]  # fmt: skip
    if p.get("search"):
        tr = "; ".join(f"{format_value(x, var)} → {g:.3g}" for x, g in p["search"]["trials"])
        rows.append(("Design search (g = max |y|/allowable or strain/limit)",
                     f"{tr}. {p['search']['message']}"))  # fmt: skip
    rows.append(("Run", f"{p['message']} (status {p['status']}); "
                 f"{p.get('cpu_time_s', math.nan):.1f} CPU-s in all"))  # fmt: skip
    if p.get("netcdf"):
        rows.append(("Results (NetCDF: envelopes, verdict, provenance)", _fe_file(p)))
    parts.append(
        T.add(
            tid,
            "Pipeline FE of the governing section"
            if tid == "pipeline"
            else f"Pipeline FE of {p['section']}",
            ["Item", "Value"],
            [[cell(k, text=True), cell(v, text=True)] for k, v in rows],
        )
    )
    if at:
        f = at.get("fe_over_section", math.nan)
        sec = next((s for s in a.sections if s["index"] == p["index"]), {})
        trials = ((sec.get("dynamic") or {}).get("bisection") or {}).get("trials", [])
        g0 = [g for x, g in trials if x0 is not None and abs(x - x0) < 1e-12]
        worst = (f"(The section solver's worst over every seed and combination at this design:"
                 f" {g0[0]:.3g} × the allowable.) " if g0 else "")  # fmt: skip
        parts.append({"kind": "p", "c": "fail" if at.get("disagree") else "muted", "text": (
            f"Section solver against pipeline FE at the section design, same storm and seed:"
            f" section max |y| {at['section_solver_max_displacement_m']:.3g} m, FE"
            f" {at['max_displacement_m']:.3g} m: ratio FE/section {f:.3g}. "
            + worst
            + (f"They DISAGREE (beyond a factor {DISAGREEMENT_FACTOR:g}). Candidate causes:"
               if at.get("disagree") else f"Within a factor {DISAGREEMENT_FACTOR:g}.")
        )})  # fmt: skip
        if at.get("disagree"):
            parts.append({"kind": "ul", "c": "", "items": at.get("causes", [])})
            parts.append({"kind": "p", "c": "muted", "text": (
                "The FE runs one seed (the worst of the section at the given design); the"
                " section's dynamic search takes every seed. The design reported is the one that"
                " passes both.")})  # fmt: skip
    if p.get("envelopes"):
        parts.append(figure_part("Pipeline FE envelopes", lambda: _envelopes_png(p),
                                 "Envelopes along the line at the accepted design. "
                                 + CLAUSES["pipeline_strain"]))  # fmt: skip
    return parts


def _envelopes_png(p: dict[str, Any]) -> str:
    """The pipeline FE's envelopes along the line: max |y| / D and max strain."""
    from matplotlib.figure import Figure

    env = p["envelopes"]
    fig = Figure(figsize=(7.5, 4.2), layout="constrained")
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    d = p["diameter_m"]
    ax1.plot(env["x"], [v / d for v in env["max_abs_y"]], "k-", lw=1.2)
    ax1.axhline(p["allowable_m"] / d, color="#c00", ls="--", lw=1.0, label="allowable")
    ax1.set_ylabel("max |y| / D [-]")
    ax1.legend(fontsize="small")
    ax2.plot(env["x"], [100.0 * v for v in env["max_strain"]], "C3-", lw=1.2)
    ax2.axhline(100.0 * p["strain_limit"], color="#c00", ls="--", lw=1.0, label="strain limit")
    ax2.set_ylabel("max strain [%]")
    ax2.set_xlabel("x along the line [m]")
    ax2.legend(fontsize="small")
    for ax in (ax1, ax2):
        ax.grid(True, alpha=0.3)
    return png(fig, "pipeline envelopes")


# ---- the page -----------------------------------------------------------------------------------
def _sea_table(s: dict[str, Any], T: Tables) -> dict[str, Any]:
    """The section's design sea states and currents."""
    rows = [[cell(ss.get(k), text=(u == "")) if u == "" else cell(_fmt(ss.get(k)))
             for k, _, u in SEA_COLUMNS] for ss in s["sea_states"]]  # fmt: skip
    return T.add(f"s{s['index']}-sea", f"Design sea states and currents: {s['name']}",
                 [h + (f" [{u}]" if u and u != "-" else "") for _, h, u in SEA_COLUMNS],
                 rows, wide=True)  # fmt: skip


def _checks_table(s: dict[str, Any], T: Tables) -> dict[str, Any]:
    """Every check at the given design, with its clause."""
    crow = []
    for c in s["checks"]:
        ok = c.get("pass")
        note = ""
        if c["level"] == "generalized":
            note = str(c.get("message") or "")
        crow.append([cell(c["level"], text=True), cell(c["name"].replace("_", " "), text=True),
                     cell(str(c["combination"]), text=True), cell(str(c["condition"]), text=True),
                     cell(_fmt(c.get("utilisation"))), verdict_cell(ok),
                     cell(CLAUSES.get(c["name"], ""), text=True),
                     cell(note, text=True)])  # fmt: skip
    return T.add(f"s{s['index']}-checks", f"Checks at the given design: {s['name']}",
                 ["Level", "Check", "Combination", "Condition", "Utilisation", "Verdict",
                  "Clause", "Note"], crow, wide=True)  # fmt: skip


def _levels_parts(s: dict[str, Any], a: Assessment, T: Tables) -> list[dict[str, Any]]:
    """The design floor's words and the minimum design per level."""
    var = a.route.variable
    parts: list[dict[str, Any]] = []
    lrow = []
    for k, v in s["levels"].items():
        lrow.append([cell(level_name(k), text=True), _level_cell(s, k, var),
                     cell(str(v.get("governing_check") or "—"), text=True),
                     cell(str(v.get("message") or ""), text=True)])  # fmt: skip
    fl = s.get("design_floor") or {}
    if fl:
        ratio = fl.get("dynamic_over_generalized_weight")
        rtxt = "" if ratio is None else f" Dynamic/generalized submerged weight: {ratio:.2f}."
        parts.append({"kind": "p", "c": "", "text": f"Design floor: {fl['words']}.{rtxt}"})
    parts.append(
        T.add(
            f"s{s['index']}-levels",
            f"Minimum design per level: {s['name']}",
            ["Level", "Minimum", "Governed by", "Message"],
            lrow,
            wide=True,
        )
    )
    return parts


def _seeds_table(s: dict[str, Any], base: dict[str, Any], T: Tables) -> dict[str, Any]:
    """The dynamic level over seeds at the given design, per combination."""
    srow = []
    for n, b in base.items():
        ys = b["max_displacement"]
        srow.append([cell(n, text=True), len(ys), _fmt(b["diameter"], 4),
                     _fmt(b["submerged_weight"], 4), _fmt(b["allowable"]),
                     _fmt(st.mean(ys)), _fmt(st.stdev(ys) if len(ys) > 1 else 0.0),
                     _fmt(max(ys)), _fmt(max(ys) / b["allowable"]),
                     cell(", ".join(f"{y:.3g}" for y in ys), text=True)])  # fmt: skip
    return T.add(
        f"s{s['index']}-seeds",
        f"Dynamic level over seeds (given design): {s['name']}",
        [
            "Combination",
            "Seeds",
            "D [m]",
            "w_s [N/m]",
            "Allowable [m]",
            "mean max |y| [m]",
            "std [m]",
            "largest [m]",
            "largest / allowable",
            "max |y| per seed [m]",
        ],
        srow,
        wide=True,
    )


def _dynamic_parts(s: dict[str, Any], a: Assessment, T: Tables) -> list[dict[str, Any]]:
    """The dynamic level: seeds strip, table over seeds, worst-seed histories, the search."""
    var = a.route.variable
    parts: list[dict[str, Any]] = []
    dyn = s.get("dynamic") or {}
    if dyn.get("base"):
        strip = ("Dynamic level at the given design: every seed's max |y| / allowable per"
                 " combination (red: above the allowable).")  # fmt: skip
        parts.append(figure_part("Dynamic level strip plot", lambda: strip_svg(dyn["base"]), strip))
        parts.append(_seeds_table(s, dyn["base"], T))
        for n, b in dyn["base"].items():
            if b.get("history"):
                text = f"{n}: lateral displacement y(t) of the worst seed, dashed ±allowable."
                draw = lambda n=n, b=b: history_svg(n, b["history"], b["allowable"])  # noqa: E731
                parts.append(figure_part(f"Displacement history of {n}", draw, text))
    if dyn.get("bisection"):
        tr = "; ".join(f"{format_value(x, var)} → {_fmt(g)}" for x, g in dyn["bisection"]["trials"])
        parts.append({"kind": "p", "c": "muted", "text": (
            "Dynamic design search (g = max over combinations and seeds of max |y| / allowable;"
            f" pass at g ≤ 1): {tr}. {dyn['bisection']['message']} —"
            f" {dyn['bisection']['storms']} storms.")})  # fmt: skip
    return [x for x in parts if x is not None]


def _validity_parts(s: dict[str, Any], a: Assessment) -> list[dict[str, Any]]:
    """The section's assumptions and validity notes, and its run identity."""
    return [
        {"kind": "h3", "id": f"v{s['index']}", "text": "Assumptions and validity"},
        {"kind": "ul", "c": "", "items": section_validity(s, a) + s["notes"]},
        {
            "kind": "p",
            "c": "muted",
            "text": (
                f"Section run identity {s.get('identity') or '—'} (SHA-256 of its inputs, levels,"
                f" options and the onbottom version); {_fmt(s.get('cpu_time_s'))} CPU-s"
                + (", reused from a previous run" if s["name"] in a.reused else "")
                + "."
            ),
        },
    ]


def _section_parts(s: dict[str, Any], a: Assessment, T: Tables) -> list[dict[str, Any]]:
    """One section's page: soil, sea states, checks, the absolute check by hand, levels, the
    V–H diagram, the dynamic level, the pipeline FE (governing section) and validity."""
    parts: list[dict[str, Any]] = []
    if s.get("no_design_reason"):
        parts.append({"kind": "p", "c": "fail", "text": "NO DESIGN: " + s["no_design_reason"]})
    parts += [_soil_table(s, T), _sea_table(s, T), _checks_table(s, T)]
    w = _absolute_worked(s, T)
    if w:
        parts.append(w)
    parts += _levels_parts(s, a, T)
    vh = vh_part(s, a.route.sections[s["index"]], a.route.force_model,
                 CLAUSES["soil_resistance"])  # fmt: skip
    if vh:
        parts.append(vh)
    parts += _dynamic_parts(s, a, T)
    if s.get("pipeline_fe"):  # [pipeline] sections = "every": the section's own check
        parts.append({"kind": "h3", "id": f"fe{s['index']}", "text": "Pipeline FE"})
        parts += _pipeline_parts(s["pipeline_fe"], a, T, tid=f"s{s['index']}-pipeline")
    elif a.pipeline and a.pipeline.get("index") == s["index"]:
        parts.append({"kind": "h3", "id": f"fe{s['index']}", "text": "Pipeline FE"})
        parts += _pipeline_parts(a.pipeline, a, T)
    return parts + _validity_parts(s, a)


def report_context(
    a: Assessment, payload: dict[str, Any], *, notes: list[str] | tuple[str, ...] = ()
) -> dict[str, Any]:
    """Everything the template needs (and ``tables``: every table with its CSV text);
    ``notes``: warnings raised outside the sections (reading the route), listed once each."""
    T = Tables()
    var = a.route.variable
    found = [s for s in a.sections if s["governing_level"]]
    gov = max(found, key=lambda s: s["design_value"] or 0.0) if found and var != "none" else None
    p = a.pipeline
    cards = [
        {"k": "sections", "v": str(len(a.sections)), "c": ""},
        {
            "k": "sections with a design",
            "v": f"{len(found)} of {len(a.sections)}",
            "c": "pass" if len(found) == len(a.sections) else "fail",
        },
    ]
    if gov is not None:
        cards.append(
            {
                "k": f"heaviest design ({gov['name']})",
                "c": "",
                "v": f"{format_value(gov['design_value'], var)}",
            }
        )
    checked = [s["pipeline_fe"] for s in a.sections if s.get("pipeline_fe")]
    if checked:  # [pipeline] sections = "every"
        n = sum(bool(c["pass"]) for c in checked)
        cards.append({"k": "pipeline FE (every section)", "v": f"{n} of {len(checked)} pass",
                      "c": "pass" if n == len(checked) else "fail"})  # fmt: skip
    elif p is not None:
        cards.append({"k": "pipeline FE (governing section)", "c": "pass" if p["pass"] else "fail",
                      "v": ("pass, design raised" if p.get("raised") else "pass")
                      if p["pass"] else "FAIL"})  # fmt: skip
    cards.append({"k": "allowable displacement", "v": str(payload["route"]["allowable"]), "c": ""})
    cards.append({"k": f"run time (wall; {len(a.reused)} section(s) reused)" if a.reused
                  else "run time (wall)", "v": f"{a.wall_time_s:.0f} s", "c": ""})  # fmt: skip

    used = sorted({m["key"] for s in a.sections for m in section_marks(s, a)})
    summary = [
        T.add("summary", "Summary per KP section (design: the lightest passing design among the"
              " levels run, never below F109's generalized requirement unless opted in by name,"
              " raised where the pipeline FE asks for more)",
              [h for _, h, _ in SUMMARY_COLUMNS],
              [[f(s, a) for _, _, f in SUMMARY_COLUMNS] for s in a.sections], wide=True),
        {"kind": "p", "c": "muted", "text": "Marks on the design: " + ("; ".join(
            f"{k} = {MARKS[k]}" for k in used) if used else "none") + ". Colours: green pass,"
         " red fail or no design, grey not assessed (not run, not covered)."},
        {"kind": "p", "c": "muted", "text": (
            "Weight saved: submerged weight (pipe condition of [pipe]) at the absolute design"
            " minus at the dynamic design, and as a fraction of the former. Dynamic and"
            " generalized designs are never below the flotation minimum.")},
    ]  # fmt: skip
    no = [s for s in a.sections if not s["governing_level"] and var != "none"]
    if no:
        summary.append({"kind": "ul", "c": "fail", "items": [
            f"{s['name']}: NO DESIGN — " + (s.get("no_design_reason")
                                           or "no level run finds a passing design in the range")
            for s in no]})  # fmt: skip
    extra = list(notes)
    notes: dict[str, list[str]] = {n: ["route"] for n in dict.fromkeys(extra)}
    for s in a.sections:
        for n in s["notes"]:
            if s["name"] not in notes.setdefault(n, []):
                notes[n].append(s["name"])
    warn = [
        {"kind": "ul", "c": "", "items": [f"{n} ({', '.join(v)})" for n, v in notes.items()]}
        if notes
        else {"kind": "p", "c": "muted", "text": "No warnings."}
    ]
    comp = payload["comparison"]
    crow = []
    for c in comp:
        why = "expected: see the note above" if c["reason"] == WHY_LIGHTER else c["reason"]
        crow.append([cell(c["section"], text=True), format_value(c["absolute_value"], var),
                     format_value(c["dynamic_value"], var), cell(c["heavier"], text=True),
                     cell(why, text=True)])  # fmt: skip
    sections = [
        {"id": "summary", "title": "Summary per KP section", "page": False, "parts": summary},
        {"id": "warnings", "title": "Warnings and notes", "page": False, "parts": warn},
        {"id": "inputs", "title": "The assessed pipe and design basis", "page": True,
         "parts": _pipe_tables(a, T) + _basis_tables(a, T)},
        {"id": "comparison", "title": "Absolute against dynamic", "page": False, "parts": [
            {"kind": "p", "c": "muted", "text": WHY_LIGHTER},
            T.add("comparison", "Absolute against dynamic design",
                  ["Section", "Absolute", "Dynamic", "Heavier", "Why"], crow, wide=True)]},
    ]  # fmt: skip
    for s in a.sections:
        sections.append({"id": f"s{s['index']}", "page": True, "parts": _section_parts(s, a, T),
                         "title": f"Section {s['name']} (KP {s['kp_start_m'] / 1e3:g}–"
                         f"{s['kp_end_m'] / 1e3:g} km)"})  # fmt: skip
    prov = payload["provenance"]
    sections += [
        {"id": "validity", "title": "Assumptions and validity", "page": True,
         "parts": [{"kind": "ul", "c": "", "items": VALIDITY}]},
        {"id": "clauses", "title": "Clause references", "page": False, "parts": [
            T.add("clauses", "Clause references", ["Key", "Reference"],
                  [[cell(k, text=True), cell(v, text=True)] for k, v in CLAUSES.items()])]},
        {"id": "provenance", "title": "Provenance", "page": False, "parts": [
            T.add("provenance", "Provenance", ["Item", "Value"],
                  [[cell(k, text=True), cell(json.dumps(v) if isinstance(v, (list, dict))
                    else _fmt(v, 4), text=True)] for k, v in prov.items()], wide=True)]},
    ]  # fmt: skip
    return {
        "title": f"On-bottom stability assessment — {a.route.name}",
        "subtitle": f"design variable {var.replace('_', ' ')} · {a.route.dynamic.seeds} seeds ·"
        f" storms {a.route.dynamic.build_up_hours:g} h build-up +"
        f" {a.route.dynamic.peak_hours:g} h peak · {a.wall_time_s:.0f} s",
        "provenance": {"onbottom_version": prov["onbottom_version"],
                       "git_commit": str(prov["git_commit"])[:12], "date": prov["date"]},
        "cards": cards,
        "sections": sections,
        "tables": T.items,
    }  # fmt: skip


def _environment():
    import jinja2

    import onbottom

    folder = Path(onbottom.__file__).parent / "report" / "templates"
    return jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(folder)),
        autoescape=jinja2.select_autoescape(["html", "j2"]),
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
    )


def render(ctx: dict[str, Any]) -> str:
    """The HTML page of :func:`report_context`."""
    return _environment().get_template("assess.html.j2").render(**ctx)
