"""The Fourier force model (model id 2): forces per half-cycle from a user coefficient table.

Structure from Sørensen, Bryndum & Jacobsen (1986), Bryndum, Jacobsen & Tsahalis (1992,
J. Offshore Mech. Arct. Eng. 114:231) and the AGA/PRCI Level 3 approach
(Level 3 of the AGA/PRCI on-bottom stability software): in each half-cycle of
the flow the force is a Fourier series in the half-cycle's phase, scaled by ½ρD U_m², with
coefficients interpolated over K and M from measured regular-wave tests. The measured
coefficient databases are licensed, so the table is the user's (:class:`FourierTable`); the
package ships only a synthetic example (:meth:`FourierModel.example`).

How irregular flow is split into half-cycles, how U_m, T, K and M of a half-cycle are
estimated causally with the memory weight, the quasi-steady fallback and the pipe-motion
correction: module docstring of :mod:`onbottom.hydro._fourier_kernel` and
``docs/theory/fourier_model.md``. That procedure is a documented **reconstruction** of the
published structure, not the licensed programs' code.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

from onbottom._validate import in_range, integer, non_negative, one_of
from onbottom.errors import InputError, OutOfRangeWarning
from onbottom.hydro._fourier_kernel import (
    P_CD,
    P_CL,
    P_CM,
    P_HEADER,
    P_MEMORY,
    P_NHARM,
    P_NK,
    P_NM,
    P_PHASE,
)
from onbottom.hydro.fourier_table import FourierTable

__all__ = ["FORCE_FOURIER", "PHASES", "FourierModel"]

FORCE_FOURIER = 2
"""Model id of the Fourier force model in ``hydro._force_dispatch``."""
PHASES = ("time", "flow")
"""Phase rules of a half-cycle (``docs/theory/fourier_model.md``)."""


@dataclass(frozen=True, kw_only=True, eq=False)
class FourierModel:
    """Fourier force model with a user coefficient table (see the module docstring).

    Parameters
    ----------
    table : FourierTable
        The coefficient table (K, M grid; with a roughness axis, ``roughness`` is required).
    harmonics : int or None
        Harmonic order N used, 1 <= N <= the table's order; None = the table's order.
    memory_weight : float
        w in [0, 1): weight of the previous estimate when a completed half-cycle updates the
        wave amplitude and period (Û ← (1 − w) a_k + w Û); default 0.25, the value used by
        programs of this kind (the AGA/PRCI Level 3 approach).
    phase : str
        How the phase θ and the scale of the current half-cycle are found: ``"time"`` (the
        elapsed time since its zero crossing, θ = π τ / T̂_h, scale Û from the completed
        half-cycles) or ``"flow"`` (default: the instantaneous phase of the wave from U and U̇
        with the estimated period, so that θ reaches π exactly at each zero crossing). Both
        are exact in regular flow; in irregular flow "flow" follows the record more closely
        and jumps less at crossings (theory page, "Irregular flow: the two phase rules").
    roughness : float or None
        Pipe roughness k/D [-] when the table has a roughness axis (linear between slices).
    drag_coefficient : float
        C_D [-] of the quasi-steady fallback law and of the pipe-motion (relative velocity)
        correction, in [0, 10]; default 0.7 (common practice, not a DNV-RP-F109 value).
    lift_coefficient : float
        C_L [-] of the fallback law, in [0, 10]; default 0.9 (common practice).
    inertia_coefficient : float
        C_M [-] of the fallback law, in [0, 10]; default 3.29 (potential flow, plane wall).
    added_mass : float or None
        C_a [-] of the added mass on the pipe's acceleration (solver's mass side), >= 0;
        None → C_M − 1.
    """

    table: FourierTable
    harmonics: int | None = None
    memory_weight: float = 0.25
    phase: str = "flow"
    roughness: float | None = None
    drag_coefficient: float = 0.7
    lift_coefficient: float = 0.9
    inertia_coefficient: float = 3.29
    added_mass: float | None = None
    name: str = "fourier"
    model_id: int = FORCE_FOURIER

    def __post_init__(self) -> None:
        if not isinstance(self.table, FourierTable):
            raise InputError(
                f"FourierModel.table = {type(self.table).__name__} is invalid: expected a"
                " FourierTable (FourierTable.load(path) reads a CSV or NetCDF table)"
            )
        if self.table.has_roughness:
            if self.roughness is None:
                raise InputError(
                    "FourierModel.roughness = None is invalid: the table has a roughness axis"
                    f" (k/D = {self.table.roughness_grid.tolist()}); give the pipe's k/D"
                )
            non_negative("FourierModel.roughness", self.roughness)
        elif self.roughness is not None:
            raise InputError(
                f"FourierModel.roughness = {self.roughness!r} is invalid: the table has no"
                " roughness axis"
            )
        if self.harmonics is not None:
            integer("FourierModel.harmonics", self.harmonics, 1, self.table.harmonics)
        one_of("FourierModel.phase", self.phase, PHASES)
        in_range("FourierModel.memory_weight", self.memory_weight, 0.0, 1.0, high_inclusive=False)
        for key in ("drag_coefficient", "lift_coefficient", "inertia_coefficient"):
            in_range(f"FourierModel.{key}", getattr(self, key), 0.0, 10.0)
        if self.added_mass is not None:
            non_negative("FourierModel.added_mass", self.added_mass)
        elif self.inertia_coefficient < 1.0:
            raise InputError(
                f"FourierModel.inertia_coefficient = {self.inertia_coefficient!r} is invalid"
                " without added_mass: C_a = C_M − 1 must be >= 0"
            )
        if self.model_id != FORCE_FOURIER:
            raise InputError(f"FourierModel.model_id = {self.model_id!r} is invalid: must be 2")

    @classmethod
    def example(cls, **kwargs: Any) -> FourierModel:
        """The model with the shipped synthetic example table (no licensed numbers)."""
        return cls(table=FourierTable.example(), **kwargs)

    @property
    def harmonic_order(self) -> int:
        """N used by the kernel."""
        return self.table.harmonics if self.harmonics is None else int(self.harmonics)

    @property
    def added_mass_coefficient(self) -> float:
        """C_a [-] (the solver puts ρ π D²/4 C_a on the mass side)."""
        if self.added_mass is not None:
            return float(self.added_mass)
        return float(self.inertia_coefficient) - 1.0

    @property
    def resolved_table(self) -> FourierTable:
        """The 2-D (K, M) table at the model's roughness."""
        if self.roughness is None:
            return self.table
        return self.table.at_roughness(self.roughness)

    def params(self) -> np.ndarray:
        """The kernel's parameter row (layout: :mod:`onbottom.hydro._fourier_kernel`)."""
        tab = self.resolved_table
        n = self.harmonic_order
        nk, nm = tab.k_grid.size, tab.m_grid.size
        coef = np.asarray(tab.coefficients[0][..., : 2 * n + 1], dtype=float)
        row = np.zeros(P_HEADER + nk + nm + coef.size)
        row[P_NHARM] = n
        row[P_NK] = nk
        row[P_NM] = nm
        row[P_MEMORY] = self.memory_weight
        row[P_PHASE] = PHASES.index(self.phase)
        row[P_CD] = self.drag_coefficient
        row[P_CL] = self.lift_coefficient
        row[P_CM] = self.inertia_coefficient
        row[P_HEADER : P_HEADER + nk] = tab.k_grid
        row[P_HEADER + nk : P_HEADER + nk + nm] = tab.m_grid
        row[P_HEADER + nk + nm :] = np.ascontiguousarray(coef).ravel()
        return row

    def parameter_table(
        self, keulegan_carpenter: np.ndarray, current_ratio: np.ndarray
    ) -> np.ndarray:
        """Array (n_stages, n_params): the same row for every stage.

        The coefficients are **not** resolved per stage: a storm stage's K = U_s T_u / D and
        M = V / U_s are spectral values, while the Fourier model needs each half-cycle's own
        K and M, which scatter widely around them in an irregular sea. The row carries the
        whole (K, M) grid and the kernel interpolates at every half-cycle
        (``docs/theory/fourier_model.md``). The row is long (8 + n_K + n_M + 2 n_K n_M (2N+1)
        floats: 3,002 for the example table), so a solver should keep one row per stage, not
        one per time sample. A stage whose K or |M| lies outside the table's grid gets an
        :class:`~onbottom.errors.OutOfRangeWarning` here, since many of its half-cycles will
        be clamped to the grid's edge.
        """
        k = np.atleast_1d(np.asarray(keulegan_carpenter, dtype=float))
        m = np.atleast_1d(np.asarray(current_ratio, dtype=float))
        if k.shape != m.shape:
            raise InputError(
                f"FourierModel.parameter_table: K has shape {k.shape} and M {m.shape}:"
                " expected one value of each per stage"
            )
        tab = self.resolved_table
        kg, mg = tab.k_grid, tab.m_grid
        for j in range(k.size):
            if not (kg[0] <= k[j] <= kg[-1]) or not (mg[0] <= abs(m[j]) <= mg[-1]):
                warnings.warn(
                    f"stage {j}: K = {k[j]:.4g}, M = {m[j]:.4g} lie outside the Fourier"
                    f" table's grid (K {kg[0]:g}..{kg[-1]:g}, M {mg[0]:g}..{mg[-1]:g}); the"
                    " half-cycles outside it use the grid's edge coefficients",
                    OutOfRangeWarning,
                    stacklevel=2,
                )
        row = self.params()
        return np.ascontiguousarray(np.broadcast_to(row, (k.size, row.size)))

    def describe(self) -> dict[str, Any]:
        """Provenance attributes."""
        d: dict[str, Any] = {
            "force_model": self.name,
            "force_model_id": self.model_id,
            "fourier_harmonics": self.harmonic_order,
            "fourier_memory_weight": self.memory_weight,
            "fourier_phase": self.phase,
            "drag_coefficient": self.drag_coefficient,
            "lift_coefficient": self.lift_coefficient,
            "inertia_coefficient": self.inertia_coefficient,
            "added_mass_coefficient": self.added_mass_coefficient,
            "force_model_source": (
                "Fourier force model per half-cycle (Sorensen, Bryndum & Jacobsen 1986;"
                " Bryndum, Jacobsen & Tsahalis 1992, JOMAE 114:231; AGA/PRCI Level 3"
                " structure) with a user coefficient table; half-cycle tracking, memory"
                " weight and quasi-steady fallback as in docs/theory/fourier_model.md"
            ),
            "reconstruction": 1,
        }
        if self.roughness is not None:
            d["roughness_k_over_D"] = self.roughness
        d.update(self.table.describe())
        return d
