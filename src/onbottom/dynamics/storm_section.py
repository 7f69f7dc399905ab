"""Dynamic on-bottom stability of a rigid pipe section in a storm (loads fed back by motion).

The storm's near-bed flow (:func:`onbottom.hydro.storm_kinematics.storm_kinematics`) drives a
rigid section through a pluggable hydrodynamic force model
(:class:`onbottom.hydro.force_model.MorisonLift` by default): Morison drag with the relative
velocity U + V − ẏ, inertia on the flow acceleration, added mass on the pipe's acceleration,
lift F_Z reducing the contact force V(t) = w_s − F_Z(t) that drives the soil model every step,
and the DNV-RP-F109 reductions r_perm,z, r_tr and r_pen updated from the soil's current
penetration. One numba loop (:mod:`onbottom.dynamics._storm_kernel`) integrates the storm with
implicit Newmark steps, the drag tangent inside the Newton iteration, step cut-back and growth,
lift-off and runaway events. Theory: docs/theory/storm_section.md.

F109 dynamic criteria (DNV-RP-F109 (2017) §3.5, dynamic lateral stability analysis): lateral
displacement <= 0.5D ("virtually stable") and <= 10D.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import xarray as xr

from onbottom._jit import call_literal
from onbottom._validate import in_range, non_negative, one_of, positive
from onbottom.dynamics import _storm_kernel as K
from onbottom.dynamics._settings import check_chunks, check_newton, check_steps
from onbottom.dynamics.driver import Recorder, drive, progress_bar
from onbottom.dynamics.result import (
    CRITERIA_OVER_D,
    SolverResult,
    dynamic_criteria,
    penetration_limit,
    penetration_reason,
    records_dataset,
    run_outcome,
)
from onbottom.dynamics.section import STATUS_OUTSIDE_VALIDITY
from onbottom.errors import InputError
from onbottom.hydro.force_model import N_FORCE_STATE, ForceModel, MorisonLift, parameter_rows
from onbottom.hydro.reductions import LoadReductions
from onbottom.hydro.storm_kinematics import StormKinematics, storm_kinematics
from onbottom.inputs import consistency
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.storm import Current, Storm
from onbottom.results import provenance
from onbottom.soil.base import LateralResistanceModel

__all__ = [
    "CRITERIA_OVER_D",
    "STATUS_OUTSIDE_VALIDITY",
    "LoadReductions",
    "StormSectionResult",
    "StormSolverSettings",
    "penetration_limit",
    "simulate_storm_section",
]

logger = logging.getLogger(__name__)

_LIFTOFF = {"free": K.LIFTOFF_FREE, "stop": K.LIFTOFF_STOP}


@dataclass(frozen=True, kw_only=True, slots=True)
class StormSolverSettings:
    """Settings of :func:`simulate_storm_section`.

    Parameters
    ----------
    dt_max : float
        Initial and largest time step [s], > 0 (default 0.1 s ≈ T_u/100 for T_u ≈ 10 s).
    dt_min : float or None
        Smallest step [s], > 0; None → dt_max·1e-6.
    max_displacement_increment_over_d : float
        Largest |Δy|/D per accepted step [-], > 0 (resolves the soil model's regions).
    force_tolerance : float
        Relative residual tolerance of the Newton iterations [-], in (0, 1e-3].
    max_iterations : int
        Newton/bisection iterations per step, >= 5.
    newmark_gamma, newmark_beta : float
        Newmark parameters; default ½, ¼ (average acceleration: second order, energy
        conserving). γ > ½ adds numerical damping (first order).
    stop_displacement_over_d : float
        |y|/D at which the run stops as a runaway [-], > 0 (default 10, the F109 L_10 limit).
    liftoff : {"free", "stop"}
        At V <= 0 the pipe is free of soil while lifted ("free") or the run stops.
    record_interval : float or None
        Time between recorded rows [s], >= 0; 0 → every step; None → no records (summary only;
        the fast path for seeds and sweeps).
    chunks : int
        Chunks of the storm between progress updates, >= 1.
    """

    dt_max: float = 0.1
    dt_min: float | None = None
    max_displacement_increment_over_d: float = 0.05
    force_tolerance: float = 1.0e-9
    max_iterations: int = 60
    newmark_gamma: float = 0.5
    newmark_beta: float = 0.25
    stop_displacement_over_d: float = 10.0
    liftoff: str = "free"
    record_interval: float | None = 0.0
    chunks: int = 20

    def __post_init__(self) -> None:
        c = "StormSolverSettings"
        check_steps(c, self.dt_max, self.dt_min)
        positive(f"{c}.max_displacement_increment_over_d", self.max_displacement_increment_over_d)
        check_newton(c, self.force_tolerance, 1e-3, self.max_iterations, 5)
        in_range("StormSolverSettings.newmark_gamma", self.newmark_gamma, 0.5, 1.0)
        in_range(
            "StormSolverSettings.newmark_beta",
            self.newmark_beta,
            0.25 * (self.newmark_gamma + 0.5) ** 2 - 1e-12,
            0.5,
        )
        positive("StormSolverSettings.stop_displacement_over_d", self.stop_displacement_over_d)
        one_of("StormSolverSettings.liftoff", self.liftoff, _LIFTOFF)
        if self.record_interval is not None:
            non_negative("StormSolverSettings.record_interval", self.record_interval)
        check_chunks(c, self.chunks)


@dataclass(frozen=True, kw_only=True)
class StormSectionResult(SolverResult):
    """Result of :func:`simulate_storm_section` (a :class:`.result.SolverResult`).

    Attributes
    ----------
    success : bool
        True if the run ended normally: end of storm, runaway stop or lift-off stop (the
        physical outcomes); False on numerical failure.
    status : int
        A :class:`~onbottom.dynamics.status.Status`: 1 end of storm, 2 runaway (stop limit
        reached), 3 lift-off stop, −1 step failure, −2 soil kernel NaN, −3 the run left the
        soil model's range (penetration beyond :func:`penetration_limit`, D/2 for Verley &
        Sotberg / Verley & Lund): the run went on to its end (or stop) and its numbers are
        kept, ``success`` is False and the message says when and where (as
        :func:`onbottom.dynamics.section.simulate_section`).
    message : str
    diameter : float
        D [m].
    max_displacement : float
        max |y| [m] over the run.
    final_displacement : float
        y at the end of the run [m].
    criteria : dict
        {"0.5D": bool, "10D": bool}: True if max |y| <= limit·D (and the run did not stop on a
        runaway beyond it).
    summary : dict
        n_steps, n_rejected, time_of_max [s], final_time [s], max_penetration [m],
        min_penetration [m], out_of_range_time [s] (first time the penetration exceeded
        :func:`penetration_limit`, −1 if never), out_of_range_displacement [m] (y then),
        penetration_limit [m], n_liftoff, first_liftoff_time [s] (−1 if none), min_contact_force
        [N/m], max_lift [N/m], work_hydro [J/m], work_soil [J/m], kinetic_energy [J/m],
        mean_newton_iterations.
    data : xarray.Dataset or None
        Time series (dimension ``time``): y, y_dot, z, F_hydro, F_Z, V, F_friction,
        F_passive, F_soil, work_hydro, work_soil, U, r_y, r_z, region; None without records.
    """

    success: bool
    status: int
    message: str
    diameter: float
    max_displacement: float
    final_displacement: float
    criteria: dict[str, bool]
    summary: dict[str, float] = field(default_factory=dict)
    data: xr.Dataset | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (keys of ``onbottom storm --json``)."""
        return {
            "max_displacement_m": self.max_displacement,
            "final_displacement_m": self.final_displacement,
            "max_displacement_over_D": self.max_displacement / self.diameter,
            "criteria": dict(self.criteria),
            "status": self.status,
            "success": self.success,
            "message": self.message,
            "summary": dict(self.summary),
        }


_REC_NAMES = {
    "y": K.REC_Y,
    "y_dot": K.REC_YD,
    "z": K.REC_Z,
    "F_hydro": K.REC_FY,
    "F_Z": K.REC_FZ,
    "V": K.REC_V,
    "F_friction": K.REC_FF,
    "F_passive": K.REC_FP,
    "F_soil": K.REC_R,
    "work_hydro": K.REC_W_HYDRO,
    "work_soil": K.REC_W_SOIL,
    "U": K.REC_U,
    "r_y": K.REC_RY,
    "r_z": K.REC_RZ,
    "region": K.REC_REGION,
}


def simulate_storm_section(
    pipe: Pipe,
    soil: LateralResistanceModel,
    storm: Storm | StormKinematics,
    *,
    depth: float | None = None,
    current: Current | None = None,
    z0: float | None = None,
    sample_interval: float | None = None,
    force_model: ForceModel | None = None,
    reductions: LoadReductions | None = None,
    settings: StormSolverSettings | None = None,
    progress: bool = False,
    attrs: Mapping[str, Any] | None = None,
) -> StormSectionResult:
    """Simulate a rigid pipe section on the seabed through a storm.

    Parameters
    ----------
    pipe : Pipe
        D, w_s and the structural mass (contents included).
    soil : LateralResistanceModel
        Lateral soil model (Coulomb, Verley & Sotberg, Verley & Lund); its initial state is
        the as-laid penetration.
    storm : Storm or StormKinematics
        The storm (synthesised here with ``depth``, ``current``, ``z0``) or its precomputed
        kinematics (then ``depth``/``current`` are ignored).
    depth : float or None
        Water depth [m], > D (the pipe's outer diameter) and with every stage below breaking
        (:mod:`onbottom.inputs.consistency`); needed with a :class:`Storm`.
    current : Current or None
        Steady current.
    z0 : float or None
        Seabed roughness [m] when ``current.z0`` is None.
    sample_interval : float or None
        Flow sample interval [s] of the synthesis (None → min T_p/50).
    force_model : ForceModel or None
        Default :class:`~onbottom.hydro.force_model.MorisonLift` (C_D 0.7, C_M 3.29, C_L 0.9).
    reductions : LoadReductions or None
        Default: permeable seabed, penetration reductions, no trench.
    settings : StormSolverSettings or None
    progress : bool
        tqdm progress bar over chunks of the storm.
    attrs : mapping or None
        Extra provenance attributes.
    """
    fm, red, s = _checked_models(pipe, soil, force_model, reductions, settings)
    d = pipe.outer_diameter
    kin, storm_obj = _kinematics(storm, pipe, depth, current, z0, sample_interval)
    st, mass, dt_min = _settings_array(pipe, fm, red, s, kin)
    z_lim = penetration_limit(soil)
    st[K.ST_Z_LIMIT] = z_lim
    dyn = np.zeros(K.N_DYN)
    dyn[K.D_DT] = s.dt_max
    status, recorder = _integrate(soil, fm, s, kin, st, dyn, progress)

    ymax = float(dyn[K.D_YMAX])
    # a runaway stop, even one flagged outside the model's validity below, meets no criterion
    # at or above its stop limit
    criteria = dynamic_criteria(
        ymax, d, s.stop_displacement_over_d, stopped=status == K.STATUS_LIMIT
    )
    t_out = float(dyn[K.D_T_ZLIMIT])
    limit = f"{s.stop_displacement_over_d:g}D at t = {dyn[K.D_T_LIMIT]:.1f} s"
    outside = None
    if t_out >= 0.0:
        y_out = f"y = {dyn[K.D_Y_ZLIMIT]:.4g} m"
        model = f"the {soil.name} model"
        outside = penetration_reason(z_lim, t_out, y_out, float(dyn[K.D_ZMAX]), d, model)
    success, status, message = run_outcome(
        logger,
        status,
        run="storm",
        t=float(dyn[K.D_T]),
        dt_min=dt_min,
        detail=limit if status == K.STATUS_LIMIT else "",
        outside=outside,
    )
    summary = _summary(dyn, mass, z_lim)
    if summary["n_liftoff"] > 0 and status != K.STATUS_LIFTOFF:
        message += f"; lift-off {summary['n_liftoff']} time(s), pipe free of soil while lifted"
    data = None
    if s.record_interval is not None:
        data = _records(recorder, pipe, soil, fm, red, s, kin, storm_obj, mass, ymax, criteria,
                        status, message, t_out, attrs)  # fmt: skip
    return StormSectionResult(
        success=bool(success),
        status=int(status),
        message=message,
        diameter=pipe.outer_diameter,
        max_displacement=ymax,
        final_displacement=float(dyn[K.D_Y]),
        criteria=criteria,
        summary=summary,
        data=data,
    )


def _checked_models(pipe, soil, force_model, reductions, settings):
    """Stage of :func:`simulate_storm_section`: the pipe and soil checked, the force model,
    reductions and settings with their defaults."""
    if not isinstance(pipe, Pipe):
        raise InputError(f"pipe = {type(pipe).__name__} is invalid: expected Pipe")
    if not isinstance(soil, LateralResistanceModel):
        raise InputError(f"soil = {type(soil).__name__} is invalid: need LateralResistanceModel")
    fm = force_model if force_model is not None else MorisonLift()
    if not isinstance(fm, ForceModel):
        raise InputError(
            f"force_model = {type(fm).__name__} is invalid: expected a ForceModel"
            " (name, model_id, added_mass_coefficient, parameter_table, describe)"
        )
    red = reductions if reductions is not None else LoadReductions()
    s = settings if settings is not None else StormSolverSettings()
    return fm, red, s


def _kinematics(storm, pipe, depth, current, z0, sample_interval):
    """Stage of :func:`simulate_storm_section`: the storm's kinematics (given, or synthesised
    after the consistency rules of the depth and sea states); (kinematics, storm or None)."""
    if isinstance(storm, StormKinematics):
        return storm, None
    if not isinstance(storm, Storm):
        raise InputError(f"storm = {type(storm).__name__} is invalid: expected Storm")
    d = pipe.outer_diameter
    if depth is None:
        raise InputError("depth = None is invalid: the water depth [m] is needed")
    consistency.scalar("depth", depth)
    consistency.scalar("z0", z0)
    consistency.scalar("sample_interval", sample_interval)
    # errors only: the case files report the warnings of these rules with file and line
    found = consistency.depth_and_diameter(depth, d, depth_field="depth")
    for i, stage in enumerate(storm.stages):
        found += consistency.sea_state(
            stage.hs,
            stage.tp,
            depth,
            hs_field=f"storm.stages[{i}].hs",
            tp_field=f"storm.stages[{i}].tp",
            depth_field="depth",
        )
    consistency.raise_first(found)
    kin = storm_kinematics(
        storm, depth, diameter=d, current=current, z0=z0, sample_interval=sample_interval
    )
    return kin, storm


def _settings_array(pipe, fm, red, s, kin):
    """Stage of :func:`simulate_storm_section`: the kernel's settings buffer (``ST_*``),
    the mass m + m_a [kg/m] and dt_min [s]."""
    d = pipe.outer_diameter
    rho = pipe.seawater_density
    ca = fm.added_mass_coefficient
    mass = pipe.structural_mass + ca * rho * math.pi * d * d / 4.0
    ry_c, rz_c = red.constant_factors()
    dt_min = s.dt_min if s.dt_min is not None else s.dt_max * 1e-6
    st = np.zeros(K.N_SETTINGS)
    st[K.ST_DT_MAX] = s.dt_max
    st[K.ST_DT_MIN] = dt_min
    st[K.ST_DU_MAX] = s.max_displacement_increment_over_d * d
    st[K.ST_RTOL] = s.force_tolerance
    st[K.ST_MAX_ITER] = s.max_iterations
    st[K.ST_Y_LIMIT] = s.stop_displacement_over_d * d
    st[K.ST_MASS] = mass
    st[K.ST_GAMMA] = s.newmark_gamma
    st[K.ST_BETA] = s.newmark_beta
    st[K.ST_RHO] = rho
    st[K.ST_D] = d
    st[K.ST_WS] = pipe.submerged_weight
    st[K.ST_RY_CONST] = ry_c
    st[K.ST_RZ_CONST] = rz_c
    st[K.ST_USE_PEN] = 1.0 if red.penetration else 0.0
    st[K.ST_LIFTOFF] = _LIFTOFF[s.liftoff]
    st[K.ST_REC_INTERVAL] = s.record_interval if s.record_interval is not None else math.inf
    st[K.ST_CURRENT] = kin.current
    st[K.ST_DTS] = kin.sample_interval
    st[K.ST_T_END] = kin.duration
    st[K.ST_FORCE_MODEL] = fm.model_id
    return st, mass, dt_min


def _integrate(soil, fm, s, kin, st, dyn, progress):
    """Stage of :func:`simulate_storm_section`: the kernel's loop over the storm in chunks
    (the progress bar's), from the initial state; (status, recorder)."""
    d = float(st[K.ST_D])
    fparams = parameter_rows(fm, kin.weights, kin.stage_parameters, kin.current, d)
    fstate = np.zeros(N_FORCE_STATE)
    params = np.ascontiguousarray(soil.packed_parameters(), dtype=float)
    state = np.array(soil.initial_state(), dtype=float)
    model_id = int(soil.model_id)
    force_id = int(fm.model_id)
    ku = np.ascontiguousarray(kin.velocity, dtype=float)
    ka = np.ascontiguousarray(kin.acceleration, dtype=float)
    if s.record_interval is None:
        rec = np.empty((0, K.N_REC))
    else:
        per = max(s.record_interval, s.dt_max)
        cap = int(min(kin.duration / per * 1.2 + 1024, 2_000_000))
        rec = np.empty((cap, K.N_REC))
    start = (params, state, st, fparams, fstate, ku, ka, dyn, 0.0, rec, -1)  # n0 < 0: the start
    recorder = Recorder(rec, call_literal(K.integrate, 2, model_id, force_id, *start)[0])

    def advance(t_stop, rows, n0):
        args = (params, state, st, fparams, fstate, ku, ka, dyn, t_stop, rows, n0)
        return call_literal(K.integrate, 2, model_id, force_id, *args)

    chunks = int(s.chunks) if progress else 1
    status = K.STATUS_CHUNK
    if s.liftoff == "stop" and dyn[K.D_LIFTED] == 1.0:
        status = K.STATUS_LIFTOFF  # lifted off at the start
    with progress_bar(progress, chunks, "storm", "chunk") as bar:
        status = drive(
            advance,
            lambda k: kin.duration * k / chunks if k < chunks else kin.duration,
            recorder=recorder,
            status=status,
            bar=bar,
        )
    return status, recorder


def _summary(dyn, mass, z_lim) -> dict[str, float]:
    """Stage of :func:`simulate_storm_section`: the run's summary from the kernel's running
    state (:attr:`StormSectionResult.summary`)."""
    t_out = float(dyn[K.D_T_ZLIMIT])
    return {
        "n_steps": int(dyn[K.D_N_STEPS]),
        "n_rejected": int(dyn[K.D_N_REJECT]),
        "time_of_max": float(dyn[K.D_T_YMAX]),
        "final_time": float(dyn[K.D_T]),
        "max_penetration": float(dyn[K.D_ZMAX]),
        "min_penetration": float(dyn[K.D_ZMIN]),
        "out_of_range_time": t_out,
        "out_of_range_displacement": float(dyn[K.D_Y_ZLIMIT]) if t_out >= 0.0 else math.nan,
        "penetration_limit": z_lim,
        "n_liftoff": int(dyn[K.D_N_LIFTOFF]),
        "first_liftoff_time": float(dyn[K.D_T_LIFTOFF]),
        "min_contact_force": float(dyn[K.D_V_MIN]),
        "max_lift": float(dyn[K.D_FZ_MAX]),
        "work_hydro": float(dyn[K.D_W_HYDRO]),
        "work_soil": float(dyn[K.D_W_SOIL]),
        "kinetic_energy": float(0.5 * mass * dyn[K.D_YD] ** 2),
        "mean_newton_iterations": float(dyn[K.D_N_ITER] / max(dyn[K.D_N_STEPS], 1.0)),
        "mass": float(mass),
    }


def _records(recorder, pipe, soil, fm, red, s, kin, storm_obj, mass, ymax, criteria, status,
             message, t_out, attrs) -> xr.Dataset:  # fmt: skip
    """Stage of :func:`simulate_storm_section`: the recorded time series with the run's
    provenance (:attr:`StormSectionResult.data`)."""
    prov = provenance(
        "simulate_storm_section",
        {"soil_model": soil.name, **dict(soil.parameters())},
        diameter=pipe.outer_diameter,
        submerged_weight=pipe.submerged_weight,
        mass=mass,
        seed=int(kin.seed),
        current=kin.current,
        storm=_describe_storm(storm_obj),
        stage_parameters=kin.stage_parameters,
        reductions={
            "permeable_seabed": red.permeable_seabed,
            "penetration": red.penetration,
            "trench_depth_over_d": red.trench_depth_over_d,
            "trench_angle_deg": red.trench_angle_deg,
        },
        dt_max=s.dt_max,
        status=int(status),
        message=message,
        max_displacement=ymax,
        criteria_0_5D=int(criteria["0.5D"]),
        criteria_10D=int(criteria["10D"]),
        out_of_range=int(t_out >= 0.0),
        out_of_range_time=t_out,
        soil_reference=soil.reference,
        **fm.describe(),
        **(dict(attrs) if attrs else {}),
    )
    return records_dataset(recorder.records(), _REC_NAMES, K.REC_T, prov)


def _describe_storm(storm: Storm | None) -> Any:
    if storm is None:
        return "precomputed kinematics"
    return {
        "seed": storm.seed,
        "build_up_s": storm.build_up_s,
        "decay_s": storm.decay_s,
        "transition_s": storm.transition_s,
        "stages": [
            {
                "hs": x.hs,
                "tp": x.tp,
                "gamma": x.peak_enhancement,
                "spectrum": x.spectrum,
                "duration_s": x.duration_s,
                "direction_deg": x.direction_deg,
                "spreading_s": x.spreading_s,
            }
            for x in storm.stages
        ],
    }
