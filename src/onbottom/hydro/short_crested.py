"""Short-crested near-bed kinematics along a pipeline (single-summation synthesis, numpy FFT).

Near-bed wave velocity normal to a straight pipe on the x axis (wave directions θ measured
from the pipe axis, 90° = waves travelling normal to the pipe; shared/spec
on-bottom-stability.md, "Sea states and storms")::

    u_n(x, t) = Σ_j a_j G(ω_j) sin θ_j cos(ω_j t − k_j x cos θ_j + φ_j)

* a_j = √(2 S_ηη(ω_j) Δω) from the JONSWAP/Pierson–Moskowitz spectrum
  (:mod:`onbottom.hydro.spectra`, DNV-RP-C205 §3.5.5), G = ω/sinh(kd) the linear transfer to
  the seabed (:mod:`onbottom.hydro.kinematics`, DNV-RP-F109 §3.4.3);
* **single summation**: one direction θ_j per frequency component, drawn from the cos^2s
  spreading density D(θ) ∝ cos^2s(θ − θ_m) on |θ − θ_m| ≤ π/2 (DNV-RP-C205 §3.5.8.4) by its
  inverse CDF — the sea is ergodic and no separate spreading factor R_D is applied;
  s = 0 gives a long-crested sea (every θ_j = θ_m);
* φ_j uniform on [0, 2π) from ``numpy.random.default_rng(seed)``.

The frequencies are the harmonics ω_j = jΔω of the record length T = 2π/Δω ≥ the storm
duration (so the series does not repeat within the storm), summed by one inverse real FFT per
node; nodes are processed in blocks, and the result is kept in float32 (velocity and
acceleration: 8 bytes per node and sample — 500 nodes × 3.5 h at 0.2 s ≈ 0.25 GB).

A storm is a list of stages (H_s, duration); the series of the peak sea state (largest H_s,
its T_p) is scaled by the envelope H_s(t)/H_s,peak, ramping linearly between stages and from
zero at the start (default 0.5 h build-up, 3 h peak; spec "Storm") [I: the spectral shape
of the peak is kept through the build-up].
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from onbottom._validate import in_range, non_negative, positive
from onbottom.errors import InputError
from onbottom.hydro.kinematics import seabed_transfer, wave_number
from onbottom.hydro.spectra import jonswap

__all__ = [
    "NodeKinematics",
    "ShortCrestedSea",
    "directions_cos2s",
    "regular_node_kinematics",
    "storm_envelope",
]


@dataclass(frozen=True, eq=False)
class NodeKinematics:
    """Near-bed wave velocity and acceleration normal to the pipe at every node.

    Attributes
    ----------
    t0 : float
        Time of the first sample [s].
    dt : float
        Sample interval [s] (the solver interpolates linearly).
    velocity : ndarray, float32 (n_times, n_nodes)
        U [m/s].
    acceleration : ndarray, float32 (n_times, n_nodes)
        dU/dt [m/s²].
    """

    t0: float
    dt: float
    velocity: np.ndarray
    acceleration: np.ndarray

    def __post_init__(self) -> None:
        positive("NodeKinematics.dt", self.dt)
        if self.velocity.shape != self.acceleration.shape or self.velocity.ndim != 2:
            raise InputError(
                "NodeKinematics.velocity/acceleration are invalid: need equal 2-D shapes"
                f" (n_times, n_nodes), got {self.velocity.shape} and {self.acceleration.shape}"
            )

    @property
    def t_end(self) -> float:
        """Time of the last sample [s]."""
        return self.t0 + self.dt * (self.velocity.shape[0] - 1)

    @property
    def nbytes(self) -> int:
        """Memory held [bytes]."""
        return int(self.velocity.nbytes + self.acceleration.nbytes)


def directions_cos2s(
    n: int, mean_deg: float, spreading_s: float, rng: np.random.Generator
) -> np.ndarray:
    """Draw ``n`` directions [rad] from D(θ) ∝ cos^2s(θ − θ_m), |θ − θ_m| ≤ π/2.

    Inverse-CDF sampling on a fine grid (4001 points). ``spreading_s`` = 0 → all θ_m
    (long-crested).
    """
    mean = math.radians(mean_deg)
    if spreading_s <= 0.0:
        return np.full(n, mean)
    g = np.linspace(-0.5 * math.pi, 0.5 * math.pi, 4001)
    pdf = np.cos(g) ** (2.0 * spreading_s)
    cdf = np.concatenate(([0.0], np.cumsum(0.5 * (pdf[1:] + pdf[:-1]) * np.diff(g))))
    cdf /= cdf[-1]
    return mean + np.interp(rng.uniform(0.0, 1.0, n), cdf, g)


def storm_envelope(
    time: np.ndarray, stages: tuple[tuple[float, float], ...], build_up: float
) -> tuple[np.ndarray, np.ndarray]:
    """Envelope e(t) = H_s(t)/H_s,peak and de/dt for stages ((H_s [m], duration [s]), ...).

    H_s rises linearly from 0 over ``build_up`` [s] to the first stage's H_s, then steps
    between stages by linear ramps of min(600 s, stage duration/10) [I].
    """
    t = np.asarray(time, dtype=float)
    hs_peak = max(h for h, _ in stages)
    knots_t = [0.0]
    knots_h = [0.0]
    tc = build_up
    knots_t.append(tc)
    knots_h.append(stages[0][0])
    for i, (h, dur) in enumerate(stages):
        if i > 0:
            ramp = min(600.0, 0.1 * dur)
            knots_t.append(tc + ramp)
            knots_h.append(h)
        tc += dur
        knots_t.append(tc)
        knots_h.append(h)
    kt = np.array(knots_t)
    kh = np.array(knots_h) / hs_peak
    if build_up <= 0.0:
        kt, kh = kt[1:], kh[1:]
    e = np.interp(t, kt, kh)
    slope = np.diff(kh) / np.maximum(np.diff(kt), 1e-12)
    idx = np.clip(np.searchsorted(kt, t, side="right") - 1, 0, len(slope) - 1)
    de = np.where((t >= kt[0]) & (t <= kt[-1]), slope[idx], 0.0)
    return e, de


@dataclass(frozen=True, kw_only=True)
class ShortCrestedSea:
    """A (short-crested) sea state for kinematics along a pipeline.

    Parameters
    ----------
    hs : float
        Significant wave height H_s [m], > 0.
    tp : float
        Peak period T_p [s], > 0.
    depth : float
        Water depth d [m], > 0.
    direction_deg : float
        Mean wave direction relative to the pipe axis θ_m [deg], in [0, 180] (90 = normal).
    spreading_s : float
        Exponent s of cos^2s spreading [-], in [0, 100]; 0 = long-crested.
    gamma : float or None
        JONSWAP γ [-] in [1, 7]; None → DNV rule (DNV-RP-C205 §3.5.5.5).
    omega_max_factor : float
        Highest frequency as a multiple of ω_p [-], in (1, 10] (default 5).
    """

    hs: float
    tp: float
    depth: float
    direction_deg: float = 90.0
    spreading_s: float = 0.0
    gamma: float | None = None
    omega_max_factor: float = 5.0

    def __post_init__(self) -> None:
        positive("ShortCrestedSea.hs", self.hs)
        positive("ShortCrestedSea.tp", self.tp)
        positive("ShortCrestedSea.depth", self.depth)
        in_range("ShortCrestedSea.direction_deg", self.direction_deg, 0.0, 180.0)
        in_range("ShortCrestedSea.spreading_s", self.spreading_s, 0.0, 100.0)
        if self.gamma is not None:
            in_range("ShortCrestedSea.gamma", self.gamma, 1.0, 7.0)
        in_range(
            "ShortCrestedSea.omega_max_factor",
            self.omega_max_factor,
            1.0,
            10.0,
            low_inclusive=False,
        )

    def components(self, duration: float, seed: int | None) -> dict[str, np.ndarray]:
        """Frequency components ω, amplitude a·G·sin θ, k cos θ, φ for a record ≥ duration."""
        positive("duration", duration)
        dw = 2.0 * math.pi / duration
        wp = 2.0 * math.pi / self.tp
        n = max(math.ceil(self.omega_max_factor * wp / dw), 8)
        w = dw * np.arange(1, n + 1)
        rng = np.random.default_rng(seed)
        phase = rng.uniform(0.0, 2.0 * math.pi, n)
        theta = directions_cos2s(n, self.direction_deg, self.spreading_s, rng)
        amp = np.sqrt(2.0 * jonswap(w, self.hs, self.tp, self.gamma) * dw)
        g = seabed_transfer(w, self.depth)
        k = wave_number(w, self.depth)
        return {
            "omega": w,
            "amplitude": amp * g * np.sin(theta),
            "k_axial": k * np.cos(theta),
            "phase": phase,
            "theta": theta,
        }

    def node_kinematics(
        self,
        x: np.ndarray,
        duration: float,
        *,
        dt: float | None = None,
        seed: int | None = 0,
        stages: tuple[tuple[float, float], ...] | None = None,
        build_up: float = 0.0,
        block_nodes: int = 64,
    ) -> NodeKinematics:
        """Velocity and acceleration normal to the pipe at positions ``x`` [m] over [0, duration].

        Parameters
        ----------
        x : array
            Node positions along the pipe axis [m].
        duration : float
            Length of the series [s], > 0.
        dt : float or None
            Sample interval [s]; None → T_p/60 (12 samples per period at 5ω_p; the
            solver interpolates linearly between samples).
        seed : int or None
            Seed of the phases and directions.
        stages, build_up : see :func:`storm_envelope`; None → constant sea state.
        block_nodes : int
            Nodes per FFT block (memory of the complex work array).
        """
        x = np.asarray(x, dtype=float)
        positive("duration", duration)
        step = self.tp / 60.0 if dt is None else positive("dt", dt)
        non_negative("build_up", build_up)
        n_t = math.ceil(duration / step) + 1
        # record length: a power-of-two FFT with the requested sample interval, ≥ duration
        nfft = 1 << max(math.ceil(math.log2(n_t + 1)), 4)
        comp = self.components(nfft * step, seed)
        w = comp["omega"]
        if w.size >= nfft // 2:
            raise InputError(
                f"dt = {step!r} s is invalid: too coarse for ω_max = {w[-1]:.3g} rad/s"
                f" (need dt < {math.pi / w[-1]:.3g} s)"
            )
        time = step * np.arange(n_t)
        if stages is not None:
            env, denv = storm_envelope(time, stages, build_up)
        else:
            env, denv = np.ones(n_t), np.zeros(n_t)
        vel = np.empty((n_t, x.size), dtype=np.float32)
        acc = np.empty((n_t, x.size), dtype=np.float32)
        half = nfft // 2 + 1
        for b0 in range(0, x.size, block_nodes):
            xb = x[b0 : b0 + block_nodes]
            c = comp["amplitude"][None, :] * np.exp(
                1j * (comp["phase"][None, :] - np.outer(xb, comp["k_axial"]))
            )
            spec = np.zeros((xb.size, half), dtype=complex)
            spec[:, 1 : w.size + 1] = 0.5 * nfft * c
            u = np.fft.irfft(spec, n=nfft, axis=1)[:, :n_t]
            spec[:, 1 : w.size + 1] *= 1j * w[None, :]
            a = np.fft.irfft(spec, n=nfft, axis=1)[:, :n_t]
            vel[:, b0 : b0 + xb.size] = (u * env[None, :]).T
            acc[:, b0 : b0 + xb.size] = (a * env[None, :] + u * denv[None, :]).T
        return NodeKinematics(t0=0.0, dt=step, velocity=vel, acceleration=acc)


def regular_node_kinematics(
    n_nodes: int,
    duration: float,
    dt: float,
    amplitude: float,
    period: float,
    *,
    ramp: float = 0.0,
    x: np.ndarray | None = None,
    wavelength: float | None = None,
) -> NodeKinematics:
    """Regular near-bed velocity U = e(t)·U_w sin(ωt − κx) at every node (tests, examples).

    ``ramp`` [s]: linear ramp of the amplitude from 0; ``wavelength`` [m] along the pipe (None:
    in phase along the whole line, i.e. a long-crested wave normal to the pipe).
    """
    n_t = math.ceil(duration / dt) + 1
    t = dt * np.arange(n_t)
    w = 2.0 * math.pi / positive("period", period)
    kx = 0.0 if wavelength is None else 2.0 * math.pi / wavelength
    xx = np.zeros(n_nodes) if x is None else np.asarray(x, dtype=float)
    arg = w * t[:, None] - kx * xx[None, :]
    if ramp > 0.0:
        e = np.minimum(t / ramp, 1.0)[:, None]
        de = np.where(t < ramp, 1.0 / ramp, 0.0)[:, None]
    else:
        e = np.ones((n_t, 1))
        de = np.zeros((n_t, 1))
    u = amplitude * np.sin(arg)
    a = amplitude * w * np.cos(arg)
    return NodeKinematics(
        t0=0.0,
        dt=dt,
        velocity=(e * u).astype(np.float32),
        acceleration=(e * a + de * u).astype(np.float32),
    )
