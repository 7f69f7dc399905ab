"""Reproduce the calibration workflow of Youssef & Cassidy (2014) on simulated records.

The measured centrifuge records of Youssef (2012) are not public. The workflow is therefore
exercised on *virtual* records: each of the seven tests is simulated by the section solver
with the paper's Table 2 parameters, resampled onto a 1 s time base and perturbed by seeded
Gaussian measurement noise; A, B, C and μ are then fitted back to each record alone (a
Table 2) and recommended values follow the paper's rules (a Table 3,
:data:`onbottom.calibration.summary.PAPER_RULES`). The comparison with the paper's values is a
check of the *method* (how well the data determine each parameter), not of the model against
the tests; see ``docs/validation/calibration.md``.

Run ``python -m onbottom.calibration.paper`` to print the tables.
"""

from __future__ import annotations

import argparse
import logging
import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import xarray as xr

from onbottom._validate import non_negative, positive
from onbottom.calibration.fit import CalibrationResult, calibrate
from onbottom.calibration.objective import HISTORY_ONLY, MisfitWeights
from onbottom.calibration.parameters import Parameter
from onbottom.calibration.records import TestRecord, record_from_result
from onbottom.calibration.simulators import CentrifugeSimulator
from onbottom.calibration.summary import fit_each, parameter_table, recommend, to_markdown

__all__ = [
    "PAPER_TABLE2",
    "PaperCalibration",
    "calibrate_paper",
    "default_parameters",
    "gamma_dependence",
    "paper_records",
    "virtual_record",
]

logger = logging.getLogger(__name__)

PAPER_TABLE2: dict[str, dict[str, float]] = {
    "Inclined 1": {"A": 0.25, "B": 0.35, "C": 0.79, "mu": 0.48},
    "Inclined 2": {"A": 0.25, "B": 0.45, "C": 1.05, "mu": 0.60},
    "Inclined 3": {"A": 0.25, "B": 0.45, "C": 1.18, "mu": 0.65},
    "Inclined 4": {"A": 0.45, "B": 0.35, "C": 0.96, "mu": 0.75},
    "Inclined 5": {"A": 0.25, "B": 0.35, "C": 0.84, "mu": 0.85},
    "Regular": {"A": 0.25, "B": 0.28, "C": 0.97, "mu": 0.85},
    "Irregular": {"A": 0.25, "B": 0.24, "C": 1.12, "mu": 0.85},
}
"""Youssef & Cassidy (2014) Table 2: calibrated A, B, C, μ of each centrifuge test."""


def default_parameters(
    start: dict[str, float] | None = None, gamma: float | None = None
) -> tuple[Parameter, ...]:
    """A, B, C, μ with the bounds used here (μ: the paper's search range 0.4–1.2).

    Start values default to the paper's Table 3 (μ = 0.6); ``gamma`` [N/m³], if given, is
    added as a fixed parameter.
    """
    s = {"A": 0.25, "B": 0.35, "C": 0.98, "mu": 0.6, **(start or {})}
    bounds = {"A": (0.05, 1.0), "B": (0.05, 1.0), "C": (0.5, 1.5), "mu": (0.4, 1.2)}
    out = [Parameter(name=k, value=s[k], lower=lo, upper=hi) for k, (lo, hi) in bounds.items()]
    if gamma is not None:
        g = positive("gamma", gamma)
        out.append(
            Parameter(name="gamma", value=g, lower=0.5 * g, upper=2 * g, vary=False, units="N/m3")
        )
    return tuple(out)


def virtual_record(
    name: str,
    params: dict[str, float],
    *,
    gamma: float | None = None,
    noise: float = 0.01,
    sample_interval: float = 1.0,
    seed: int | np.random.SeedSequence | None = 0,
    simulator: CentrifugeSimulator | None = None,
) -> TestRecord:
    """A record of centrifuge test ``name`` simulated with ``params`` plus measurement noise.

    Parameters
    ----------
    name : str
        Centrifuge test ("Inclined 1", ..., "Irregular").
    params : dict
        A, B, C, mu (and optionally gamma) of the simulation.
    gamma : float or None
        γ' [N/m³] (None: preset default).
    noise : float
        Standard deviation of the Gaussian noise as a fraction of each channel's scale
        (u: the displacement limit, w: max penetration), >= 0.
    sample_interval : float
        Time step of the record [s], > 0 (the simulation is linearly resampled).
    seed : int, SeedSequence or None
        Seed of the noise.
    simulator : CentrifugeSimulator or None
        Simulator (default ``CentrifugeSimulator(gamma=gamma)``).
    """
    non_negative("noise", noise)
    positive("sample_interval", sample_interval)
    sim_fn = simulator or CentrifugeSimulator(gamma=gamma)
    tmp = TestRecord(
        name=name,
        data=xr.Dataset(
            {"y": ("time", [0.0, 0.0]), "z": ("time", [0.0, 0.0])}, coords={"time": [0.0, 1.0]}
        ),
        diameter=1.0,
        programme=name,
    )
    res = sim_fn(tmp, params)
    if not res.success:
        raise RuntimeError(f"simulation of {name} with {params} failed: {res.message}")
    ds = res.data
    t_end = float(ds["time"].values[-1])
    t = np.arange(0.0, t_end, sample_interval)
    if t_end - t[-1] > 1e-9:
        t = np.append(t, t_end)
    out = xr.Dataset(coords={"time": t})
    for col in ("H", "V", "y", "z"):
        out[col] = ("time", np.interp(t, ds["time"].values, ds[col].values))
    limit = _attr_float(ds.attrs.get("displacement_limit"))
    rng = np.random.default_rng(seed)
    u_scale = limit if limit is not None else float(np.max(np.abs(out["y"])))
    out["y"] = out["y"] + noise * u_scale * rng.standard_normal(t.size)
    out["z"] = out["z"] + noise * float(np.max(out["z"])) * rng.standard_normal(t.size)
    out.attrs = dict(ds.attrs)
    return record_from_result(
        out,
        name=name,
        programme=name,
        metadata={
            "source": "virtual record: section solver + Gaussian noise",
            "truth": ", ".join(f"{k}={v:g}" for k, v in params.items()),
            "noise_fraction": float(noise),
        },
    )


def _attr_float(value: Any) -> float | None:
    try:
        x = float(value)
    except (TypeError, ValueError):
        return None
    return x if math.isfinite(x) else None


def paper_records(
    names: Sequence[str] | None = None,
    *,
    gamma: float | None = None,
    noise: float = 0.01,
    seed: int = 0,
) -> list[TestRecord]:
    """Virtual records of the seven tests with the paper's Table 2 parameters (independent
    noise streams from ``np.random.SeedSequence(seed).spawn``)."""
    names = list(names or PAPER_TABLE2)
    seeds = np.random.SeedSequence(seed).spawn(len(names))
    sim = CentrifugeSimulator(gamma=gamma)
    return [
        virtual_record(n, PAPER_TABLE2[n], gamma=gamma, noise=noise, seed=s, simulator=sim)
        for n, s in zip(names, seeds, strict=True)
    ]


@dataclass(frozen=True, kw_only=True)
class PaperCalibration:
    """Per-test fits (Table 2), recommended values (Table 3) and the truth used."""

    results: tuple[CalibrationResult, ...]
    table2: list[dict[str, Any]]
    table3: list[dict[str, Any]]
    truth: dict[str, dict[str, float]]
    wall_time: float

    def markdown(self) -> str:
        names = ["A", "B", "C", "mu"]
        rows = []
        for row in self.table2:
            t = self.truth.get(row["case"], {})
            r = {"case": row["case"]}
            for n in names:
                if n in row:
                    se = row.get(f"{n}_se", math.nan)
                    r[n] = f"{row[n]:.3f} ± {se:.3f}" if math.isfinite(se) else f"{row[n]:.3f}"
                    r[f"{n} (paper)"] = t.get(n, math.nan)
            zs = [
                abs(row[n] - t[n]) / row[f"{n}_se"]
                for n in names
                if n in t and row.get(f"{n}_se", 0.0) > 0.0
            ]
            r["max |z|"] = max(zs) if zs else math.nan
            r["misfit"] = row["misfit"]
            rows.append(r)
        return (
            "Table 2 (fitted ± 1 s.e.; paper values used to make the records)\n\n"
            + to_markdown(rows, floatfmt=".3g")
            + "\nTable 3 (recommended; rules of the paper)\n\n"
            + to_markdown(
                self.table3,
                columns=["parameter", "min", "mean", "max", "rule", "recommended"],
            )
        )


def calibrate_paper(
    records: Sequence[TestRecord] | None = None,
    *,
    gamma: float | None = None,
    noise: float = 0.01,
    seed: int = 0,
    start: dict[str, float] | None = None,
    weights: MisfitWeights | None = None,
    **calibrate_kwargs: Any,
) -> PaperCalibration:
    """Fit A, B, C, μ to each (virtual) record and summarise as Tables 2 and 3.

    ``records`` default to :func:`paper_records` (``gamma``, ``noise``, ``seed``).
    ``weights`` default to :data:`~onbottom.calibration.objective.HISTORY_ONLY`: the records
    are noisy, and the scalar features of a noisy signal are biased.
    ``calibrate_kwargs`` go to :func:`~onbottom.calibration.fit.calibrate` (method, maxiter,
    popsize, client, n_workers, ...).
    """
    t0 = time.perf_counter()
    recs = (
        list(records) if records is not None else paper_records(gamma=gamma, noise=noise, seed=seed)
    )
    calibrate_kwargs.setdefault("simulator", CentrifugeSimulator(gamma=gamma))
    calibrate_kwargs.setdefault("seed", seed)
    results = fit_each(
        recs, default_parameters(start), weights=weights or HISTORY_ONLY, **calibrate_kwargs
    )
    rows = parameter_table(results)
    return PaperCalibration(
        results=tuple(results),
        table2=rows,
        table3=recommend(rows),
        truth={r.name: PAPER_TABLE2.get(r.name, {}) for r in recs},
        wall_time=time.perf_counter() - t0,
    )


def gamma_dependence(
    name: str = "Inclined 1",
    gammas: Sequence[float] = (6.0e3, 7.5e3, 9.0e3),
    *,
    record_gamma: float | None = None,
    noise: float = 0.01,
    seed: int = 0,
    **calibrate_kwargs: Any,
) -> list[dict[str, Any]]:
    """How the fitted A, B, C, μ depend on the assumed submerged unit weight γ'.

    The paper does not give γ'. One virtual record of test ``name`` is made with
    ``record_gamma`` (None: the preset default) and calibrated assuming each of ``gammas``
    [N/m³] in turn; the rows show how the factors absorb a wrong γ' (all of Eqs 3–8 scale with
    γ'D² or γ'D³, so A, B and C trade off against γ').
    """
    rec = virtual_record(name, PAPER_TABLE2[name], gamma=record_gamma, noise=noise, seed=seed)
    calibrate_kwargs.setdefault("seed", seed)
    calibrate_kwargs.setdefault("weights", HISTORY_ONLY)
    rows = []
    for g in gammas:
        res = calibrate(
            rec, default_parameters(), simulator=CentrifugeSimulator(gamma=g), **calibrate_kwargs
        )
        row: dict[str, Any] = {"gamma [kN/m3]": g / 1e3}
        for p in res.parameters:
            row[p.name] = p.value
        row["misfit"] = res.misfit
        rows.append(row)
    return rows


def main(argv: Sequence[str] | None = None) -> None:  # pragma: no cover - CLI wrapper
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--gamma", type=float, default=None, help="γ' [N/m³]")
    ap.add_argument("--noise", type=float, default=0.01)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--workers", type=int, default=0)
    ap.add_argument("--maxiter", type=int, default=40)
    ap.add_argument("--gamma-study", action="store_true", help="also fit Inclined 1 with other γ'")
    args = ap.parse_args(argv)
    out = calibrate_paper(
        gamma=args.gamma,
        noise=args.noise,
        seed=args.seed,
        n_workers=args.workers,
        maxiter=args.maxiter,
    )
    print(out.markdown())
    print(f"wall time {out.wall_time:.1f} s\n")
    if args.gamma_study:
        rows = gamma_dependence(n_workers=args.workers)
        print("Inclined 1 record made with the preset γ', fitted assuming other γ':\n")
        print(to_markdown(rows))


if __name__ == "__main__":  # pragma: no cover
    main()
