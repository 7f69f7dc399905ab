"""The near-bed flow synthesiser: seeded random-phase wave velocity U(t), U̇(t) (pure numpy).

Every synthesised wave flow of the package (a sea state's record, the V–H load envelope, a
storm on a section, a storm along a pipeline) is built from the same stages:

1. **Spectrum** (:func:`bed_spectrum`, :func:`sea_state_spectrum`): the JONSWAP or
   Pierson–Moskowitz surface spectrum S_ηη (:func:`onbottom.hydro.spectra.jonswap`,
   DNV-RP-C205 §3.5.5) and its linear transfer to the seabed, S_UU = G² S_ηη,
   G = ω / sinh(k d) (DNV-RP-F109 §3.4.3, :func:`onbottom.hydro.kinematics.seabed_transfer`).
2. **Amplitudes** (:func:`spectral_amplitudes`): a_j = √(2 S(ω_j) Δω) on equal bands Δω —
   the standard random-phase method (DNV-RP-C205 §3.5.11); the variance of the signal is
   M_0 of the discretised spectrum.
3. **Phases** (:func:`random_phases`): φ_j uniform on [0, 2π) from
   ``numpy.random.default_rng(seed)``; the same seed gives bitwise the same series.
4. **Evaluation**, x(t) = Σ_j a_j cos(ω_j t + φ_j) and its derivative, by one of three
   equivalent sums: :func:`direct_sum` (any times; bands ω_j = (j + ½)Δω of
   :func:`midpoint_grid`), :func:`offset_fft_sum` (the same bands on a uniform time grid, one
   complex inverse FFT) and :func:`harmonic_series` (harmonics ω_j = jΔω of a record at least
   as long as the storm, :func:`harmonic_grid`, one inverse real FFT).
5. **Spreading** (:mod:`onbottom.hydro.spreading`): on a section the flow normal to the pipe is
   scaled by R_D and the sign of sin θ_w; along a pipeline each component gets its own
   direction from the cos^s density and the spreading comes out of the sum (single summation).
6. **Stage blending** (:func:`stage_weights`, :func:`add_stage`): stage weights w_k(t) (linear
   build-up, blends, decay; see :class:`~onbottom.inputs.storm.Storm`) multiply each stage's
   series: U = Σ_k w_k U_k, U̇ = Σ_k (w_k U̇_k + ẇ_k U_k). The phases are drawn once per storm
   and shared by all stages, so stage blends are coherent.
7. **Per-node evaluation** (:func:`node_components`, :func:`node_block_series`): the pipeline's
   short-crested flow u_n(x, t) = Σ_j a_j G sin θ_j cos(ω_j t − k_j x cos θ_j + φ_j) at a
   block of nodes, one inverse real FFT per node and stage.

The public synthesisers built from these stages: :func:`random_phase_series`,
:func:`near_bed_velocity_series`, :func:`bed_velocity_record` (load envelope),
:func:`section_storm_flow` (:func:`onbottom.hydro.storm_kinematics.storm_kinematics`) and
:func:`node_synthesis` with :func:`node_block_series`
(:func:`onbottom.hydro.short_crested.pipeline_kinematics`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.fft import irfft, next_fast_len

from onbottom._validate import positive
from onbottom.hydro.kinematics import seabed_transfer, wave_number
from onbottom.hydro.spectra import jonswap
from onbottom.hydro.spreading import direction_sign, directions_cos_s, spreading_factor
from onbottom.inputs.storm import SeaState, Storm

__all__ = [
    "NodeSynthesis",
    "add_stage",
    "bed_spectrum",
    "bed_velocity_record",
    "direct_sum",
    "harmonic_grid",
    "harmonic_series",
    "midpoint_grid",
    "near_bed_velocity_series",
    "node_block_series",
    "node_components",
    "node_synthesis",
    "offset_fft_sum",
    "random_phase_series",
    "random_phases",
    "regular_velocity_series",
    "sea_state_spectrum",
    "section_storm_flow",
    "spectral_amplitudes",
    "stage_weights",
]


# ---------------------------------------------------------------- spectrum and amplitudes


def sea_state_spectrum(sea: SeaState, omega: NDArray) -> NDArray:
    """Surface spectrum S_ηη(ω) [m²·s/rad] of a sea state (JONSWAP; γ = 1 is P–M)."""
    return jonswap(omega, sea.hs, sea.tp, sea.peak_enhancement)


def bed_spectrum(
    omega: NDArray, depth: float, hs: float, tp: float, gamma: float | None
) -> NDArray:
    """Near-bed velocity spectrum S_UU = G(ω)² S_ηη(ω) [m²/s/rad] of a JONSWAP sea state.

    ``omega`` [rad/s], ``depth`` d [m], ``hs`` H_s [m], ``tp`` T_p [s], ``gamma`` γ [-] (None:
    the DNV rule of :func:`onbottom.hydro.spectra.jonswap`).
    """
    return seabed_transfer(omega, depth) ** 2 * jonswap(omega, hs, tp, gamma)


def spectral_amplitudes(spectrum: NDArray, d_omega: float) -> NDArray:
    """Component amplitudes a_j = √(2 S(ω_j) Δω) [x] of a one-sided spectrum S [x²·s/rad].

    ``d_omega`` Δω [rad/s]; negative spectral values count as zero.
    """
    return np.sqrt(2.0 * np.maximum(spectrum, 0.0) * d_omega)


def random_phases(seed: int | np.random.Generator | None, n: int) -> NDArray:
    """n phases φ_j [rad] uniform on [0, 2π) from ``numpy.random.default_rng(seed)``.

    A :class:`numpy.random.Generator` continues its own stream (the pipeline draws its
    direction numbers after the phases from the same generator).
    """
    rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
    return rng.uniform(0.0, 2.0 * math.pi, n)


# ---------------------------------------------------------------- frequency grids


def midpoint_grid(tp: float, n_components: int, omega_max_factor: float) -> tuple[NDArray, float]:
    """Band centres ω_j = (j + ½)Δω [rad/s], Δω = f ω_p / N, j < N (f = ``omega_max_factor``).

    The record of these bands repeats after 2π/Δω = N T_p / f.
    """
    wp = 2.0 * math.pi / tp
    dw = omega_max_factor * wp / n_components
    return dw * (np.arange(n_components) + 0.5), dw


def harmonic_grid(n_samples: int, sample_interval: float, *, fast: bool) -> tuple[int, float]:
    """(N_fft, Δω): an even record length N_fft >= ``n_samples`` and Δω = 2π/(N_fft Δt) [rad/s].

    The harmonics jΔω repeat after N_fft Δt >= the record, so the series never repeats within
    it. ``fast``: N_fft with small prime factors (scipy's ``next_fast_len``), else the next even
    number.
    """
    nfft = n_samples + (n_samples % 2)
    if fast:
        nfft = next_fast_len(nfft, real=True)
        while nfft % 2:
            nfft = next_fast_len(nfft + 1, real=True)
    return nfft, 2.0 * math.pi / (nfft * sample_interval)


# ---------------------------------------------------------------- evaluation


def direct_sum(
    omega: NDArray, amplitude: NDArray, phase: NDArray, time: NDArray
) -> tuple[NDArray, NDArray]:
    """x(t) = Σ_j a_j cos(ω_j t + φ_j) and dx/dt at any times (O(n_t · n_ω) work)."""
    arg = np.outer(time, omega) + phase
    return np.cos(arg) @ amplitude, -np.sin(arg) @ (amplitude * omega)


def offset_fft_sum(
    amplitude: NDArray, phase: NDArray, d_omega: float, n_fft: int, n_t: int
) -> tuple[NDArray, NDArray, NDArray]:
    """(t, x, dx/dt) of :func:`direct_sum` on the bands ω_j = (j + ½)Δω, by one inverse FFT.

    With t_m = m Δt, Δt = 2π/(N Δω) (N = ``n_fft`` >= the number of bands):
    Σ_j a_j cos(ω_j t_m + φ_j) = Re[e^{iΔω t_m/2} Σ_j a_j e^{iφ_j} e^{2πi jm/N}], m < ``n_t``.
    """
    n_c = amplitude.size
    w = d_omega * (np.arange(n_c) + 0.5)
    dt = 2.0 * math.pi / d_omega / n_fft
    c = np.zeros(n_fft, dtype=complex)
    c[:n_c] = amplitude * np.exp(1j * phase)
    cw = np.zeros(n_fft, dtype=complex)
    cw[:n_c] = c[:n_c] * w
    t = dt * np.arange(n_t)
    shift = np.exp(0.5j * d_omega * t)
    x = (shift * np.fft.ifft(c)[:n_t] * n_fft).real
    dxdt = (1j * shift * np.fft.ifft(cw)[:n_t] * n_fft).real
    return t, x, dxdt


def harmonic_series(
    spec: NDArray,
    omega: NDArray,
    n_fft: int,
    n_t: int,
    inverse_rfft: Callable[..., NDArray] = irfft,
    *,
    overwrite: bool = False,
    bins: slice | None = None,
) -> tuple[NDArray, NDArray]:
    """x and dx/dt at t_m = mΔt, m < ``n_t``, from one-sided harmonic coefficients.

    ``spec[..., j]`` = (N/2) a_j e^{iφ_j} on the harmonics ``omega[j]`` = jΔω, j = 0 … N/2
    (N = ``n_fft``, last axis), so that x(t_m) = Σ_j a_j cos(jΔω t_m + φ_j) is one inverse real
    FFT; dx/dt is that of iω·spec. ``inverse_rfft``: ``scipy.fft.irfft`` or
    ``numpy.fft.irfft``; ``overwrite``: multiply ``spec`` by iω in place (no work copy), only
    on the harmonics ``bins`` when given (the others must be zero).
    """
    x = inverse_rfft(spec, n_fft, axis=-1)[..., :n_t]
    if overwrite:
        band = slice(None) if bins is None else bins
        spec[..., band] *= 1j * omega[band]
        d = spec
    else:
        d = 1j * omega * spec
    return x, inverse_rfft(d, n_fft, axis=-1)[..., :n_t]


# ---------------------------------------------------------------- stage blending


def stage_weights(storm: Storm, t: NDArray) -> tuple[NDArray, NDArray]:
    """w_k(t) [-] and dw_k/dt [1/s] of the storm's stages, shape (n_stages, n_t).

    Linear blends of length ``transition_s`` centred on each stage boundary, times the linear
    build-up and decay envelope; Σ_k w_k = envelope.
    """
    ns = len(storm.stages)
    w = np.zeros((ns, t.size))
    dw = np.zeros((ns, t.size))
    starts = storm.stage_start_times
    ends = [s + st.duration_s for s, st in zip(starts, storm.stages, strict=True)]
    h = 0.5 * storm.transition_s
    for k in range(ns):
        # the first stage starts at 1, the last does not end: constants, not arrays
        up, dup = _ramp(t, starts[k], h) if k > 0 else (1.0, 0.0)
        down, ddown = _ramp(t, ends[k], h) if k < ns - 1 else (0.0, 0.0)
        w[k] = np.subtract(up, down)
        dw[k] = np.subtract(dup, ddown)
    env = np.ones(t.size)
    denv = np.zeros(t.size)
    if storm.build_up_s > 0.0:
        m = t < storm.build_up_s
        env[m] = t[m] / storm.build_up_s
        denv[m] = 1.0 / storm.build_up_s
    if storm.decay_s > 0.0:
        t_dec = storm.duration_s - storm.decay_s
        m = t > t_dec
        env[m] = np.maximum(storm.duration_s - t[m], 0.0) / storm.decay_s
        denv[m] = -1.0 / storm.decay_s
    return w * env, dw * env + w * denv


def _ramp(t: NDArray, centre: float, half: float) -> tuple[NDArray, NDArray]:
    """0 → 1 linearly over [centre − half, centre + half] (a step when half = 0), and its slope."""
    if half > 0.0:
        x = (t - (centre - half)) / (2.0 * half)
        return np.clip(x, 0.0, 1.0), np.where((x > 0.0) & (x < 1.0), 1.0 / (2.0 * half), 0.0)
    return (t >= centre).astype(float), np.zeros(t.size)


def add_stage(u: NDArray, a: NDArray, w: NDArray, dw: NDArray, u_k: NDArray, a_k: NDArray) -> None:
    """Blend one stage in place: U += w_k U_k, U̇ += w_k U̇_k + ẇ_k U_k (time on the last axis)."""
    u += w * u_k
    a += w * a_k + dw * u_k


# ---------------------------------------------------------------- synthesisers


def random_phase_series(
    omega: np.ndarray, spectrum: np.ndarray, time: np.ndarray, seed: int | None
) -> tuple[np.ndarray, np.ndarray]:
    """Synthesise x(t) and dx/dt from a one-sided spectrum by random phases (direct sum).

    Parameters
    ----------
    omega : array
        Equally spaced band-centre frequencies ω_j [rad/s], > 0.
    spectrum : array
        S(ω_j) [x²·s/rad].
    time : array
        Times t [s].
    seed : int or None
        Seed of ``numpy.random.default_rng`` for the phases.

    Returns
    -------
    x, dxdt : arrays
        The signal [x] and its time derivative [x/s].
    """
    w = np.asarray(omega, dtype=float)
    s = np.asarray(spectrum, dtype=float)
    t = np.asarray(time, dtype=float)
    dw = float(w[1] - w[0]) if w.size > 1 else 1.0
    amp = spectral_amplitudes(s, dw)
    return direct_sum(w, amp, random_phases(seed, w.size), t)


def near_bed_velocity_series(
    time: np.ndarray,
    hs: float,
    tp: float,
    depth: float,
    *,
    gamma: float | None = None,
    seed: int | None = 0,
    n_components: int = 256,
    omega_max_factor: float = 5.0,
) -> tuple[np.ndarray, np.ndarray]:
    """Near-bed wave velocity U(t) and dU/dt normal to the pipe from a JONSWAP sea state.

    :func:`bed_spectrum` on the bands of :func:`midpoint_grid`, synthesised with seeded random
    phases by :func:`direct_sum` (long-crested waves travelling normal to the pipe).

    Parameters
    ----------
    time : array
        Times [s].
    hs, tp : float
        Significant wave height [m] and peak period [s], > 0.
    depth : float
        Water depth [m], > 0.
    gamma : float or None
        JONSWAP γ [-]; None → DNV rule.
    seed : int or None
        Random-phase seed.
    n_components : int
        Number of frequency bands, >= 8.
    omega_max_factor : float
        Upper frequency as a multiple of ω_p [-], > 1.
    """
    positive("tp", tp)
    if n_components < 8:
        raise ValueError("n_components must be >= 8")
    w, _ = midpoint_grid(tp, n_components, omega_max_factor)
    return random_phase_series(w, bed_spectrum(w, depth, hs, tp, gamma), time, seed)


def regular_velocity_series(
    time: np.ndarray, amplitude: float, period: float, phase: float = 0.0
) -> tuple[np.ndarray, np.ndarray]:
    """Regular near-bed velocity U(t) = U_w sin(2πt/T + φ) and dU/dt [m/s, m/s²]."""
    t = np.asarray(time, dtype=float)
    w = 2.0 * math.pi / positive("period", period)
    return amplitude * np.sin(w * t + phase), amplitude * w * np.cos(w * t + phase)


def bed_velocity_record(
    hs: float,
    tp: float,
    depth: float,
    gamma: float,
    seed: int | None,
    n_components: int,
    duration: float,
    samples_per_peak_period: int,
) -> tuple[NDArray, NDArray, NDArray]:
    """(t, U, dU/dt) of :func:`near_bed_velocity_series` (same bands, amplitudes and phases,
    ``omega_max_factor`` 5) on a uniform grid by :func:`offset_fft_sum`.

    Δt is the largest step <= T_p/``samples_per_peak_period`` that divides the repeat period
    2π/Δω; the record stops at ``duration`` [s] or at the repeat period.
    """
    w, dw = midpoint_grid(tp, n_components, 5.0)
    amp = spectral_amplitudes(bed_spectrum(w, depth, hs, tp, gamma), dw)
    phase = random_phases(seed, n_components)
    period = 2.0 * math.pi / dw
    n_fft = max(2 * n_components, math.ceil(period / (tp / samples_per_peak_period)))
    dt = period / n_fft
    n_t = min(n_fft, math.floor(duration / dt) + 1)
    return offset_fft_sum(amp, phase, dw, n_fft, n_t)


def section_storm_flow(
    storm: Storm, depth: float, sample_interval: float, omega_max_factor: float
) -> tuple[NDArray, NDArray, NDArray]:
    """U(t_m), U̇(t_m) normal to a pipe section and the stage weights of a storm.

    Harmonics of a fast FFT length (:func:`harmonic_grid`) up to ``omega_max_factor`` × the
    highest ω_p (and below the Nyquist frequency); one set of phases for all harmonics of the
    record (index j = 0 … N/2); each stage's flow is scaled by R_D and the sign of sin θ_w
    (:func:`onbottom.hydro.spreading.spreading_factor`, DNV-RP-F109 §3.4.3) and blended.

    Returns
    -------
    (velocity [m/s], acceleration [m/s²], weights (n_stages, n_t) [-]) at t_m = m Δt_s,
    m = 0 … ⌈duration/Δt_s⌉.
    """
    dts = sample_interval
    n = math.ceil(storm.duration_s / dts) + 1
    nfft, dw = harmonic_grid(n, dts, fast=True)
    wmax = omega_max_factor * max(2.0 * math.pi / s.tp for s in storm.stages)
    nbins = nfft // 2 + 1
    omega = dw * np.arange(nbins)
    active = (omega > 0.0) & (omega <= wmax) & (omega < math.pi / dts)
    # the active harmonics are j = 1 … J (ω_j increases): the phases are drawn for j <= J only
    # (the generator's first draws, as from a draw of all N/2 + 1) and e^{iφ_j} computed there;
    # the other harmonics carry no energy (zero coefficients)
    n_active = int(np.count_nonzero(active))
    rot = np.zeros(nbins, dtype=complex)
    rot[active] = np.exp(1j * random_phases(storm.seed, n_active + 1)[1:])
    g2 = np.zeros(nbins)
    g2[active] = seabed_transfer(omega[active], depth) ** 2
    weights, dweights = stage_weights(storm, np.arange(n) * dts)
    u = np.zeros(n)
    a = np.zeros(n)
    for k, sea in enumerate(storm.stages):
        s_eta = np.zeros(nbins)
        s_eta[active] = sea_state_spectrum(sea, omega[active])
        amp = spectral_amplitudes(g2 * s_eta, dw)
        rd = float(spreading_factor(sea.spreading_s, wave_direction_deg=sea.direction_deg))
        spec = (0.5 * nfft) * amp * rot * (rd * direction_sign(sea.direction_deg))
        uk, ak = harmonic_series(spec, omega, nfft, n)
        add_stage(u, a, weights[k], dweights[k], uk, ak)
    return u, a, weights


@dataclass(frozen=True, eq=False)
class NodeSynthesis:
    """Everything the per-node evaluation of a storm needs (:func:`node_synthesis`).

    Attributes: ``sample_interval`` Δt_s [s]; ``n_t`` samples; ``n_fft`` record length;
    ``omega`` harmonics jΔω [rad/s], j = 0 … N/2; ``n_components`` n_c (harmonics 1 … n_c
    carry energy); ``phase`` φ_j [rad] (n_c); ``stage_amplitude`` a_j G sin θ_j [m/s] and
    ``stage_kx`` k_j cos θ_j [rad/m] per stage (n_c each); ``weights``, ``dweights`` w_k(t),
    ẇ_k(t) (n_stages, n_t).
    """

    sample_interval: float
    n_t: int
    n_fft: int
    omega: NDArray
    n_components: int
    phase: NDArray
    stage_amplitude: tuple[NDArray, ...]
    stage_kx: tuple[NDArray, ...]
    weights: NDArray
    dweights: NDArray


def node_components(
    sea: SeaState, omega: NDArray, d_omega: float, transfer: NDArray, k: NDArray, uniform: NDArray
) -> tuple[NDArray, NDArray]:
    """(a_j G_j sin θ_j [m/s], k_j cos θ_j [rad/m]) of one stage of a single-summation sea.

    ``omega`` ω_j [rad/s], ``transfer`` G(ω_j) [1/s], ``k`` k_j [rad/m], ``uniform`` numbers in
    [0, 1) giving the directions θ_j (:func:`onbottom.hydro.spreading.directions_cos_s`).
    """
    theta = directions_cos_s(uniform, sea.direction_deg, sea.spreading_s)
    a = spectral_amplitudes(sea_state_spectrum(sea, omega), d_omega)
    return a * transfer * np.sin(theta), k * np.cos(theta)


def node_synthesis(
    storm: Storm, depth: float, sample_interval: float, omega_max_factor: float
) -> NodeSynthesis:
    """Set up the short-crested flow of a storm along a pipeline (harmonics, phases, directions).

    Harmonics jΔω, j = 1 … n_c, of an even record length (:func:`harmonic_grid`) up to
    ``omega_max_factor`` × the highest ω_p or the Nyquist frequency; one generator
    ``default_rng(storm.seed)`` draws the phases then the direction numbers, shared by all
    stages.
    """
    dts = sample_interval
    n_t = math.ceil(storm.duration_s / dts) + 1
    nfft, dw = harmonic_grid(n_t, dts, fast=False)
    wmax = min(omega_max_factor * max(2.0 * math.pi / s.tp for s in storm.stages), math.pi / dts)
    n_c = max(int(wmax / dw), 1)
    w = dw * np.arange(1, n_c + 1)
    rng = np.random.default_rng(storm.seed)
    phase = random_phases(rng, n_c)
    uni = rng.uniform(0.0, 1.0, n_c)
    g = seabed_transfer(w, depth)
    k = wave_number(w, depth)
    weights, dweights = stage_weights(storm, dts * np.arange(n_t))
    parts = [node_components(sea, w, dw, g, k, uni) for sea in storm.stages]
    return NodeSynthesis(
        sample_interval=dts,
        n_t=n_t,
        n_fft=nfft,
        omega=dw * np.arange(nfft // 2 + 1),
        n_components=n_c,
        phase=phase,
        stage_amplitude=tuple(p[0] for p in parts),
        stage_kx=tuple(p[1] for p in parts),
        weights=weights,
        dweights=dweights,
    )


def node_block_series(
    syn: NodeSynthesis, x: NDArray, work: NDArray | None = None
) -> tuple[NDArray, NDArray]:
    """U(x_i, t_m), U̇(x_i, t_m) normal to the pipe at the nodes ``x`` [m], shape (n_x, n_t).

    One inverse real FFT per node and stage (:func:`harmonic_series` with ``numpy.fft``),
    blended by :func:`add_stage`. ``work``: a complex array of at least (n_x, N/2 + 1) reused
    between blocks.
    """
    nb = x.size
    half = syn.n_fft // 2 + 1
    if work is None:
        work = np.zeros((nb, half), dtype=complex)
    n_c = syn.n_components
    band = slice(1, n_c + 1)
    ub = np.zeros((nb, syn.n_t))
    ab = np.zeros((nb, syn.n_t))
    for kk in range(len(syn.stage_amplitude)):
        c = syn.stage_amplitude[kk][None, :] * np.exp(
            1j * (syn.phase[None, :] - np.outer(x, syn.stage_kx[kk]))
        )
        spec = work[:nb]
        spec[:] = 0.0
        spec[:, band] = 0.5 * syn.n_fft * c
        uk, ak = harmonic_series(
            spec, syn.omega, syn.n_fft, syn.n_t, np.fft.irfft, overwrite=True, bins=band
        )
        add_stage(ub, ab, syn.weights[kk][None, :], syn.dweights[kk][None, :], uk, ak)
    return ub, ab
