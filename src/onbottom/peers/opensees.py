"""The pipeline FE problem in OpenSees (OpenSeesPy), a standing peer of onbottom's solver.

:func:`run_opensees` builds the same discrete problem as :func:`onbottom.dynamics.pipeline.
simulate_pipeline` for a :class:`~onbottom.dynamics.pipeline.PipelineModel` loaded by a
:class:`~onbottom.dynamics.pipeline.user_load.TravellingSineLoad` in still water:

- ``elasticBeamColumn`` elements (A = EA, E = 1, I = EI) with ``geomTransf Corotational``: the
  same corotational formulation as onbottom's beam (chord length and rotation, the basic
  forces N = EA·(L − L₀)/L₀, M = EI/L₀·[[4, 2], [2, 4]]·θ);
- at every node a ``zeroLength`` element to a fixed ground node with two ``ElasticPP``
  materials: axial E = μ_ax·W_s·ℓ/δ_ax, ε_y = δ_ax and lateral E = μ·W_s·ℓ/δ, ε_y = δ — exactly
  onbottom's :class:`~onbottom.soil.coulomb.CoulombFriction` (elastic–perfectly plastic
  return map, capacity μV, V = W_s with no hydrodynamic lift) and its axial friction;
- the lumped nodal masses of onbottom (axial m·ℓ, lateral (m + C_a ρπD²/4)·ℓ, rotary
  m·D²/8·ℓ);
- the load ℓ·q(x_i, t) as two ``Plain`` patterns, q = A·r(t)·[sin kx·cos ωτ − cos kx·sin ωτ],
  whose ``Path`` series r·cos ωτ and r·sin ωτ are sampled at the time steps;
- ``BandSPD``, ``Newton`` (KrylovNewton, then NewtonLineSearch for a step whose Newton
  iterations cycle on the kink of an ElasticPP material), ``Newmark`` γ = ½, β = ¼ (α = 0) or
  ``HHT`` with OpenSees' α = 1 + α_HHT, at a fixed Δt; the envelope of |y| from an
  ``EnvelopeNode`` recorder (16 digits).

With α = 0 both programs solve the same discrete equations; with α < 0 OpenSees evaluates the
internal and spring forces at the interpolated displacement d_{n+1+α} while onbottom
interpolates the forces, (1 + α)P(d_{n+1}) − αP_n: the same for a linear problem, a small
difference once the springs yield. Validation page: docs/validation/opensees_peer.md.

OpenSeesPy is optional (``pip install onbottom[peers]``); :func:`import_opensees` raises
ImportError with the reason when it is absent or cannot load.
"""

from __future__ import annotations

import math
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from onbottom._validate import in_range, positive
from onbottom.dynamics.pipeline import PipelineModel, PipelineSettings, simulate_pipeline
from onbottom.dynamics.pipeline.node_layout import ND_J, ND_MASS_U, ND_MASS_V, ND_TRIB
from onbottom.dynamics.pipeline.user_load import TravellingSineLoad, still_water
from onbottom.errors import InputError
from onbottom.inputs.pipe import Pipe
from onbottom.soil.coulomb import CoulombFriction

__all__ = [
    "PeerRun",
    "compare",
    "import_opensees",
    "peer_model",
    "run_onbottom",
    "run_opensees",
]


def import_opensees() -> Any:
    """The ``openseespy.opensees`` module; ImportError (with the reason) when unusable.

    openseespylinux 3.7 ships its BLAS/LAPACK in ``openseespylinux/lib`` but does not find
    them without a system libblas3; they are preloaded from there when the first import fails.
    """
    try:
        import openseespy.opensees as ops  # type: ignore[import-not-found]

        return ops
    except ImportError as exc:
        raise ImportError(
            f"openseespy is not installed ({exc}): pip install onbottom[peers]"
        ) from None
    except RuntimeError:
        pass
    import ctypes
    import importlib.util
    import sys

    spec = importlib.util.find_spec("openseespylinux")
    if spec is None or spec.origin is None:
        raise ImportError("openseespy failed to load and openseespylinux was not found")
    lib = Path(spec.origin).parent / "lib"
    for name in ("libquadmath.so.0", "libgfortran.so.4", "libblas.so.3", "liblapack.so.3"):
        if (lib / name).exists():
            ctypes.CDLL(str(lib / name), mode=ctypes.RTLD_GLOBAL)
    for mod in [m for m in sys.modules if m.startswith(("openseespy", "openseespylinux"))]:
        del sys.modules[mod]
    try:
        import openseespy.opensees as ops  # type: ignore[import-not-found]
    except (ImportError, RuntimeError) as exc:
        raise ImportError(f"openseespy is installed but does not load ({exc})") from None
    return ops


@dataclass(frozen=True, kw_only=True)
class PeerRun:
    """One run of the peer problem.

    Attributes
    ----------
    program : str
        "onbottom" or "opensees".
    max_abs_y : ndarray
        Envelope of |lateral displacement| per node [m].
    n_steps : int
        Time steps taken.
    cpu_time : float
        Process CPU time of the time integration [s] (onbottom: ``simulate_pipeline`` warm;
        OpenSees: the ``analyze`` calls).
    n_nodes : int
    info : dict
        Program-specific counters (rejected steps, fallback steps, ...).
    """

    program: str
    max_abs_y: np.ndarray
    n_steps: int
    cpu_time: float
    n_nodes: int
    info: dict[str, Any] = field(default_factory=dict)

    @property
    def per_node_step(self) -> float:
        """CPU time per node and step [s]."""
        return self.cpu_time / max(self.n_nodes * self.n_steps, 1)


def peer_model(
    n_elements: int = 500,
    length: float = 1000.0,
    *,
    amplitude: float = 450.0,
    wavelength: float = 200.0,
    period: float = 20.0,
    ramp: float = 30.0,
    axial_amplitude: float = 50.0,
) -> PipelineModel:
    """The standing peer problem: a straight pipe fixed at both ends on Coulomb soil.

    D = 0.4 m, W_s = 600 N/m, EI = 5·10⁷ N·m², EA = 5·10⁹ N, μ = 0.6 (δ = 1 mm), μ_ax = 0.5
    (δ_ax = 5 mm), no hydrodynamic load (still water, no relative-velocity drag; added mass
    C_a = 1 kept), loaded by a travelling sinusoid q_y = A sin(2π(x/λ − t/T)) (default
    450 N/m = 1.25 μW_s, λ = 200 m, T = 20 s: 10 m/s, half-cosine ramp 30 s) with an axial
    component of the same phase (50 N/m). ``n_elements`` >= 2, ``length`` [m] > 0.
    """
    if int(n_elements) < 2:
        raise InputError(f"n_elements = {n_elements!r} is invalid: >= 2")
    positive("length", length)
    pipe = Pipe(
        outer_diameter=0.4, submerged_weight=600.0, bending_stiffness=5e7, axial_stiffness=5e9
    )
    from onbottom.dynamics.pipeline import SoilSection

    soil = (
        SoilSection(
            start=0.0,
            end=length,
            model=CoulombFriction(friction_coefficient=0.6, mobilisation_displacement=1e-3),
            axial_friction_coefficient=0.5,
        ),
    )
    return PipelineModel(
        pipe=pipe,
        length=float(length),
        element_length=float(length) / int(n_elements),
        soil=soil,
        end_conditions="fixed",
        axial_mobilisation=5e-3,
        relative_velocity=False,
        user_load=TravellingSineLoad(
            amplitude=amplitude,
            wavelength=wavelength,
            period=period,
            ramp=ramp,
            axial_amplitude=axial_amplitude,
        ),
    )


def check_model(model: PipelineModel) -> TravellingSineLoad:
    """Raise :class:`~onbottom.errors.InputError` for what the OpenSees build does not cover;
    return the model's travelling load."""
    if not isinstance(model, PipelineModel):
        raise InputError(f"model = {type(model).__name__} is invalid: expected PipelineModel")
    load = model.user_load
    if not isinstance(load, TravellingSineLoad):
        raise InputError(
            "model.user_load is invalid for the OpenSees peer: expected a TravellingSineLoad"
        )
    for sec in model.sections:
        if not isinstance(sec.model, CoulombFriction):
            raise InputError(
                f"model.soil = {sec.model.name} is invalid for the OpenSees peer: only"
                " CoulombFriction is elastic–perfectly plastic (ElasticPP)"
            )
    if model.relative_velocity or model.current != 0.0:
        raise InputError(
            "model is invalid for the OpenSees peer: the hydrodynamic load must be off"
            " (relative_velocity=False, current=0, still water)"
        )
    if model.effective_axial_force != 0.0:
        raise InputError(
            f"model.effective_axial_force = {model.effective_axial_force!r} is invalid for the"
            " OpenSees peer: must be 0"
        )
    if "spring" in model.ends:
        raise InputError(
            "model.end_conditions = 'spring' is invalid for the OpenSees peer: fixed, pinned"
            " or free"
        )
    return load


def _n_steps(duration: float, dt: float) -> int:
    positive("duration", duration)
    positive("dt", dt)
    n = round(duration / dt)
    if n < 1 or abs(n * dt - duration) > 1e-9 * duration:
        raise InputError(
            f"duration = {duration!r} s is invalid: must be a whole number of steps dt = {dt!r} s"
        )
    return n


def _settings(dt: float, alpha: float, force_tolerance: float) -> PipelineSettings:
    # a fixed step: no cut-back on displacement, no growth
    return PipelineSettings(
        alpha=alpha,
        dt_max=dt,
        max_iterations=50,
        force_tolerance=force_tolerance,
        max_displacement_increment_over_d=1e6,
        growth=1.0,
        record_interval=None,
    )


def run_onbottom(
    model: PipelineModel,
    duration: float,
    *,
    dt: float = 0.1,
    alpha: float = 0.0,
    force_tolerance: float = 1e-9,
) -> PeerRun:
    """onbottom's run of the peer problem at a fixed step ``dt`` [s] for ``duration`` [s]
    (HHT ``alpha`` in [−1/3, 0]; 0: Newmark γ = ½, β = ¼). ``force_tolerance``: Newton
    residual over W_s·ℓ_e [-] (default 1e-9, far below the differences compared; the solver's
    own default is 1e-6)."""
    check_model(model)
    _n_steps(duration, dt)
    in_range("alpha", alpha, -1.0 / 3.0, 0.0)
    kin = still_water(model.x.size, duration)
    c0 = time.process_time()
    res = simulate_pipeline(model, kin, settings=_settings(dt, alpha, force_tolerance))
    cpu = time.process_time() - c0
    if not res.success:
        raise RuntimeError(f"onbottom's peer run failed: {res.message}")
    return PeerRun(
        program="onbottom",
        max_abs_y=res.envelopes["max_abs_y"].values.copy(),
        n_steps=int(res.summary["n_steps"]),
        cpu_time=cpu,
        n_nodes=model.x.size,
        info={
            "n_rejected": int(res.summary["n_rejected"]),
            "mean_newton_iterations": round(float(res.summary["mean_newton_iterations"]), 3),
            "n_factorisations": int(res.summary["n_factorisations"]),
        },
    )


def _build(ops: Any, model: PipelineModel, load: TravellingSineLoad, n_steps: int, dt: float):
    arr = model.arrays()
    nodes = arr["nodes"]
    x = model.x
    n = x.size
    ws = model.pipe.submerged_weight
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    sec_of = model.node_section()
    secs = model.sections
    for i in range(n):
        ell = float(nodes[i, ND_TRIB])
        ops.node(i + 1, float(x[i]), 0.0)
        ops.mass(
            i + 1, float(nodes[i, ND_MASS_U]), float(nodes[i, ND_MASS_V]),
            float(nodes[i, ND_J]),
        )  # fmt: skip
        sec = secs[int(sec_of[i])]
        soil = sec.model
        assert isinstance(soil, CoulombFriction)
        d_ax = model.axial_mobilisation
        d_lat = soil.mobilisation_displacement
        ops.uniaxialMaterial("ElasticPP", 2 * i + 1, sec.mu_axial * ws * ell / d_ax, d_ax)
        ops.uniaxialMaterial(
            "ElasticPP", 2 * i + 2, soil.friction_coefficient * ws * ell / d_lat, d_lat
        )
        ops.node(n + i + 1, float(x[i]), 0.0)
        ops.fix(n + i + 1, 1, 1, 1)
        ops.element(
            "zeroLength", n + i, n + i + 1, i + 1, "-mat", 2 * i + 1, 2 * i + 2, "-dir", 1, 2
        )
    for node, cond in ((1, model.ends[0]), (n, model.ends[1])):
        if cond == "fixed":
            ops.fix(node, 1, 1, 1)
        elif cond == "pinned":
            ops.fix(node, 1, 1, 0)
    ops.geomTransf("Corotational", 1)
    for e in range(n - 1):
        ops.element("elasticBeamColumn", e + 1, e + 1, e + 2, model.ea, 1.0, model.ei, 1)
    # q = A r(τ) sin(kx − ωτ) = A r [sin kx · cos ωτ − cos kx · sin ωτ], τ = t − t_s
    t = dt * np.arange(n_steps + 2)
    tau = t - load.start
    r = load.ramp_factor(t)
    w = 2.0 * math.pi / load.period
    k = 2.0 * math.pi / load.wavelength
    ops.timeSeries("Path", 1, "-dt", dt, "-values", *(r * np.cos(w * tau)).tolist())
    ops.timeSeries("Path", 2, "-dt", dt, "-values", *(r * np.sin(w * tau)).tolist())
    for pat, shape in ((1, np.sin(k * x)), (2, -np.cos(k * x))):
        ops.pattern("Plain", pat, pat)
        for i in range(n):
            ell = float(nodes[i, ND_TRIB])
            ops.load(
                i + 1,
                ell * load.axial_amplitude * float(shape[i]),
                ell * load.amplitude * float(shape[i]),
                0.0,
            )


def run_opensees(
    model: PipelineModel,
    duration: float,
    *,
    dt: float = 0.1,
    alpha: float = 0.0,
    tolerance: float = 1e-10,
    max_iterations: int = 50,
) -> PeerRun:
    """OpenSees's run of the peer problem (see the module docstring).

    ``dt`` [s] fixed step, ``duration`` [s], ``alpha`` HHT-α in [−1/3, 0] (0: Newmark
    γ = ½, β = ¼), ``tolerance`` [m] on the norm of the displacement increment (NormDispIncr),
    ``max_iterations`` Newton iterations before a step is retried with KrylovNewton and then
    NewtonLineSearch (fixed Δt, as onbottom's run).
    """
    load = check_model(model)
    n_steps = _n_steps(duration, dt)
    in_range("alpha", alpha, -1.0 / 3.0, 0.0)
    ops = import_opensees()
    n = model.x.size
    with tempfile.TemporaryDirectory(prefix="onbottom_opensees_") as tmp:
        env_file = Path(tmp) / "envelope.out"
        _build(ops, model, load, n_steps, dt)
        ops.recorder(
            "EnvelopeNode", "-file", str(env_file), "-precision", 16,
            "-node", *range(1, n + 1), "-dof", 2, "disp",
        )  # fmt: skip
        ops.constraints("Plain")
        ops.numberer("RCM")
        ops.system("BandSPD")
        ops.test("NormDispIncr", tolerance, int(max_iterations), 0)
        ops.algorithm("Newton")
        if alpha == 0.0:
            ops.integrator("Newmark", 0.5, 0.25)
        else:
            ops.integrator("HHT", 1.0 + alpha)
        ops.analysis("Transient")
        fallbacks = 0
        c0 = time.process_time()
        done = 0
        while done < n_steps:
            ok = ops.analyze(n_steps - done, dt)
            done = round(ops.getTime() / dt)
            if ok < 0:
                for alg in (("KrylovNewton",), ("NewtonLineSearch",)):
                    ops.algorithm(*alg)
                    ok = ops.analyze(1, dt)
                    if ok == 0:
                        break
                ops.algorithm("Newton")
                if ok < 0:
                    ops.wipe()
                    raise RuntimeError(f"OpenSees's peer run failed at t = {done * dt:g} s")
                fallbacks += 1
                done = round(ops.getTime() / dt)
        cpu = time.process_time() - c0
        ops.wipe()  # closes the recorder
        env = np.loadtxt(env_file, ndmin=2)
    return PeerRun(
        program="opensees",
        max_abs_y=env[-1].copy(),
        n_steps=done,
        cpu_time=cpu,
        n_nodes=n,
        info={"fallback_steps": fallbacks},
    )


def compare(
    model: PipelineModel, duration: float, *, dt: float = 0.1, alpha: float = 0.0
) -> dict[str, Any]:
    """Both runs and the relative difference of their |y| envelopes.

    Returns {"onbottom": PeerRun, "opensees": PeerRun, "max_rel_diff": max over nodes of
    |Δ envelope| / max envelope, "peak_rel_diff": relative difference of the largest |y|}.
    """
    ob = run_onbottom(model, duration, dt=dt, alpha=alpha)
    os_ = run_opensees(model, duration, dt=dt, alpha=alpha)
    scale = float(np.max(os_.max_abs_y))
    return {
        "onbottom": ob,
        "opensees": os_,
        "max_rel_diff": float(np.max(np.abs(ob.max_abs_y - os_.max_abs_y)) / scale),
        "peak_rel_diff": float(abs(np.max(ob.max_abs_y) - scale) / scale),
    }
