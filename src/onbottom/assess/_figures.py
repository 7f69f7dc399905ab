"""Figures of the ``onbottom assess`` design report, each drawn from the results and the models
that ran: inline SVG strip plots and histories, PNG data URIs (the report stays one file), and
the V–H diagram of a section (:func:`vh_part`) from the force model and soil model the route
built from its case.

A figure that cannot be drawn is never dropped in silence: :func:`figure_part` turns the error
into a visible note on the page (:func:`not_drawn`: the figure, the error class and message).
"""

from __future__ import annotations

import html
import math
from collections.abc import Callable
from typing import Any

__all__ = ["figure_part", "history_svg", "not_drawn", "png", "strip_svg", "vh_part"]

NOT_DRAWN_CLASS = "fail figure-not-drawn"
"""CSS classes of the note that stands where a figure could not be drawn."""


def not_drawn(what: str, exc: BaseException) -> dict[str, Any]:
    """The page part standing for figure ``what`` that raised ``exc``: its class and message."""
    return {"kind": "p", "c": NOT_DRAWN_CLASS,
            "text": f"{what} not drawn: {type(exc).__name__}: {exc}"}  # fmt: skip


def figure_part(
    what: str, draw: Callable[[], str], caption: str | Callable[[], str]
) -> dict[str, Any] | None:
    """A figure of the page: ``draw()`` gives its HTML (empty: nothing to draw, no part);
    ``caption`` its text (or a function of what ``draw`` found). An error while drawing is the
    note of :func:`not_drawn` in the figure's place."""
    try:
        body = draw()
        if not body:
            return None
        text = caption() if callable(caption) else caption
    except Exception as exc:  # shown on the page, never swallowed
        return not_drawn(what, exc)
    return {"kind": "figure", "html": body, "caption": text}


def strip_svg(base: dict[str, Any]) -> str:
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


def history_svg(name: str, h: dict[str, Any], allowable: float) -> str:
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
def png(fig: Any, alt: str) -> str:
    import base64
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=160)
    data = base64.b64encode(buf.getvalue()).decode("ascii")
    width = int(fig.get_figwidth() * 80)  # drawn at 160 dpi, shown at 80 px per inch
    return f"<img alt='{html.escape(alt)}' width='{width}' src='data:image/png;base64,{data}'>"


# ---- the V–H diagram ----------------------------------------------------------------------------
VH_TOP = 3
"""Combinations drawn in a V–H diagram: those with the highest absolute lateral utilisation."""


def _vh_rows(s: dict[str, Any]) -> list[dict[str, Any]]:
    """The absolute lateral check rows of the section with a design load, highest first."""
    seas = {ss["combination"] for ss in s["sea_states"]}
    rows = [
        c for c in s["checks"]
        if c["name"] == "absolute_lateral" and "f_y" in (c.get("details") or {})
        and c["combination"] in seas and c.get("utilisation") is not None
    ]  # fmt: skip
    return sorted(rows, key=lambda c: -c["utilisation"])[:VH_TOP]


def _storm_envelope(setup: Any) -> tuple[Any, dict[str, Any]]:
    """Cycle peaks of the storm setup's force model on the fixed pipe (at the given design)
    through the setup's storm, reduced by r_y, r_z of its soil model's as-laid penetration;
    and what was used (for the caption)."""
    from onbottom.hydro.fixed_pipe import fixed_pipe_envelope
    from onbottom.hydro.reductions import penetration_reduction
    from onbottom.hydro.storm_kinematics import StormKinematics, storm_kinematics
    from onbottom.soil.base import S_Z

    pipe, fm, red = setup.pipe, setup.force_model, setup.reductions
    d = pipe.outer_diameter
    storm = setup.storm
    if isinstance(storm, StormKinematics):
        kin, hs, tp = storm, math.nan, math.nan
    else:
        kin = storm_kinematics(storm, setup.depth, diameter=d, current=setup.current,
                               z0=setup.z0, sample_interval=setup.sample_interval)  # fmt: skip
        peak = max(storm.stages, key=lambda st: st.hs)
        hs, tp = peak.hs, peak.tp
    ry, rz = red.constant_factors()
    z = float(setup.soil.initial_state()[S_Z])
    if red.penetration:
        py, pz = penetration_reduction(z / d)
        ry, rz = ry * float(py), rz * float(pz)
    env = fixed_pipe_envelope(fm, kin, diameter=d, submerged_weight=pipe.submerged_weight,
                              density=pipe.seawater_density, r_y=ry, r_z=rz, hs=hs,
                              tp=tp)  # fmt: skip
    used = {"force": fm.name, "soil": setup.soil.name, "seed": int(kin.seed),
            "duration": float(kin.duration), "r_y": ry, "r_z": rz, "z": z}  # fmt: skip
    return env, used


def vh_figure(s: dict[str, Any], section: Any) -> tuple[str, str]:
    """V–H diagram of a section at the given design, and its caption ("": nothing to draw).

    For the three combinations with the highest absolute utilisation: the peak load of every
    wave cycle of the dynamic level's storm of that combination on a fixed pipe, from the force
    model the route built (``section.storms[k].setup.force_model``: the registered model of
    ``[hydro] model`` with its options) and the load reductions at its soil model's as-laid
    penetration; F109's design load point (w_s − F*_Z, F*_Y) of the absolute check; the soil's
    resistance envelope H = μV + F_R of that check (Eq 3.38 without γ_SC). Drawn by
    :func:`onbottom.plotting.load_envelope.plot_load_envelope`.
    """
    rows = _vh_rows(s)
    if not rows:
        return "", ""
    storms = {st.name: st for st in section.storms}
    missing = [c["combination"] for c in rows if c["combination"] not in storms]
    if missing:
        raise LookupError(f"no storm of the dynamic level for combination(s) {missing!r}")
    from onbottom.plotting.load_envelope import plot_load_envelope

    envs, labels, used = [], [], []
    for c in rows:
        env, u = _storm_envelope(storms[c["combination"]].setup)
        envs.append(env)
        used.append(u)
        labels.append(str(c["combination"])[:28])
    fig = plot_load_envelope(envs, labels, title=f"{s['name']}: V–H at the given design")
    _vh_resistance(fig.axes[0], rows)
    fig.set_size_inches(9.5, 5.0)
    fig.axes[0].legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize="x-small")
    return png(fig, f"V–H diagram of {s['name']}"), _vh_caption(used)


def _vh_resistance(ax: Any, rows: list[dict[str, Any]]) -> None:
    """F109's design load points and the resistance lines H = μV + F_R of the checks."""
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


def _vh_caption(used: list[dict[str, Any]]) -> str:
    """What the V–H diagram was computed with: force model, soil model, storm, reductions."""
    forces = sorted({u["force"] for u in used})
    soils = sorted({u["soil"] for u in used})
    seeds = sorted({u["seed"] for u in used})
    red = "; ".join(dict.fromkeys(f"r_y {u['r_y']:.3g}, r_z {u['r_z']:.3g}" for u in used))
    return (
        "V–H diagram at the given design: the peak load of every wave cycle of the dynamic"
        f" level's storm ({used[0]['duration'] / 3600.0:.3g} h, seed"
        f" {', '.join(map(str, seeds))}) on a fixed pipe, force model"
        f" {', '.join(forces)} (as built from the case's [hydro]), times the F109 load"
        f" reductions at the as-laid penetration of the {', '.join(soils)} soil model ({red});"
        " V = w_s − F_Z, H = |F_Y|; crosses: the absolute check's design load; lines: the"
        " soil's resistance H = μV + F_R of the absolute check, without γ_SC. "
    )


def vh_part(s: dict[str, Any], section: Any, force_model: str, clause: str) -> dict | None:
    """The V–H diagram of :func:`vh_figure` as a page part (``clause`` ends the caption), or
    the note that says why it is not drawn (an error while drawing; no storm built, the
    dynamic level off: the route's ``force_model`` named)."""
    if _vh_rows(s) and not section.storms:
        return {"kind": "p", "c": "muted", "text": (
            "V–H diagram not drawn: the dynamic level did not run, so the route built no storm"
            f" to load the pipe with its force model ({force_model!r} of [hydro]); the cycle"
            " loads are drawn only from the model the route runs.")}  # fmt: skip
    found: dict[str, str] = {}

    def draw() -> str:
        body, found["caption"] = vh_figure(s, section)
        return body

    return figure_part("V–H diagram", draw, lambda: found["caption"] + clause)
