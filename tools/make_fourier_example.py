"""Write the synthetic example Fourier table ``src/onbottom/data/fourier_example.csv``.

Run from the repository root: ``python3 tools/make_fourier_example.py``.

The table holds **no measured and no licensed numbers**. It is the Fourier fit
(:func:`onbottom.hydro.fourier_fit.synthetic_morison_table`, harmonic order 5) of a Morison
force in regular flow, F_Y = ½ρD C_D W|W| + ρ(πD²/4) C_M U̇, F_Z = ½ρD C_L W², W = U + V, with
coefficients that vary with K by invented, smooth rules:

    C_D(K) = 0.7 + 4/(K + 4),   C_L(K) = 0.9 + 3/(K + 4),   C_M(K) = 2.5 + 3.2/(K + 4)

(C_D → 0.7, C_L → 0.9 at large K, the common-practice constants of
``onbottom.hydro.force_model.MorisonLift``; C_M ≈ 3.03 at K = 2). It exists so that the
Fourier model can be run and tested out of the box; a design needs a table measured for the
pipe (for example the DHI / AGA-PRCI databases, under their licences) or fitted from the
user's own flume tests with :mod:`onbottom.hydro.fourier_fit`.
"""

from __future__ import annotations

import sys
from pathlib import Path

K_GRID = [2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 12.5, 15.0, 20.0, 25.0, 30.0, 40.0, 60.0]
M_GRID = [0.0, 0.2, 0.4, 0.6, 0.8]
HARMONICS = 5
OUT = Path(__file__).resolve().parents[1] / "src" / "onbottom" / "data" / "fourier_example.csv"


def cd(k: float) -> float:
    """Invented drag coefficient rule C_D(K) [-]."""
    return 0.7 + 4.0 / (k + 4.0)


def cl(k: float) -> float:
    """Invented lift coefficient rule C_L(K) [-]."""
    return 0.9 + 3.0 / (k + 4.0)


def cm(k: float) -> float:
    """Invented inertia coefficient rule C_M(K) [-]."""
    return 2.5 + 3.2 / (k + 4.0)


def build():
    """The example table (a :class:`~onbottom.hydro.fourier_table.FourierTable`)."""
    from onbottom.hydro.fourier_fit import synthetic_morison_table

    return synthetic_morison_table(
        K_GRID,
        M_GRID,
        cd=cd,
        cm=cm,
        cl=cl,
        harmonics=HARMONICS,
        source="SYNTHETIC example: Fourier fit of a Morison force with invented C(K) rules;"
        " no measured or licensed data (tools/make_fourier_example.py)",
        metadata={
            "rules": "C_D=0.7+4/(K+4); C_L=0.9+3/(K+4); C_M=2.5+3.2/(K+4)",
        },
    )


def main() -> int:
    """Write the table."""
    build().to_csv(
        OUT,
        comments=[
            "onbottom synthetic Fourier force coefficient table (example only, not for design)",
            "F_Y = s 1/2 rho D U_m^2 [A0 + sum_n (A_n cos n theta + B_n sin n theta)],"
            " theta = pi tau / T_h per half-cycle; F_Z likewise without s",
            "M is the signed half-cycle current ratio s V / U_m; see docs/theory/fourier_model.md",
        ],
    )
    print(f"wrote {OUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
