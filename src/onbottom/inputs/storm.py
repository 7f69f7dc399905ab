"""Sea states, storms and current (immutable, validated; no physics beyond bookkeeping).

A :class:`Storm` is a sequence of :class:`SeaState` stages played in order, optionally preceded
by a linear build-up and followed by a linear decay of the wave amplitude. The default storm of
DNV-RP-F109's generalized-stability background and of PONDUS (Bai, *Pipelines and Risers*,
§8.4) is a 3-h sea state at the peak after a 0.5-h build-up (:meth:`Storm.standard`).

The physics (spectra, transfer to the seabed, spreading reduction R_D, random-phase synthesis,
the log profile of the current) lives in :mod:`onbottom.hydro.storm_kinematics`; this module only
describes what the engineer specifies.

Units: SI (m, s); angles carry the suffix ``_deg``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from onbottom._validate import in_range, non_negative, one_of, positive
from onbottom.errors import InputError

__all__ = ["SPECTRA", "Current", "SeaState", "Storm"]

SPECTRA = ("jonswap", "pierson-moskowitz")
"""Spectrum names accepted by :class:`SeaState`."""

_THREE_HOURS = 3.0 * 3600.0


@dataclass(frozen=True, kw_only=True, slots=True)
class SeaState:
    """A stationary short-term sea state (one storm stage).

    Parameters
    ----------
    hs : float
        Significant wave height H_s [m], in (0, 30].
    tp : float
        Spectral peak period T_p [s], in (0, 40].
    gamma : float or None
        JONSWAP peak-enhancement factor γ [-] in [1, 7]; None → the DNV rule from T_p/√H_s
        (DNV-RP-C205 §3.5.5.5, used by DNV-RP-F109 §3.4.3). Only with ``spectrum="jonswap"``.
    spectrum : {"jonswap", "pierson-moskowitz"}
        Spectral shape (Pierson–Moskowitz = JONSWAP with γ = 1).
    duration_s : float
        Duration of the stage [s], > 0; default 3 h (10 800 s, the F109 design sea state).
    direction_deg : float
        Mean wave direction relative to the pipe axis [deg], in [0, 360]; 90 = waves travel
        normal to the pipe in +y, 270 = normal in −y, 0/180 = along the pipe.
    spreading_s : float
        Exponent s of the cos^s directional spreading function [-], in [0, 100]; 0 = long-crested
        (no spreading). F109 suggests s = 2–8 (DNV-RP-F109 (2017) §3.4.3).
    """

    hs: float
    tp: float
    gamma: float | None = None
    spectrum: str = "jonswap"
    duration_s: float = _THREE_HOURS
    direction_deg: float = 90.0
    spreading_s: float = 0.0

    def __post_init__(self) -> None:
        in_range("SeaState.hs", self.hs, 0.0, 30.0, low_inclusive=False)
        in_range("SeaState.tp", self.tp, 0.0, 40.0, low_inclusive=False)
        one_of("SeaState.spectrum", self.spectrum, SPECTRA)
        if self.gamma is not None:
            if self.spectrum != "jonswap":
                raise InputError(
                    f"SeaState.gamma = {self.gamma!r} is invalid with spectrum ="
                    f" {self.spectrum!r}: γ applies to the JONSWAP spectrum only"
                )
            in_range("SeaState.gamma", self.gamma, 1.0, 7.0)
        positive("SeaState.duration_s", self.duration_s)
        in_range("SeaState.direction_deg", self.direction_deg, 0.0, 360.0)
        in_range("SeaState.spreading_s", self.spreading_s, 0.0, 100.0)

    @property
    def peak_enhancement(self) -> float:
        """γ actually used [-]: the given value, 1 for Pierson–Moskowitz, else the DNV rule.

        DNV rule (DNV-RP-C205 §3.5.5.5): φ = T_p/√H_s; γ = 5 for φ ≤ 3.6,
        exp(5.75 − 1.15 φ) for 3.6 < φ < 5, 1 for φ ≥ 5.
        """
        if self.spectrum == "pierson-moskowitz":
            return 1.0
        if self.gamma is not None:
            return float(self.gamma)
        phi = self.tp / math.sqrt(self.hs)
        if phi <= 3.6:
            return 5.0
        if phi < 5.0:
            return math.exp(5.75 - 1.15 * phi)
        return 1.0

    @property
    def long_crested(self) -> bool:
        """True when there is no directional spreading (s = 0)."""
        return self.spreading_s == 0.0

    def with_duration(self, duration_s: float) -> SeaState:
        """A copy with another duration [s]."""
        return replace(self, duration_s=duration_s)


@dataclass(frozen=True, kw_only=True, slots=True)
class Storm:
    """A storm: sea-state stages in order, with an optional linear build-up and decay.

    The wave amplitude is multiplied by an envelope e(t): e rises linearly from 0 to 1 during
    the ``build_up_s`` seconds *before* the first stage (with the first stage's spectrum), is 1
    through the stages, and falls linearly to 0 during the ``decay_s`` seconds *after* the last
    stage (with the last stage's spectrum). Between consecutive stages the spectra are blended
    linearly over ``transition_s`` seconds centred on the stage boundary (our choice: F109 and
    PONDUS do not say how stages join; a blend keeps U(t) continuous).

    Parameters
    ----------
    stages : tuple of SeaState
        At least one stage; played in order, each for its ``duration_s``.
    seed : int
        Seed of the random phases [-], in [0, 2**63 − 1]; the same seed gives the same storm.
    build_up_s : float
        Duration of the linear build-up before the first stage [s], >= 0.
    decay_s : float
        Duration of the linear decay after the last stage [s], >= 0.
    transition_s : float
        Blending time between consecutive stages [s], >= 0, at most the shorter neighbouring
        stage.
    """

    stages: tuple[SeaState, ...]
    seed: int = 0
    build_up_s: float = 0.0
    decay_s: float = 0.0
    transition_s: float = 60.0

    def __post_init__(self) -> None:
        if isinstance(self.stages, SeaState):
            object.__setattr__(self, "stages", (self.stages,))
        if not isinstance(self.stages, tuple):
            try:
                object.__setattr__(self, "stages", tuple(self.stages))
            except TypeError:
                raise InputError(
                    f"Storm.stages = {self.stages!r} is invalid: expected a sequence of SeaState"
                ) from None
        if len(self.stages) == 0:
            raise InputError("Storm.stages = () is invalid: need at least one SeaState")
        for i, s in enumerate(self.stages):
            if not isinstance(s, SeaState):
                raise InputError(
                    f"Storm.stages[{i}] = {type(s).__name__} is invalid: expected SeaState"
                )
        if isinstance(self.seed, bool) or not isinstance(self.seed, int):
            raise InputError(f"Storm.seed = {self.seed!r} is invalid: expected an integer >= 0")
        if not 0 <= self.seed < 2**63:
            raise InputError(f"Storm.seed = {self.seed!r} is invalid: must lie in [0, 2**63)")
        non_negative("Storm.build_up_s", self.build_up_s)
        non_negative("Storm.decay_s", self.decay_s)
        non_negative("Storm.transition_s", self.transition_s)
        if len(self.stages) > 1:
            shortest = min(s.duration_s for s in self.stages)
            if self.transition_s > shortest:
                raise InputError(
                    f"Storm.transition_s = {self.transition_s!r} is invalid: must be <= the"
                    f" shortest stage duration {shortest:g} s"
                )

    # ---- constructors -------------------------------------------------------------------
    @classmethod
    def standard(
        cls,
        peak: SeaState,
        *,
        build_up_hours: float = 0.5,
        peak_hours: float = 3.0,
        decay_hours: float = 0.0,
        seed: int = 0,
    ) -> Storm:
        """The default design storm: linear build-up, then the peak sea state, then decay.

        Default 0.5 h build-up + 3 h at the peak (F109 generalized-method background and
        PONDUS, Bai *Pipelines and Risers* §8.4).

        Parameters
        ----------
        peak : SeaState
            The peak sea state (its own duration is replaced by ``peak_hours``).
        build_up_hours, peak_hours, decay_hours : float
            Durations [h]; build-up and decay >= 0, peak > 0.
        seed : int
            Random-phase seed.
        """
        if not isinstance(peak, SeaState):
            raise InputError(f"peak = {type(peak).__name__} is invalid: expected SeaState")
        bu = non_negative("build_up_hours", build_up_hours)
        ph = positive("peak_hours", peak_hours)
        de = non_negative("decay_hours", decay_hours)
        return cls(
            stages=(peak.with_duration(ph * 3600.0),),
            seed=seed,
            build_up_s=bu * 3600.0,
            decay_s=de * 3600.0,
        )

    # ---- derived ------------------------------------------------------------------------
    @property
    def duration_s(self) -> float:
        """Total duration: build-up + stages + decay [s]."""
        return self.build_up_s + sum(s.duration_s for s in self.stages) + self.decay_s

    @property
    def stage_start_times(self) -> tuple[float, ...]:
        """Start time of each stage [s] (t = 0 at the start of the build-up)."""
        t = self.build_up_s
        out = []
        for s in self.stages:
            out.append(t)
            t += s.duration_s
        return tuple(out)

    @property
    def peak(self) -> SeaState:
        """The stage with the largest H_s (the first one on ties)."""
        return max(self.stages, key=lambda s: s.hs)

    def with_seed(self, seed: int) -> Storm:
        """A copy with another seed."""
        return replace(self, seed=seed)


@dataclass(frozen=True, kw_only=True, slots=True)
class Current:
    """A steady current, specified at a reference height above the seabed.

    Parameters
    ----------
    velocity : float
        Current speed V(z_r) at the reference height [m/s], in [0, 10].
    reference_height : float
        Reference height z_r above the seabed [m], > 0.
    direction_deg : float
        Current direction relative to the pipe axis [deg], in [0, 360]; 90 = normal to the
        pipe in +y, 270 = normal in −y.
    z0 : float or None
        Seabed roughness z_0 [m], > 0; None → from the seabed's d_50 (DNV-RP-F109 Table 3-1,
        :data:`onbottom.hydro.SEABED_ROUGHNESS`) where the caller knows it.
    """

    velocity: float
    reference_height: float = 1.0
    direction_deg: float = 90.0
    z0: float | None = None

    def __post_init__(self) -> None:
        in_range("Current.velocity", self.velocity, 0.0, 10.0)
        positive("Current.reference_height", self.reference_height)
        in_range("Current.direction_deg", self.direction_deg, 0.0, 360.0)
        if self.z0 is not None:
            positive("Current.z0", self.z0)
