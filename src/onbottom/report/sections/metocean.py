"""Report section: metocean statistics of the shipped synthetic hindcast.

``examples/hindcast_synthetic.csv`` (25 years, 3-hourly, drawn from known distributions by
``tools/make_synthetic_hindcast.py``) is analysed as ``onbottom metocean`` does: storms per
direction sector, POT/GPD return values with 95 % profile-likelihood intervals (pyextremes),
the DNV-RP-C205 H_s–T_p model and IFORM contours (virocon), the F109 design table.

Checks fixed before the run: the omnidirectional 1-, 10- and 100-year H_s intervals contain the
storm-based levels of the generating model from a 2000-year draw
(:data:`~onbottom.metocean.synthetic.STORM_LEVELS_2000Y`); the fitted Weibull parameters of
H_s lie within 5 % of the generating ones.
"""

from __future__ import annotations

from onbottom.report.content import Check, SectionContent, SectionContext, Table, within
from onbottom.report.registry import section

REQUIRES = ("onbottom.metocean", "pyextremes", "virocon")
EXAMPLE = "examples/hindcast_synthetic.csv"
WEIBULL_RTOL = 0.05
"""Tolerance of the fitted Weibull parameters against the generating ones [-]."""


@section(
    "metocean",
    "Metocean statistics: return values and contours of a hindcast",
    order=85,
    slow=True,
    requires=REQUIRES,
)
def build(ctx: SectionContext) -> SectionContent:
    """Analyse the synthetic hindcast; compare with the generating model."""
    from onbottom.metocean.analysis import MetoceanOptions, analyse_hindcast
    from onbottom.metocean.hindcast import read_hindcast
    from onbottom.metocean.synthetic import EXAMPLE_MODEL, STORM_LEVELS_2000Y
    from onbottom.metocean.table import design_rows

    path = None if ctx.repo_root is None else ctx.repo_root / EXAMPLE
    if path is None or not path.is_file():
        return SectionContent(
            summary=f"{EXAMPLE} is not in this build (the report runs outside the repository).",
            checks=[
                Check(
                    name="example hindcast",
                    value="absent",
                    reference=None,
                    tolerance="—",
                    status="info",
                )
            ],
        )
    result = analyse_hindcast(read_hindcast(path), MetoceanOptions(sectors=8))
    omni = result.hs["omni"]
    checks = []
    for i, rp in enumerate(omni.return_periods):
        ref = STORM_LEVELS_2000Y[float(rp)]
        lo, hi = float(omni.lower[i]), float(omni.upper[i])
        checks.append(
            Check(
                name=f"{rp:g}-year H_s (omni) against the generating model",
                value=f"{omni.value[i]:.2f} [{lo:.2f}, {hi:.2f}]",
                reference=ref,
                tolerance="inside the 95 % interval",
                status="pass" if lo <= ref <= hi else "fail",
                unit="m",
                note="reference: storm-based level of a 2000-year draw of the same model",
            )
        )
    j, m = result.joint, EXAMPLE_MODEL
    for name, got, ref in (
        ("Weibull α of H_s", j.hs_scale, m.hs_scale),
        ("Weibull β of H_s", j.hs_shape, m.hs_shape),
        ("Weibull γ of H_s", j.hs_location, m.hs_location),
    ):
        checks.append(within(name, got, ref, rtol=WEIBULL_RTOL, note="virocon fit (moments)"))
    rows = design_rows(result)
    rps = list(omni.return_periods)
    cols = ["sector"]
    for rp in rps:
        cols += [f"H_s {rp:g} y [m]", f"T_p {rp:g} y [s]"]
    cols += [f"current {rp:g} y [m/s]" for rp in rps]
    table = Table(
        caption="Design values per sector (waves from; current coming from); T_p is the median"
        " of T_p | H_s of the joint model",
        columns=cols,
        rows=[
            [r.sector]
            + [v for i in range(len(rps)) for v in (r.hs[i], r.tp[i])]
            + list(r.current or [None] * len(rps))
            for r in rows
        ],
        digits=3,
    )
    from onbottom.plotting.metocean import plot_contours, plot_return_levels

    figures = [
        ctx.save_figure(
            plot_return_levels(result, title=path.name),
            "return_levels",
            "Return values of H_s and current: GPD fits per sector, storm peaks, 95 % intervals.",
            dpi=80,
        ),
        ctx.save_figure(
            plot_contours(result),
            "contours",
            "Sea states of the record and the 1-, 10-, 100-year IFORM contours.",
            dpi=80,
        ),
    ]
    return SectionContent(
        summary="The shipped synthetic hindcast (25 years, 3-hourly, known distributions)"
        " analysed as `onbottom metocean` does: declustered storms per sector, POT/GPD return"
        " values with profile-likelihood intervals, the DNV-RP-C205 joint model and IFORM"
        " contours, the F109 design table.",
        checks=checks,
        tables=[table],
        figures=figures,
        notes=["Methods, verification and limits: docs/theory/metocean.md."],
        sources=[
            "Coles (2001), An Introduction to Statistical Modeling of Extreme Values, §4.3",
            "DNV-RP-C205 (2019) §3.6.3; Haver & Winterstein (2009)",
        ],
    )
