"""The words of the ``onbottom assess`` outputs: clause references, validity notes, level
names and design values as text (shared by ``results.json``, the console and the design
report)."""

from __future__ import annotations

from typing import Any

__all__ = [
    "CLAUSES",
    "LEVEL_NAMES",
    "RECONSTRUCTED",
    "VALIDITY",
    "WHY_LIGHTER",
    "format_value",
    "level_name",
    "section_validity",
]

CLAUSES: dict[str, str] = {
    "vertical_stability": "DNV-RP-F109 (2017) §3.3, Eq 3.1 (flotation, γ_W = 1.1)",
    "absolute_lateral": "DNV-RP-F109 (2017) §3.6, Eq 3.38 (with C*_Y Table 3-9, γ_SC Tables"
    " 3-5 to 3-8, load reductions Eqs 3.17–3.22)",
    "absolute_vertical": "DNV-RP-F109 (2017) §3.6, Eq 3.39 (with C*_Z Table 3-10)",
    "generalized_lateral": "DNV-RP-F109 (2010/2017) §3.5 (groups K, M, N, L); L_stable and"
    " L_10 from F109's Tables 3-2 to 3-4 (sand; clay not reproduced), checks/f109_generalized.py",
    "dynamic_curves_lateral": "the tool's own `onbottom curves` sweeps (dynamic model), read in"
    " F109's groups K, M, N, L: not F109's tables",
    "dynamic_lateral": "DNV-RP-F109 (2017) §3.4 (dynamic lateral stability analysis;"
    " allowable displacement §3.4.1); storm section solver docs/theory/storm_section.md",
    "design_sea_state": "DNV-RP-F109 (2017) §3.4.3 (JONSWAP, transfer to the seabed, U_s,"
    " T_u; directional spreading R_D)",
    "soil_resistance": "DNV-RP-F109 (2017) §3.4.6 (Coulomb friction μ and passive resistance"
    " F_R, Eqs 3.29–3.32 sand, 3.33–3.36 clay), as in Eq 3.38",
    "pipeline_strain": "DNV-RP-F109 (2017) §3.4.1 / §3.5 (displacement beyond 0.5D: check the"
    " strain); DNV-ST-F101 (2021) §5.4.12 displacement-controlled criterion (the limit here is a"
    " user value, default 0.2 %)",
}

VALIDITY: list[str] = [
    "Verley & Sotberg sand model: the penetration-from-work law (Eq 6) and the maximum"
    " penetration law (Eq 8) are reconstructions (onbottom.soil.verley_sotberg); the dynamic"
    " level on sand rests on them.",
    "Wake force model (hydro/wake.py; the default of the dynamic level, as of `onbottom"
    " curves`): a reconstruction of Lambrakos et al. (1987) / Wake II calibrated only to F109's"
    " peak-load coefficients C*_Y, C*_Z (Tables 3-9/3-10), not to measured force histories.",
    "Morison + lift with constant coefficients ([hydro] model = 'morison'): its peak loads"
    " are about 2.5 times below F109's C*_Y, C*_Z, so a dynamic design weight from"
    " it is unconservative; without wake effects it also misses the reduced drift under"
    " opposing wave and current (Chao, Lambrakos & Verley, OTC 6060, 1989).",
    "F109 tables (C*_Y, C*_Z, γ_SC) as in two agreeing public transcriptions"
    " (checks/f109_tables.py); check against the standard.",
    "The generalized level uses F109's own tables (§3.5; sand Tables 3-2 to 3-4 from public"
    " transcriptions, confidence per table in docs/theory/dnv_rp_f109.md; clay not"
    " reproduced) and never extrapolates; where they do not cover the point it says 'not"
    " covered'. The design is never below it unless [levels] allow_below_generalized says why.",
    "Pipeline FE of the governing section (when run): a straight stretch with fixed (or"
    " pinned/free) ends, the section's soil and force model, one seed (the worst of the"
    " section at the given design); its strain limit is a user value (default 0.2 %, a"
    " screening value, not the DNV-ST-F101 design strain).",
]

RECONSTRUCTED = {
    "sand": VALIDITY[0],
    "wake": VALIDITY[1],
    "morison": VALIDITY[2],
}
"""The validity note of each reconstructed model, by seabed or force-model name."""

WHY_LIGHTER = (
    "Expected: the absolute method (F109 §3.6) is conservative by design — it asks for no"
    " movement at all under the single design oscillation (U*, T*) with peak-load"
    " coefficients and ignores the resistance the pipe gains as it penetrates and the"
    " displacement the criterion allows (0.5D or 10D). The dynamic level lets the pipe move up"
    " to the allowable displacement in a full storm with soil resistance that builds up. It"
    " rests on reconstructed models (the wake force model, the default, calibrated to F109's"
    " peak-load coefficients only; the Verley & Sotberg sand laws): read the saving with their"
    " validity notes."
)


LEVEL_NAMES = {
    "vertical": "flotation",
    "absolute": "absolute",
    "generalized": "generalized",
    "dynamic": "dynamic",
    "dynamic_curves": "dynamic curves",
    "pipeline_fe": "pipeline FE",
}
"""How each level is named on the page and the console."""


def level_name(level: str | None) -> str:
    """The printed name of a level key (None: "none")."""
    return "none" if level is None else LEVEL_NAMES.get(level, level)


def format_value(x: Any, variable: str) -> str:
    """A design value as text: mm of concrete, N/m of submerged weight, or "no solution"."""
    if x is None:
        return "no solution"
    if variable == "concrete_thickness":
        return f"{1e3 * x:.1f} mm"
    return f"{x:.0f} N/m"


def section_validity(s: dict[str, Any], a: Any) -> list[str]:
    """The assumptions and validity notes that apply to this section (reconstructed models
    flagged)."""
    notes = []
    model = s["seabed_model"]
    if model in RECONSTRUCTED and "dynamic" in s["levels"]:
        notes.append("RECONSTRUCTED MODEL — " + RECONSTRUCTED[model])
    force = a.route.force_model if "dynamic" in s["levels"] else None
    if force in RECONSTRUCTED:
        notes.append("RECONSTRUCTED MODEL — " + RECONSTRUCTED[force])
    notes.append(VALIDITY[3])
    if "generalized" in s["levels"]:
        notes.append(VALIDITY[4])
    return notes
