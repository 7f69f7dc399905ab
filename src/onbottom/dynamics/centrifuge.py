"""Presets of the seven Youssef (2012) centrifuge tests (Youssef & Cassidy 2014, ISOPE).

Data from Youssef & Cassidy (2014), "Calibration of Verley and Sotberg soil resistance model
for pipelines placed on calcareous soils", ISOPE 2014, pp. 141–148: Table 1 (V_peak, V_i,
displacement limit, load cycles used), Table 2 (A, B, C, μ per test), Table 3 (recommended
A, B, C) and the loading protocol of Figs 5–8. All values are prototype scale at 50 g:
D = 1.0 m, loads per metre of pipe.

Assumptions (where the paper is silent; docs/validation/youssef_cassidy_2014.md discusses
each and the reproduction reports the sensitivity):

1. **Inclination α of tests 4 and 5.** Tests 1–3 use α = 30° (paper, Fig. 6). For tests 4
   and 5 we infer α by limit equilibrium with the paper's own calibrated μ
   (:func:`alpha_range_from_limit_equilibrium`): the friction-only sliding load
   H_f = μV_i/(1 + μ/tan α) must not exceed the amplitude of the last load cycle
   (n_last·ΔH) and the passive part (at most ~0.5 kN/m for A ≤ 0.45) must make up the rest.
   Test 4 (μ = 0.75, cycle 15, 3.75 kN/m): α ∈ (25.6°, 31.5°] → **α = 30°**, the angle of
   tests 1–3. Test 5 (μ = 0.85, cycle 30, 7.5 kN/m; the ±8 kN/m H axis of Fig. 15 confirms
   the large loads): α ∈ (63.6°, 69.0°] → **α = 65°**. This lies outside the 20°–45°
   hydrodynamic envelope of the paper's Fig. 4, so test 5 is flagged as inferred with low
   confidence.
2. **Submerged unit weight γ'** (not given in the paper): one value for all tests,
   γ' = 7.5 kN/m³ (:data:`SUBMERGED_UNIT_WEIGHT`), from γ' = (G_s − 1)γ_w/(1 + e) with
   G_s ≈ 2.75 for carbonate sand and e ≈ 1.3, the middle of the void ratios 1.12–1.48 the
   paper quotes (Airey et al. 1988). Range for e = 1.12–1.48: 6.9–8.1 kN/m³.
3. **Cycle shape**: sine (+peak at ¼, −peak at ¾ of a cycle). The fractions in Table 1
   (.27, .75, .25, .29, .25) all sit at or just after a load peak, which a sine (or a
   triangle, offered as an option) reproduces.
4. **Time**: the paper's cycle durations (40 s inclined, 60 s regular group, 50 s irregular
   group) are used directly as the time axis (``time_basis="paper"``). They are probably
   model time at 50 g; ``time_basis="prototype"`` multiplies them by N = 50 (dynamic time
   scaling). The cycles to the limit change by up to −2.3 (Regular −2.03, Irregular −2.29,
   Inclined 3 −1.10, Inclined 4 +0.93; docs/validation/bands/centrifuge_bands.md), and the
   distance run past the limit grows without bound (no stop within the half cycle).
5. **Mass**: m = pipe mass (from W_s = V_i and the buoyancy of a 1 m pipe, 1 878 kg/m for
   Inclined 1) + added mass C_a = 2.29 (cylinder on a wall), :func:`section_mass`.
6. **Regular/irregular loads**: shapes from the Morison model of :mod:`onbottom.hydro`,
   scaled to the first-cycle peaks read from Figs 7–8 (:mod:`onbottom.dynamics.programmes`);
   one "cycle" of Table 1 is one group (60 s / 50 s), not a regular sub-cycle.
7. **Table 3 runs**: A, B, C from Table 3 with each test's Table 2 μ (the paper leaves μ to
   the site's geotechnical report; the per-test μ is our "site" value).
"""

from __future__ import annotations

import functools
import math
import re
from dataclasses import dataclass
from typing import Any

from onbottom._validate import in_range, one_of, positive
from onbottom.dynamics.programmes import (
    LoadProgramme,
    inclined_cyclic,
    irregular_wave_current_groups,
    regular_wave_current_groups,
)
from onbottom.dynamics.section import SectionResult, SolverSettings, section_mass
from onbottom.dynamics.section_run import SectionRun
from onbottom.errors import InputError
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.soil.base import LateralResistanceModel
from onbottom.soil.coulomb import CoulombFriction

__all__ = [
    "ADDED_MASS_COEFFICIENT",
    "AMPLITUDE_STEP",
    "G_LEVEL",
    "PIPE_DIAMETER",
    "RECOMMENDED",
    "SUBMERGED_UNIT_WEIGHT",
    "TESTS",
    "CentrifugeTest",
    "ParameterSet",
    "alpha_range_from_limit_equilibrium",
    "build_pipe",
    "build_programme",
    "build_soil",
    "centrifuge_run",
    "get_test",
    "run_centrifuge_test",
]

G_LEVEL: float = 50.0
"""Centrifuge acceleration N [g] (paper: 50 g)."""

PIPE_DIAMETER: float = 1.0
"""Prototype pipe diameter D [m] (model 20 mm at 50 g)."""

SUBMERGED_UNIT_WEIGHT: float = 7.5e3
"""Submerged unit weight γ' of the calcareous sand used for every test [N/m³] (assumption 2)."""

ADDED_MASS_COEFFICIENT: float = 2.29
"""C_a [-] of the added mass (π²/3 − 1, cylinder on a plane wall)."""

AMPLITUDE_STEP: float = 0.25e3
"""Increase of the H amplitude per inclined load cycle [N/m] (paper: 0.25 kN/m)."""

INCLINED_PERIOD: float = 40.0
"""Duration of one inclined load cycle [s] (paper)."""


@dataclass(frozen=True, kw_only=True, slots=True)
class ParameterSet:
    """Calcareous Verley & Sotberg factors A, B, C [-] and friction μ [-] (None = per test)."""

    A: float
    B: float
    C: float
    mu: float | None = None


@dataclass(frozen=True, kw_only=True, slots=True)
class CentrifugeTest:
    """One of the seven tests.

    Attributes
    ----------
    name : str
        "Inclined 1" … "Inclined 5", "Regular", "Irregular".
    kind : str
        "inclined", "regular" or "irregular".
    installation_load : float
        V_peak [N/m] (Table 1).
    vertical_load : float
        V_i [N/m] (Table 1).
    displacement_limit : float
        Largest horizontal displacement of the box [m] (Table 1).
    cycles_used : float
        Load cycles to reach the limit in the test (Table 1).
    table2 : ParameterSet
        Calibrated A, B, C, μ (Table 2).
    period : float
        Cycle (group) duration on the paper's time axis [s].
    alpha_deg : float or None
        Load-path inclination to the V axis [deg] (inclined tests).
    alpha_source : str
        "paper" or "inferred" (see the module docstring).
    """

    name: str
    kind: str
    installation_load: float
    vertical_load: float
    displacement_limit: float
    cycles_used: float
    table2: ParameterSet
    period: float
    alpha_deg: float | None = None
    alpha_source: str = ""


_KN = 1.0e3


def _inclined(name, vp, vi, lim, cyc, a, b, c, mu, alpha, src) -> CentrifugeTest:
    return CentrifugeTest(
        name=name,
        kind="inclined",
        installation_load=vp * _KN,
        vertical_load=vi * _KN,
        displacement_limit=lim,
        cycles_used=cyc,
        table2=ParameterSet(A=a, B=b, C=c, mu=mu),
        period=INCLINED_PERIOD,
        alpha_deg=alpha,
        alpha_source=src,
    )


TESTS: dict[str, CentrifugeTest] = {
    t.name: t
    for t in (
        _inclined("Inclined 1", 42.98, 10.52, 3.0, 13.27, 0.25, 0.35, 0.79, 0.48, 30.0, "paper"),
        _inclined("Inclined 2", 23.30, 9.60, 2.0, 13.75, 0.25, 0.45, 1.05, 0.60, 30.0, "paper"),
        _inclined("Inclined 3", 27.11, 10.34, 5.0, 16.25, 0.25, 0.45, 1.18, 0.65, 30.0, "paper"),
        _inclined("Inclined 4", 33.92, 11.12, 2.5, 14.29, 0.45, 0.35, 0.96, 0.75, 30.0, "inferred"),
        _inclined("Inclined 5", 35.43, 11.71, 2.5, 29.25, 0.25, 0.35, 0.84, 0.85, 65.0, "inferred"),
        CentrifugeTest(
            name="Regular",
            kind="regular",
            installation_load=35.05 * _KN,
            vertical_load=11.20 * _KN,
            displacement_limit=3.0,
            cycles_used=46.22,
            table2=ParameterSet(A=0.25, B=0.28, C=0.97, mu=0.85),
            period=60.0,
        ),
        CentrifugeTest(
            name="Irregular",
            kind="irregular",
            installation_load=34.57 * _KN,
            vertical_load=11.46 * _KN,
            displacement_limit=3.0,
            cycles_used=31.25,
            table2=ParameterSet(A=0.25, B=0.24, C=1.12, mu=0.85),
            period=50.0,
        ),
    )
}
"""The seven tests by name (Table 1 and Table 2 of the paper)."""

RECOMMENDED = ParameterSet(A=0.25, B=0.35, C=0.98, mu=None)
"""Table 3 recommended calcareous factors (μ from the site: here each test's Table 2 μ)."""


def get_test(name: str) -> CentrifugeTest:
    """Look a test up by name, tolerant of case, spaces, dashes ("inclined-1", "Inclined1")."""
    key = re.sub(r"[\s_\-]+", "", str(name)).lower()
    for t in TESTS.values():
        if t.name.replace(" ", "").lower() == key:
            return t
    raise InputError(f"test = {name!r} is invalid: must be one of {', '.join(map(repr, TESTS))}")


def alpha_range_from_limit_equilibrium(
    friction_coefficient: float,
    vertical_load: float,
    last_amplitude: float,
    max_passive: float = 0.5e3,
) -> tuple[float, float]:
    """Range of α [deg] consistent with failure in the cycle of amplitude ``last_amplitude``.

    Friction-only sliding on the inclined path needs H = μ(V_i − H/tan α), i.e.
    H_f = μV_i/(1 + μ/tan α). Failure in the last cycle requires H_f <= last_amplitude
    (upper bound on α) and H_f + F_r,max > last_amplitude (lower bound), with F_r,max the
    largest passive resistance the model can add.

    Parameters
    ----------
    friction_coefficient : float
        μ [-], > 0.
    vertical_load : float
        V_i [N/m], > 0.
    last_amplitude : float
        H amplitude of the cycle in which the limit was reached [N/m], > 0.
    max_passive : float
        Largest passive resistance [N/m], >= 0.

    Returns
    -------
    (alpha_min_deg, alpha_max_deg) : tuple of float
        NaN bounds where no α in (0°, 90°] satisfies the condition.
    """
    mu = positive("friction_coefficient", friction_coefficient)
    vi = positive("vertical_load", vertical_load)
    h = positive("last_amplitude", last_amplitude)

    def alpha_for(hf: float) -> float:
        # μ V_i /(1 + μ/tanα) = hf → tanα = μ / (μ V_i / hf − 1)
        den = mu * vi / hf - 1.0
        if den <= 0.0:
            return 90.0
        return math.degrees(math.atan(mu / den))

    hi = alpha_for(h)
    lo_h = h - max_passive
    lo = alpha_for(lo_h) if lo_h > 0.0 else 0.0
    return lo, hi


def build_pipe(test: CentrifugeTest) -> Pipe:
    """Prototype pipe: D = 1 m, W_s = V_i (mass from W_s and buoyancy, :class:`Pipe`)."""
    return Pipe(outer_diameter=PIPE_DIAMETER, submerged_weight=test.vertical_load)


def _n_cycles(test: CentrifugeTest, alpha_deg: float | None) -> int:
    n = math.ceil(2.0 * test.cycles_used) + 5
    if test.kind == "inclined" and alpha_deg is not None and alpha_deg < 90.0:
        # cycles until the load path reaches V = 0 (lift-off), plus two
        lift_off = test.vertical_load * math.tan(math.radians(alpha_deg)) / AMPLITUDE_STEP
        n = min(n, math.ceil(lift_off) + 2)
    elif test.kind != "inclined":
        n = math.ceil(test.cycles_used) + 5
    return max(n, math.ceil(test.cycles_used) + 2)


@functools.lru_cache(maxsize=64)
def _programme_cached(
    name: str,
    n_cycles: int | None,
    time_basis: str,
    shape: str,
    alpha_deg: float | None,
    points_per_cycle: int,
) -> LoadProgramme:
    test = TESTS[name]
    factor = G_LEVEL if time_basis == "prototype" else 1.0
    alpha = test.alpha_deg if alpha_deg is None else alpha_deg
    n = _n_cycles(test, alpha) if n_cycles is None else n_cycles
    label = test.name
    if test.kind == "inclined":
        return inclined_cyclic(
            test.vertical_load,
            AMPLITUDE_STEP,
            test.period * factor,
            alpha,
            n,
            shape=shape,
            points_per_cycle=points_per_cycle,
            installation_load=test.installation_load,
            name=label,
        )
    if test.kind == "regular":
        return regular_wave_current_groups(
            test.vertical_load,
            n,
            group_period=test.period * factor,
            installation_load=test.installation_load,
            points_per_sub_cycle=max(16, points_per_cycle // 2),
            name=label,
        )
    return irregular_wave_current_groups(
        test.vertical_load,
        n,
        group_period=test.period * factor,
        installation_load=test.installation_load,
        points_per_group=max(64, 5 * points_per_cycle),
        name=label,
    )


def build_programme(
    test: CentrifugeTest | str,
    *,
    n_cycles: int | None = None,
    time_basis: str = "paper",
    shape: str = "sine",
    alpha_deg: float | None = None,
    points_per_cycle: int = 200,
) -> LoadProgramme:
    """Load programme of a test (cached: the same arguments return the same object).

    Parameters
    ----------
    test : CentrifugeTest or str
        The test or its name.
    n_cycles : int or None
        Cycles (groups); None → enough to pass the paper's count (inclined tests: up to
        two cycles past lift-off of the load path).
    time_basis : {"paper", "prototype"}
        Paper durations used as they are, or multiplied by N = 50 (assumption 4).
    shape : {"sine", "triangle"}
        Inclined cycle shape (assumption 3).
    alpha_deg : float or None
        Override of the load-path inclination [deg] (inclined tests).
    points_per_cycle : int
        Samples per inclined cycle (regular: half of it per sub-cycle; irregular: five times
        it per group); sets the largest time step.
    """
    t = get_test(test) if isinstance(test, str) else test
    one_of("time_basis", time_basis, ("paper", "prototype"))
    if alpha_deg is not None:
        in_range("alpha_deg", alpha_deg, 0.0, 90.0, low_inclusive=False)
    return _programme_cached(
        t.name,
        None if n_cycles is None else int(n_cycles),
        time_basis,
        shape,
        None if alpha_deg is None else float(alpha_deg),
        int(points_per_cycle),
    )


def build_soil(
    test: CentrifugeTest | str,
    *,
    parameters: str = "table2",
    A: float | None = None,
    B: float | None = None,
    C: float | None = None,
    mu: float | None = None,
    gamma: float | None = None,
    model: str = "verley_sotberg",
    **options: Any,
) -> LateralResistanceModel:
    """Soil model of a test.

    Parameters
    ----------
    test : CentrifugeTest or str
        The test or its name.
    parameters : {"table2", "recommended"}
        Base parameter set: the test's Table 2 values or Table 3 (with the test's μ).
    A, B, C, mu : float or None
        Overrides [-].
    gamma : float or None
        Submerged unit weight γ' [N/m³]; None → :data:`SUBMERGED_UNIT_WEIGHT`.
    model : {"verley_sotberg", "coulomb"}
        Calcareous Verley & Sotberg (Youssef & Cassidy 2014) or friction only.
    **options
        Further keyword arguments of ``VerleySotberg`` (e.g. ``work_law``, ``passive_law``).
    """
    t = get_test(test) if isinstance(test, str) else test
    one_of("parameters", parameters, ("table2", "recommended"))
    one_of("model", model, ("verley_sotberg", "coulomb"))
    base = t.table2 if parameters == "table2" else RECOMMENDED
    mu_v = mu if mu is not None else (base.mu if base.mu is not None else t.table2.mu)
    if model == "coulomb":
        return CoulombFriction(friction_coefficient=mu_v, **options)
    from onbottom.soil.verley_sotberg import VerleySotberg

    g = SUBMERGED_UNIT_WEIGHT if gamma is None else gamma
    sand = Sand(submerged_unit_weight=g, friction_coefficient=mu_v, kind="calcareous")
    return VerleySotberg.calcareous(
        build_pipe(t),
        sand,
        A=base.A if A is None else A,
        B=base.B if B is None else B,
        C=base.C if C is None else C,
        installation_load=t.installation_load,
        **options,
    )


def run_centrifuge_test(
    name: str,
    *,
    A: float | None = None,
    B: float | None = None,
    C: float | None = None,
    mu: float | None = None,
    gamma: float | None = None,
    dt: float | None = None,
    parameters: str = "table2",
    model: str = "verley_sotberg",
    after_limit: str = "stop",
    alpha_deg: float | None = None,
    time_basis: str = "paper",
    shape: str = "sine",
    n_cycles: int | None = None,
    settings: SolverSettings | None = None,
    progress: bool = False,
    soil_options: dict[str, Any] | None = None,
) -> SectionResult:
    """Simulate one centrifuge test (fast entry for calibration loops).

    Parameters
    ----------
    name : str
        Test name ("Inclined 1", ..., "Regular", "Irregular"; case/space tolerant).
    A, B, C, mu : float or None
        Overrides of the factors and friction [-]; None → from ``parameters``.
    gamma : float or None
        γ' [N/m³]; None → :data:`SUBMERGED_UNIT_WEIGHT`.
    dt : float or None
        Largest time step [s]; None → programme sample interval (period/200 inclined).
    parameters : {"table2", "recommended"}
        Base parameter set.
    model : {"verley_sotberg", "coulomb"}
        Soil model.
    after_limit : {"stop", "runaway_end", "continue"}
        Behaviour at the displacement limit (see :func:`simulate_section`).
    alpha_deg : float or None
        Load-path inclination override [deg] (inclined tests).
    time_basis : {"paper", "prototype"}
        See :func:`build_programme`.
    shape : {"sine", "triangle"}
        Inclined cycle shape.
    n_cycles : int or None
        Programme length in cycles (groups).
    settings : SolverSettings or None
        Solver settings (``dt`` overrides its dt_max).
    progress : bool
        tqdm progress bar.
    soil_options : dict or None
        Extra options of the soil model (see :func:`build_soil`).

    Returns
    -------
    SectionResult
        ``cycles_to_limit`` compares with Table 1 "load cycles used".
    """
    return centrifuge_run(
        name,
        A=A,
        B=B,
        C=C,
        mu=mu,
        gamma=gamma,
        dt=dt,
        parameters=parameters,
        model=model,
        after_limit=after_limit,
        alpha_deg=alpha_deg,
        time_basis=time_basis,
        shape=shape,
        n_cycles=n_cycles,
        settings=settings,
        soil_options=soil_options,
    ).simulate(progress=progress)


def centrifuge_run(
    name: str,
    *,
    A: float | None = None,
    B: float | None = None,
    C: float | None = None,
    mu: float | None = None,
    gamma: float | None = None,
    dt: float | None = None,
    parameters: str = "table2",
    model: str = "verley_sotberg",
    after_limit: str = "stop",
    alpha_deg: float | None = None,
    time_basis: str = "paper",
    shape: str = "sine",
    n_cycles: int | None = None,
    settings: SolverSettings | None = None,
    soil_options: dict[str, Any] | None = None,
) -> SectionRun:
    """The :class:`~onbottom.dynamics.section_run.SectionRun` of one centrifuge test, built
    (programme, soil, mass, limit, settings; parameters as :func:`run_centrifuge_test`)."""
    test = get_test(name)
    prog = build_programme(
        test, n_cycles=n_cycles, time_basis=time_basis, shape=shape, alpha_deg=alpha_deg
    )
    soil = build_soil(
        test,
        parameters=parameters,
        A=A,
        B=B,
        C=C,
        mu=mu,
        gamma=gamma,
        model=model,
        **(soil_options or {}),
    )
    s = settings if settings is not None else SolverSettings()
    if dt is not None:
        s = SolverSettings(
            integrator=s.integrator,
            dt_max=positive("dt", dt),
            dt_min=s.dt_min,
            max_displacement_increment=s.max_displacement_increment,
            force_tolerance=s.force_tolerance,
            max_iterations=s.max_iterations,
            chunks=s.chunks,
        )
    pipe = build_pipe(test)
    g = SUBMERGED_UNIT_WEIGHT if gamma is None else gamma
    return SectionRun(
        programme=prog,
        soil=soil,
        mass=section_mass(pipe, ADDED_MASS_COEFFICIENT),
        displacement_limit=test.displacement_limit,
        after_limit=after_limit,
        settings=s,
        attrs={
            "test": test.name,
            "parameter_set": parameters,
            "submerged_unit_weight": g,
            "alpha_deg": (alpha_deg or test.alpha_deg) if test.kind == "inclined" else "n/a",
            "time_basis": time_basis,
            "paper_cycles_used": test.cycles_used,
            "source": "Youssef & Cassidy (2014) ISOPE pp. 141-148, Tables 1-3",
        },
    )
