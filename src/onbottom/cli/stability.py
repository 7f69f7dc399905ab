"""``onbottom stability``: DNV-RP-F109 design checks and the minimum concrete thickness."""

from __future__ import annotations

import warnings
from pathlib import Path
from typing import Any

import click

from onbottom.cli._common import EXIT_INVALID_RESULT, emit_json, handle_errors, json_option

__all__ = ["command"]


def _section_summary(section: Any, condition: str) -> dict[str, Any]:
    from onbottom.inputs.pipe_buildup import PipeBuildUp

    if isinstance(section, PipeBuildUp):
        return section.properties(condition).as_dict()
    return {
        "condition": "as given",
        "outer_diameter": section.outer_diameter,
        "submerged_weight": section.submerged_weight,
        "specific_gravity": section.specific_gravity,
        "buoyancy": section.buoyancy,
    }


def check_reference_height(case: Any, case_path: Path, seabed: Any) -> None:
    """[current] reference_height must lie above the seabed roughness z_0 (given, or F109
    Table 3-1 from the seabed) — a case-file error naming the key (F109 Eq 3.3 log profile)."""
    from onbottom._casefile import CaseFileError
    from onbottom.checks.absolute import seabed_roughness

    c = case.current
    z0 = c.z0 if c.z0 is not None else seabed_roughness(seabed)
    if c.reference_height <= z0:
        raise CaseFileError(
            f"{case_path}: current.reference_height = {c.reference_height!r} m is invalid: not"
            f" above the seabed roughness z_0 = {z0:g} m (F109 Table 3-1), where the"
            " logarithmic current profile (F109 Eq 3.3) is undefined",
            field="current.reference_height",
            file=str(case_path),
        )


def evaluate_case(case_path: Path) -> dict[str, Any]:
    """Run the checks (and the design solve) of a case file; return the JSON payload."""
    from onbottom.cases.stability import load_stability_case, penetration_outside_validity
    from onbottom.checks.design import (
        CheckOptions,
        NoFeasibleDesignError,
        design_concrete_thickness,
        design_submerged_weight,
        run_checks,
    )
    from onbottom.errors import OutOfRangeWarning

    caught: list[warnings.WarningMessage] = []
    with warnings.catch_warnings(record=True) as loading:
        warnings.simplefilter("always", OutOfRangeWarning)
        case = load_stability_case(case_path)
        section = case.section()
        seabed = case.seabed.seabed()
        env = case.environment_object()
        combos = case.load_combinations()
    check_reference_height(case, case_path, seabed)
    caught.extend(loading)
    d = case.design
    from onbottom.checks.registry import get_check

    for name in d.checks:  # an unknown name: an error naming the key and the choices
        get_check(name, where="design.checks")
    options = CheckOptions(
        safety_class=d.safety_class,
        region=d.region,
        vertical_conditions=tuple(d.vertical_conditions),
        vertical_safety_factor=d.vertical_safety_factor,
        penetration=case.seabed.initial_penetration,
        trench_depth=case.seabed.trench_depth,
        trench_angle_deg=case.seabed.trench_angle_deg,
        permeable=d.permeable,
        checks=tuple(d.checks),
    )
    from onbottom.inputs.consistency import warnings_reported_by_case

    with warnings.catch_warnings(record=True) as checking, warnings_reported_by_case():
        warnings.simplefilter("always", OutOfRangeWarning)
        rows = run_checks(section, seabed, env, combos, options)
        design: dict[str, Any] = {"solve_for": d.solve_for}
        if d.solve_for != "none":
            try:
                if d.solve_for == "concrete_thickness":
                    res = design_concrete_thickness(
                        section,
                        seabed,
                        env,
                        combos,
                        options,
                        layer=d.layer,
                        thickness_min=d.thickness_min,
                        thickness_max=d.thickness_max,
                    )
                else:
                    res = design_submerged_weight(
                        section,
                        seabed,
                        env,
                        combos,
                        options,
                        weight_min=d.weight_min,
                        weight_max=d.weight_max,
                    )
                design.update(res.as_dict())
                design["section"] = _section_summary(res.section, case.pipe.condition)
            except NoFeasibleDesignError as exc:
                design.update(
                    {
                        "success": False,
                        "status": 2,
                        "message": str(exc),
                        "variable": exc.variable,
                        "value": None,
                        "best_value": exc.best_value,
                        "best_utilisation": exc.best_utilisation,
                    }
                )
    caught.extend(checking)
    invalid = penetration_outside_validity(rows)
    notes = sorted({str(w.message) for w in caught if issubclass(w.category, OutOfRangeWarning)})
    from onbottom.cases.stability import HydroTable

    if case.hydro != HydroTable():
        notes.append(
            "[hydro] is not used by the F109 checks (their load coefficients are Tables"
            " 3-9/3-10 and their reductions Eqs 3.17-3.22); it applies to `onbottom loads`"
            " and `onbottom storm`"
        )
    return {
        "case": str(case_path),
        "section": _section_summary(section, case.pipe.condition),
        "checks": [
            {k: v for k, v in r.as_dict().items() if k != "details"} | {"details": r.details}
            for r in rows
        ],
        "success": bool(design.get("success", True)) and not invalid,
        "message": "; ".join(invalid)
        if invalid
        else ("" if design.get("success", True) else "the design solve has no solution"),
        "all_pass": all(r.passes for r in rows),
        "design": design,
        "warnings": notes,
    }


def _table(payload: dict[str, Any]) -> str:
    lines = []
    s = payload["section"]
    lines.append(
        f"Section ({s['condition']}): D = {s['outer_diameter']:.4f} m, "
        f"w_s = {s['submerged_weight']:.1f} N/m, s_g = {s['specific_gravity']:.4f}"
    )
    lines.append("")
    lines.append(f"{'check':<20} {'combination':<32} {'condition':<13} {'util.':>8}  verdict")
    for r in payload["checks"]:
        verdict = "pass" if r["pass"] else "FAIL"
        u = r["utilisation"]
        shown = f"{u:>8.3f}" if isinstance(u, (int, float)) else f"{'n/a':>8}"
        lines.append(
            f"{r['name']:<20} {r['combination'][:32]:<32} {r['condition']:<13} {shown}  {verdict}"
        )
    lines.append("")
    lines.append("All checks pass." if payload["all_pass"] else "At least one check FAILS.")
    d = payload["design"]
    if d["solve_for"] != "none":
        if d.get("success"):
            unit = "m" if d["variable"].endswith("thickness") else "N/m"
            value = d["value"] * 1e3 if unit == "m" else d["value"]
            shown = f"{value:.1f} mm" if unit == "m" else f"{value:.1f} N/m"
            lines.append(
                f"Design: minimum {d['variable']} = {shown} (governing utilisation"
                f" {d['utilisation']:.3f}, {d['governing_check']}); {d['message']}"
            )
        else:
            lines.append(f"Design: no solution — {d['message']}")
    for w in payload["warnings"]:
        lines.append(f"warning: {w}")
    if not payload["success"] and payload["message"]:
        lines.append(f"NOT VALID: {payload['message']}")
    return "\n".join(lines)


@click.command("stability")
@click.argument("case", type=click.Path(dir_okay=False, path_type=Path))
@json_option
@handle_errors
def command(case: Path, as_json: bool) -> None:
    """DNV-RP-F109 design checks of CASE (TOML): flotation (Eq 3.1), absolute lateral static
    stability (Eqs 3.38/3.39) per load combination, and the minimum concrete thickness or
    submerged weight ([design] solve_for).

    --json prints {"checks": [{name, combination, condition, utilisation, pass, details}],
    "design": {...}, "section": {...}, "all_pass", "success", "warnings"}. Failing checks are
    a result, not an error: the exit status is 0. A design solve with no solution in its
    range ("design": {"success": false}) exits 3 (no valid result); input errors exit 1.
    """
    payload = evaluate_case(case)
    if as_json:
        emit_json(payload)
    else:
        click.echo(_table(payload))
    if not payload["success"]:
        raise click.exceptions.Exit(EXIT_INVALID_RESULT)
