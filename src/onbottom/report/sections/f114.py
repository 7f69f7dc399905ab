"""Report section: DNVGL-RP-F114 drained penetration against the reference table and the tests.

Two comparisons:

1. Q_v of F114 Eq 4.9 (:class:`onbottom.soil.penetration_sand.DrainedPenetration`) against the
   reference table of an independent implementation (groundhog, rounded to 0.1 kN/m):
   D = 0.5 m, γ' = 15.9 / 16.7 kN/m³, φ' = 33° / 40°, four
   N_γ expressions, z/D = 0.1–0.5. Tolerance ±1 % or ±0.06 kN/m (the rounding), the same as
   ``tests/unit/test_penetration_f114.py``.
2. The centrifuge resistances the penetration paper reports (``onbottom.dem.published``; SM
   and SD specimens, read from its text, "about") against the F114 range spanned by the lower
   estimate (φ' = 33° = φ_c, Davis & Booker smooth N_γ) and the upper estimate (φ' = 40°,
   Davis & Booker rough N_γ): each measured value must lie inside the range. The range is the
   project's choice (docs/theory/dnv_rp_f114.md); F114's own bound definition was not available.
"""

from __future__ import annotations

import numpy as np

from onbottom.report.content import Check, SectionContent, SectionContext, Table, within
from onbottom.report.registry import section

D = 0.5
"""Pipe diameter of the reference case [m] (penetration paper, prototype)."""

LEVELS = (0.1, 0.2, 0.3, 0.4, 0.5)
"""Penetrations z/D [-] of the reference table."""

REFERENCE_TABLE: tuple[tuple[float, float, str, tuple[float, ...]], ...] = (
    (16.7, 33, "davis_booker_smooth", (10.6, 18.8, 25.0, 33.1, 43.5)),
    (16.7, 33, "brinch_hansen", (18.4, 32.7, 43.2, 53.9, 65.1)),
    (16.7, 33, "davis_booker_rough", (20.0, 35.5, 46.9, 58.1, 69.5)),
    (16.7, 33, "vesic", (26.4, 47.0, 62.1, 75.4, 87.6)),
    (16.7, 40, "davis_booker_smooth", (32.9, 58.5, 76.8, 96.3, 121.5)),
    (16.7, 40, "brinch_hansen", (59.8, 106.3, 139.6, 168.0, 196.2)),
    (16.7, 40, "davis_booker_rough", (64.5, 114.6, 150.5, 180.5, 209.2)),
    (16.7, 40, "vesic", (82.2, 146.2, 191.9, 227.8, 258.5)),
    (15.9, 33, "davis_booker_rough", (19.0, 33.8, 44.7, 55.3, 66.2)),
    (15.9, 40, "vesic", (78.3, 139.2, 182.7, 216.9, 246.1)),
)
"""γ' [kN/m³], φ' [deg], N_γ expression, Q_v [kN/m] at :data:`LEVELS` (DNVGL-RP-F114 (2017) Eq 4.9,
groundhog's implementation)."""

SPECIMEN_GAMMA_KN = {"SM": 15.9, "SD": 16.7}
"""Dry unit weight of the paper's specimens [kN/m³] (estimated from the paper's relative
densities D_r)."""

_RTOL, _ATOL = 0.01, 0.06
_SHALLOW_NOTE = (
    ". Documented: at shallow embedment the tests are stiffer than bearing-capacity theory"
    " (75 kN/m at 0.1D needs φ' ≈ 40–41° with rough N_γ; docs/theory/dnv_rp_f114.md)"
)


@section("f114", "DNVGL-RP-F114 vertical penetration (drained sand)", order=10)
def build(ctx: SectionContext) -> SectionContent:
    """Compare F114 Eq 4.9 with the reference table and the paper's centrifuge values."""
    import matplotlib.pyplot as plt

    from onbottom.dem.published import PUBLISHED
    from onbottom.soil.penetration_sand import DrainedBounds, DrainedPenetration

    z = np.asarray(LEVELS) * D
    checks: list[Check] = []
    rows = []
    for gamma_kn, phi, method, expected in REFERENCE_TABLE:
        model = DrainedPenetration(
            diameter=D, unit_weight=gamma_kn * 1e3, friction_angle_deg=phi, n_gamma=method
        )
        q = model.resistance(z) / 1e3
        rows.append([f"{gamma_kn:g} / {phi:g}° / {method}", model.n_gamma_value, *q])
        for lev, qi, ref in zip(LEVELS, q, expected, strict=True):
            checks.append(
                within(
                    f"Q_v at {lev:g}D, γ' {gamma_kn:g}, φ' {phi:g}°, {method}",
                    float(qi),
                    ref,
                    rtol=_RTOL,
                    atol=_ATOL,
                    unit="kN/m",
                    tolerance="±1 % or ±0.06 kN/m",
                    note="F114 Eq 4.9 (groundhog)",
                )
            )

    # the paper's centrifuge values against the lower/upper F114 range
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    zz = np.linspace(0.0, 0.5, 51) * D
    for name, case in PUBLISHED.items():
        gamma = SPECIMEN_GAMMA_KN[name] * 1e3
        bounds = DrainedBounds.from_friction_angles(
            diameter=D,
            unit_weight=gamma,
            lower_friction_angle_deg=33.0,
            upper_friction_angle_deg=40.0,
        )
        lo, up = bounds.resistance(zz)
        color = "C0" if name == "SM" else "C3"
        ax.fill_betweenx(zz / D, lo / 1e3, up / 1e3, color=color, alpha=0.12, lw=0)
        ax.plot(lo / 1e3, zz / D, color=color, ls="--", lw=1, label=f"{name}: F114 lower (33°)")
        ax.plot(up / 1e3, zz / D, color=color, ls=":", lw=1.2, label=f"{name}: F114 upper (40°)")
        wd = np.array(sorted(case.resistance))
        v = np.array([case.resistance[k] for k in wd]) / 1e3
        ax.plot(v, wd, "o", color=color, label=f"{name}: centrifuge (paper)")
        lo_p, up_p = bounds.resistance(wd * D)
        for r, vi, a, b in zip(wd, v, lo_p / 1e3, up_p / 1e3, strict=True):
            inside = a <= vi <= b
            checks.append(
                Check(
                    name=f"{name} centrifuge V at {r:g}D inside F114 range",
                    value=f"{a:.1f} – {b:.1f}",
                    reference=float(vi),
                    tolerance="lower ≤ test ≤ upper",
                    status="pass" if inside else "fail",
                    unit="kN/m",
                    note=(
                        f"γ_d {SPECIMEN_GAMMA_KN[name]:g} kN/m³; paper values are 'about'"
                        + ("" if inside else _SHALLOW_NOTE)
                    ),
                )
            )
    ax.invert_yaxis()
    ax.set_xlabel("vertical resistance Q_v [kN/m]")
    ax.set_ylabel("penetration z/D [-]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2)
    ax.set_title("F114 Eq 4.9 range and the penetration paper's centrifuge tests (D = 0.5 m)")
    fig_ref = ctx.save_figure(
        fig,
        "range_vs_centrifuge",
        "F114 drained penetration, lower estimate (φ' = 33°, Davis & Booker smooth N_γ) to upper"
        " estimate (φ' = 40°, rough N_γ), with the centrifuge resistances the paper reports.",
    )
    table = Table(
        caption="Q_v [kN/m] computed by onbottom for the reference cases (D = 0.5 m)",
        columns=["γ' [kN/m³] / φ' / N_γ", "N_γ [-]", *[f"{lev:g}D" for lev in LEVELS]],
        rows=rows,
        digits=1,
    )
    return SectionContent(
        summary=(
            "F114 Eq 4.9 (drained sand, plane strain, depth factor 1.2) evaluated for the"
            " penetration paper's pipe (D = 0.5 m) and compared, value by value, with an"
            " independent implementation; then the paper's centrifuge resistances are placed"
            " in the range between the lower and upper estimates."
        ),
        checks=checks,
        tables=[table],
        figures=[fig_ref],
        notes=[
            "The lower/upper definition (φ_c with smooth N_γ, peak φ' with rough N_γ) is the"
            " project's choice; the standard's own definition was not available"
            " (docs/theory/dnv_rp_f114.md).",
            "The specimens' dry unit weights are estimates from the relative densities the"
            " paper quotes (its §4.1); the tests were run dry, so γ' = γ_d.",
        ],
        sources=[
            "DNVGL-RP-F114 (2017) Eq 4.9; reference values from groundhog's implementation",
            "penetration paper (centrifuge 25 g + DEM), §4.2, via onbottom.dem.published",
        ],
    )
