"""Outputs of ``onbottom assess``: ``results.json``, ``dynamic.nc``, ``report.html`` (+ PDF).

Every file is written under a temporary name and renamed when complete
(:mod:`onbottom.results`); the case file is only read.

``results.json`` keys (:data:`RESULTS_KEYS`): ``schema`` ("onbottom.assess/1"),
``provenance`` (onbottom version, git commit, date, machine, case source and SHA-256 of its
text, run identity), ``route`` (name, sections count), ``summary`` (one row per section:
section, kp_start_m, kp_end_m, water_depth_m, seabed, governing_check, max_utilisation at
the given design, variable, vertical_value / absolute_value / generalized_value /
dynamic_value — the minimum of the design variable per level, m or N/m, null where the level
has no solution or was not run — governing_level, design_value, saved_submerged_weight_n_per_m),
``sections`` (everything per section: checks with details, levels, per-seed dynamic results
and the search trials (key ``bisection``), notes, the section's ``onbottom stability`` case
document),
``comparison`` (per section: which of the absolute and dynamic designs is heavier, and why),
``validity`` (notes on reconstructed models), ``clauses`` (equation → clause reference),
``pipeline`` (the pipeline FE run of the governing section, ``[levels] pipeline_fe``: section,
combination, seed, design value, max_displacement_m / _over_D, max_strain, strain_limit,
strain_check, worst_node_x_m, status, envelopes {x, max_abs_y, max_strain, max_abs_moment}
[m, m, -, N·m], wall_time_s; null when not run).

Figures are embedded (inline SVG, PNG as data URIs): the report is one self-contained file.
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import html
import json
import math
import platform
import subprocess
from pathlib import Path
from typing import Any

from onbottom._version import __version__, content_hash
from onbottom.assess.core import Assessment
from onbottom.results import atomic_write, save_dataset, write_text_atomic

__all__ = [
    "CLAUSES",
    "RESULTS_KEYS",
    "VALIDITY",
    "comparison",
    "format_value",
    "provenance_block",
    "results_payload",
    "write_outputs",
]

RESULTS_KEYS = (
    "schema",
    "provenance",
    "route",
    "summary",
    "sections",
    "comparison",
    "validity",
    "clauses",
    "pipeline",
)

CLAUSES: dict[str, str] = {
    "vertical_stability": "DNV-RP-F109 (2017) §3.3, Eq 3.1 (flotation, γ_W = 1.1)",
    "absolute_lateral": "DNV-RP-F109 (2017) §3.6, Eq 3.38 (with C*_Y Table 3-9, γ_SC Tables"
    " 3-5 to 3-8, load reductions Eqs 3.17–3.22)",
    "absolute_vertical": "DNV-RP-F109 (2017) §3.6, Eq 3.39 (with C*_Z Table 3-10)",
    "generalized_lateral": "DNV-RP-F109 (2017) §3.5 (groups K, M, N, L); L from the tool's own"
    " `onbottom curves` sweeps, not from F109's tables",
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
    " are about 2.5 times below F109's C*_Y, C*_Z (issue 30), so a dynamic design weight from"
    " it is unconservative; without wake effects it also misses the reduced drift under"
    " opposing wave and current (Chao, Lambrakos & Verley, OTC 6060, 1989).",
    "F109 tables (C*_Y, C*_Z, γ_SC) as in two agreeing public transcriptions"
    " (checks/f109_tables.py); check against the standard.",
    "The generalized level uses only the tool's own committed curve sweeps and never"
    " extrapolates; where none covers the point it says 'not covered'.",
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


def _git_commit() -> str:
    try:
        r = subprocess.run(
            ["git", "rev-parse", "HEAD"],
            cwd=Path(__file__).resolve().parent,
            capture_output=True,
            text=True,
            timeout=5,
            check=False,
        )
        return r.stdout.strip() if r.returncode == 0 and r.stdout.strip() else "unknown"
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def provenance_block(a: Assessment, case_text: str | None) -> dict[str, Any]:
    """Version, commit, date, machine, case source and hash, run identity."""
    return {
        "onbottom_version": __version__,
        "git_commit": _git_commit(),
        "date": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "machine": f"{platform.node()} ({platform.platform()}, {platform.processor() or '?'})",
        "python": platform.python_version(),
        "case_source": a.source,
        "case_sha256": None
        if case_text is None
        else hashlib.sha256(case_text.encode("utf-8")).hexdigest(),
        "run_identity": a.identity,
        "onbottom_content_hash": content_hash(),
        "wall_time_s": a.wall_time_s,
        "sections_reused": a.reused,
        "sections_recomputed": [{"section": n, "reason": r} for n, r in a.recomputed],
    }


def comparison(a: Assessment) -> list[dict[str, Any]]:
    """Per section: absolute vs dynamic design, which is heavier, and the reason stated."""
    out = []
    for s in a.sections:
        lv = s["levels"]
        xa = (lv.get("absolute") or {}).get("value")
        xd = (lv.get("dynamic") or {}).get("value")
        if "absolute" not in lv or "dynamic" not in lv:
            continue
        if xa is None and xd is None:
            verdict, why = "neither", "no design in the range at either level"
        elif xa is None:
            verdict = "absolute"
            why = (
                "the absolute method finds no design in the range while storms on the section"
                " stay within the allowable: it requires zero movement under the single design"
                " oscillation (U*, T*) with peak load coefficients, whereas the dynamic level"
                " lets the soil resistance build up with penetration and allows the"
                " displacement"
            )
        elif xd is None:
            verdict = "dynamic"
            why = (
                "the dynamic level finds no design in the range: some seed exceeds the"
                " allowable even at the upper bound (check the storm and the soil model)"
            )
        elif xd < xa:
            verdict = "absolute"
            why = WHY_LIGHTER
        elif xd > xa:
            verdict = "dynamic"
            why = (
                "the dynamic level asks for more weight than the absolute method here: the"
                " absolute method is meant to be conservative, so this points at the dynamic"
                " model's assumptions (the force model and its calibration, the soil model's"
                " range, every seed rather than the mean must pass) or at a small number of"
                " seeds — treat it as a finding to review"
            )
        else:
            verdict, why = "equal", "both levels give the same design"
        out.append({"section": s["name"], "absolute_value": xa, "dynamic_value": xd,
                    "heavier": verdict, "reason": why})  # fmt: skip
    return out


def _json_safe(x: Any) -> Any:
    if isinstance(x, dict):
        return {str(k): _json_safe(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_json_safe(v) for v in x]
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if hasattr(x, "item") and not isinstance(x, (str, bytes)):
        try:
            return _json_safe(x.item())
        except (TypeError, ValueError):
            return str(x)
    return x


def results_payload(a: Assessment, case_text: str | None) -> dict[str, Any]:
    """The ``results.json`` document (keys: :data:`RESULTS_KEYS`)."""
    summary = a.summary
    return _json_safe({
        "schema": "onbottom.assess/1",
        "provenance": provenance_block(a, case_text),
        "route": {"name": a.route.name, "sections": len(a.sections),
                  "variable": a.route.variable,
                  "allowable": a.route.dynamic.allowable
                  if a.route.dynamic.allowable != "user"
                  else f"{a.route.dynamic.allowable_displacement_m} m"},
        "summary": summary.astype(object).where(summary.notna(), None).to_dict("records"),
        "sections": a.sections,
        "comparison": comparison(a),
        "validity": VALIDITY,
        "clauses": CLAUSES,
        "pipeline": a.pipeline,
    })  # fmt: skip


# ---- HTML ------------------------------------------------------------------------------------
def _fmt(x: Any, unit: str = "", digits: int = 3) -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "—"
    if isinstance(x, bool):
        return "pass" if x else "FAIL"
    if isinstance(x, (int, float)):
        return f"{x:.{digits}g}{(' ' + unit) if unit else ''}"
    return html.escape(str(x))


def format_value(x: Any, variable: str) -> str:
    """A design value as text: mm of concrete, N/m of submerged weight, or "no solution"."""
    if x is None:
        return "no solution"
    if variable == "concrete_thickness":
        return f"{1e3 * x:.1f} mm"
    return f"{x:.0f} N/m"


def _strip_svg(base: dict[str, Any]) -> str:
    """Inline SVG: every seed's max |y| / allowable per combination (a strip plot)."""
    names = list(base)
    if not names:
        return ""
    ratios = {n: [y / base[n]["allowable"] for y in base[n]["max_displacement"]] for n in names}
    top = max(1.2, max(max(v) for v in ratios.values()) * 1.1)
    w, row, left = 640, 28, 230
    h = row * len(names) + 40

    def xpos(r: float) -> float:
        return left + (w - left - 20) * min(r, top) / top

    parts = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" role="img"'
        ' aria-label="max displacement over allowable per seed">',
        f'<line x1="{xpos(1.0):.1f}" y1="5" x2="{xpos(1.0):.1f}" y2="{h - 25}" stroke="#c00"'
        ' stroke-dasharray="4 3"/>',
        f'<text x="{xpos(1.0) + 3:.1f}" y="15" font-size="11" fill="#c00">allowable</text>',
        f'<line x1="{left}" y1="{h - 25}" x2="{w - 20}" y2="{h - 25}" stroke="#333"/>',
        f'<text x="{left}" y="{h - 8}" font-size="11">0</text>',
        f'<text x="{w - 130}" y="{h - 8}" font-size="11">{top:.2g} × allowable</text>',
    ]
    for k, n in enumerate(names):
        y = 20 + k * row
        parts.append(
            f'<text x="5" y="{y + 4}" font-size="11">{html.escape(n[:34])}</text>'
            f'<line x1="{left}" y1="{y}" x2="{w - 20}" y2="{y}" stroke="#ddd"/>'
        )
        for r in ratios[n]:
            color = "#c00" if r > 1.0 else "#06c"
            parts.append(
                f'<circle cx="{xpos(r):.1f}" cy="{y}" r="4" fill="{color}" fill-opacity="0.7"/>'
            )
    parts.append("</svg>")
    return "".join(parts)


def _history_svg(name: str, h: dict[str, Any], allowable: float) -> str:
    """Inline SVG: y(t) of the worst seed with the ±allowable lines."""
    t, y = h.get("time") or [], h.get("y") or []
    if len(t) < 2:
        return ""
    w, hh, left, pad = 640, 160, 50, 18
    top = max(max(abs(v) for v in y), allowable) * 1.1 or 1.0
    tx = lambda v: left + (w - left - 10) * (v - t[0]) / (t[-1] - t[0])  # noqa: E731
    ty = lambda v: hh / 2 - (hh / 2 - pad) * v / top  # noqa: E731
    pts = " ".join(f"{tx(a):.1f},{ty(b):.1f}" for a, b in zip(t, y, strict=True))
    return (
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{hh + 14}" role="img"'
        f' aria-label="lateral displacement history, seed {h["seed"]}">'
        f'<text x="{left}" y="12" font-size="11">{html.escape(name)} — seed {h["seed"]}'
        f" (worst): y(t) [m], dashed ±allowable</text>"
        f'<line x1="{left}" y1="{ty(0):.1f}" x2="{w - 10}" y2="{ty(0):.1f}" stroke="#999"/>'
        + "".join(
            f'<line x1="{left}" y1="{ty(s * allowable):.1f}" x2="{w - 10}"'
            f' y2="{ty(s * allowable):.1f}" stroke="#c00" stroke-dasharray="4 3"/>'
            for s in (1, -1)
        )
        + f'<polyline fill="none" stroke="#06c" stroke-width="1" points="{pts}"/>'
        f'<text x="2" y="{ty(top / 1.1) + 4:.1f}" font-size="10">{top / 1.1:.2g}</text>'
        f'<text x="2" y="{ty(0) + 4:.1f}" font-size="10">0</text>'
        f'<text x="{left}" y="{hh + 12}" font-size="10">t = {t[0]:.0f} s</text>'
        f'<text x="{w - 80}" y="{hh + 12}" font-size="10">{t[-1]:.0f} s</text></svg>'
    )


# ---- figures (PNG data URIs: the report stays one file) ---------------------------------------
def _png(fig: Any, alt: str) -> str:
    import base64
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=80)
    data = base64.b64encode(buf.getvalue()).decode("ascii")
    return f"<img alt='{html.escape(alt)}' src='data:image/png;base64,{data}'>"


def _vh_figure(s: dict[str, Any], water_density: float) -> str:
    """V–H diagram of the section at the given design: every wave cycle's peak load in the
    design sea states (:func:`onbottom.hydro.load_envelope.load_envelope`, drawn by
    :func:`onbottom.plotting.load_envelope.plot_load_envelope`), F109's design load point
    (w_s − F*_Z, F*_Y) of the absolute check and the soil's resistance envelope H = μV + F_R
    (Eq 3.38 without γ_SC) of the three combinations with the highest absolute utilisation."""
    from onbottom.hydro.forces import MorisonCoefficients
    from onbottom.hydro.load_envelope import load_envelope
    from onbottom.plotting.load_envelope import plot_load_envelope

    seas = {ss["combination"]: ss for ss in s["sea_states"]}
    rows = [
        c for c in s["checks"]
        if c["name"] == "absolute_lateral" and "f_y" in (c.get("details") or {})
        and c["combination"] in seas and c.get("utilisation") is not None
    ]  # fmt: skip
    rows = sorted(rows, key=lambda c: -c["utilisation"])[:3]
    if not rows:
        return ""
    envs, labels = [], []
    try:
        for c in rows:
            det, ss = c["details"], seas[c["combination"]]
            envs.append(
                load_envelope(
                    hs=ss["hs"], tp=ss["tp"], depth=s["water_depth"], diameter=det["diameter"],
                    submerged_weight=det["submerged_weight"], current=max(det["v_star"], 0.0),
                    gamma=ss["gamma"], wave_direction_deg=ss["wave_direction_deg"] or 90.0,
                    spreading_s=ss["spreading_s"], coefficients=MorisonCoefficients(),
                    r_y=det["r_y"], r_z=det["r_z"], density=water_density,
                )
            )  # fmt: skip
            labels.append(str(c["combination"])[:28])
    except Exception as exc:  # a figure must not sink the report; the reason is shown
        return f"<p class='note'>V–H diagram not drawn: {html.escape(str(exc))}</p>"
    fig = plot_load_envelope(envs, labels, title=f"{s['name']}: V–H at the given design")
    ax = fig.axes[0]
    vmax = max(ax.get_xlim()[1], 1e-3)
    for k, c in enumerate(rows):
        det = c["details"]
        mu, fr = det["friction_coefficient"], det.get("passive_resistance") or 0.0
        ax.plot([0.0, vmax], [1e-3 * fr, mu * vmax + 1e-3 * fr], color=f"C{k}", lw=1.5,
                label=f"resistance μV + F_R ({str(c['combination'])[:18]})")  # fmt: skip
        ax.plot(1e-3 * (det["submerged_weight"] - det["f_z"]), 1e-3 * det["f_y"], marker="X",
                ms=10, color=f"C{k}", mec="k", ls="none",
                label=f"F109 design load, util. {c['utilisation']:.2f}")  # fmt: skip
    ax.set_ylim(0.0, max(ax.get_ylim()[1], max(1e-3 * r["details"]["f_y"] for r in rows) * 1.2))
    fig.set_size_inches(9.5, 5.0)
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize="x-small")
    return _png(fig, f"V–H diagram of {s['name']}")


def _pipeline_html(p: dict[str, Any], var: str) -> str:
    """The pipeline FE run of the governing section: envelopes along the line and a table."""
    from matplotlib.figure import Figure

    e = html.escape
    env = p["envelopes"]
    fig = Figure(figsize=(7.5, 4.2), layout="constrained")
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    d = p["diameter_m"]
    ax1.plot(env["x"], [v / d for v in env["max_abs_y"]], "k-", lw=1.2)
    ax1.axhline(0.5, color="#c00", ls="--", lw=1.0, label="0.5D")
    ax1.set_ylabel("max |y| / D [-]")
    ax1.legend(fontsize="small")
    ax2.plot(env["x"], [100.0 * v for v in env["max_strain"]], "C3-", lw=1.2)
    ax2.axhline(100.0 * p["strain_limit"], color="#c00", ls="--", lw=1.0, label="strain limit")
    ax2.set_ylabel("max strain [%]")
    ax2.set_xlabel("x along the line [m]")
    ax2.legend(fontsize="small")
    for ax in (ax1, ax2):
        ax.grid(True, alpha=0.3)
    verdict = {None: "not checked", True: "pass", False: "FAIL"}[p.get("strain_check")]
    rows = [
        ("Governing storm", f"{p['combination']} (seed {p['seed']}), condition {p['condition']}"),
        ("Design value", "the given design" if p["design_value"] is None
         else format_value(p["design_value"], var)),
        ("Line", f"{p['length_m']:g} m, {p['n_nodes']} nodes, ends {p['end_conditions']}"),
        ("D, w_s", f"{d:.4g} m, {p['submerged_weight_n_per_m']:.4g} N/m"),
        ("Max lateral displacement", f"{p['max_displacement_m']:.3g} m"
         f" = {p['max_displacement_over_D']:.3g} D at x = {p['worst_node_x_m']:.0f} m"),
        ("Max strain", f"{100 * p['max_strain']:.3g} % (limit {100 * p['strain_limit']:.3g} %:"
         f" {verdict})"),
        ("F109 criteria", ", ".join(f"{k}: {'pass' if v else 'FAIL'}"
                                    for k, v in p["criteria"].items())),
        ("Run", f"{e(p['message'])} (status {p['status']}), {p['wall_time_s']:.0f} s"),
    ]  # fmt: skip
    out = [
        "<h3>Pipeline FE of the governing section</h3>",
        _png(fig, "pipeline envelopes along the line"),
        "<table>",
        *(f"<tr><th>{e(k)}</th><td>{e(str(v))}</td></tr>" for k, v in rows),
        "</table>",
        f"<p class='note'>{e(CLAUSES['pipeline_strain'])}. Theory: docs/theory/pipeline_fe.md.</p>",
    ]
    return "\n".join(out)


def _seed_stats(base: dict[str, Any]) -> str:
    """Distribution over seeds per combination: mean, standard deviation, largest, and the
    final displacement's mean."""
    import statistics as st

    out = ["<table><tr><th>Combination</th><th>Seeds</th><th>mean max |y| [m]</th>"
           "<th>std [m]</th><th>largest [m]</th><th>largest / allowable</th>"
           "<th>mean final y [m]</th></tr>"]  # fmt: skip
    for n, b in base.items():
        ys = b["max_displacement"]
        sd = st.stdev(ys) if len(ys) > 1 else 0.0
        out.append(
            f"<tr><td>{html.escape(n)}</td><td>{len(ys)}</td><td>{st.mean(ys):.3g}</td>"
            f"<td>{sd:.3g}</td><td>{max(ys):.3g}</td><td>{max(ys) / b['allowable']:.3g}</td>"
            f"<td>{st.mean(b['final_displacement']):.3g}</td></tr>"
        )
    out.append("</table>")
    return "".join(out)


def _section_validity(s: dict[str, Any], a: Assessment) -> list[str]:
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


_SEA_STATE_KEYS = (
    "combination", "condition", "hs", "tp", "gamma", "wave_direction_deg", "spreading_s",
    "current_velocity", "current_reference_height", "current_direction_deg",
)  # fmt: skip

_CSS = """
body{font-family:system-ui,Segoe UI,Helvetica,Arial,sans-serif;margin:2em;max-width:70em;color:#222}
h1{font-size:1.6em}h2{border-bottom:1px solid #ccc;padding-top:1em}
table{border-collapse:collapse;margin:.5em 0 1em}td,th{border:1px solid #bbb;padding:3px 7px;
font-size:.9em;text-align:left}th{background:#eef}.fail{color:#b00;font-weight:bold}
.pass{color:#070}.note{font-size:.9em;color:#444}code{background:#f4f4f4}
@media print{.section{page-break-before:always}}
"""


def report_html(a: Assessment, payload: dict[str, Any]) -> str:
    """The design report (self-contained HTML: inline CSS and SVG, no external resource)."""
    var = a.route.variable
    e, fv = html.escape, format_value
    out = [
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>",
        f"<title>On-bottom stability assessment — {e(a.route.name)}</title>",
        f"<style>{_CSS}</style></head><body>",
        f"<h1>On-bottom stability assessment — {e(a.route.name)}</h1>",
        f"<p class='note'>onbottom {e(__version__)} · design variable: {e(var)} · allowable"
        f" displacement of the dynamic level: {e(str(payload['route']['allowable']))} (every"
        f" seed) · {a.route.dynamic.seeds} seeds · storms {a.route.dynamic.build_up_hours:g} h"
        f" build-up + {a.route.dynamic.peak_hours:g} h peak.</p>",
        "<h2 id='summary'>Summary per KP section</h2><table><tr><th>Section</th><th>KP [km]"
        "</th><th>Depth [m]</th><th>Seabed</th><th>Governing check (given design)</th>"
        "<th>Utilisation</th><th>Flotation min.</th><th>Absolute min.</th><th>Generalized</th>"
        "<th>Dynamic min.</th><th>Design (level)</th><th>Weight saved by dynamic [N/m]</th>"
        "</tr>",
    ]
    for s in a.sections:
        lv = s["levels"]
        ws = s.get("weight_saved") or {}
        u = s["max_utilisation"]
        gen = lv.get("generalized")
        if gen is None:
            gtxt = "not run"
        elif gen.get("value") is not None:
            gtxt = format_value(gen["value"], var)
        else:
            gtxt = "not covered" if not gen["covered"] else "partly covered"
        out.append(
            f"<tr><td><a href='#s{s['index']}'>{e(s['name'])}</a></td>"
            f"<td>{s['kp_start_m'] / 1e3:g}–{s['kp_end_m'] / 1e3:g}</td>"
            f"<td>{s['water_depth']:g}</td><td>{e(s['seabed_model'])}</td>"
            f"<td>{e(s['governing_check'])}</td>"
            f"<td class='{'fail' if u and u > 1 else 'pass'}'>{_fmt(u)}</td>"
            + "".join(
                f"<td>{fv((lv.get(k) or {}).get('value'), var) if k in lv else 'not run'}</td>"
                for k in ("vertical", "absolute")
            )
            + f"<td>{gtxt}</td>"
            + f"<td>{fv(lv['dynamic']['value'], var) if 'dynamic' in lv else 'not run'}</td>"
            + f"<td>{fv(s['design_value'], var) if s['governing_level'] else 'no solution'}"
            f" ({e(str(s['governing_level']))})</td>"
            f"<td>{_fmt(ws.get('saved_submerged_weight'), digits=4)}</td></tr>"
        )
    out.append("</table>")
    out.append(
        "<p class='note'>Design: the lightest design among the levels run that passes (each is"
        " a complete F109 method); the dynamic value is never below the flotation minimum."
        " Weight saved: submerged weight (pipe condition of [pipe]) at the absolute design"
        " minus at the dynamic design.</p>"
    )
    out.append("<h2 id='comparison'>Absolute against dynamic</h2>")
    out.append(f"<p class='note'>{e(WHY_LIGHTER)} Where the dynamic level asks for more than"
               " the absolute method, the row says so as a finding to review.</p>")  # fmt: skip
    out.append("<table><tr><th>Section</th>"
               "<th>Absolute</th><th>Dynamic</th><th>Heavier</th><th>Why</th></tr>")  # fmt: skip
    for c in payload["comparison"]:
        out.append(
            f"<tr><td>{e(c['section'])}</td><td>{format_value(c['absolute_value'], var)}</td>"
            f"<td>{format_value(c['dynamic_value'], var)}</td><td>{e(c['heavier'])}</td>"
            f"<td>{e(c['reason'])}</td></tr>"
        )
    out.append("</table>")
    for s in a.sections:
        out.append(f"<div class='section'><h2 id='s{s['index']}'>Section {e(s['name'])}"
                   f" (KP {s['kp_start_m'] / 1e3:g}–{s['kp_end_m'] / 1e3:g} km)</h2>")  # fmt: skip
        doc = s["stability_document"]
        out.append(
            "<h3>Inputs</h3><pre>"
            + e(json.dumps({k: doc[k] for k in ("environment", "seabed")}, indent=1))
            + "</pre>"
        )
        out.append("<h3>Design sea states and currents</h3><table><tr><th>Combination</th>"
                   "<th>Condition</th><th>H_s [m]</th><th>T_p [s]</th><th>γ</th>"
                   "<th>Wave dir. [deg]</th><th>Spreading s</th><th>Current [m/s]</th>"
                   "<th>at z_r [m]</th><th>Current dir. [deg]</th></tr>")  # fmt: skip
        for ss in s["sea_states"]:
            out.append(
                "<tr>" + "".join(f"<td>{_fmt(ss[k])}</td>" for k in _SEA_STATE_KEYS) + "</tr>"
            )
        out.append(f"</table><p class='note'>{e(CLAUSES['design_sea_state'])}</p>")
        out.append("<h3>Checks at the given design</h3><table><tr><th>Level</th><th>Check</th>"
                   "<th>Combination</th><th>Condition</th><th>Utilisation</th><th>Verdict</th>"
                   "<th>Clause / note</th></tr>")  # fmt: skip
        for c in s["checks"]:
            note = CLAUSES.get(c["name"], "")
            if c["level"] == "generalized":
                note = f"{note}. {c.get('message', '')}"
            verdict = "not covered" if c.get("pass") is None else ("pass" if c["pass"] else "FAIL")
            out.append(
                f"<tr><td>{e(c['level'])}</td><td>{e(c['name'])}</td>"
                f"<td>{e(str(c['combination']))}</td><td>{e(str(c['condition']))}</td>"
                f"<td>{_fmt(c.get('utilisation'))}</td>"
                f"<td class='{'fail' if verdict == 'FAIL' else 'pass'}'>{verdict}</td>"
                f"<td class='note'>{e(note)}</td></tr>"
            )
        out.append("</table><h3>Minimum design per level</h3><table><tr><th>Level</th>"
                   "<th>Minimum</th><th>Governed by</th><th>Message</th></tr>")  # fmt: skip
        for k, v in s["levels"].items():
            out.append(
                f"<tr><td>{e(k)}</td><td>{format_value(v.get('value'), var)}</td>"
                f"<td>{e(str(v.get('governing_check') or '—'))}</td>"
                f"<td class='note'>{e(str(v.get('message', '')))}</td></tr>"
            )
        out.append("</table>")
        out.append("<h3>V–H diagram (given design)</h3>")
        out.append(_vh_figure(s, a.route.water_density))
        out.append(
            "<p class='note'>Dots: the peak load of every wave cycle of a 3-h record of the"
            " design sea state on a fixed pipe (Morison C_D 0.9, C_M 3.29, C_L 0.9, times r_y,"
            " r_z; seed 0), V = w_s − F_Z, H = |F_Y|. Crosses: the absolute check's design load"
            " (F*_Y, w_s − F*_Z). Lines: the soil's resistance envelope H = μV + F_R at the"
            f" as-laid penetration, without γ_SC. {e(CLAUSES['soil_resistance'])}.</p>"
        )
        dyn = s.get("dynamic") or {}
        if dyn.get("base"):
            out.append("<h3>Dynamic level: max displacement over seeds (given design)</h3>")
            out.append(_strip_svg(dyn["base"]))
            out.append(_seed_stats(dyn["base"]))
            out.append("<table><tr><th>Combination</th><th>D [m]</th><th>w_s [N/m]</th>"
                       "<th>Allowable [m]</th><th>max |y| per seed [m]</th><th>Status</th>"
                       "</tr>")  # fmt: skip
            for n, b in dyn["base"].items():
                ys = ", ".join(f"{y:.3g}" for y in b["max_displacement"])
                out.append(
                    f"<tr><td>{e(n)}</td><td>{b['diameter']:.4g}</td>"
                    f"<td>{b['submerged_weight']:.4g}</td><td>{b['allowable']:.3g}</td>"
                    f"<td>{ys}</td><td>{e(str(sorted(set(b['status']))))}</td></tr>"
                )
            out.append("</table>")
            for n, b in dyn["base"].items():
                if b.get("history"):
                    out.append(_history_svg(n, b["history"], b["allowable"]))
        if dyn.get("bisection"):
            tr = "; ".join(
                f"{format_value(x, var)} → {_fmt(g)}" for x, g in dyn["bisection"]["trials"]
            )
            out.append(
                "<p class='note'>Search on the design variable (g = max over combinations"
                " and seeds of max |y| / allowable; pass at g ≤ 1; a failing trial stops at its"
                f" first seed above the allowable): {e(tr)}. {e(dyn['bisection']['message'])}"
                f" — {dyn['bisection']['storms']} storms.</p>"
            )
        if a.pipeline and a.pipeline.get("index") == s["index"]:
            out.append(_pipeline_html(a.pipeline, var))
        out.append("<h3>Assumptions and validity</h3><ul>")
        out += [f"<li class='note'>{e(n)}</li>" for n in _section_validity(s, a) + s["notes"]]
        out.append("</ul>")
        out.append(
            f"<p class='note'>Provenance: section run identity {e(str(s.get('identity')))}"
            f" (SHA-256 of its inputs, levels, options and the onbottom version);"
            f" {_fmt(s.get('wall_time_s'))} s of worker time"
            + (", reused from a previous run" if s["name"] in a.reused else "")
            + "; see <a href='#provenance'>Provenance</a>.</p>"
        )
        out.append("</div>")
    out.append("<h2 id='validity'>Assumptions and validity</h2><ul>")
    out += [f"<li>{e(v)}</li>" for v in VALIDITY]
    out.append("</ul><h2 id='clauses'>Clause references</h2><table>")
    out += [f"<tr><td>{e(k)}</td><td>{e(v)}</td></tr>" for k, v in CLAUSES.items()]
    out.append("</table><h2 id='provenance'>Provenance</h2><table>")
    out += [f"<tr><td>{e(k)}</td><td>{e(str(v))}</td></tr>"
            for k, v in payload["provenance"].items()]  # fmt: skip
    out.append("</table></body></html>")
    return "\n".join(out)


def write_outputs(
    a: Assessment, out: str | Path, *, case_text: str | None = None, pdf: bool = True
) -> dict[str, Any]:
    """Write results.json, dynamic.nc, report.html and (WeasyPrint installed) report.pdf into
    ``out``; return ``{"files": [...], "pdf": str | None (why not)}``."""
    outp = Path(out)
    payload = results_payload(a, case_text)
    files = [write_text_atomic(outp / "results.json", json.dumps(payload, indent=1))]
    ds = a.dynamic_dataset()
    if ds.data_vars:
        files.append(save_dataset(ds, outp / "dynamic.nc"))
    text = report_html(a, payload)
    files.append(write_text_atomic(outp / "report.html", text))
    why = None
    if pdf:
        try:
            from weasyprint import HTML  # optional: onbottom[pdf]
        except (ImportError, OSError) as exc:
            why = f"report.pdf not written: WeasyPrint is not available ({type(exc).__name__})"
        else:
            atomic_write(outp / "report.pdf", lambda tmp: HTML(string=text).write_pdf(tmp))
            files.append(outp / "report.pdf")
    else:
        why = "report.pdf not asked for"
    return {"files": [str(f) for f in files], "pdf": why}
