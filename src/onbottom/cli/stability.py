"""``onbottom stability``: DNV-RP-F109 design checks and the minimum concrete thickness.

Case file: :mod:`onbottom.cases.stability`; computation:
:func:`onbottom.checks.evaluation.evaluate_stability`; this module prints or writes JSON."""

from __future__ import annotations

import warnings
from pathlib import Path
from typing import Any

import click

from onbottom.cli._common import EXIT_INVALID_RESULT, emit_json, handle_errors, json_option

__all__ = ["command"]


def _evaluate(case: Path) -> dict[str, Any]:
    """The JSON payload of a case file: its checks and design solve
    (:func:`onbottom.checks.evaluation.evaluate_stability` on the inputs built by
    :mod:`onbottom.cases.stability`) and every :class:`OutOfRangeWarning` raised on the way."""
    from onbottom.cases.stability import (
        build_stability_inputs,
        load_stability_case,
        unused_table_notes,
    )
    from onbottom.checks.evaluation import evaluate_stability
    from onbottom.errors import OutOfRangeWarning
    from onbottom.inputs.consistency import warnings_reported_by_case

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", OutOfRangeWarning)
        sc = load_stability_case(case)
        inputs = build_stability_inputs(sc, case)
        with warnings_reported_by_case():
            result = evaluate_stability(inputs)
    notes = sorted({str(w.message) for w in caught if issubclass(w.category, OutOfRangeWarning)})
    return {"case": str(case), **result.as_dict(), "warnings": notes + unused_table_notes(sc)}


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
    for g in payload.get("generalized", []):
        crits = []
        for key, crit in (("L_stable", "0.5D"), ("L_10", "10D")):
            u = g[f"utilisation_{crit}"]
            crits.append(f"{key} {g[key]:.3g} (util. {u:.3f})" if u is not None
                         else f"{key} not covered ({g[f'{key}_reason']})")  # fmt: skip
        lines.append(f"F109 generalized (§3.5 tables), {g['combination']}: " + "; ".join(crits))
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
    payload = _evaluate(case)
    if as_json:
        emit_json(payload)
    else:
        click.echo(_table(payload))
    if not payload["success"]:
        raise click.exceptions.Exit(EXIT_INVALID_RESULT)
