"""How the Fourier model's two phase rules behave in irregular flow (prints a table).

A Fourier table of a pure, constant-coefficient Morison force (C_D 0.7, C_M 3.29, C_L 0.9;
K 2…201 in steps of 15 %, M 0…±0.8, N = 5) reproduces Morison exactly in regular flow; in
irregular flow it cannot, since each half-wave is forced into the shape of a regular wave's.
This script measures by how much, on one hour of a JONSWAP-like near-bed record (T_p 12 s,
U_s = 2 std(U) = 1 m/s, D 0.5 m, Δt 0.05 s, seed 2), for the phase rules "time" and "flow"
and memory weights 0 and 0.25: the RMS difference from Morison (F_Y, F_Z) over the record
after the first 100 s, relative to Morison's peak |F_Y|; the number of steps where F_Y jumps
by more than 20 % of that peak; the share of samples forced by the series (the rest use the
quasi-steady law); half-cycles clamped to the grid / all half-cycles.

    python benchmarks/fourier_irregular_check.py      (about a minute; the table fit dominates)
"""

from __future__ import annotations

import math
import sys

import numpy as np

from onbottom.hydro import _fourier_kernel as FK
from onbottom.hydro.fourier import FourierModel
from onbottom.hydro.fourier_fit import synthetic_morison_table

D, RHO = 0.5, 1025.0
CD, CM, CL = 0.7, 3.29, 0.9


SMOKE = "--smoke" in sys.argv[1:]
"""Tiny size (CI: the script finishes and prints its figures)."""


def record(seed: int = 2, duration: float = 3600.0, dt: float = 0.05):
    """JONSWAP-shaped (γ 3.3, T_p 12 s) near-bed velocity scaled to U_s = 2 std = 1 m/s."""
    rng = np.random.default_rng(seed)
    om = np.linspace(0.25, 1.5, 300)
    wp = 2.0 * math.pi / 12.0
    sig = 0.08
    spec = (
        om**-5
        * np.exp(-1.25 * (wp / om) ** 4)
        * 3.3 ** np.exp(-((om - wp) ** 2) / (2 * sig**2 * wp**2))
    )
    amp = np.sqrt(2.0 * spec * (om[1] - om[0]))
    ph = rng.uniform(0.0, 2.0 * math.pi, om.size)
    t = np.arange(1, int(duration / dt)) * dt
    u = np.zeros_like(t)
    dudt = np.zeros_like(t)
    for a, w, p in zip(amp, om, ph, strict=True):
        u += a * np.cos(w * t + p)
        dudt -= a * w * np.sin(w * t + p)
    scale = 1.0 / (2.0 * u.std())
    return t, u * scale, dudt * scale


def main() -> None:
    """Print the comparison table."""
    k_grid = [float(x) for x in np.round(2.0 * 1.15 ** np.arange(34), 4)]
    m_grid = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8]
    table = synthetic_morison_table(k_grid, m_grid, cd=CD, cm=CM, cl=CL, harmonics=5)
    t, u, dudt = record(duration=150.0) if SMOKE else record()
    print("V [m/s]  phase  w     rms F_Y  rms F_Z  jumps>20%  series  clamped")
    for v in (0.0, 0.3):
        w_tot = u + v
        fy_m = 0.5 * RHO * D * CD * w_tot * np.abs(w_tot) + 0.25 * math.pi * RHO * D * D * CM * dudt
        fz_m = 0.5 * RHO * D * CL * w_tot * w_tot
        peak = np.abs(fy_m).max()
        for phase in ("time", "flow"):
            for memory in (0.0, 0.25):
                params = FourierModel(table=table, phase=phase, memory_weight=memory).params()
                st = np.zeros(16)
                sn = np.zeros(16)
                out = np.zeros(4)
                f = np.empty((t.size, 2))
                mode = np.empty(t.size)
                for i in range(t.size):
                    FK.fourier_kernel(params, st, t[i], u[i], dudt[i], v, 0.0, D, RHO, sn, out)
                    st[:] = sn
                    f[i] = out[0], out[2]
                    mode[i] = sn[FK.S_MODE]
                late = t > 100.0
                rms_y = math.sqrt(np.mean((f[late, 0] - fy_m[late]) ** 2)) / peak
                rms_z = math.sqrt(np.mean((f[late, 1] - fz_m[late]) ** 2)) / peak
                jumps = int(np.sum(np.abs(np.diff(f[:, 0])) > 0.2 * peak))
                print(
                    f"{v:7.1f}  {phase:5s}  {memory:4.2f}  {rms_y:7.3f}  {rms_z:7.3f}  {jumps:9d}"
                    f"  {mode.mean():6.2f}  {sn[FK.S_NCLAMP]:.0f}/{sn[FK.S_NCROSS]:.0f}"
                )


if __name__ == "__main__":
    main()
