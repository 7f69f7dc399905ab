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

import contextlib
import datetime as _dt
import hashlib
import html
import json
import math
import os
import platform
import socket
import subprocess
from pathlib import Path
from typing import Any

from onbottom._version import __version__, content_hash
from onbottom.assess.core import Assessment
from onbottom.errors import InputError
from onbottom.results import atomic_write, save_dataset, write_text_atomic

__all__ = [
    "CLAUSES",
    "LOCK_NAME",
    "MARK_NAME",
    "RELIABILITY_NAMES",
    "RESULTS_KEYS",
    "VALIDITY",
    "OutputFolder",
    "claim_output_folder",
    "comparison",
    "format_value",
    "level_name",
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
    w, hh, left, pad = 640, 160, 58, 18
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
        f'<text x="22" y="{ty(top / 1.1) + 4:.1f}" font-size="10">{top / 1.1:.2g}</text>'
        f'<text x="22" y="{ty(0) + 4:.1f}" font-size="10">0</text>'
        f'<text x="{left}" y="{hh + 12}" font-size="10">{t[0]:.0f}</text>'
        f'<text x="{(left + w) / 2 - 30:.0f}" y="{hh + 12}" font-size="11">time t [s]</text>'
        f'<text x="12" y="{hh / 2 + 30:.0f}" font-size="11" transform="rotate(-90 12'
        f' {hh / 2 + 30:.0f})">y [m]</text>'
        f'<text x="{w - 40}" y="{hh + 12}" font-size="10">{t[-1]:.0f}</text></svg>'
    )


# ---- figures (PNG data URIs: the report stays one file) ---------------------------------------
def _png(fig: Any, alt: str) -> str:
    import base64
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=160)
    data = base64.b64encode(buf.getvalue()).decode("ascii")
    width = int(fig.get_figwidth() * 80)  # drawn at 160 dpi, shown at 80 px per inch
    return f"<img alt='{html.escape(alt)}' width='{width}' src='data:image/png;base64,{data}'>"


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


def report_html(a: Assessment, payload: dict[str, Any]) -> str:
    """The design report (self-contained HTML: the shared report style, inline figures)."""
    from onbottom.assess._report import render, report_context

    return render(report_context(a, payload))


def write_outputs(
    a: Assessment,
    out: str | Path,
    *,
    case_text: str | None = None,
    pdf: bool = True,
    notes: list[str] | tuple[str, ...] = (),
) -> dict[str, Any]:
    """Write results.json, dynamic.nc, report.html and (WeasyPrint installed) report.pdf into
    ``out``; return ``{"files": [...], "pdf": str | None (why not)}``. ``notes``: warnings
    raised while the route was read and run, listed in the report with the sections' own."""
    outp = Path(out)
    payload = results_payload(a, case_text)
    files = [write_text_atomic(outp / "results.json", json.dumps(payload, indent=1))]
    ds = a.dynamic_dataset()
    if ds.data_vars:
        files.append(save_dataset(ds, outp / "dynamic.nc"))
    from onbottom.assess._report import render, report_context

    ctx = report_context(a, payload, notes=notes)
    for tb in ctx["tables"]:
        files.append(write_text_atomic(outp / tb["csv"], tb["csv_text"]))
    text = render(ctx)
    files.append(write_text_atomic(outp / "report.html", text))
    why = None
    if pdf:
        try:
            from weasyprint import HTML  # optional: onbottom[pdf]
        except (ImportError, OSError) as exc:
            why = f"report.pdf not written: WeasyPrint is not available ({type(exc).__name__})"
        else:
            atomic_write(
                outp / "report.pdf",
                lambda tmp: HTML(string=text, base_url=str(outp)).write_pdf(tmp),
            )
            files.append(outp / "report.pdf")
    else:
        why = "report.pdf not asked for"
    return {"files": [str(f) for f in files], "pdf": why}


# ---- the output folder: whose files, which run -----------------------------------------------
MARK_NAME = ".onbottom-assess"
"""The file that marks a folder as written by ``onbottom assess`` (its files may be replaced)."""

LOCK_NAME = ".onbottom-assess.lock"
"""The lock file of the run writing a folder (its process id and host)."""

_OWN_NAMES = frozenset(
    {"results.json", "dynamic.nc", "report.html", "report.pdf", "sections", "pipeline.nc"}
)

RELIABILITY_NAMES = frozenset(
    {
        "campaign.zarr",
        "design.zarr",
        "reliability.json",
        "exceedance.png",
        "convergence.png",
        "importance.png",
        "design.png",
        "report.html",
        "tables",
    }
)
"""What ``onbottom reliability`` writes into its ``--out``."""
_GENERATOR = '<meta name="generator" content="onbottom'


class OutputFolder:
    """The ``--out`` folder of ``onbottom assess``, held for one run (:func:`claim_output_folder`;
    a context manager: the lock file is removed on exit). ``notes``: what was found (a stale
    lock taken over)."""

    def __init__(self, path: Path, notes: list[str], lock: Path | None = None) -> None:
        self.path = path
        self.notes = notes
        self.lock = path / LOCK_NAME if lock is None else lock

    def __enter__(self) -> OutputFolder:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.release()

    def release(self) -> None:
        """Remove the lock file if it is still this process's."""
        lock = self.lock
        try:
            if _lock_owner(lock)[0] == os.getpid():
                lock.unlink()
        except OSError:
            pass


def _refuse(message: str) -> InputError:
    err = InputError(message)
    err.field = "--out"  # type: ignore[attr-defined]
    return err


def _foreign(out: Path, mark: str, own: frozenset[str]) -> list[str]:
    """Entries of ``out`` that the command did not write (empty: the folder is its own or
    empty). With the ``mark`` file every entry is taken as the tool's; without it (a folder of
    an older run) only the tool's names ``own``, and a report.html carrying its mark."""
    entries = sorted(out.iterdir(), key=lambda q: q.name)
    if (out / mark).is_file():
        return []
    names = own | {mark, mark + ".lock"}
    foreign = [
        q.name
        for q in entries
        if q.name not in names
        and not any(q.name.startswith(n) for n in names)  # its partial and temporary files
        and not (q.name.startswith(".") and q.name.endswith(".tmp"))
    ]
    page = out / "report.html"
    if page.is_file():
        try:
            with page.open("rb") as fh:
                head = fh.read(4096).decode("utf-8", "replace")
        except OSError:
            head = ""
        if _GENERATOR not in head:
            foreign.append("report.html")
    return foreign


def _lock_owner(lock: Path) -> tuple[int | None, str]:
    """(process id, host) written in a lock file; (None, "") if unreadable."""
    try:
        pid, _, host = lock.read_text(encoding="utf-8").strip().partition(" ")
        return int(pid), host
    except (OSError, ValueError):
        return None, ""


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True  # a process of another user
    except OSError:
        return True
    return True


def claim_output_folder(
    out: str | Path,
    *,
    force: bool = False,
    command: str = "assess",
    own: frozenset[str] = _OWN_NAMES,
) -> OutputFolder:
    """Check and lock ``--out`` for one ``onbottom assess`` run (or ``command``'s, writing the
    names ``own``: ``onbottom reliability`` with :data:`RELIABILITY_NAMES`).

    * the filesystem root and the home folder: refused (as ``onbottom report``'s
      :func:`onbottom.report.build.check_report_folder`; an assessment writes report.html,
      results.json, dynamic.nc and sections/ into the folder);
    * a folder holding files that onbottom did not write (no :data:`MARK_NAME`, and a name
      that is not the tool's, or a report.html without its generator mark): refused unless
      ``force``;
    * a folder that another run is writing (:data:`LOCK_NAME` of a live process on this
      host): refused, naming the process; a lock left by a process that is gone (killed) is
      taken over, with a note.

    Returns the held :class:`OutputFolder` (use it in ``with``); every refusal is an
    :class:`~onbottom.errors.InputError` with ``field = "--out"``.
    """
    p = Path(out).expanduser()
    full = p.resolve()
    if full.parent == full or full == Path.home().resolve():
        where = "the filesystem root" if full.parent == full else "the home folder"
        raise _refuse(
            f"--out = {str(p)!r} is invalid: onbottom {command} needs a folder of its own,"
            f" not {where} (e.g. --out {command}_results)"
        )
    if p.exists() and not p.is_dir():
        raise _refuse(f"--out = {str(p)!r} is invalid: it is a file, expected a folder")
    notes: list[str] = []
    if p.is_dir() and not force:
        foreign = _foreign(p, f".onbottom-{command}", own)
        if foreign:
            shown = ", ".join(foreign[:5]) + (
                f" and {len(foreign) - 5} more" if len(foreign) > 5 else ""
            )
            raise _refuse(
                f"--out = {str(p)!r} is invalid: it holds files that onbottom did not write"
                f" ({shown}); choose another folder or pass --force to write there anyway"
            )
    p.mkdir(parents=True, exist_ok=True)
    lock = p / f".onbottom-{command}.lock"
    me = f"{os.getpid()} {socket.gethostname()}"
    for _ in range(2):
        try:
            fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
        except FileExistsError:
            pid, host = _lock_owner(lock)
            if pid is not None and host == socket.gethostname() and not _alive(pid):
                notes.append(
                    f"{lock} was left by process {pid}, which is gone (killed?): taken over"
                )
                with contextlib.suppress(OSError):
                    lock.unlink()
                continue
            who = f"process {pid} on {host or 'an unknown host'}" if pid else "another run"
            raise _refuse(
                f"--out = {str(p)!r} is in use: {who} is writing it (lock file {lock}); wait"
                " for it to finish or choose another --out (if no such run exists, delete the"
                " lock file)"
            ) from None
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(me + "\n")
        break
    else:  # pragma: no cover - two takeovers raced
        raise _refuse(f"--out = {str(p)!r} is in use: its lock file {lock} keeps reappearing")
    mark = p / f".onbottom-{command}"
    if not mark.is_file():
        write_text_atomic(mark, f"written by onbottom {command}: its files may be replaced\n")
    return OutputFolder(p, notes, lock)
