"""Generalized-stability curves from dynamic storm analyses (what F109 tabulates, recomputed).

For each point (soil, N, M, K) and criterion (max |y| = 0.5D: L_stable; 10D: L_10) the weight
parameter L = w_s/(½ ρ_w D U_s²) is found by bisection in log L
(the construction of DNV-RP-F109's generalized-stability curves from dynamic runs, F109 §3.5),
with one of two **curve statistics** (:attr:`CurveSettings.statistic`):

* ``"fractile"`` (default): **each seed gets its own bisection** for the L at which its storm's
  maximum |y| crosses the criterion; the point reports the ``fractile`` (default 0.9) of these
  per-seed L as its L (the design value) and their median beside it
  (:func:`seed_quantile`: linear interpolation between order statistics, Hyndman & Fan
  type 7, numpy's default). The 0.9 fractile is on the heavy (conservative) side — at that L
  nine storms in ten of the sea state keep the pipe within the criterion — and is the highest
  fractile that 10 seeds resolve by interpolation between two seeds without resting on the
  single heaviest one (0.95 would sit half-way to it). Default 10 seeds;
* ``"mean_of_maxima"`` (the former statistic, kept by name for comparison): one bisection of
  the seed-averaged maximum |y|, in which a single runaway seed (a maximum of tens of D) can
  decide the mean.

Construction of a point (our choices; F109 and PONDUS do not publish theirs):

* K = U_s T_u/D and N = U_s/(g T_u) fix U_s = √(K N g D) and T_u = √(K D/(N g)); a JONSWAP
  sea state (γ = 3.3, T_n/T_p = 0.1, long-crested, normal to the pipe) with these U_s, T_u is
  built by :func:`onbottom.hydro.storm_kinematics.sea_state_for_velocity`;
* the current V = M·U_s is uniform over the pipe (no profile: M is defined with the mean
  current over D);
* w_s = L·½ ρ_w D U_s², the pipe mass follows from w_s and buoyancy (s_g = 1 + 2NKL/π);
* sand: Verley & Sotberg silica with γ'_s and μ; clay: Verley & Lund with s_u = G_c D γ_s;
* the same seeds are used at every L (common random numbers: a smooth L ↦ max |y|);
* **early stop** (``"fractile"`` with ``early_stop``, the default): a storm stops as soon as
  |y| reaches the criterion (``stop_displacement_over_d`` of the storm solver): its verdict
  (reaches the criterion or not) is then known, and the trajectory up to the stop is the one
  of the full run, so the verdict, every bisection step and the per-seed L are exactly those
  of full runs. A storm that stopped early reports max |y| = the criterion (``_stopped_early``
  counts them). Without ``early_stop``, and for ``"mean_of_maxima"`` (which averages
  magnitudes), storms stop as runaways at twice the target (at least 10D); there a stopped seed
  counts with its displacement at the stop, so the mean is a lower bound of the unstopped mean
  and the L found can only be lower (less conservative) than with unstopped runs — by little,
  since the stop is far above the target — and a bisection evaluation stops early once the
  seeds run so far decide which side of the target the mean is on;
* a storm whose penetration left the soil model's range (z > D/2, status −3 of
  :func:`~onbottom.dynamics.storm_section.simulate_storm_section`) counts with its
  displacement, and the point is marked ``out_of_range`` (NetCDF variable
  ``<criterion>_out_of_range``, CSV column, open marker in the figure, report table) when any
  storm at the two L values that bracket the answer (of any seed, for ``"fractile"``; or,
  without an answer, at any L tried) left the range: its L rests on the model outside its
  calibration. A storm stopped early is flagged for what happened up to its stop.

Each point is one task on Dask (:mod:`onbottom.study.engine`); seeds run inside the task.
With ``store`` (a folder; ``onbottom curves`` uses ``<output>.tasks``) every finished point is
written at once to its own small file (:class:`onbottom.results.TaskStore`), so an interrupted
sweep resumes without repeating the points it finished.

Files written before the per-seed statistic (no ``statistic`` attribute, no ``seed``
dimension) hold the mean of maxima: :func:`curve_statistic` says which statistic a dataset
holds, and :func:`curves_table` reads both.
"""

from __future__ import annotations

import logging
import math
import time
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
import xarray as xr

from onbottom._validate import in_range, positive
from onbottom.constants import GRAVITY, RHO_SEAWATER
from onbottom.dynamics.status import Status
from onbottom.dynamics.storm_section import (
    STATUS_OUTSIDE_VALIDITY,
    StormSolverSettings,
    simulate_storm_section,
)
from onbottom.errors import InputError, OutOfRangeWarning, RunInterrupted
from onbottom.hydro.force_model import ForceModel
from onbottom.hydro.reductions import LoadReductions
from onbottom.hydro.storm_kinematics import (
    StormKinematics,
    sea_state_for_velocity,
    storm_kinematics,
)
from onbottom.hydro.wake import WakeModel
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Clay, Sand
from onbottom.inputs.storm import Storm
from onbottom.results import TaskStore, annotate, provenance
from onbottom.soil.base import LateralResistanceModel
from onbottom.soil.verley_lund import VerleyLund
from onbottom.soil.verley_sotberg import VerleySotberg

__all__ = [
    "CRITERIA",
    "DEFAULT_FRACTILE",
    "STATISTICS",
    "CurveSettings",
    "clay_validity_limit",
    "curve_statistic",
    "curves_table",
    "find_weight_parameter",
    "point_kinematics",
    "point_summary",
    "seed_quantile",
    "stability_curves",
]

logger = logging.getLogger(__name__)

STATUS_LIMIT = int(Status.LIMIT)

CRITERIA: dict[str, float] = {"L_stable": 0.5, "L_10": 10.0}
"""Criterion name → target seed-averaged maximum displacement over D."""

SOILS = ("sand", "clay")

STATISTICS: dict[str, str] = {
    "fractile": "a fractile (and the median) over the seeds of each seed's own L",
    "mean_of_maxima": "L of the seed-averaged max |y| (mean of maxima; former statistic, a"
    " single runaway seed can dominate it)",
}
"""Curve statistics (module docstring): name → what L is."""

DEFAULT_FRACTILE = 0.9
"""Fractile of the per-seed L reported as a point's L (the heavy, conservative side: at it nine
storms in ten stay within the criterion; the highest fractile 10 seeds resolve between two of
them)."""

QUANTILE_METHOD = "linear (Hyndman & Fan type 7, numpy.quantile's default)"


@dataclass(frozen=True, kw_only=True)
class CurveSettings:
    """Settings of :func:`stability_curves` (SI).

    Parameters
    ----------
    diameter : float
        Pipe outer diameter D [m], in [0.005, 5] (results are dimensionless; D sets the
        scale).
    seeds : int
        Seeds (storms per L), >= 1; seeds first_seed, first_seed + 1, ... Default 10, the
        fewest over which the 0.9 fractile is resolved between two seeds.
    first_seed : int
        >= 0.
    build_up_hours, peak_hours : float
        Storm: linear build-up and peak duration [h].
    tolerance : float
        Relative width of the final L bracket [-], in (0, 0.5].
    l_min, l_max : float
        Initial bracket of L [-]; widened (×/÷ 4, up to 6 times) if it does not bracket.
    gamma : float
        JONSWAP γ of the synthetic sea states [-].
    tn_over_tp : float
        T_n/T_p of the synthetic sea states [-] (sets the water depth).
    time_step : float
        Largest solver step [s].
    sand_unit_weight : float
        γ'_s of the sand [N/m³]; sand_friction μ [-].
    clay_gc : float
        G_c = s_u/(D γ_s) of the clay [-]; clay_unit_weight γ_s (total) and
        clay_submerged_unit_weight γ' [N/m³]; clay_friction μ [-].
    water_density : float
        ρ_w [kg/m³].
    force_model : ForceModel
        Hydrodynamic force model (:mod:`onbottom.hydro.registry`: ``MorisonLift``,
        ``WakeModel``, ``FourierModel``); default the wake model with its F109-calibrated
        constants (:class:`~onbottom.hydro.wake.WakeModel`; constant Morison coefficients
        give peak loads ~2.5x below F109's and unconservative curves).
    statistic : {"fractile", "mean_of_maxima"}
        Curve statistic (module docstring): per-seed bisections reported as a fractile and the
        median (default), or the former seed-averaged maximum.
    fractile : float
        Fractile of the per-seed L reported as the point's L [-], in [0.5, 0.99]; default
        :data:`DEFAULT_FRACTILE` (0.9).
    early_stop : bool
        ``"fractile"`` only: stop each storm once |y| reaches the criterion (its verdict is
        then known; the results equal those of full runs). False: run to the runaway stop
        (twice the criterion, at least 10D), as the former statistic does.
    """

    diameter: float = 0.5
    seeds: int = 10
    first_seed: int = 0
    build_up_hours: float = 0.5
    peak_hours: float = 3.0
    tolerance: float = 0.02
    l_min: float = 1.0
    l_max: float = 300.0
    gamma: float = 3.3
    tn_over_tp: float = 0.1
    time_step: float = 0.1
    sand_unit_weight: float = 10.0e3
    sand_friction: float = 0.6
    clay_gc: float = 0.222
    clay_unit_weight: float = 18.0e3
    clay_submerged_unit_weight: float = 8.0e3
    clay_friction: float = 0.2
    water_density: float = RHO_SEAWATER
    force_model: ForceModel = field(default_factory=WakeModel)
    statistic: str = "fractile"
    fractile: float = DEFAULT_FRACTILE
    early_stop: bool = True

    def __post_init__(self) -> None:
        in_range("CurveSettings.diameter", self.diameter, 0.005, 5.0)  # mm typed as m
        if int(self.seeds) < 1 or int(self.first_seed) < 0:
            raise InputError(
                f"CurveSettings.seeds = {self.seeds!r} / first_seed = {self.first_seed!r} are"
                " invalid: need seeds >= 1 and first_seed >= 0"
            )
        in_range("CurveSettings.build_up_hours", self.build_up_hours, 0.0, 100.0)
        in_range("CurveSettings.peak_hours", self.peak_hours, 0.0, 100.0, low_inclusive=False)
        in_range("CurveSettings.tolerance", self.tolerance, 0.0, 0.5, low_inclusive=False)
        positive("CurveSettings.l_min", self.l_min)
        if not self.l_max > self.l_min:
            raise InputError(
                f"CurveSettings.l_max = {self.l_max!r} is invalid: must be > l_min = {self.l_min!r}"
            )
        positive("CurveSettings.time_step", self.time_step)
        positive("CurveSettings.sand_unit_weight", self.sand_unit_weight)
        positive("CurveSettings.clay_gc", self.clay_gc)
        positive("CurveSettings.water_density", self.water_density)
        if self.statistic not in STATISTICS:
            raise InputError(
                f"CurveSettings.statistic = {self.statistic!r} is invalid: must be one of"
                f" {tuple(STATISTICS)}"
            )
        in_range("CurveSettings.fractile", self.fractile, 0.5, 0.99)


def point_kinematics(k: float, m: float, n: float, s: CurveSettings) -> list[StormKinematics]:
    """Flow of every seed at (K, M, N): U_s = √(K N g D), T_u = √(K D/(N g)), V = M U_s."""
    positive("K", k)
    positive("N", n)
    in_range("M", m, 0.0, 100.0)
    d = s.diameter
    us = math.sqrt(k * n * GRAVITY * d)
    tu = math.sqrt(k * d / (n * GRAVITY))
    sea, depth = sea_state_for_velocity(
        us, tu, tn_over_tp=s.tn_over_tp, gamma=s.gamma, duration_s=s.peak_hours * 3600.0
    )
    storm = Storm(stages=(sea,), build_up_s=s.build_up_hours * 3600.0)
    out = []
    for i in range(int(s.seeds)):
        kin = storm_kinematics(storm.with_seed(s.first_seed + i), depth, diameter=d)
        out.append(replace(kin, current=m * us))
    return out


def clay_validity_limit(k: float, n: float, s: CurveSettings) -> float:
    """L at which S·G_c^0.3 = 2.5, the upper validity of the Verley & Lund penetration fit.

    S = w_s/(D s_u) = L ½ ρ_w U_s²/s_u (Bai, *Pipelines and Risers*, p. 107: the fit holds
    for S·G^0.3 < 2.5 and over-predicts beyond; DNV-RP-F109 (2017) §3.4.6).
    """
    su = s.clay_gc * s.diameter * s.clay_unit_weight
    us2 = k * n * GRAVITY * s.diameter
    return 2.5 / s.clay_gc**0.3 * su / (0.5 * s.water_density * us2)


def _soil(soil: str, pipe: Pipe, s: CurveSettings) -> LateralResistanceModel:
    if soil == "sand":
        return VerleySotberg.silica(
            pipe,
            Sand(submerged_unit_weight=s.sand_unit_weight, friction_coefficient=s.sand_friction),
        )
    clay = Clay(
        undrained_shear_strength=s.clay_gc * s.diameter * s.clay_unit_weight,
        submerged_unit_weight=s.clay_submerged_unit_weight,
        unit_weight=s.clay_unit_weight,
        friction_coefficient=s.clay_friction,
    )
    return VerleyLund.from_seabed(pipe, clay)


def _mean_max(
    soil: str,
    weight_parameter: float,
    kins: list[StormKinematics],
    us: float,
    target: float,
    s: CurveSettings,
) -> tuple[bool, float, int, list[float], int]:
    """(mean max |y|/D >= target?, mean over the seeds run, seeds run, max |y|/D per seed
    run, seeds out of the soil model's range)."""
    d = s.diameter
    ws = weight_parameter * 0.5 * s.water_density * d * us * us
    pipe = Pipe(outer_diameter=d, submerged_weight=ws, seawater_density=s.water_density)
    soil_model = _soil(soil, pipe, s)
    stop = max(2.0 * target, 10.0)
    settings = StormSolverSettings(
        dt_max=s.time_step, stop_displacement_over_d=stop, record_interval=None
    )
    red = LoadReductions(permeable_seabed=soil != "clay")
    n = len(kins)
    total = 0.0
    per_seed: list[float] = []
    n_out = 0
    for i, kin in enumerate(kins):
        r = simulate_storm_section(
            pipe, soil_model, kin, force_model=s.force_model, reductions=red, settings=settings
        )
        if r.status == STATUS_OUTSIDE_VALIDITY:
            n_out += 1  # ran to its end outside the soil model's range: counted, flagged
        elif not r.success:
            raise RuntimeError(f"seed {kin.seed}: {r.message}")
        total += r.max_displacement / d
        per_seed.append(r.max_displacement / d)
        run = i + 1
        # decided already? (remaining seeds add between 0 and stop each)
        if total >= target * n:
            return True, total / run, run, per_seed, n_out
        if total + (n - run) * (stop + 0.1) < target * n:
            return False, total / run, run, per_seed, n_out
    return total / n >= target, total / n, n, per_seed, n_out


def find_weight_parameter(
    soil: str, k: float, m: float, n: float, criterion: str, s: CurveSettings
) -> dict[str, Any]:
    """L of one point and criterion with the statistic of ``s`` (module docstring).

    Returns a dict with L (the design value: the fractile, or the mean-of-maxima L), bracket,
    evaluations, storms, runtime, out_of_range (storms at the final bracket — any L tried
    without an answer — that left the soil model's range), a status message, and for
    ``"fractile"`` also ``L_median``, ``per_seed`` (each seed's L, NaN where it has none),
    ``per_seed_low``/``per_seed_high`` (each seed's bracket), ``per_seed_storms``,
    ``per_seed_stopped_early``, ``stopped_early`` (storms stopped once their verdict was known) and
    ``seeds_no_crossing``.
    """
    if soil not in SOILS:
        raise InputError(f"soil = {soil!r} is invalid: must be one of {SOILS}")
    if criterion not in CRITERIA:
        raise InputError(f"criterion = {criterion!r} is invalid: must be one of {tuple(CRITERIA)}")
    if s.statistic == "fractile":
        return _find_per_seed(soil, k, m, n, criterion, s)
    return _find_mean_of_maxima(soil, k, m, n, criterion, s)


def seed_quantile(values: Sequence[float], censored: Sequence[str], p: float) -> float:
    """The ``p`` quantile of per-seed L (linear interpolation between order statistics,
    Hyndman & Fan type 7 — ``numpy.quantile``'s default), seeds without a crossing included.

    ``censored[i]`` is ``""`` where ``values[i]`` is the seed's L, ``"below"`` where the seed
    stayed below the criterion at every L tried (its L is lower than any tried) and ``"above"``
    where it exceeded the criterion at every L tried (higher than any tried). Such seeds take
    their place in the order; the quantile is NaN where it would interpolate from one of them.
    """
    x = [
        -math.inf if c == "below" else math.inf if c == "above" else float(v)
        for v, c in zip(values, censored, strict=True)
    ]
    if not x or any(math.isnan(v) for v in x):
        return math.nan
    x.sort()
    h = (len(x) - 1) * p
    i = math.floor(h)
    frac = h - i
    a = x[i]
    if frac == 0.0:
        return a if math.isfinite(a) else math.nan
    b = x[min(i + 1, len(x) - 1)]
    if not (math.isfinite(a) and math.isfinite(b)):
        return math.nan
    return a + frac * (b - a)


def _pipe_and_soil(
    soil: str, weight_parameter: float, us: float, s: CurveSettings
) -> tuple[Pipe, LateralResistanceModel]:
    d = s.diameter
    ws = weight_parameter * 0.5 * s.water_density * d * us * us
    pipe = Pipe(outer_diameter=d, submerged_weight=ws, seawater_density=s.water_density)
    return pipe, _soil(soil, pipe, s)


def _bisect(moves: Any, s: CurveSettings, cap: float) -> tuple[float, float, str, str]:
    """Bracket and bisect in log L for the crossing of ``moves`` (True: the criterion is
    reached at that L). Returns (lo, hi, censored, message) with censored ``""`` when
    [lo, hi] brackets the crossing within the tolerance, ``"below"`` when the criterion is
    not reached even at the lightest L tried (lo), ``"above"`` when it is reached even at the
    heaviest L tried (hi)."""
    lo, hi = s.l_min, s.l_max
    if hi > cap:
        hi = cap
        lo = min(lo, cap / 4.0)
    tries = 0
    while not moves(lo):
        if tries == 6:
            return (
                lo,
                hi,
                "below",
                f"even L = {lo:.3g} stays below the target (a light pipe lifts off and"
                " oscillates with the flow without drifting)",
            )
        hi, lo = lo, lo / 4.0
        tries += 1
    tries = 0
    while moves(hi):
        if hi >= cap:
            return (
                lo,
                hi,
                "above",
                f"the target is exceeded up to L = {cap:.3g}, the Verley & Lund validity"
                " limit S·G_c^0.3 = 2.5 (Bai, Pipelines and Risers, §5): L is beyond the soil"
                " model",
            )
        if tries == 6:
            return lo, hi, "above", f"even L = {hi:.3g} exceeds the target"
        lo, hi = hi, min(hi * 4.0, cap)
        tries += 1
    while hi / lo > 1.0 + s.tolerance:
        mid = math.sqrt(lo * hi)
        if moves(mid):
            lo = mid
        else:
            hi = mid
    return lo, hi, "", "converged"


def _seed_search(
    soil: str, kin: StormKinematics, us: float, target: float, cap: float, s: CurveSettings
) -> dict[str, Any]:
    """One seed's own bisection: the L at which its storm's max |y| crosses target·D."""
    d = s.diameter
    stop = target if s.early_stop else max(2.0 * target, 10.0)
    settings = StormSolverSettings(
        dt_max=s.time_step, stop_displacement_over_d=stop, record_interval=None
    )
    red = LoadReductions(permeable_seabed=soil != "clay")
    runs: dict[float, tuple[bool, float, bool, bool]] = {}

    def moves(lv: float) -> bool:
        if lv not in runs:
            pipe, soil_model = _pipe_and_soil(soil, lv, us, s)
            r = simulate_storm_section(
                pipe, soil_model, kin, force_model=s.force_model, reductions=red, settings=settings
            )
            outside = r.status == STATUS_OUTSIDE_VALIDITY
            if not outside and not r.success:
                raise RuntimeError(f"seed {kin.seed}: {r.message}")
            runs[lv] = (
                bool(r.max_displacement >= target * d),  # the verdict: reaches the criterion
                r.max_displacement / d,
                bool(r.max_displacement >= stop * d),  # stopped at the stop limit
                outside,
            )
        return runs[lv][0]

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OutOfRangeWarning)
        lo, hi, censored, message = _bisect(moves, s, cap)
    ok = not censored
    keep = (lo, hi) if ok else tuple(runs)
    return {
        "L": math.sqrt(lo * hi) if ok else math.nan,
        "L_low": lo if ok else math.nan,
        "L_high": hi if ok else math.nan,
        "censored": censored,
        "message": message,
        "max_low": runs[lo][1] if ok else math.nan,
        "max_high": runs[hi][1] if ok else math.nan,
        "storms": len(runs),
        "stopped_early": sum(1 for v in runs.values() if v[2]) if s.early_stop else 0,
        "stopped": sum(1 for v in runs.values() if v[2]),
        "out_of_range": sum(1 for lv in keep if runs[lv][3]),
    }


def _find_per_seed(
    soil: str, k: float, m: float, n: float, criterion: str, s: CurveSettings
) -> dict[str, Any]:
    """Each seed's own bisection; the point's L is the fractile of the per-seed L."""
    target = CRITERIA[criterion]
    t0 = time.perf_counter()
    c0 = time.process_time()
    kins = point_kinematics(k, m, n, s)
    us = math.sqrt(k * n * GRAVITY * s.diameter)
    cap = clay_validity_limit(k, n, s) if soil == "clay" else math.inf
    seeds = [_seed_search(soil, kin, us, target, cap, s) for kin in kins]
    cens = [r["censored"] for r in seeds]
    per_seed = [r["L"] for r in seeds]
    value = seed_quantile(per_seed, cens, s.fractile)
    median = seed_quantile(per_seed, cens, 0.5)
    # the quantile is monotone in each seed's value: the fractiles of the seeds' bracket ends
    # bracket the fractile of their crossings, within the tolerance
    lo = seed_quantile([r["L_low"] for r in seeds], cens, s.fractile)
    hi = seed_quantile([r["L_high"] for r in seeds], cens, s.fractile)
    ok = math.isfinite(value)
    width = hi / lo - 1.0 if ok and lo > 0.0 else math.nan
    n_no = sum(1 for c in cens if c)
    if ok:
        message = "converged"
        if n_no:
            message += (
                f"; {n_no} of {len(seeds)} seed(s) without a crossing in the L tried, ranked"
                " beyond it"
            )
    else:
        reasons = sorted({r["message"] for r in seeds if r["censored"]})
        message = (
            f"no {s.fractile:g} fractile: {n_no} of {len(seeds)} seed(s) have no crossing"
            f" ({'; '.join(reasons)})"
        )
    n_out = sum(r["out_of_range"] for r in seeds)
    if n_out:
        message += (
            f"; outside the soil model's range: {n_out} storm(s) at the seeds' bracketing L"
            " values (or any L tried without a crossing) buried the pipe beyond D/2"
        )
    low = [r["max_low"] for r in seeds if not r["censored"]]
    high = [r["max_high"] for r in seeds if not r["censored"]]
    storms = sum(r["storms"] for r in seeds)
    return {
        "soil": soil,
        "K": float(k),
        "M": float(m),
        "N": float(n),
        "criterion": criterion,
        "L": value,
        "L_median": median,
        "L_low": lo,
        "L_high": hi,
        "bracket_width": width,
        "converged": bool(ok and width <= s.tolerance * (1.0 + 1e-9)),
        **_seed_spread("low", low),
        **_seed_spread("high", high),
        "evaluations": storms,
        "storms": storms,
        "stopped_early": sum(r["stopped_early"] for r in seeds),
        "seeds_no_crossing": n_no,
        "per_seed": per_seed,
        "per_seed_low": [r["L_low"] for r in seeds],
        "per_seed_high": [r["L_high"] for r in seeds],
        "per_seed_storms": [r["storms"] for r in seeds],
        "per_seed_stopped_early": [r["stopped_early"] for r in seeds],
        "per_seed_censored": cens,
        "runtime_s": time.perf_counter() - t0,
        "cpu_s": time.process_time() - c0,
        "success": bool(ok),
        "error": False,
        "out_of_range": int(n_out),
        "message": message,
    }


def _find_mean_of_maxima(
    soil: str, k: float, m: float, n: float, criterion: str, s: CurveSettings
) -> dict[str, Any]:
    """Bisect log L for the seed-averaged max |y| = target·D of ``criterion`` (the former
    statistic)."""
    target = CRITERIA[criterion]
    t0 = time.perf_counter()
    c0 = time.process_time()
    kins = point_kinematics(k, m, n, s)
    us = math.sqrt(k * n * GRAVITY * s.diameter)
    evals = 0
    storms = 0
    cache: dict[float, bool] = {}
    outside: dict[float, int] = {}
    seeds_at: dict[float, list[float]] = {}

    def moves(lv: float) -> bool:
        nonlocal evals, storms
        if lv not in cache:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", OutOfRangeWarning)
                above, _, ran, per_seed, n_out = _mean_max(soil, lv, kins, us, target, s)
            cache[lv] = above
            outside[lv] = n_out
            seeds_at[lv] = per_seed
            evals += 1
            storms += ran
        return cache[lv]

    lo, hi = s.l_min, s.l_max
    cap = clay_validity_limit(k, n, s) if soil == "clay" else math.inf
    message = "converged"
    if hi > cap:
        hi = cap
        lo = min(lo, cap / 4.0)
    for _ in range(6):
        if moves(lo):
            break
        hi, lo = lo, lo / 4.0
    else:
        message = (
            f"even L = {lo:.3g} stays below the target (a light pipe lifts off and"
            " oscillates with the flow without drifting)"
        )
    for _ in range(6):
        if not moves(hi):
            break
        if hi >= cap:
            message = (
                f"the target is exceeded up to L = {cap:.3g}, the Verley & Lund validity limit"
                " S·G_c^0.3 = 2.5 (Bai, Pipelines and Risers, §5): L is beyond the soil model"
            )
            break
        lo, hi = hi, min(hi * 4.0, cap)
    else:
        message = f"even L = {hi:.3g} exceeds the target"
    ok = moves(lo) and not moves(hi)
    if ok:
        while hi / lo > 1.0 + s.tolerance:
            mid = math.sqrt(lo * hi)
            if moves(mid):
                lo = mid
            else:
                hi = mid
    value = math.sqrt(lo * hi) if ok else math.nan
    width = hi / lo - 1.0 if lo > 0.0 else math.inf
    converged = bool(ok and width <= s.tolerance * (1.0 + 1e-9))
    if ok and not converged:  # pragma: no cover - the bisection runs to the tolerance
        message = f"bracket [{lo:.4g}, {hi:.4g}] wider than the tolerance {s.tolerance:g}"
    n_out = outside.get(lo, 0) + outside.get(hi, 0) if ok else sum(outside.values())
    if n_out:
        message += (
            f"; outside the soil model's range: {n_out} storm(s)"
            + (" at the bracketing L values" if ok else "")
            + " buried the pipe beyond D/2"
        )
    return {
        "soil": soil,
        "K": float(k),
        "M": float(m),
        "N": float(n),
        "criterion": criterion,
        "L": value,
        "L_low": lo,
        "L_high": hi,
        "bracket_width": width,
        "converged": converged,
        **_seed_spread("low", seeds_at.get(lo)),
        **_seed_spread("high", seeds_at.get(hi)),
        "evaluations": evals,
        "storms": storms,
        "runtime_s": time.perf_counter() - t0,
        "cpu_s": time.process_time() - c0,
        "success": bool(ok),
        "error": False,
        "out_of_range": int(n_out),
        "message": message,
    }


def _seed_spread(end: str, values: list[float] | None) -> dict[str, float]:
    """Mean, smallest and largest max |y|/D over the seeds run at one end of the bracket."""
    if not values:
        return {
            f"seed_mean_{end}": math.nan,
            f"seed_min_{end}": math.nan,
            f"seed_max_{end}": math.nan,
        }
    return {
        f"seed_mean_{end}": float(np.mean(values)),
        f"seed_min_{end}": float(np.min(values)),
        f"seed_max_{end}": float(np.max(values)),
    }


POINT_FIELDS = (
    "L",
    "L_low",
    "L_high",
    "bracket_width",
    "converged",
    "seed_mean_low",
    "seed_min_low",
    "seed_max_low",
    "seed_mean_high",
    "seed_min_high",
    "seed_max_high",
    "evaluations",
    "storms",
    "runtime_s",
)
"""Numbers of one curve point stored per criterion in the dataset (``{criterion}_{field}``
for the others than L)."""


_VARIABLE = {"L_low": "bracket_low", "L_high": "bracket_high", "runtime_s": "runtime"}
"""Dataset variable (after ``{criterion}_``) of a point field whose name differs."""


@dataclass(frozen=True)
class _PointJob:
    settings: CurveSettings

    def __call__(self, item: tuple[str, float, float, float, str]) -> dict[str, Any]:
        soil, k, m, n, crit = item
        try:
            return find_weight_parameter(soil, k, m, n, crit, self.settings)
        except Exception as exc:  # recorded, the sweep goes on
            return {
                "soil": soil,
                "K": k,
                "M": m,
                "N": n,
                "criterion": crit,
                "L": math.nan,
                "L_low": math.nan,
                "L_high": math.nan,
                "bracket_width": math.nan,
                "converged": False,
                **_seed_spread("low", None),
                **_seed_spread("high", None),
                "evaluations": 0,
                "storms": 0,
                "runtime_s": 0.0,
                "cpu_s": 0.0,
                "success": False,
                "error": True,
                "out_of_range": 0,
                "message": f"{type(exc).__name__}: {exc}",
            }


def stability_curves(
    k_values: Sequence[float],
    m_values: Sequence[float],
    n_values: Sequence[float] = (0.003,),
    *,
    soils: Sequence[str] = SOILS,
    criteria: Sequence[str] = tuple(CRITERIA),
    settings: CurveSettings | None = None,
    n_workers: int | None = None,
    scheduler: str | None = None,
    client: Any = None,
    progress: bool = False,
    store: Any = None,
    restart: bool = False,
    identity: Any = None,
) -> xr.Dataset:
    """L_stable and L_10 on a grid of soil × N × M × K (module docstring).

    Parameters
    ----------
    k_values, m_values, n_values : sequences of float
        K > 0, M >= 0, N > 0 [-].
    soils : sequence of {"sand", "clay"}
    criteria : sequence of {"L_stable", "L_10"}
    settings : CurveSettings or None
    n_workers : int or None
        Local Dask worker processes (None → one per core; 0 → in this process).
    scheduler : str or None
        Address of a Dask scheduler.
    client : distributed.Client or None
    progress : bool
    store : path or None
        Folder keeping each finished point (one JSON file per point, written as it finishes);
        points found there with this run's identity are not computed again.
    restart : bool
        Empty ``store`` first (start afresh).
    identity : any
        JSON-able description of the inputs for the run identity of the stored points
        (default: the text of the settings).

    Returns
    -------
    xarray.Dataset
        L_stable, L_10 (and their L/(2 + M)² forms, brackets, evaluations, storms, runtime)
        over dimensions (soil, N, M, K); with the statistic ``"fractile"`` also
        ``<criterion>_median``, ``_stopped_early``, ``_seeds_no_crossing`` and per seed
        (dimension ``seed``) ``_per_seed`` (each seed's L), ``_per_seed_low``/``_high``,
        ``_per_seed_storms``, ``_per_seed_stopped_early``; attributes: total storms, wall
        time, settings, ``statistic``, ``seeds`` (and ``fractile``, ``quantile_method``,
        ``early_stop``, ``stopped_early``).
    """
    s = settings if settings is not None else CurveSettings()
    ks, ms, ns = _checked_grid(k_values, m_values, n_values, soils, criteria)
    items = [(so, k, m, n, c) for so in soils for n in ns for m in ms for k in ks for c in criteria]
    t0 = time.perf_counter()
    rows, workers = _run_points(
        _PointJob(s), items, s, store, restart, identity, n_workers, scheduler, client, progress
    )
    wall = time.perf_counter() - t0
    return _to_dataset(rows, list(soils), ns, ms, ks, list(criteria), s, wall, workers)


def _checked_grid(k_values, m_values, n_values, soils, criteria):
    """Stage of :func:`stability_curves`: the grid checked (sequences, names, ranges, no
    repeated value); (K, M, N) as lists of floats."""
    for name, vals in (
        ("k_values", k_values),
        ("m_values", m_values),
        ("n_values", n_values),
        ("soils", soils),
        ("criteria", criteria),
    ):
        if isinstance(vals, (str, bytes)) or not hasattr(vals, "__iter__"):
            err = InputError(
                f"{name} = {vals!r} is invalid: expected a sequence of values (a list), not"
                " one value"
            )
            err.field = name  # type: ignore[attr-defined]
            raise err
    for soil in soils:
        if soil not in SOILS:
            raise InputError(f"soils = {soil!r} is invalid: must be one of {SOILS}")
    for c in criteria:
        if c not in CRITERIA:
            raise InputError(f"criteria = {c!r} is invalid: must be one of {tuple(CRITERIA)}")
    ks = [positive("K", x) for x in k_values]
    ms = [in_range("M", x, 0.0, 100.0) for x in m_values]
    ns = [positive("N", x) for x in n_values]
    if not ks or not ms or not ns or not soils or not criteria:
        raise InputError("the grid is empty: give at least one K, M, N, soil and criterion")
    for name, vals in (("K", ks), ("M", ms), ("N", ns), ("soils", soils), ("criteria", criteria)):
        if len(set(vals)) != len(list(vals)):
            err = InputError(
                f"{name} = {list(vals)!r} is invalid: a value is repeated (give each value once)"
            )
            err.field = name  # type: ignore[attr-defined]
            raise err
    return ks, ms, ns


def _run_points(job, items, s, store, restart, identity, n_workers, scheduler, client,
                progress):  # fmt: skip
    """Stage of :func:`stability_curves`: every point's row, those of ``store`` read back and
    the rest computed (each kept in the store as it finishes); (rows in ``items`` order,
    workers)."""
    ts = None
    done: dict[int, dict[str, Any]] = {}
    if store is not None:
        ident = identity if identity is not None else repr(s)
        ts = TaskStore(
            store, {"study": "stability_curves", "inputs": ident}, restart=restart, what="point"
        )
        done = ts.load([_point_key(x) for x in items])
        if done:
            logger.info(
                "resuming: %d of %d points already done in %s", len(done), len(items), store
            )
    todo = [x for i, x in enumerate(items) if i not in done]
    new: dict[tuple, dict[str, Any]] = {}

    def keep(item: tuple, row: dict[str, Any]) -> None:
        new[tuple(item)] = row
        if ts is not None and not row["error"]:  # an exception may be transient
            ts.put(_point_key(item), row)

    from onbottom.study.engine import run_streamed

    try:
        workers = run_streamed(
            job,
            todo,
            keep,
            n_workers=n_workers,
            scheduler=scheduler,
            client=client,
            progress=progress,
            unit="point",
        )
    except KeyboardInterrupt:
        raise RunInterrupted(
            _interrupted(
                len(done) + sum(1 for r in new.values() if not r["error"]), len(items), store
            )
        ) from None
    return [done[i] if i in done else new[tuple(x)] for i, x in enumerate(items)], workers


def _point_key(item: tuple) -> dict[str, Any]:
    soil, k, m, n, crit = item
    return {"soil": soil, "K": float(k), "M": float(m), "N": float(n), "criterion": crit}


def _per_seed_variables(data, c, idx, soils, ns, ms, ks, s) -> None:
    """Variables of the per-seed statistic: the median, the storms stopped early, the seeds
    without a crossing (soil, N, M, K) and each seed's L and bracket (…, seed)."""
    shape = (len(soils), len(ns), len(ms), len(ks))
    n_seeds = int(s.seeds)
    point = {name: np.full(shape, np.nan) for name in ("L_median", "stopped_early")}
    point["seeds_no_crossing"] = np.full(shape, np.nan)
    seed = {
        name: np.full((*shape, n_seeds), np.nan)
        for name in (
            "per_seed",
            "per_seed_low",
            "per_seed_high",
            "per_seed_storms",
            "per_seed_stopped_early",
        )
    }
    for a, so in enumerate(soils):
        for b, n in enumerate(ns):
            for i, m in enumerate(ms):
                for j, k in enumerate(ks):
                    r = idx[(so, n, m, k, c)]
                    for name, arr in point.items():
                        arr[a, b, i, j] = r.get(name, np.nan)
                    for name, arr in seed.items():
                        values = r.get(name)
                        if values is not None and len(values) == n_seeds:
                            arr[a, b, i, j, :] = values
    dims = ("soil", "N", "M", "K")
    data[f"{c}_median"] = (
        dims,
        point["L_median"],
        {"long_name": f"median over the seeds of each seed's own L at {c}", "units": "1"},
    )
    data[f"{c}_stopped_early"] = (
        dims,
        point["stopped_early"],
        {
            "long_name": f"storms of the point ({c}) stopped once |y| reached the criterion"
            " (their max |y| is the criterion, not the storm's maximum)",
            "units": "1",
        },
    )
    data[f"{c}_seeds_no_crossing"] = (
        dims,
        point["seeds_no_crossing"],
        {"long_name": f"seeds without a crossing of {c} in the L tried", "units": "1"},
    )
    sdims = (*dims, "seed")
    for name, long in (
        ("per_seed", "each seed's own L (geometric mean of its final bracket; NaN: none)"),
        ("per_seed_low", "low end of each seed's final bracket"),
        ("per_seed_high", "high end of each seed's final bracket"),
        ("per_seed_storms", "storms run by each seed's bisection"),
        (
            "per_seed_stopped_early",
            "storms of each seed's bisection stopped once |y| reached the criterion (every"
            " storm whose verdict was 'reaches the criterion', with early_stop)",
        ),
    ):
        data[f"{c}_{name}"] = (sdims, seed[name], {"long_name": f"{c}: {long}", "units": "1"})


def _to_dataset(rows, soils, ns, ms, ks, criteria, s, wall, workers) -> xr.Dataset:
    """The sweep's dataset from its point rows: the variables per criterion
    (:func:`_criterion_variables`), the attributes of the run (:func:`_run_attributes`) and of
    each variable (:func:`_describe_variables`), and the combined out-of-range flag."""
    idx = {(r["soil"], r["N"], r["M"], r["K"], r["criterion"]): r for r in rows}
    data: dict[str, Any] = {}
    for c in criteria:
        _criterion_variables(data, c, idx, soils, ns, ms, ks, s)
    coords: dict[str, Any] = {"soil": soils, "N": ns, "M": ms, "K": ks}
    if s.statistic == "fractile":
        coords["seed"] = np.arange(int(s.first_seed), int(s.first_seed) + int(s.seeds))
    ds = xr.Dataset(data, coords=coords, attrs=_run_attributes(rows, s, wall, workers))
    for c in criteria:
        _describe_variables(ds, c, s)
    ds["out_of_range"] = sum(ds[f"{c}_out_of_range"] for c in criteria).clip(max=1)
    ds["out_of_range"] = ds["out_of_range"].astype(np.int8)
    ds["out_of_range"].attrs.update(
        long_name="1: a criterion's storms left the soil model's range (z > D/2)",
        units="1",
        flag_values="0 1",
        flag_meanings="in_range out_of_range",
    )
    return annotate(ds)


def _criterion_variables(data, c, idx, soils, ns, ms, ks, s) -> None:
    """Stage of :func:`_to_dataset`: the variables of criterion ``c`` over (soil, N, M, K)
    (and per seed with the statistic ``"fractile"``), added to ``data``."""
    shape = (len(soils), len(ns), len(ms), len(ks))
    arrs = {name: np.full(shape, np.nan) for name in (*POINT_FIELDS, "out_of_range")}
    for a, so in enumerate(soils):
        for b, n in enumerate(ns):
            for i, m in enumerate(ms):
                for j, k in enumerate(ks):
                    r = idx[(so, n, m, k, c)]
                    for name in arrs:
                        arrs[name][a, b, i, j] = r.get(name, 0)
    dims = ("soil", "N", "M", "K")
    data[c] = (dims, arrs["L"])
    data[f"{c}_over_2_plus_M_squared"] = (
        dims,
        arrs["L"] / (2.0 + np.asarray(ms))[None, None, :, None] ** 2,
    )
    data[f"{c}_bracket_low"] = (dims, arrs["L_low"])
    data[f"{c}_bracket_high"] = (dims, arrs["L_high"])
    data[f"{c}_bracket_width"] = (dims, arrs["bracket_width"])
    data[f"{c}_converged"] = (dims, np.nan_to_num(arrs["converged"]).astype(np.int8))
    for name in POINT_FIELDS:
        if name.startswith("seed_"):
            data[f"{c}_{name}"] = (dims, arrs[name])
    data[f"{c}_evaluations"] = (dims, arrs["evaluations"])
    data[f"{c}_storms"] = (dims, arrs["storms"])
    data[f"{c}_runtime"] = (dims, arrs["runtime_s"])
    data[f"{c}_out_of_range"] = (dims, (arrs["out_of_range"] > 0).astype(np.int8))
    if s.statistic == "fractile":
        _per_seed_variables(data, c, idx, soils, ns, ms, ks, s)


def _run_attributes(rows, s, wall, workers) -> dict[str, Any]:
    """Stage of :func:`_to_dataset`: the provenance and totals of the run (storms, times,
    failures, points without a crossing, the statistic)."""
    failures = [
        {k2: r[k2] for k2 in ("soil", "K", "M", "N", "criterion", "message")}
        for r in rows
        if r["error"]
    ]
    no_crossing = [
        {k2: r[k2] for k2 in ("soil", "K", "M", "N", "criterion", "message")}
        for r in rows
        if not r["success"] and not r["error"]
    ]
    total_storms = int(sum(r["storms"] for r in rows))
    busy = float(sum(r["runtime_s"] for r in rows))
    cpu = float(sum(r["cpu_s"] for r in rows))
    return provenance(
        "stability_curves",
        {k2: (v.describe() if k2 == "force_model" else v) for k2, v in s.__dict__.items()},
        total_storms=total_storms,
        wall_time_s=wall,
        busy_time_s=busy,
        cpu_time_s=cpu,
        workers=workers,
        storms_per_hour=total_storms / wall * 3600.0 if wall > 0 else math.nan,
        failures=failures,
        no_crossing=no_crossing,
        method=(
            "per-seed bisections in log L of each storm's max |y|, reported as a fractile"
            " and the median over the seeds (onbottom.study.stability_curves)"
            if s.statistic == "fractile"
            else "bisection in log L of the seed-averaged max |y| of storms"
            " (onbottom.study.stability_curves)"
        ),
        statistic=s.statistic,
        statistic_description=STATISTICS[s.statistic],
        seeds=int(s.seeds),
        **(
            {
                "fractile": float(s.fractile),
                "quantile_method": QUANTILE_METHOD,
                "early_stop": int(bool(s.early_stop)),
                "stopped_early": int(sum(r.get("stopped_early", 0) for r in rows)),
            }
            if s.statistic == "fractile"
            else {}
        ),
    )


def _describe_variables(ds, c, s) -> None:
    """Stage of :func:`_to_dataset`: long names, units and flags of criterion ``c``'s
    variables."""
    ds[c].attrs.update(
        long_name=f"weight parameter L = w_s/(0.5 rho_w D U_s^2) at {CRITERIA[c]:g}D: "
        + (
            f"the {s.fractile:g} fractile over {s.seeds} seeds of each seed's own L"
            if s.statistic == "fractile"
            else f"L of the mean over {s.seeds} seeds of the max |y| (mean of maxima)"
        ),
        units="1",
        statistic=s.statistic,
    )
    ds[f"{c}_out_of_range"].attrs.update(
        long_name=f"1: storms deciding {c} buried the pipe beyond the soil model's range",
        units="1",
        flag_values="0 1",
        flag_meanings="in_range out_of_range",
    )
    ds[f"{c}_converged"].attrs.update(
        long_name=f"1 if the bracket of {c} is within the tolerance asked for"
        f" (relative width <= {s.tolerance:g}); 0: not converged, L is not reported",
        units="1",
    )
    ds[f"{c}_bracket_width"].attrs.update(
        long_name=f"relative width L_high/L_low - 1 of the final bracket of {c}", units="1"
    )
    for end in ("low", "high"):
        for stat in ("mean", "min", "max"):
            ds[f"{c}_seed_{stat}_{end}"].attrs.update(
                long_name=(
                    f"{stat} over the seeds of max |y|/D at the {end} end of each seed's own"
                    f" bracket of {c}"
                    + (
                        " (storms stopped early at the criterion count with the criterion)"
                        if end == "low" and s.early_stop
                        else ""
                    )
                    if s.statistic == "fractile"
                    else f"{stat} over the seeds run of max |y|/D at the {end} end of the"
                    f" bracket of {c}"
                ),
                units="1",
            )


def curve_statistic(ds: xr.Dataset) -> dict[str, Any]:
    """Which statistic a curve dataset holds: ``{"statistic", "seeds", "fractile", "label"}``.

    Files written before the per-seed statistic have no ``statistic`` attribute: they hold the
    mean of maxima (``"mean_of_maxima"``); their seed count is read from the ``parameters``
    attribute (None if absent). ``label`` says it in words for tables and figures.
    """
    import json

    name = str(ds.attrs.get("statistic", "mean_of_maxima"))
    seeds = ds.attrs.get("seeds")
    if seeds is None:
        try:
            seeds = json.loads(ds.attrs.get("parameters", "{}")).get("seeds")
        except (TypeError, ValueError):
            seeds = None
    seeds = None if seeds is None else int(seeds)
    fractile = float(ds.attrs["fractile"]) if "fractile" in ds.attrs else None
    over = f" over {seeds} seeds" if seeds is not None else ""
    if name == "fractile":
        label = f"{fractile:g} fractile (and median){over} of each seed's own L"
        if int(ds.attrs.get("early_stop", 0)):
            label += "; storms stopped once their verdict was known"
    else:
        label = (
            f"mean of maxima{over}: L of the seed-averaged max |y| (former statistic; a single"
            " runaway seed can dominate it)"
        )
    return {"statistic": name, "seeds": seeds, "fractile": fractile, "label": label}


def curves_table(ds: xr.Dataset, *, per_seed: bool = False) -> list[dict[str, Any]]:
    """Rows soil, N, M, K, L_stable, L_10 and their L/(2 + M)² forms, and per criterion its
    bracket (``_L_low``, ``_L_high``, ``_bracket_width``), ``_converged`` and the seeds' spread
    at both ends of the bracket (``_seed_mean/min/max_low/high``, max |y|/D), ``_evaluations``,
    ``_storms``, ``_runtime_s``, ``<criterion>_out_of_range`` (1: storms deciding the point
    left the soil model's range), ``_median`` (the median of the per-seed L; NaN in a file of
    the mean-of-maxima statistic), ``_stopped_early`` (storms stopped once their verdict was
    known), ``_seeds_no_crossing``, and the row's ``statistic`` and ``seeds``
    (:func:`curve_statistic`) (for CSV and JSON). Both the per-seed and the former
    (mean-of-maxima, no seed dimension) files are read.

    ``per_seed``: add ``<criterion>_per_seed``, the list of each seed's L (JSON; not for CSV).
    """
    rows = []
    crits = [c for c in CRITERIA if c in ds]
    stat = curve_statistic(ds)
    for so in ds["soil"].values:
        for n in ds["N"].values:
            for m in ds["M"].values:
                for k in ds["K"].values:
                    row: dict[str, Any] = {
                        "soil": str(so),
                        "N": float(n),
                        "M": float(m),
                        "K": float(k),
                        "statistic": stat["statistic"],
                        "seeds": stat["seeds"],
                    }
                    for c in crits:
                        at = {"soil": so, "N": n, "M": m, "K": k}
                        v = float(ds[c].sel(**at))
                        row[c] = v
                        row[f"{c}/(2+M)^2"] = v / (2.0 + float(m)) ** 2
                        key = f"{c}_out_of_range"
                        row[key] = int(ds[key].sel(soil=so, N=n, M=m, K=k)) if key in ds else 0
                        for name in POINT_FIELDS[1:]:
                            var = _VARIABLE.get(name, name)
                            if f"{c}_{var}" in ds:
                                x = ds[f"{c}_{var}"].sel(**at).item()
                                row[f"{c}_{name}"] = bool(x) if name == "converged" else float(x)
                        for name in ("median", "stopped_early", "seeds_no_crossing"):
                            var = f"{c}_{name}"
                            row[var] = float(ds[var].sel(**at).item()) if var in ds else math.nan
                        if per_seed:
                            var = f"{c}_per_seed"
                            row[var] = (
                                [float(x) for x in ds[var].sel(**at).values] if var in ds else []
                            )
                    rows.append(row)
    return rows


def point_summary(row: dict[str, Any]) -> str:
    """One line of a row of :func:`curves_table` (``onbottom curves`` prints one per point):
    per criterion L (and the median of the per-seed L where the file has it), its bracket,
    the seeds' spread (of their L where the row has them, ``per_seed=True``; else of max
    |y|/D at both ends of the bracket), and NOT CONVERGED where the bracket is wider than the
    tolerance."""
    parts = []
    for c in ("L_stable", "L_10"):
        if c not in row:
            continue
        lo, hi = row.get(f"{c}_L_low"), row.get(f"{c}_L_high")
        spread = (
            f"; seeds max|y|/D {row[f'{c}_seed_min_low']:.3g}-{row[f'{c}_seed_max_low']:.3g}"
            f" at L_low, {row[f'{c}_seed_min_high']:.3g}-{row[f'{c}_seed_max_high']:.3g} at"
            " L_high"
            if f"{c}_seed_min_low" in row
            else ""
        )
        median = row.get(f"{c}_median", math.nan)
        med = f", median {median:.3g}" if isinstance(median, float) and median == median else ""
        seeds = [x for x in row.get(f"{c}_per_seed") or [] if x == x]
        if seeds:  # the per-seed L: their spread says more than max |y| at the stops
            spread = f"; seeds' L {min(seeds):.3g}-{max(seeds):.3g}"
        if row.get(f"{c}_converged", True):
            parts.append(
                f"{c} = {row[c]:.3g} [{lo:.3g}, {hi:.3g}]{med}, {c}/(2+M)^2 ="
                f" {row[f'{c}/(2+M)^2']:.3g}{spread}"
            )
        else:
            parts.append(f"{c} NOT CONVERGED (bracket [{lo:.3g}, {hi:.3g}]){med}{spread}")
    return "; ".join(parts)


def _interrupted(kept: int, total: int, store: Any) -> str:
    """The one-line message of an interrupted run."""
    head = f"interrupted after {kept} of {total} points"
    if store is None:
        return head + " (nothing kept: no store)"
    if kept == 0:
        return head + "; run the same command again to start"
    return head + f"; they are kept in {store}: run the same command again to resume"
