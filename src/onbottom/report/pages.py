"""Result pages of single commands (``onbottom metocean``, ``onbottom reliability``) rendered by
the validation report's machinery: the same template, :class:`SectionContent` blocks, tables
written as CSV beside the page, provenance.

:func:`write_page` writes ``report.html`` (and ``tables/*.csv``) into a command's output
folder; the figures the command saved there are referenced, not copied.
:func:`metocean_sections` and :func:`reliability_sections` turn a command's results into the
sections of its page: data and method, the tables, the figures, and the assumptions.

Why a page per command and not a section of ``onbottom assess``'s report: a route case does not
reference a hindcast (its sea states are typed in, or pasted from ``metocean``'s
``case_<sector>.toml``), and a reliability campaign is a study of one section, minutes to
hours long — too heavy to rerun inside an assessment. Each page stands beside the files it
describes and can be linked from a design report.
"""

from __future__ import annotations

import hashlib
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from onbottom.report.content import FigureRef, SectionContent, Table

__all__ = ["metocean_sections", "reliability_sections", "write_page"]


def _sha256(path: Path) -> str | None:
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError:
        return None


def _version(dist: str) -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version(dist)
    except PackageNotFoundError:
        return "not installed"


def write_page(
    out: Path,
    title: str,
    sections: Sequence[tuple[str, str, SectionContent]],
    *,
    command: str,
    inputs: dict[str, Any] | None = None,
    run_time: float = math.nan,
    json_name: str | None = None,
) -> Path:
    """Render ``sections`` into ``out/report.html`` with the report template.

    Parameters
    ----------
    out : Path
        The command's output folder (exists).
    title : str
        Page title.
    sections : sequence of (name, title, SectionContent)
        In page order; figure paths relative to ``out``.
    command : str
        The command line that rebuilds the page (shown under Provenance).
    inputs : dict or None
        Further provenance rows (input files and their SHA-256, options, package versions).
    run_time : float
        Seconds the command took (NaN: not measured).
    json_name : str or None
        The command's JSON file beside the page, linked under Provenance.

    Returns
    -------
    Path
        ``report.html``.
    """
    from onbottom.report.build import (
        RenderedSection,
        _environment,
        _write_tables,
        provenance,
        repo_root,
    )
    from onbottom.results import write_text_atomic

    rendered = []
    for i, (name, sec_title, content) in enumerate(sections):
        rs = RenderedSection(name=name, title=sec_title, order=i, state="ok", content=content)
        _write_tables(rs, out)
        rendered.append(rs)
    prov = provenance(repo_root())
    prov["run_time"] = round(run_time, 1) if math.isfinite(run_time) else "–"
    html = (
        _environment()
        .get_template("report.html.j2")
        .render(
            title=title,
            sections=rendered,
            provenance=prov,
            n_pass=sum(s.n_pass for s in rendered),
            n_fail=sum(s.n_fail for s in rendered),
            n_info=0,
            show_totals=False,
            command=command,
            generator=" ".join(command.split()[:2]),
            extra_provenance={k: str(v) for k, v in (inputs or {}).items()},
            json_name=json_name,
        )
    )
    return write_text_atomic(out / "report.html", html)


def _f(x: Any) -> Any:
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


# ------------------------------------------------------------------------------ metocean
def _tail_section(result, figures: dict[str, str] | None = None) -> SectionContent | None:
    """The omnidirectional H_s fit's tail guard, exponential alternative and censored storms."""
    t = getattr(result, "tail", None)
    if t is None:
        return None
    rps = [float(r) for r in t.return_periods]
    lv = result.hs["omni"]

    def cells(v, lo, hi) -> list[str]:
        return [f"{x:.2f} [{a:.2f}, {b:.2f}]" for x, a, b in zip(v, lo, hi, strict=True)]

    rows = [
        ["GPD (as fitted)", t.shape, *cells(lv.value, lv.lower, lv.upper)],
        ["exponential (ξ = 0)", 0.0, *cells(*t.exponential)],
    ]
    c = t.censored_fit
    if c:
        rows.append(
            [
                "GPD, gap-ended storms censored",
                c["shape"],
                *cells(c["value"], c["lower"], c["upper"]),
            ]
        )
    crow = [[tm, p] for tm, p in t.censored_peaks]
    end = "none (ξ ≥ 0)" if not math.isfinite(t.endpoint) else f"{t.endpoint:.3g}"
    tables = [
        Table(
            caption="Omnidirectional H_s return values [m] (95 % interval) by tail model",
            columns=["fit", "ξ", *[f"{r:g} y" for r in rps]],
            rows=rows,
            digits=3,
        )
    ]
    if crow:
        tables.append(
            Table(caption="Storms ending at a data gap of 12 h or more (censored peaks)",
                  columns=["peak time (UTC)", "H_s peak [m]"], rows=crow, digits=3)
        )  # fmt: skip
    return SectionContent(
        summary=f"{t.storms} storms, ξ̂ = {t.shape:.2f}, fitted end-point {end} against the"
        f" record's largest storm {t.record_max:.3g}. "
        + (
            " ".join(f"WARNING: {w}." for w in t.warnings)
            if t.warnings
            else "No short-tail warning."
        )
        + " A storm whose cluster ends at a gap of 12 h or more (a buoy failing in the storm)"
        " is a censored observation: its true peak is at least the recorded one.",
        tables=tables,
        figures=[
            FigureRef(
                figures["threshold"],
                "Mean residual life and threshold stability of ξ̂ (storm peaks declustered at"
                " each threshold); the red line is the threshold used.",
            )
        ]
        if figures and "threshold" in figures
        else [],
        sources=["Coles (2001) §4.3.1, §4.4", "docs/theory/metocean.md"],
    )


def metocean_sections(
    result, rows, *, source: Path, figures: dict[str, str], notes: Sequence[str]
) -> tuple[list[tuple[str, str, SectionContent]], dict[str, Any]]:
    """Sections and provenance rows of ``onbottom metocean``'s page.

    Parameters
    ----------
    result : MetoceanResult
        The analysis.
    rows : list of DesignRow
        The design table.
    source : Path
        The hindcast file.
    figures : dict
        ``{"return_levels": file, "contours": file}`` relative to the page (missing: no figure).
    notes : sequence of str
        The command's notes (extrapolation, sectors without values).
    """
    tail = _tail_section(result, figures)
    sections = [
        ("data", "Hindcast", _metocean_data(result, source)),
        ("extremes", "Storms and return values", _metocean_extremes(result, figures)),
        *([("tail", "What the tail fit can be trusted with", tail)] if tail else []),
        ("joint", "Joint model and environmental contours", _metocean_joint(result, figures)),
        ("design_table", "DNV-RP-F109 design table", _metocean_design_table(result, rows)),
        ("assumptions", "Assumptions and limits", _metocean_assumptions(notes)),
    ]
    return sections, _metocean_provenance(result, source)


def _metocean_data(result, source: Path) -> SectionContent:
    """The hindcast: its length, step, series and their statistics."""
    import numpy as np

    hc = result.hindcast
    data_rows = []
    for name, arr, unit in (
        ("H_s", hc.hs, "m"),
        ("T_p", hc.tp, "s"),
        ("current speed", hc.current_speed, "m/s"),
    ):
        if arr is None:
            continue
        a = np.asarray(arr, dtype=float)
        a = a[np.isfinite(a)]
        data_rows.append(
            [
                f"{name} [{unit}]",
                float(np.mean(a)),
                float(np.quantile(a, 0.5)),
                float(np.quantile(a, 0.99)),
                float(np.max(a)),
            ]
        )
    missing = (
        f", {hc.n_missing} missing ({100 * hc.n_missing / hc.hs.size:.1f} %: no storm there;"
        " the rate is per observed year)"
        if hc.n_missing
        else ""
    )
    data = SectionContent(
        summary=f"{source.name}: {hc.years:.2f} observed years at a {hc.step_hours:g}-hour step,"
        f" {hc.hs.size - hc.n_missing} sea states{missing}"
        f"{', with current' if hc.has_current else ', no current'}"
        f"{'' if hc.has_direction else ', no wave direction (omnidirectional only)'}."
        " Read by the strict reader: no gap, duplicate or impossible value (units checked).",
        tables=[
            Table(
                caption="The record",
                columns=["series", "mean", "median", "99 %", "max"],
                rows=data_rows,
                digits=2,
            )
        ],
    )
    return data


def _metocean_extremes(result, figures: dict[str, str]) -> SectionContent:
    """Storms over threshold, GPD parameters and return values per sector and series."""
    o = result.options
    rps = list(o.return_periods)
    conf = f"{100 * o.confidence:g} %"
    ext_rows = []
    for name in ["omni", *result.sectors]:
        for what, levels, unit in (("H_s", result.hs, "m"), ("current", result.current, "m/s")):
            if levels is None:
                continue
            lv = levels[name]
            ext_rows.append(
                [
                    name,
                    f"{what} [{unit}]",
                    _f(float(lv.storms.threshold)),
                    int(lv.storms.peak.size),
                    _f(float(lv.shape)),
                    _f(float(lv.scale)),
                ]
                + [
                    f"{v:.2f} [{lo:.2f}, {hi:.2f}]" if math.isfinite(v) else "–"
                    for v, lo, hi in zip(lv.value, lv.lower, lv.upper, strict=True)
                ]
            )
        if o.sectors == 1:
            break
    figs_ext = []
    if "return_levels" in figures:
        figs_ext.append(
            FigureRef(
                figures["return_levels"],
                f"Return values of H_s and current per sector: GPD fits, storm peaks, {conf}"
                " intervals.",
            )
        )
    return SectionContent(
        summary=f"Peaks over threshold: each series' threshold gives about {o.storm_rate:g}"
        f" storms a year, exceedances closer than {o.r_hours:g} h are one storm; generalised"
        f" Pareto fit of the storm peaks (pyextremes), {o.ci_method} {conf} intervals.",
        tables=[
            Table(
                caption="Storms, GPD parameters and return values [value, interval]",
                columns=["sector", "series", "threshold", "storms", "ξ", "σ"]
                + [f"{r:g} y" for r in rps],
                rows=ext_rows,
                digits=3,
            )
        ],
        figures=figs_ext,
    )


def _metocean_joint(result, figures: dict[str, str]) -> SectionContent:
    """The H_s–T_p(–current) joint model and the IFORM contours."""
    j = result.joint
    jrows = [
        ["H_s Weibull α, β, γ", f"{j.hs_scale:.4f} m, {j.hs_shape:.4f}, {j.hs_location:.4f} m"],
        ["μ(h) = a0 + a1 h^a2 of ln T_p", ", ".join(f"{v:.4f}" for v in j.mu)],
        ["σ(h) = b0 + b1 exp(b2 h) of ln T_p", ", ".join(f"{v:.4f}" for v in j.sigma)],
    ]
    cm = result.current_model
    if cm is not None:
        jrows += [
            ["current Weibull α_U, β_U", f"{cm.scale:.4f} m/s, {cm.shape:.4f}"],
            ["Spearman ρ_S (H_s, U); copula ρ", f"{cm.spearman:.4f}; {cm.rho:.4f}"],
        ]
    figs_joint = []
    if "contours" in figures:
        figs_joint.append(
            FigureRef(
                figures["contours"],
                "Sea states of the record and the IFORM contours of the return periods.",
            )
        )
    crow = [[f"{rp:g}", float(h.max())] for rp, (h, _) in result.contours.items()]
    return SectionContent(
        summary="H_s–T_p: DNV-RP-C205 (2019) §3.6.3 model fitted by virocon (Weibull H_s by"
        " moments, log-normal T_p | H_s); IFORM contours (virocon). Current: Weibull speed"
        " joined to H_s by a Gaussian copula (ρ from Spearman's ρ_S)"
        + ("." if cm is not None else " — not fitted: the record has no current."),
        tables=[
            Table(caption="Joint model", columns=["parameter", "value"], rows=jrows),
            Table(
                caption="Highest H_s on each contour",
                columns=["return period [y]", "max H_s [m]"],
                rows=crow,
                digits=2,
            ),
        ],
        figures=figs_joint,
    )


def _metocean_design_table(result, rows) -> SectionContent:
    """The DNV-RP-F109 design table per sector."""
    rps = list(result.options.return_periods)
    cols = ["sector", "centre [deg]"]
    for rp in rps:
        cols += [f"H_s {rp:g} y [m]", f"T_p {rp:g} y [s]"]
        if rows[0].current is not None:
            cols += [f"U {rp:g} y [m/s]"]
        if rows[0].current_with_hs is not None:
            cols += [f"U | H_s {rp:g} y median [m/s]", f"U | H_s {rp:g} y 90 % [m/s]"]
    trows = []
    for r in rows:
        line: list[Any] = [r.sector, _f(r.centre_deg)]
        for i in range(len(rps)):
            line += [_f(r.hs[i]), _f(r.tp[i])]
            if r.current is not None:
                line += [_f(r.current[i])]
            if r.current_with_hs is not None:
                line += [_f(r.current_with_hs[i]), _f(r.current_with_hs_p90[i])]
        trows.append(line)
    return SectionContent(
        summary="Per sector (waves coming from; current sectored by where it comes from): the"
        " values DNV-RP-F109 (2017) §3.4.2's combinations need — 100-year waves with the"
        " 10-year current and 10-year waves with the 100-year current — and, from the joint"
        " model, the current that goes with each return-period H_s (the joint-statistics"
        " alternative). design_table.csv and case_<sector>.toml hold the same values.",
        tables=[Table(caption="Design table", columns=cols, rows=trows, digits=3)],
    )


def _metocean_assumptions(notes: Sequence[str]) -> SectionContent:
    """Assumptions and limits, with the command's notes."""
    return SectionContent(
        notes=[
            "Storms are independent (declustering) and the climate stationary over the record.",
            "Return values beyond about 4 times the record length are extrapolations: read"
            " their intervals (Coles 2001 §4.4).",
            "T_p for a return-period H_s is the median of T_p | H_s; F109 §3.4.4 asks to scan"
            " the 5–95 % range given in the table's CSV.",
            "The IFORM contour's highest H_s reads the all-sea-state Weibull far beyond the"
            " data (about 1e-6 per sea state at 100 years): it differs from the storm-based"
            " value mainly through that extrapolation (JSON contour_check;"
            " docs/theory/metocean.md).",
            "The current model is omnidirectional; its Gaussian copula has no tail"
            " dependence; a tidal current is not Weibull in detail.",
            *notes,
        ],
        sources=[
            "Coles (2001) §4.3",
            "DNV-RP-C205 (2019) §3.6.3",
            "DNV-RP-F109 (2017) §3.4.2",
            "Haver & Winterstein (2009)",
            "Kruskal (1958)",
            "docs/theory/metocean.md",
        ],
    )


def _metocean_provenance(result, source: Path) -> dict[str, Any]:
    """Provenance rows: the hindcast, its hash, the options, the package versions."""
    o = result.options
    rps = list(o.return_periods)
    return {
        "hindcast": str(source),
        "hindcast SHA-256": _sha256(source),
        "options": (
            f"sectors {o.sectors}, return periods {rps}, storm rate {o.storm_rate:g}/y,"
            f" r {o.r_hours:g} h, confidence {o.confidence:g}, CI {o.ci_method},"
            f" bootstrap {o.n_bootstrap}, seed {o.seed}"
        ),
        "packages": f"pyextremes {_version('pyextremes')}, virocon {_version('virocon')},"
        f" scipy {_version('scipy')}",
    }


# --------------------------------------------------------------------------- reliability
def reliability_sections(
    payload: dict[str, Any], *, figures: dict[str, str], case: Path
) -> tuple[list[tuple[str, str, SectionContent]], dict[str, Any]]:
    """Sections and provenance rows of ``onbottom reliability``'s page, from its JSON payload.

    Parameters
    ----------
    payload : dict
        ``onbottom reliability --json``'s payload.
    figures : dict
        ``{"exceedance"|"convergence"|"importance"|"design": file}`` relative to the page.
    case : Path
        The case file.
    """
    est = payload["estimates"]
    sections = [
        ("climate", "Storm climate and uncertain inputs", _reliability_climate(payload)),
        ("estimates", "Exceedance probabilities", _reliability_estimates(est, figures)),
        ("importance", "Importance of the inputs", _reliability_importance(est, figures)),
    ]
    d = payload.get("design")
    if d is not None:
        design = _reliability_design(d, figures)
        sections.append(("design", "Response-based design on the environmental contour", design))
    t = payload.get("target")
    if t:
        sections.append(("target", "Against the DNV-OS-F101 target", _reliability_target(t)))
    assumptions = _reliability_assumptions(payload)
    sections.append(("campaign", "Campaign, assumptions and limits", assumptions))
    return sections, _reliability_provenance(payload, case)


def _reliability_climate(payload: dict[str, Any]) -> SectionContent:
    """The storm climate (rate, GPD, sectors, current model) and the random inputs."""
    cl = payload.get("climate") or {}
    crows: list[list[Any]] = [
        ["storms per year λ [1/y]", payload["storms_per_year"]],
        ["pipe outer diameter D [m]", payload["diameter"]],
        ["random inputs", ", ".join(payload["inputs"])],
    ]
    if cl:
        crows += [
            ["hindcast", cl.get("hindcast")],
            ["POT threshold u [m]", cl.get("threshold")],
            ["GPD σ [m], ξ", f"{cl.get('gpd_scale'):.4f}, {cl.get('gpd_shape'):.4f}"],
            [
                "sectors (share of storms)",
                ", ".join(
                    f"{s} {f:.2f}"
                    for s, f in zip(
                        cl.get("sectors", []), cl.get("sector_frequencies", []), strict=True
                    )
                )
                or "omnidirectional",
            ],
        ]
        cm = cl.get("current_model")
        crows.append(
            [
                "current",
                "from the case's inputs (not the hindcast)"
                if cm is None
                else f"U | H_s: Weibull α_U {cm['scale']:.3f} m/s, β_U {cm['shape']:.3f};"
                f" Gaussian copula ρ {cm['rho']:.3f}",
            ]
        )
    return SectionContent(
        summary="Each storm's peak sea state is drawn from the long-term model of the site"
        " (storm-peak H_s: Poisson rate and GPD; T_p | H_s; the sector; the current | H_s)"
        " with the uncertain soil inputs and the storm seed; one dynamic section run per"
        " storm gives its maximum lateral displacement Y.",
        tables=[Table(caption="Storm climate and inputs", columns=["", "value"], rows=crows)],
    )


def _reliability_estimates(est: list[dict[str, Any]], figures: dict[str, str]) -> SectionContent:
    """P[Y > limit] per storm, per year and in the design life, with their intervals."""
    erows = []
    for e in est:
        le = "≤ " if e["upper_bound"] else ""  # an upper bound (no failure, or levels short)

        def g(v, le=le):
            return None if v is None else f"{le}{v:.3g}"

        def iv(pair):
            lo, hi = pair
            return "–" if lo is None or hi is None else f"[{lo:.2g}, {hi:.2g}]"

        erows.append(
            [
                e["label"],
                e["limit"],
                e["method"],
                g(e["probability"]),
                iv(e["interval"]),
                "upper bound" if e["upper_bound"] else e["cv"],
                g(e["annual"]),
                iv(e["annual_interval"]),
                g(e["lifetime"]),
                iv(e["lifetime_interval"]),
                e["interval_kind"],
                e["reliability_index"],
                e["storms"],
                e["computed"],
                e["failed_runs"],
            ]
        )
    figs = [
        FigureRef(figures[k], cap)
        for k, cap in (
            ("exceedance", "Exceedance probability per storm against displacement."),
            ("convergence", "Convergence of the estimator (probability and CV per block/level)."),
        )
        if k in figures
    ]
    return SectionContent(
        summary="P[Y > limit] per storm by the estimator of the case with its 95 % interval"
        " (Monte Carlo: Clopper–Pearson, a flagged one-sided bound when no storm fails;"
        " importance sampling: the weights' standard error; subset simulation: Au & Beck's CV"
        " with the chains' correlation), its coefficient of variation, and per year"
        " (1 − exp(−λ p)) and design life, the intervals mapped through the same formulas.",
        tables=[
            Table(
                caption="Exceedance probabilities",
                columns=[
                    "limit",
                    "limit [m]",
                    "method",
                    "P per storm",
                    "95 % interval",
                    "CV",
                    "P per year",
                    "95 % interval (year)",
                    "P in the design life",
                    "95 % interval (life)",
                    "interval",
                    "β",
                    "storms",
                    "computed",
                    "failed runs",
                ],
                rows=erows,
                digits=4,
            )
        ],
        figures=figs,
    )


def _reliability_importance(est: list[dict[str, Any]], figures: dict[str, str]) -> SectionContent:
    """What drives failure: E[u | failure] and SRRC² per limit."""
    names = sorted({k for e in est for k in e["importance"]})
    irows = [[e["label"], e["importance_kind"]] + [e["importance"].get(n) for n in names]
             for e in est]  # fmt: skip
    fnames = list(dict.fromkeys(k for e in est for k in e.get("failure_mean", {})))
    frows = [[e["label"]] + [e["failure_mean"].get(n) for n in fnames] for e in est]
    return SectionContent(
        summary="What drives failure, two measures that answer different questions."
        " Mean standardized input given failure, E[u | failure]: how many standard deviations"
        " from its median each input stood in the storms that failed (the failing storms of"
        " Monte Carlo or of subset simulation's last level, the weighted failing storms of"
        " importance sampling) — the inputs that make a storm fail. SRRC², squared"
        " standardised rank regression coefficients of Y over an unbiased block of storms: the"
        " share of the variance of Y over all storms each input explains (the bulk of the"
        " response, not its tail; the rest, 1 − R², is the storm seed and interactions).",
        tables=[
            Table(
                caption="Mean standardized input given failure, E[u | failure] [SD]",
                columns=["limit", *fnames],
                rows=frows,
                digits=3,
            ),
            Table(
                caption="SRRC² over all storms (the bulk of the response)",
                columns=["limit", "measure", *names],
                rows=irows,
                digits=3,
            ),
        ],
        figures=[FigureRef(figures["importance"], "Importance of the inputs per limit.")]
        if "importance" in figures
        else [],
    )


def _reliability_design(d: dict[str, Any], figures: dict[str, str]) -> SectionContent:
    """The response-based design along the environmental contour."""
    g, f = d["governing"], d["f109"]
    drows = [
        [f"{p['hs']:.2f}", f"{p['tp']:.2f}", p["seeds"], p.get("mean"), p.get("fractile")]
        for p in d["points"]
    ]
    return SectionContent(
        summary=f"Response-based design: dynamic runs along the {d['return_period']:g}-year"
        f" IFORM contour; the design displacement is the {d['fractile']:g} fractile at the"
        f" governing point (H_s {g['hs']:.2f} m, T_p {g['tp']:.1f} s):"
        f" {d['design_displacement']:.4g} m, against {f['fractile']:.4g} m for F109's"
        f" return-period sea state (H_s {f['hs']:.2f} m, T_p {f['tp']:.1f} s).",
        tables=[
            Table(
                caption="Contour points",
                columns=["H_s [m]", "T_p [s]", "seeds", "mean Y [m]", "fractile Y [m]"],
                rows=drows,
                digits=4,
            )
        ],
        figures=[FigureRef(figures["design"], "Maximum displacement along the contour.")]
        if "design" in figures
        else [],
    )


def _reliability_target(t: dict[str, Any]) -> SectionContent:
    """The annual probability per limit against the DNV-OS-F101 target."""
    return SectionContent(
        summary=f"Annual probability per limit against the target"
        f" {t['annual_target']:.0e} per year of the {t['safety_class']} safety class"
        f" ({t['source']}): pass when the 95 % interval's upper end lies below it,"
        " fail when its lower end lies above it, undecided otherwise.",
        tables=[
            Table(
                caption="Annual probability against the target",
                columns=["limit", "P per year", "95 % upper", "verdict"],
                rows=[[r["label"], r["annual"], r["upper"], r["verdict"]] for r in t["limits"]],
                digits=3,
            )
        ],
    )


def _reliability_assumptions(payload: dict[str, Any]) -> SectionContent:
    """The campaign's counts, and the assumptions and limits of the estimate."""
    c = payload["campaign"]
    return SectionContent(
        summary=f"Campaign: {c['requested']} storms asked for, {c['computed']} run,"
        f" {c['reused']} read back from the store, {c['failed']} failed;"
        f" {c['seconds_per_storm']:.3g} s per storm (compute time)."
        if c["computed"]
        else f"Campaign: {c['requested']} storms asked for, all read back from the store.",
        notes=[
            "Storms arrive as a Poisson process; a year fails when any of its storms does.",
            "The storm seed is an input like the others (S ~ U(0, 1)); subset simulation's CV"
            " includes the chains' correlation but not the levels' (a lower bound).",
            "Lifetime assumptions: the soil (μ, γ') is drawn anew for every storm, not once per"
            " route; the metocean fit's own uncertainty is not carried into the lifetime; the"
            " storm peak lasts the case's peak_hours (F109's design storm is 3 h); the current"
            " is drawn for the storm, not as the maximum over its window; one omnidirectional"
            " severity for every sector.",
            "Numerical failures of a storm run count as exceedances (conservative).",
            "Only the storm peak's sea state is drawn; the build-up and decay follow the"
            " case's storm shape.",
            "The current, when drawn from the hindcast, is at the case's reference height and"
            " (with sectors) goes with the waves.",
            *payload.get("notes", []),
        ],
        sources=["docs/theory/reliability.md", "Au & Beck (2001)", "Melchers & Beck (2018)"],
    )


def _reliability_provenance(payload: dict[str, Any], case: Path) -> dict[str, Any]:
    """Provenance rows: the case, its hash, the output folder, the package versions."""
    return {
        "case": str(case),
        "case SHA-256": _sha256(case),
        "output": payload["out"],
        "packages": f"openturns {_version('openturns')}, zarr {_version('zarr')},"
        f" dask {_version('dask')}, virocon {_version('virocon')},"
        f" pyextremes {_version('pyextremes')}",
    }
