"""Fit a Fourier coefficient table from force and velocity time series (e.g. a flume test).

Procedure (``docs/theory/fourier_model.md``, "Fitting a table"), for each regular-wave run of
total flow W(t) = U(t) + V at the pipe and measured forces F_Y(t), F_Z(t) per unit length:

1. split W into half-cycles at its zero crossings (crossing times by a cubic through the four
   samples around the sign change, Newton from the linear estimate); only complete
   half-cycles (crossing to crossing) are used, and ``discard`` of them first (start-up);
2. per half-cycle k: direction s_k, peak P_k of |W| (parabola through the largest sample and
   its neighbours), wave amplitude a_k = P_k − s_k V (>= P_k/2) and period
   T_k / f(s_k V / a_k), f(m) = ½ + asin(m)/π — the same estimators the kernel uses
   (:mod:`onbottom.hydro._fourier_kernel`), exact for a regular wave with a current;
3. the run's U_m and T are the means over its half-cycles; K = U_m T / D, M = V / U_m (or the
   nominal values given with the run, to put runs on a design grid);
4. per half-cycle, least squares of s_k F_Y / (½ρD U_m²) and F_Z / (½ρD U_m²) on
   1, cos θ, sin θ, …, cos Nθ, sin Nθ with θ = π (t − t_start) / T_k;
5. the coefficients are averaged over the half-cycles of one direction: the table rows
   (K, +|M|) (half-cycles with the current) and (K, −|M|) (against it); without current all
   half-cycles give the row (K, 0).

:func:`synthetic_morison_table` builds a table from a Morison force in regular flow this way;
it makes the package's synthetic example (``tools/make_fourier_example.py``) and the
verification that a Morison table reproduces Morison.
"""

from __future__ import annotations

import csv
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from onbottom._validate import in_range, integer, non_negative, positive
from onbottom.errors import InputError
from onbottom.hydro.fourier_table import (
    MAX_HARMONICS,
    FourierTable,
    coefficient_names,
    fourier_basis,
)

__all__ = [
    "FourierRun",
    "HalfCycle",
    "RunFit",
    "fit_fourier_table",
    "fit_run",
    "half_cycles",
    "morison_regular_run",
    "read_run_csv",
    "synthetic_morison_table",
    "table_from_fits",
]

M_CLIP = 0.95
"""|m| limit of f(m), as in the kernel."""


def _fraction(m: float) -> float:
    return 0.5 + math.asin(min(max(m, -M_CLIP), M_CLIP)) / math.pi


@dataclass(frozen=True, eq=False)
class FourierRun:
    """One regular-wave run: time series at the pipe (all arrays of one length).

    Parameters
    ----------
    time : array
        t [s], strictly increasing.
    velocity : array
        Total flow W = U + V normal to the pipe [m/s].
    force_y, force_z : array
        Measured lateral and vertical (lift, upward) force per unit length [N/m].
    current : float
        Steady current V [m/s] (signed) contained in ``velocity``.
    keulegan_carpenter, current_ratio : float or None
        Nominal K and M = V / U_m of the test (>= 0; keys of the table rows); None = measured.
    label : str
        Name of the run in error messages.
    """

    time: np.ndarray
    velocity: np.ndarray
    force_y: np.ndarray
    force_z: np.ndarray
    current: float = 0.0
    keulegan_carpenter: float | None = None
    current_ratio: float | None = None
    label: str = "run"

    def __post_init__(self) -> None:
        arrays = {}
        for key in ("time", "velocity", "force_y", "force_z"):
            a = np.asarray(getattr(self, key), dtype=float)
            if a.ndim != 1 or a.size < 8:
                raise InputError(
                    f"FourierRun({self.label}).{key} is invalid: expected a 1-D series of"
                    " >= 8 samples"
                )
            if not np.all(np.isfinite(a)):
                i = int(np.argmax(~np.isfinite(a)))
                raise InputError(
                    f"FourierRun({self.label}).{key}[{i}] = {float(a[i])!r} is invalid: not finite"
                )
            arrays[key] = a
        n = arrays["time"].size
        for key, a in arrays.items():
            if a.size != n:
                raise InputError(
                    f"FourierRun({self.label}).{key} has {a.size} samples, time has {n}"
                )
        dt = np.diff(arrays["time"])
        if np.any(dt <= 0.0):
            i = int(np.argmax(dt <= 0.0))
            raise InputError(
                f"FourierRun({self.label}).time is invalid: not strictly increasing at sample"
                f" {i + 1} ({float(arrays['time'][i + 1])!r} after {float(arrays['time'][i])!r})"
            )
        for key, a in arrays.items():
            a.setflags(write=False)
            object.__setattr__(self, key, a)
        object.__setattr__(self, "current", float(self.current))
        if self.keulegan_carpenter is not None:
            positive(f"FourierRun({self.label}).keulegan_carpenter", self.keulegan_carpenter)
        if self.current_ratio is not None:
            in_range(f"FourierRun({self.label}).current_ratio", self.current_ratio, 0.0, 1.0)


@dataclass(frozen=True)
class HalfCycle:
    """A complete half-cycle of a record: direction, start and end [s], sample slice, peak."""

    sign: int
    start: float
    end: float
    first: int
    stop: int
    peak: float


@dataclass(frozen=True, eq=False)
class RunFit:
    """Result of :func:`fit_run`: the run's K, M, U_m, T and the rows it gives.

    ``rows`` maps the signed half-cycle current ratio M_h to the mean coefficients (2, 2N+1);
    ``counts`` the number of half-cycles averaged; ``rms`` the RMS residual of the normalised
    force over all fitted samples (a measure of how regular the run was).
    """

    keulegan_carpenter: float
    current_ratio: float
    amplitude: float
    period: float
    rows: dict[float, np.ndarray]
    counts: dict[float, int]
    rms: float
    half_cycles: list[HalfCycle] = field(default_factory=list)

    def summary(self) -> dict[str, float | int]:
        """``K`` [-], ``M`` [-], ``U_m`` [m/s], ``T`` [s], ``half_cycles`` (the number
        averaged over every M_h) and ``rms`` [-] of the run (``onbottom fourier-fit --json``)."""
        return {
            "K": self.keulegan_carpenter,
            "M": self.current_ratio,
            "U_m": self.amplitude,
            "T": self.period,
            "half_cycles": sum(self.counts.values()),
            "rms": self.rms,
        }


def _crossing_time(t: np.ndarray, w: np.ndarray, i: int) -> float:
    """Zero of W between samples i and i+1: cubic through i−1..i+2 (linear at the ends)."""
    tc = t[i] + (t[i + 1] - t[i]) * w[i] / (w[i] - w[i + 1])
    if i < 1 or i + 2 >= t.size:
        return float(tc)
    ts = t[i - 1 : i + 3] - t[i]
    c = np.polyfit(ts, w[i - 1 : i + 3], 3)
    dc = np.polyder(c)
    x = tc - t[i]
    for _ in range(4):
        slope = np.polyval(dc, x)
        if slope == 0.0:
            break
        x -= np.polyval(c, x) / slope
    if not (0.0 <= x <= t[i + 1] - t[i]):
        return float(tc)
    return float(t[i] + x)


def half_cycles(time: np.ndarray, velocity: np.ndarray) -> list[HalfCycle]:
    """The complete half-cycles of W(t) (between two zero crossings), in time order.

    Samples where W = 0 exactly take the sign of the sample before (the first ones of the one
    after). Fewer than two crossings: an empty list.
    """
    t = np.asarray(time, dtype=float)
    w = np.asarray(velocity, dtype=float)
    s = np.sign(w)
    nz = np.nonzero(s)[0]
    if nz.size == 0:
        return []
    s[: nz[0]] = s[nz[0]]
    for i in range(nz[0] + 1, s.size):
        if s[i] == 0.0:
            s[i] = s[i - 1]
    idx = np.nonzero(s[1:] != s[:-1])[0]
    tcs = [_crossing_time(t, w, int(i)) for i in idx]
    out = []
    aw = np.abs(w)
    for j in range(len(idx) - 1):
        first, stop = int(idx[j]) + 1, int(idx[j + 1]) + 1
        k = first + int(np.argmax(aw[first:stop]))
        peak = float(aw[k])
        if first < k < stop - 1:
            c = np.polyfit(t[k - 1 : k + 2] - t[k], aw[k - 1 : k + 2], 2)
            if c[0] < 0.0:
                peak = float(c[2] - c[1] * c[1] / (4.0 * c[0]))
        out.append(HalfCycle(int(s[first]), tcs[j], tcs[j + 1], first, stop, peak))
    return out


def fit_run(
    run: FourierRun,
    *,
    diameter: float,
    rho: float,
    harmonics: int = 5,
    discard: int = 0,
) -> RunFit:
    """Fourier coefficients of one regular-wave run (procedure in the module docstring).

    diameter D [m]; rho ρ [kg/m³]; harmonics N in [1, 8]; discard: complete half-cycles
    dropped at the start (wake build-up of a test), >= 0.
    """
    d = positive("fit_run.diameter", diameter)
    rho = positive("fit_run.rho", rho)
    n = integer("fit_run.harmonics", harmonics, 1, MAX_HARMONICS)
    discard = integer("fit_run.discard", discard, 0)
    hcs = half_cycles(run.time, run.velocity)[discard:]
    if not hcs:
        raise InputError(
            f"FourierRun({run.label}): no complete half-cycle (two zero crossings of the"
            f" total flow) after discarding {discard}; a flow that does not reverse has no"
            " Fourier coefficients"
        )
    v = run.current
    amps, periods = [], []
    for h in hcs:
        a = max(h.peak - h.sign * v, 0.5 * h.peak)
        amps.append(a)
        periods.append((h.end - h.start) / _fraction(h.sign * v / a))
    um = float(np.mean(amps))
    period = float(np.mean(periods))
    kc = um * period / d if run.keulegan_carpenter is None else float(run.keulegan_carpenter)
    m = abs(v) / um if run.current_ratio is None else float(run.current_ratio)
    scale = 0.5 * rho * d * um * um
    sums: dict[float, np.ndarray] = {}
    counts: dict[float, int] = {}
    sq, nsamp = 0.0, 0
    t = run.time
    for h in hcs:
        sl = slice(h.first, h.stop)
        if h.stop - h.first < 2 * n + 2:
            raise InputError(
                f"FourierRun({run.label}): a half-cycle at t = {h.start:.4g} s has"
                f" {h.stop - h.first} samples, too few for {2 * n + 1} coefficients"
            )
        theta = math.pi * (t[sl] - h.start) / (h.end - h.start)
        basis = fourier_basis(theta, n)
        y = np.column_stack((h.sign * run.force_y[sl] / scale, run.force_z[sl] / scale))
        coef, *_ = np.linalg.lstsq(basis, y, rcond=None)
        r = basis @ coef - y
        sq += float(np.sum(r * r))
        nsamp += r.size
        key = 0.0 if v == 0.0 or m == 0.0 else (m if h.sign * v > 0.0 else -m)
        sums[key] = sums.get(key, 0.0) + coef.T
        counts[key] = counts.get(key, 0) + 1
    rows = {k: sums[k] / counts[k] for k in sorted(sums)}
    return RunFit(kc, m, um, period, rows, counts, math.sqrt(sq / nsamp), hcs)


def table_from_fits(
    fits: list[RunFit], *, source: str, metadata: dict[str, str] | None = None
) -> FourierTable:
    """Assemble the rows of several runs into a table (a full (K, M) grid; errors named)."""
    cells: dict[tuple[float, float], np.ndarray] = {}
    n = None
    for f in fits:
        for mh, coef in f.rows.items():
            key = (f.keulegan_carpenter, mh)
            if key in cells:
                raise InputError(
                    f"fit_fourier_table: two runs give the cell (K={key[0]:g}, M={key[1]:g});"
                    " give each run its nominal K and M, one run per cell"
                )
            if n is None:
                n = (coef.shape[1] - 1) // 2
            cells[key] = coef
    if not cells:
        raise InputError("fit_fourier_table: no runs")
    names = coefficient_names(n)
    rows = []
    for (k, m), coef in sorted(cells.items()):
        row = {"K": float(k), "M": float(m)}
        row.update(zip(names, (float(x) for x in coef.ravel()), strict=True))
        rows.append(row)
    return FourierTable.from_rows(rows, source=source, metadata=metadata, where="cell")


def fit_fourier_table(
    runs: list[FourierRun],
    *,
    diameter: float,
    rho: float,
    harmonics: int = 5,
    discard: int = 0,
    source: str = "fitted by onbottom.hydro.fourier_fit",
    metadata: dict[str, str] | None = None,
) -> FourierTable:
    """Fit every run (:func:`fit_run`) and assemble the table (:func:`table_from_fits`)."""
    fits = [
        fit_run(r, diameter=diameter, rho=rho, harmonics=harmonics, discard=discard) for r in runs
    ]
    return table_from_fits(fits, source=source, metadata=metadata)


RUN_COLUMNS = (("t", "s"), ("U", "m/s"), ("F_Y", "N/m"), ("F_Z", "N/m"))
"""Columns of a run CSV and the unit each must carry on the units line."""
RUN_KEYS = ("current_m_s", "K", "M", "label")
"""``# key: value`` lines a run CSV may carry (current V [m/s], nominal K and M, a name)."""


def read_run_csv(path: str | Path) -> FourierRun:
    """Read one run from CSV (strict schema; errors name the file, line and field).

    ``#`` lines are comments; ``# current_m_s: 0.3`` (the steady current V [m/s] in U, default
    0), ``# K: 10``, ``# M: 0.4`` (nominal values, optional) and ``# label: …`` are read. Then a
    header ``t,U,F_Y,F_Z``, a units line ``s,m/s,N/m,N/m``, and the samples: time [s] strictly
    increasing, total flow U + V normal to the pipe [m/s], forces per unit length [N/m].
    """
    p = Path(path)
    meta: dict[str, str] = {}
    rows: list[tuple[int, list[str]]] = []
    with p.open(encoding="utf-8", newline="") as fh:
        for no, line in enumerate(fh, start=1):
            s = line.strip()
            if not s:
                continue
            if s.startswith("#"):
                body = s.lstrip("#").strip()
                if ":" in body:
                    key, value = (x.strip() for x in body.split(":", 1))
                    if key in RUN_KEYS:
                        meta[key] = value
                continue
            rows.append((no, next(csv.reader([s]))))
    if len(rows) < 3:
        raise InputError(f"run file {str(p)!r}: expected a header, a units line and samples")
    header = [h.strip() for h in rows[0][1]]
    units = [u.strip() for u in rows[1][1]]
    names = [c for c, _ in RUN_COLUMNS]
    if header != names:
        raise InputError(
            f"run file {str(p)!r} line {rows[0][0]}: header {','.join(header)!r} is invalid:"
            f" expected {','.join(names)!r}"
        )
    if len(units) != len(RUN_COLUMNS):
        raise InputError(
            f"run file {str(p)!r} line {rows[1][0]}: the units line has {len(units)} entries"
            f" for {len(RUN_COLUMNS)} columns (expected s,m/s,N/m,N/m)"
        )
    for (col, unit), got in zip(RUN_COLUMNS, units, strict=True):
        if got != unit:
            raise InputError(
                f"run file {str(p)!r} line {rows[1][0]}: column {col} has unit {got!r}:"
                f" expected {unit!r}"
            )
    data = np.empty((len(rows) - 2, 4))
    for i, (no, fields) in enumerate(rows[2:]):
        if len(fields) != 4:
            raise InputError(f"run file {str(p)!r} line {no}: {len(fields)} fields, expected 4")
        for j, v in enumerate(fields):
            try:
                data[i, j] = float(v)
            except ValueError:
                raise InputError(
                    f"run file {str(p)!r} line {no}: {names[j]} = {v.strip()!r} is invalid:"
                    " expected a number"
                ) from None

    def number(key: str) -> float | None:
        if key not in meta:
            return None
        try:
            return float(meta[key])
        except ValueError:
            raise InputError(
                f"run file {str(p)!r}: {key} = {meta[key]!r} is invalid: expected a number"
            ) from None

    current = number("current_m_s")
    return FourierRun(
        data[:, 0],
        data[:, 1],
        data[:, 2],
        data[:, 3],
        0.0 if current is None else current,
        number("K"),
        number("M"),
        label=meta.get("label", p.name),
    )


Coefficient = float | Callable[[float], float]


def _value(c: Coefficient, kc: float) -> float:
    return float(c(kc)) if callable(c) else float(c)


def morison_regular_run(
    keulegan_carpenter: float,
    current_ratio: float,
    *,
    cd: Coefficient,
    cm: Coefficient,
    cl: Coefficient,
    diameter: float = 1.0,
    rho: float = 1025.0,
    amplitude: float = 1.0,
    n_cycles: int = 3,
    samples_per_cycle: int = 2000,
) -> FourierRun:
    """A regular-wave run whose forces are Morison's, W = U_m sin(2πt/T) + M U_m:

    F_Y = ½ρD C_D W|W| + ρ (π D²/4) C_M U̇,  F_Z = ½ρD C_L W²  (C_D, C_M, C_L: numbers or
    functions of K). T = K D / U_m; 0 <= M <= 0.9 (the flow must reverse).
    """
    kc = positive("morison_regular_run.keulegan_carpenter", keulegan_carpenter)
    m = in_range("morison_regular_run.current_ratio", current_ratio, 0.0, 0.9)
    d = positive("morison_regular_run.diameter", diameter)
    um = positive("morison_regular_run.amplitude", amplitude)
    nc = integer("morison_regular_run.n_cycles", n_cycles, 2)
    spc = integer("morison_regular_run.samples_per_cycle", samples_per_cycle, 64)
    non_negative("morison_regular_run.rho", rho)
    period = kc * d / um
    omega = 2.0 * math.pi / period
    t = np.arange(nc * spc + 1) * (period / spc)
    u = um * np.sin(omega * t)
    dudt = um * omega * np.cos(omega * t)
    w = u + m * um
    q = 0.5 * rho * d
    fy = q * _value(cd, kc) * w * np.abs(w) + 0.25 * math.pi * rho * d * d * _value(cm, kc) * dudt
    fz = q * _value(cl, kc) * w * w
    return FourierRun(t, w, fy, fz, m * um, kc, m, label=f"Morison K={kc:g} M={m:g}")


def synthetic_morison_table(
    k_values: list[float],
    m_values: list[float],
    *,
    cd: Coefficient,
    cm: Coefficient,
    cl: Coefficient,
    harmonics: int = 5,
    samples_per_cycle: int = 2000,
    source: str = "synthetic: Morison force in regular flow (onbottom.hydro.fourier_fit)",
    metadata: dict[str, str] | None = None,
) -> FourierTable:
    """A Fourier table of a pure Morison force: one regular run per K and M >= 0, fitted.

    k_values: K grid (> 0); m_values: current ratios M in [0, 0.9] (each M > 0 gives the rows
    +M and −M); cd, cm, cl: Morison coefficients, numbers or functions of K. The result holds
    no measured data.
    """
    runs = [
        morison_regular_run(
            k, m, cd=cd, cm=cm, cl=cl, n_cycles=3, samples_per_cycle=samples_per_cycle
        )
        for k in k_values
        for m in m_values
    ]
    meta = {"synthetic": "yes"} | dict(metadata or {})
    return fit_fourier_table(
        runs, diameter=1.0, rho=1025.0, harmonics=harmonics, source=source, metadata=meta
    )
