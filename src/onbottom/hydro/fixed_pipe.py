"""Loads of a registered force model on a fixed pipe through a storm's flow, per wave cycle.

What a V–H diagram of a design report plots: the storm's near-bed flow (a
:class:`~onbottom.hydro.storm_kinematics.StormKinematics`, as the storm section synthesises
it) drives the force model that the dynamic level runs (any registered one: its own kernel,
its own parameter rows per sea state, :func:`onbottom.hydro.force_model.parameter_rows`) on a
pipe at rest (ẏ = 0), times the DNV-RP-F109 load reductions r_y, r_z (Eqs 3.17–3.22, given by
the caller at the pipe's penetration). The peak of every wave cycle (between zero up-crossings
of U, at the instant of the largest |F_Y|: :func:`onbottom.hydro.load_envelope.cycle_peak_loads`)
is returned as a :class:`~onbottom.hydro.load_envelope.LoadEnvelope`.
"""

from __future__ import annotations

import math

import numpy as np

from onbottom._jit import call_literal
from onbottom._validate import in_range, positive
from onbottom.errors import InputError
from onbottom.hydro.force_model import ForceModel, parameter_rows
from onbottom.hydro.load_envelope import LoadEnvelope, cycle_peak_loads
from onbottom.hydro.storm_kinematics import StormKinematics

__all__ = ["fixed_pipe_envelope", "fixed_pipe_loads"]


def fixed_pipe_loads(
    force_model: ForceModel,
    kinematics: StormKinematics,
    *,
    diameter: float,
    density: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(t [s], F_Y [N/m], F_Z [N/m]) of ``force_model`` on a fixed pipe at every flow sample,
    before any reduction.

    Parameters
    ----------
    force_model : ForceModel
        A built force model (any registered one).
    kinematics : StormKinematics
        The near-bed flow (velocity, acceleration, current, stage weights).
    diameter : float
        Pipe outer diameter D [m], > 0.
    density : float
        Water density ρ_w [kg/m³], > 0.
    """
    if not isinstance(force_model, ForceModel):
        raise InputError(
            f"force_model = {type(force_model).__name__} is invalid: expected a ForceModel"
        )
    if not isinstance(kinematics, StormKinematics):
        raise InputError(
            f"kinematics = {type(kinematics).__name__} is invalid: expected StormKinematics"
        )
    from onbottom.hydro._fixed_pipe_kernel import fixed_pipe_record

    d = positive("diameter", diameter)
    rho = positive("density", density)
    kin = kinematics
    rows = parameter_rows(force_model, kin.weights, kin.stage_parameters, kin.current, d)
    u = np.ascontiguousarray(kin.velocity, dtype=float)
    a = np.ascontiguousarray(kin.acceleration, dtype=float)
    fy = np.empty_like(u)
    fz = np.empty_like(u)
    call_literal(
        fixed_pipe_record, 1, int(force_model.model_id), rows, float(kin.sample_interval), u, a,
        float(kin.current), d, rho, fy, fz,
    )  # fmt: skip
    return kin.sample_interval * np.arange(u.size), fy, fz


def fixed_pipe_envelope(
    force_model: ForceModel,
    kinematics: StormKinematics,
    *,
    diameter: float,
    submerged_weight: float,
    density: float,
    r_y: float = 1.0,
    r_z: float = 1.0,
    hs: float = math.nan,
    tp: float = math.nan,
) -> LoadEnvelope:
    """Peak loads per wave cycle of :func:`fixed_pipe_loads` times the reductions.

    Parameters
    ----------
    force_model, kinematics, diameter, density
        As :func:`fixed_pipe_loads`.
    submerged_weight : float
        w_s [N/m], > 0 (V = w_s − F_Z).
    r_y, r_z : float
        Load reductions r_tot,y and r_tot,z [-] in [0, 1] (DNV-RP-F109 (2017) Eqs 3.17–3.22).
    hs, tp : float
        H_s [m] and T_p [s] of the storm's peak, recorded on the envelope (NaN: unknown).
    """
    ws = positive("submerged_weight", submerged_weight)
    in_range("r_y", r_y, 0.0, 1.0)
    in_range("r_z", r_z, 0.0, 1.0)
    t, fy, fz = fixed_pipe_loads(force_model, kinematics, diameter=diameter, density=density)
    tc, h, lift = cycle_peak_loads(t, kinematics.velocity, r_y * fy, r_z * fz)
    v = ws - lift
    ang = np.degrees(np.arctan2(h, v))
    return LoadEnvelope(
        tc, h, lift, v, ang, ws, float(kinematics.duration), int(kinematics.seed), hs, tp
    )
