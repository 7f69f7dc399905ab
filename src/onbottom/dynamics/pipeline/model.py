"""The pipeline FE model: geometry, pipe properties, end conditions, soil along the route.

A straight pipeline of length L on a flat seabed along the x axis, divided into equal
2-node corotational beam elements (:mod:`._beam_kernel`); see docs/theory/pipeline_fe.md.
:meth:`PipelineModel.arrays` packs everything the numba kernel needs.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from onbottom._validate import in_range, non_negative, one_of, positive
from onbottom.dynamics.pipeline import _beam_kernel as B
from onbottom.dynamics.pipeline import _pipeline_kernel as K
from onbottom.dynamics.pipeline.user_load import UserLoad
from onbottom.errors import InputError
from onbottom.hydro.force_model import ForceModel, MorisonLift
from onbottom.hydro.reductions import LoadReductions
from onbottom.inputs.pipe import Pipe
from onbottom.soil.base import LateralResistanceModel

__all__ = ["END_CONDITIONS", "PipelineModel", "SoilSection"]

END_CONDITIONS = ("fixed", "pinned", "free", "spring")
"""End conditions: fixed (u, v, θ held), pinned (u, v held), free, spring (elastic u, v, θ)."""


@dataclass(frozen=True, kw_only=True)
class SoilSection:
    """A stretch of the route with its own lateral soil model.

    Parameters
    ----------
    start, end : float
        Positions along the pipe [m], 0 <= start < end; nodes with start <= x < end (the last
        section also takes x = L) use ``model``.
    model : LateralResistanceModel
        Lateral soil model (its initial state is the as-laid state of every node).
    axial_friction_coefficient : float or None
        μ_ax [-], in (0, 2]; None → the model's ``friction_coefficient`` (0.6 if it has none).
    """

    start: float
    end: float
    model: LateralResistanceModel
    axial_friction_coefficient: float | None = None

    def __post_init__(self) -> None:
        non_negative("SoilSection.start", self.start)
        if not self.end > self.start:
            raise InputError(
                f"SoilSection.end = {self.end!r} is invalid: must exceed start = {self.start!r}"
            )
        if not isinstance(self.model, LateralResistanceModel):
            raise InputError(
                f"SoilSection.model = {type(self.model).__name__} is invalid: expected a"
                " LateralResistanceModel"
            )
        if self.axial_friction_coefficient is not None:
            in_range(
                "SoilSection.axial_friction_coefficient",
                self.axial_friction_coefficient,
                0.0,
                2.0,
                low_inclusive=False,
            )

    @property
    def mu_axial(self) -> float:
        """Axial friction coefficient used [-]."""
        if self.axial_friction_coefficient is not None:
            return float(self.axial_friction_coefficient)
        return float(getattr(self.model, "friction_coefficient", 0.6))


@dataclass(frozen=True, kw_only=True)
class PipelineModel:
    """A straight pipeline on the seabed for the FE storm analysis.

    Parameters
    ----------
    pipe : Pipe
        D, W_s, structural mass (contents included), EI (``bending_stiffness``) and EA
        (``axial_stiffness``) unless given below.
    length : float
        Pipeline length L [m], > 0.
    element_length : float
        Target element length [m], in (0, L]; the line gets round(L/ℓ_e) equal elements.
    soil : LateralResistanceModel or tuple of SoilSection
        One model for the whole route, or route sections covering [0, L].
    bending_stiffness, axial_stiffness : float or None
        EI [N·m²] and EA [N], > 0; None → from ``pipe``.
    effective_axial_force : float
        Initial effective axial force N₀ [N] (tension +; pressure and temperature give N₀ < 0).
    end_conditions : str or (str, str)
        One of :data:`END_CONDITIONS` for both ends, or (start, end).
    end_springs : (float, float, float)
        Spring stiffnesses (axial [N/m], lateral [N/m], rotational [N·m/rad]), >= 0, at an end
        with the "spring" condition.
    axial_mobilisation : float
        Displacement mobilising full axial friction δ_ax [m], > 0 (default 5 mm) [I].
    force_model : ForceModel
        Hydrodynamic force model (any the storm section accepts; default
        :class:`~onbottom.hydro.force_model.MorisonLift`, C_D 0.7, C_M 3.29, C_L 0.9). A
        per-sea-state model needs kinematics synthesised from a storm
        (:func:`~onbottom.hydro.short_crested.pipeline_kinematics`).
    reductions : LoadReductions
        F109 load reductions (permeable seabed, penetration, trench).
    current : float
        Steady current normal to the pipe, mean over D [m/s] (signed), same at every node.
    relative_velocity : bool
        Drag on U + V − ẏ (default) or on U + V.
    strain_fibre_distance : float or None
        Distance of the outer steel fibre from the axis c [m], > 0; None → D_steel/2 from the
        layers when known, else D/2 (conservative).
    user_load : UserLoad or None
        A user-given distributed load q(x, t) [N/m] added to the hydrodynamic load
        (:class:`~onbottom.dynamics.pipeline.user_load.TravellingSineLoad`,
        :class:`~onbottom.dynamics.pipeline.user_load.TableLoad`); None → none.
    """

    pipe: Pipe
    length: float
    element_length: float
    soil: LateralResistanceModel | tuple[SoilSection, ...]
    bending_stiffness: float | None = None
    axial_stiffness: float | None = None
    effective_axial_force: float = 0.0
    end_conditions: str | tuple[str, str] = "fixed"
    end_springs: tuple[float, float, float] = (0.0, 0.0, 0.0)
    axial_mobilisation: float = 5.0e-3
    force_model: ForceModel = field(default_factory=MorisonLift)
    reductions: LoadReductions = field(default_factory=LoadReductions)
    current: float = 0.0
    relative_velocity: bool = True
    strain_fibre_distance: float | None = None
    user_load: UserLoad | None = None

    def __post_init__(self) -> None:
        c = "PipelineModel"
        if not isinstance(self.pipe, Pipe):
            raise InputError(f"{c}.pipe = {type(self.pipe).__name__} is invalid: expected Pipe")
        positive(f"{c}.length", self.length)
        in_range(f"{c}.element_length", self.element_length, 0.0, self.length, low_inclusive=False)
        if self.ei <= 0.0:
            raise InputError(
                f"{c}.bending_stiffness = {self.bending_stiffness!r} is invalid: EI must be > 0"
                " (give it, or a pipe with bending_stiffness)"
            )
        if self.ea <= 0.0:
            raise InputError(
                f"{c}.axial_stiffness = {self.axial_stiffness!r} is invalid: EA must be > 0"
                " (give it, or a pipe built from layers)"
            )
        ends = self.ends
        for e in ends:
            one_of(f"{c}.end_conditions", e, END_CONDITIONS)
        if len(self.end_springs) != 3:
            raise InputError(f"{c}.end_springs = {self.end_springs!r} is invalid: need 3 values")
        for i, k in enumerate(self.end_springs):
            non_negative(f"{c}.end_springs[{i}]", k)
        positive(f"{c}.axial_mobilisation", self.axial_mobilisation)
        if not isinstance(self.force_model, ForceModel):
            raise InputError(
                f"{c}.force_model = {type(self.force_model).__name__} is invalid: expected a"
                " ForceModel (name, model_id, added_mass_coefficient, parameter_table, describe)"
            )
        if self.strain_fibre_distance is not None:
            positive(f"{c}.strain_fibre_distance", self.strain_fibre_distance)
        if self.user_load is not None:
            if not isinstance(self.user_load, UserLoad):
                raise InputError(
                    f"{c}.user_load = {type(self.user_load).__name__} is invalid: expected a"
                    " UserLoad (TravellingSineLoad or TableLoad)"
                )
            self.user_load.check_nodes(self.n_elements + 1)
        sections = self.sections
        if abs(sections[0].start) > 1e-9 or abs(sections[-1].end - self.length) > 1e-6:
            raise InputError(
                f"{c}.soil is invalid: route sections must cover [0, {self.length:g}] m"
            )
        for a, b in itertools.pairwise(sections):
            if abs(a.end - b.start) > 1e-6:
                raise InputError(
                    f"{c}.soil is invalid: sections must be contiguous (gap or overlap at"
                    f" {a.end:g} m / {b.start:g} m)"
                )

    # ---- derived ------------------------------------------------------------------------
    @property
    def ends(self) -> tuple[str, str]:
        """End conditions (start, end)."""
        e = self.end_conditions
        return (e, e) if isinstance(e, str) else (str(e[0]), str(e[1]))

    @property
    def ei(self) -> float:
        """EI [N·m²]."""
        v = self.bending_stiffness
        return float(v if v is not None else self.pipe.bending_stiffness)

    @property
    def ea(self) -> float:
        """EA [N]."""
        v = self.axial_stiffness
        return float(v if v is not None else getattr(self.pipe, "axial_stiffness", 0.0))

    @property
    def n_elements(self) -> int:
        """Number of elements."""
        return max(round(self.length / self.element_length), 1)

    @property
    def x(self) -> np.ndarray:
        """Node positions [m]."""
        return np.linspace(0.0, self.length, self.n_elements + 1)

    @property
    def sections(self) -> tuple[SoilSection, ...]:
        """Route sections (one covering the line for a single model)."""
        if isinstance(self.soil, LateralResistanceModel):
            return (SoilSection(start=0.0, end=self.length, model=self.soil),)
        secs = tuple(self.soil)
        if not secs or not all(isinstance(s, SoilSection) for s in secs):
            raise InputError(
                "PipelineModel.soil is invalid: expected a LateralResistanceModel or a"
                " non-empty tuple of SoilSection"
            )
        return tuple(sorted(secs, key=lambda s: s.start))

    @property
    def fibre_distance(self) -> float:
        """c [m] for the bending strain."""
        if self.strain_fibre_distance is not None:
            return float(self.strain_fibre_distance)
        d = self.pipe.outer_diameter
        for layer in self.pipe.layers:
            d -= 2.0 * layer.thickness
        return 0.5 * d

    @property
    def lateral_mass(self) -> float:
        """Mass per unit length moving laterally m + C_a ρ_w π D²/4 [kg/m]."""
        return self.pipe.structural_mass + self.pipe.added_mass(
            self.force_model.added_mass_coefficient
        )

    def node_section(self) -> np.ndarray:
        """Index of the route section of every node."""
        x = self.x
        secs = self.sections
        idx = np.zeros(x.size, dtype=np.int64)
        for k, s in enumerate(secs):
            m = (x >= s.start - 1e-9) & (x < s.end - 1e-9)
            idx[m] = k
        idx[x >= secs[-1].end - 1e-9] = len(secs) - 1
        return idx

    def describe(self) -> dict[str, Any]:
        """Provenance: the model's inputs as plain values."""
        return {
            "length": self.length,
            "n_elements": self.n_elements,
            "outer_diameter": self.pipe.outer_diameter,
            "submerged_weight": self.pipe.submerged_weight,
            "structural_mass": self.pipe.structural_mass,
            "bending_stiffness": self.ei,
            "axial_stiffness": self.ea,
            "effective_axial_force": self.effective_axial_force,
            "end_conditions": list(self.ends),
            "end_springs": list(self.end_springs),
            "axial_mobilisation": self.axial_mobilisation,
            "current": self.current,
            "relative_velocity": self.relative_velocity,
            "soil": [
                {
                    "start": s.start,
                    "end": s.end,
                    "model": s.model.name,
                    "mu_axial": s.mu_axial,
                    "parameters": {k: _plain(v) for k, v in s.model.parameters().items()},
                }
                for s in self.sections
            ],
            **self.force_model.describe(),
            # only with a load, so that runs without one keep their run identity
            **({} if self.user_load is None else {"user_load": self.user_load.describe()}),
        }

    # ---- kernel arrays ------------------------------------------------------------------
    def arrays(self) -> dict[str, np.ndarray]:
        """Arrays of the numba kernel (see :mod:`._pipeline_kernel`)."""
        x = self.x
        n = x.size
        ne = n - 1
        le = self.length / ne
        props = np.zeros((ne, B.N_EL_PROPS))
        props[:, B.EL_L0] = le
        props[:, B.EL_EA] = self.ea
        props[:, B.EL_EI] = self.ei
        props[:, B.EL_N0] = self.effective_axial_force
        trib = np.full(n, le)
        if n > 1:
            trib[0] = trib[-1] = 0.5 * le
        else:
            trib[:] = self.length
        d = self.pipe.outer_diameter
        m = self.pipe.structural_mass
        red = self.reductions
        ry_c, rz_c = red.constant_factors()
        r_perm_z = 0.7 if red.permeable_seabed else 1.0
        nodes = np.zeros((n, K.N_NODE_COLS))
        nodes[:, K.ND_X0] = x
        nodes[:, K.ND_TRIB] = trib
        nodes[:, K.ND_MASS_U] = m * trib
        nodes[:, K.ND_MASS_V] = self.lateral_mass * trib
        # rotary inertia of the section about the vertical: m·r_g²·ℓ, r_g² ≈ D²/8 (thin ring)
        nodes[:, K.ND_J] = m * d * d / 8.0 * trib
        nodes[:, K.ND_CURRENT] = self.current
        nodes[:, K.ND_WS] = self.pipe.submerged_weight
        nodes[:, K.ND_R_TR_Y] = ry_c
        nodes[:, K.ND_R_TR_Z] = rz_c / r_perm_z
        secs = self.sections
        sec_of = self.node_section()
        n_par = max(s.model.packed_parameters().size for s in secs)
        n_st = max(int(s.model.state_size) for s in secs)
        model_ids = np.zeros(n, dtype=np.int64)
        sparams = np.zeros((n, n_par))
        sstate = np.zeros((n, n_st))
        for k, s in enumerate(secs):
            mask = sec_of == k
            p = s.model.packed_parameters()
            st = s.model.initial_state()
            model_ids[mask] = s.model.model_id
            sparams[mask, : p.size] = p
            sstate[mask, : st.size] = st
            nodes[mask, K.ND_MU_AX] = s.mu_axial
        ndof = B.NDOF_NODE * n
        fixed = np.zeros(ndof)
        spring = np.zeros(ndof)
        for node, cond in ((0, self.ends[0]), (n - 1, self.ends[1])):
            j = B.NDOF_NODE * node
            if cond == "fixed":
                fixed[j : j + 3] = 1.0
            elif cond == "pinned":
                fixed[j : j + 2] = 1.0
            elif cond == "spring":
                spring[j : j + 3] += np.asarray(self.end_springs, dtype=float)
        return {
            "props": props,
            "nodes": nodes,
            "fixed": fixed,
            "spring": spring,
            "model_ids": model_ids,
            "sparams": sparams,
            "sstate": sstate,
            "axst": np.zeros((n, 2)),
            "r_perm_z": np.array([r_perm_z]),
            "uload": np.zeros((1, 2, 1)) if self.user_load is None else self.user_load.table(n),
        }


def _plain(v: Any) -> Any:
    if isinstance(v, (int, float, str, bool)) or v is None:
        return v
    if isinstance(v, (tuple, list)):
        return [_plain(x) for x in v]
    if isinstance(v, Mapping):
        return {str(k): _plain(x) for k, x in v.items()}
    try:
        return float(v)
    except (TypeError, ValueError):
        return str(v)
