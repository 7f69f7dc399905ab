"""Load-controlled rigid pipe-section simulation: m·ü = H(t) − R(u, history).

A rigid section of pipe (per unit length) is loaded by a :class:`LoadProgramme` (H(t), V(t))
and resisted by a lateral soil model behind the kernel contract of :mod:`onbottom.soil.base`.
One numba loop (:mod:`onbottom.dynamics._section_kernel`) integrates the whole programme with
an implicit scheme (backward Euler by default, or Newmark average acceleration), safeguarded
Newton iterations, adaptive sub-stepping, and a terminal event at a displacement limit. Theory,
integrator and convergence evidence: docs/theory/section_dynamics.md.

m is the structural mass plus the hydrodynamic added mass per unit length (the soil and the
water move with the pipe's acceleration; see :func:`section_mass`).
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
from onbottom._validate import one_of, positive
from onbottom.dynamics import _section_kernel as K
from onbottom.dynamics._settings import check_chunks, check_newton, check_steps
from onbottom.dynamics.driver import Recorder, drive, progress_bar
from onbottom.dynamics.programmes import LoadProgramme
from onbottom.dynamics.result import (
    SolverResult,
    penetration_limit,
    penetration_reason,
    records_dataset,
    run_outcome,
)
from onbottom.dynamics.status import Status
from onbottom.errors import InputError
from onbottom.inputs.pipe import Pipe
from onbottom.results import provenance
from onbottom.soil.base import LateralResistanceModel

__all__ = ["SectionResult", "SolverSettings", "section_mass", "simulate_section"]

logger = logging.getLogger(__name__)

_SCHEMES = {"backward_euler": K.SCHEME_BACKWARD_EULER, "newmark": K.SCHEME_NEWMARK}
_AFTER = {
    "stop": K.AFTER_STOP,
    "runaway_end": K.AFTER_RUNAWAY_END,
    "continue": K.AFTER_CONTINUE,
}


def section_mass(pipe: Pipe, added_mass_coefficient: float = 2.29) -> float:
    """Mass per unit length of the moving section m = m_pipe + C_a·ρ_w·π·D²/4 [kg/m].

    Parameters
    ----------
    pipe : Pipe
        The pipe (structural mass: :attr:`Pipe.structural_mass`).
    added_mass_coefficient : float
        C_a [-], >= 0; default 2.29 = π²/3 − 1, a cylinder on a plane wall (DNV-RP-F109
        background; C_M = 1 + C_a = 3.29).
    """
    return pipe.structural_mass + pipe.added_mass(added_mass_coefficient)


@dataclass(frozen=True, kw_only=True, slots=True)
class SolverSettings:
    """Settings of :func:`simulate_section`.

    Parameters
    ----------
    integrator : {"backward_euler", "newmark"}
        Implicit scheme. Backward Euler (default) is L-stable: it damps the spurious
        high-frequency ringing of stick phases (stiff mobilisation springs) at steps far longer
        than their period. "newmark" is the average-acceleration rule (second order, no
        numerical damping).
    dt_max : float or None
        Largest time step [s], > 0; None → the programme's median sample interval.
    dt_min : float or None
        Smallest time step [s], > 0; None → dt_max·1e-7.
    max_displacement_increment : float
        Largest |Δu| per accepted step [m], > 0 (resolves the soil model's regions; default
        2 mm, i.e. 0.2% of the 1 m centrifuge pipe diameter and 1/5 of its elastic region).
    force_tolerance : float
        Relative residual tolerance of the Newton iterations [-], in (0, 1e-3].
    max_iterations : int
        Newton/bisection iterations per step, >= 5.
    chunks : int
        Number of chunks of the programme duration run between progress updates, >= 1.
    """

    integrator: str = "backward_euler"
    dt_max: float | None = None
    dt_min: float | None = None
    max_displacement_increment: float = 2.0e-3
    force_tolerance: float = 1.0e-10
    max_iterations: int = 80
    chunks: int = 20

    def __post_init__(self) -> None:
        c = "SolverSettings"
        one_of(f"{c}.integrator", self.integrator, _SCHEMES)
        check_steps(c, self.dt_max, self.dt_min)
        positive(f"{c}.max_displacement_increment", self.max_displacement_increment)
        check_newton(c, self.force_tolerance, 1e-3, self.max_iterations, 5)
        check_chunks(c, self.chunks)


@dataclass(frozen=True, kw_only=True)
class SectionResult(SolverResult):
    """Result of :func:`simulate_section` (a :class:`~onbottom.dynamics.result.SolverResult`).

    Attributes
    ----------
    success : bool
        True if the run ended normally (programme end or displacement-limit event).
    status : int
        A :class:`~onbottom.dynamics.status.Status`: 1 end of programme, 2 displacement limit
        (stopped), 5 limit reached and ran on until the pipe stopped (3 in 0.1), −1 step
        failure, −2 soil kernel NaN, −3 the run left the soil model's validity (lift-off:
        V <= 0; penetration beyond D/2 for the Verley & Sotberg sand models; the time series
        is kept, ``success`` is False).
    message : str
        Human-readable status.
    n_steps : int
        Accepted time steps.
    n_rejected : int
        Rejected (halved) steps.
    data : xarray.Dataset
        Time series (dimension ``time``): H, V, y (lateral displacement), y_dot, z
        (penetration), F_friction, F_passive, F_soil,
        work, region, soil_energy_stored, soil_energy_dissipated (their sum is the work done
        on the soil, ∫F_soil du); provenance attributes.
    time_to_limit : float or None
        Time at which |u| first reached the displacement limit [s] (linear interpolation in
        the step), None if never.
    cycles_to_limit : float or None
        The same in load cycles (t/cycle_period) [-], None if never or non-cyclic.
    summary : dict
        initial_penetration, max_penetration [m], final_displacement [m] (y at the end of the
        run), max_abs_displacement [m], final_time [s].
    """

    success: bool
    status: int
    message: str
    n_steps: int
    n_rejected: int
    data: xr.Dataset
    time_to_limit: float | None
    cycles_to_limit: float | None
    summary: dict[str, float] = field(default_factory=dict)


STATUS_OUTSIDE_VALIDITY = int(Status.OUTSIDE_VALIDITY)
"""Status of a run that left its soil model's validity (e.g. penetration > D/2)."""


_REC_NAMES = {
    "H": K.REC_H,
    "V": K.REC_V,
    "y": K.REC_U,  # lateral displacement (0.1: "u"; docs/conventions.md)
    "y_dot": K.REC_UDOT,
    "z": K.REC_W,  # penetration (0.1: "w")
    "F_friction": K.REC_FF,
    "F_passive": K.REC_FP,
    "F_soil": K.REC_FS,
    "work": K.REC_WORK,
    "region": K.REC_REGION,
    "soil_energy_stored": K.REC_E_STORED,
    "soil_energy_dissipated": K.REC_E_DISSIPATED,
}
"""Recorded variables: kernel column of each."""


def simulate_section(
    programme: LoadProgramme,
    soil: LateralResistanceModel,
    *,
    mass: float,
    displacement_limit: float | None = None,
    after_limit: str = "stop",
    settings: SolverSettings | None = None,
    progress: bool = False,
    attrs: Mapping[str, Any] | None = None,
) -> SectionResult:
    """Simulate a rigid pipe section under a load-controlled programme.

    Parameters
    ----------
    programme : LoadProgramme
        H(t), V(t) [N/m]; the run starts at ``programme.time[0]`` with u = 0, at rest.
    soil : LateralResistanceModel
        Lateral soil model; its :meth:`initial_state` is the state at the start (e.g. the
        penetration after installation).
    mass : float
        Mass per unit length of the moving section m [kg/m], > 0 (see :func:`section_mass`).
    displacement_limit : float or None
        |u| at which the run stops (terminal event) [m], > 0; None = no limit.
    after_limit : {"stop", "runaway_end", "continue"}
        What happens at the limit: stop there; run on until the pipe's velocity first returns
        to zero or reverses (the end of the runaway, to compare with a simulation that had no
        box limit); or continue to the end of the programme.
    settings : SolverSettings or None
        Integrator settings (defaults if None).
    progress : bool
        Show a tqdm progress bar over chunks of the programme duration.
    attrs : mapping or None
        Extra provenance attributes for the dataset.

    Returns
    -------
    SectionResult
    """
    m, u_lim, s, dt_max, dt_min = _checked(
        programme, soil, mass, displacement_limit, after_limit, settings
    )
    st = _settings_array(s, dt_max, dt_min, u_lim, after_limit, m)
    pt = np.ascontiguousarray(programme.time, dtype=float)
    dyn = np.zeros(K.N_DYN)
    dyn[K.D_T] = pt[0]
    dyn[K.D_DT] = dt_max
    status, recorder = _integrate(programme, soil, s, st, dyn, progress)
    n = recorder.n
    rec = recorder.records()
    t_cross = float(dyn[K.D_T_CROSS]) if dyn[K.D_CROSSED] == 1.0 else None
    cycles = None
    if t_cross is not None and programme.cycle_period is not None:
        cycles = (t_cross - float(pt[0])) / programme.cycle_period
    u = rec[:, K.REC_U]
    w = rec[:, K.REC_W]
    outside = _outside_validity(programme, soil, rec)
    limit = status in (K.STATUS_LIMIT, K.STATUS_RUNAWAY_END) and t_cross is not None
    detail = f"|y| = {u_lim:.4g} m at t = {t_cross:.4g} s" if limit else ""
    success, status, message = run_outcome(
        logger, status, run="load programme", t=dyn[K.D_T], dt_min=dt_min, detail=detail,
        outside=outside,
    )  # fmt: skip
    summary = {
        "initial_penetration": float(w[0]),
        "max_penetration": float(np.max(w)),
        "final_displacement": float(u[-1]),
        "max_abs_displacement": float(np.max(np.abs(u))),
        "final_time": float(rec[-1, K.REC_T]),
    }
    prov = provenance(
        "simulate_section",
        {"soil_model": soil.name, **dict(soil.parameters())},
        programme=programme.name,
        programme_builder=dict(programme.metadata),
        installation_load=programme.peak_vertical_load,
        cycle_period=programme.cycle_period if programme.cycle_period is not None else "none",
        mass=m,
        displacement_limit=u_lim if math.isfinite(u_lim) else "none",
        after_limit=after_limit,
        integrator=s.integrator,
        dt_max=dt_max,
        max_displacement_increment=s.max_displacement_increment,
        status=int(status),
        message=message,
        soil_reference=soil.reference,
        **(dict(attrs) if attrs else {}),
    )
    if cycles is not None:
        prov["cycles_to_limit"] = cycles
    data = records_dataset(rec, _REC_NAMES, K.REC_T, prov)
    return SectionResult(
        success=bool(success),
        status=int(status),
        message=message,
        n_steps=n - 1,
        n_rejected=int(dyn[K.D_N_REJECT]),
        data=data,
        time_to_limit=t_cross,
        cycles_to_limit=cycles,
        summary=summary,
    )


def _checked(programme, soil, mass, displacement_limit, after_limit, settings):
    """Stage of :func:`simulate_section`: the inputs checked; (m, |u| limit, settings,
    dt_max, dt_min)."""
    if not isinstance(programme, LoadProgramme):
        raise InputError(f"programme = {type(programme).__name__} is invalid: need LoadProgramme")
    if not isinstance(soil, LateralResistanceModel):
        raise InputError(f"soil = {type(soil).__name__} is invalid: need LateralResistanceModel")
    m = positive("mass", mass)
    u_lim = (
        math.inf
        if displacement_limit is None
        else positive("displacement_limit", displacement_limit)
    )
    one_of("after_limit", after_limit, _AFTER)
    s = settings if settings is not None else SolverSettings()
    dt_max = s.dt_max if s.dt_max is not None else programme.sample_interval
    dt_min = s.dt_min if s.dt_min is not None else dt_max * 1e-7
    if dt_min > dt_max:
        raise InputError(
            f"SolverSettings.dt_min = {dt_min!r} is invalid: must be <= dt_max = {dt_max!r}"
        )
    return m, u_lim, s, dt_max, dt_min


def _settings_array(s, dt_max, dt_min, u_lim, after_limit, m):
    """Stage of :func:`simulate_section`: the kernel's settings buffer (``ST_*``)."""
    st = np.zeros(K.N_SETTINGS)
    st[K.ST_SCHEME] = _SCHEMES[s.integrator]
    st[K.ST_DT_MAX] = dt_max
    st[K.ST_DT_MIN] = dt_min
    st[K.ST_DU_MAX] = s.max_displacement_increment
    st[K.ST_RTOL] = s.force_tolerance
    st[K.ST_MAX_ITER] = s.max_iterations
    st[K.ST_U_LIMIT] = u_lim
    st[K.ST_AFTER_LIMIT] = _AFTER[after_limit]
    st[K.ST_GAMMA] = 0.5
    st[K.ST_BETA] = 0.25
    st[K.ST_MASS] = m
    return st


def _integrate(programme, soil, s, st, dyn, progress):
    """Stage of :func:`simulate_section`: the kernel's loop over the programme in chunks (the
    progress bar's), from the first record; (status, recorder)."""
    pt = np.ascontiguousarray(programme.time, dtype=float)
    ph = np.ascontiguousarray(programme.horizontal_load, dtype=float)
    pv = np.ascontiguousarray(programme.vertical_load, dtype=float)
    params = np.ascontiguousarray(soil.packed_parameters(), dtype=float)
    state = np.array(soil.initial_state(), dtype=float)
    model_id = int(soil.model_id)
    cap = int(min(max(4 * pt.size, 4096), 5_000_000))
    rec = np.empty((cap, K.N_REC))
    call_literal(K.initial_record, 1, model_id, params, state, dyn, pt, ph, pv, st, rec, 0)
    t_end = float(pt[-1])
    chunk = (t_end - pt[0]) / int(s.chunks)
    recorder = Recorder(rec, 1)
    with progress_bar(progress, int(s.chunks), programme.name, "chunk") as bar:
        status = drive(
            lambda t_stop, rows, n0: call_literal(
                K.integrate, 1, model_id, params, state, dyn, pt, ph, pv, st, t_stop, rows, n0
            ),
            lambda k: pt[0] + k * chunk if k < int(s.chunks) else t_end,
            recorder=recorder,
            bar=bar,
        )
    return status, recorder


def _outside_validity(programme, soil, rec) -> str | None:
    """Stage of :func:`simulate_section`: why the run left the soil models' validity (lift-off:
    the programme's or a step's V <= 0; penetration beyond :func:`penetration_limit`), or
    None."""
    u = rec[:, K.REC_U]
    w = rec[:, K.REC_W]
    # lift-off: the vertical load of the programme (up to the end of the run) or of a step
    t_end = float(rec[-1, K.REC_T]) if len(rec) else 0.0
    tp = np.asarray(programme.time, float)
    vp = np.asarray(programme.vertical_load, float)[tp <= t_end + 1e-12]
    tp = tp[tp <= t_end + 1e-12]
    v_all = np.concatenate([vp, rec[:, K.REC_V]])
    t_all = np.concatenate([tp, rec[:, K.REC_T]])
    z_lim = penetration_limit(soil)
    if v_all.size and float(np.min(v_all)) <= 0.0:
        i = int(np.argmin(v_all))
        return (
            f"lift-off, the vertical load falls to {float(v_all[i]):.4g} N/m at t ="
            f" {float(t_all[i]):.4g} s; the soil models hold for a pipe resting on the seabed,"
            " V > 0"
        )
    if float(np.max(w)) > z_lim:
        i = int(np.argmax(w > z_lim))  # the first row beyond D/2
        return penetration_reason(
            z_lim,
            float(rec[i, K.REC_T]),
            f"y = {float(u[i]):.4g} m",
            float(np.max(w)),
            2.0 * z_lim,
            f"the {soil.name} model",
        )
    return None
