"""Reproduction of the seven centrifuge tests of Youssef & Cassidy (2014).

Runs every test with the calibrated Table 2 parameters and with the Table 3 recommended
values (each with the test's μ), and writes a comparison table (cycles to the displacement
limit against Table 1; initial and largest penetration; displacement at the end of the runaway
against the paper's Inclined 1 simulation, 3.70 m), NetCDF files and one figure per run. A
sensitivity table for the submerged unit weight γ' (not given in the paper) is written too.
Assumptions: :mod:`onbottom.dynamics.centrifuge` and docs/validation/youssef_cassidy_2014.md.
"""

from __future__ import annotations

import csv
import logging
import math
import re
from collections.abc import Callable, Iterable, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from onbottom.dynamics.centrifuge import (
    SUBMERGED_UNIT_WEIGHT,
    TESTS,
    get_test,
    run_centrifuge_test,
)
from onbottom.dynamics.section import SectionResult

__all__ = [
    "PAPER_OBSERVATIONS",
    "ReproductionRow",
    "gamma_sensitivity",
    "reproduce",
    "run_reproduction",
    "write_csv",
    "write_markdown",
]

logger = logging.getLogger(__name__)

PAPER_OBSERVATIONS: dict[str, dict[str, float]] = {
    "Inclined 1": {
        "initial_penetration": 0.065,
        "max_penetration": 0.09,
        "final_displacement_simulation": 3.70,
    },
}
"""Values the paper gives for Inclined 1: initial penetration ≈ 0.065 m and penetration
≈ 0.09 m under small cycles (read from Fig. 9d, approximate), the paper's simulated final
displacement 3.70 m (text). Cycles used come from Table 1 (:data:`TESTS`)."""


@dataclass(frozen=True, kw_only=True, slots=True)
class ReproductionRow:
    """One simulated test (lengths in m)."""

    test: str
    parameter_set: str
    A: float
    B: float
    C: float
    mu: float
    gamma_kn: float
    alpha_deg: float | None
    cycles_model: float | None
    cycles_paper: float
    cycles_difference: float | None
    initial_penetration: float
    initial_penetration_paper: float | None
    max_penetration: float
    max_penetration_paper: float | None
    final_displacement: float
    final_displacement_paper_simulation: float | None
    displacement_limit: float
    status: str
    n_steps: int


def slug(name: str) -> str:
    """File-name form of a test name ("Inclined 1" → "inclined_1")."""
    return re.sub(r"[^a-z0-9]+", "_", name.lower()).strip("_")


def _row(name: str, parameter_set: str, result: SectionResult) -> ReproductionRow:
    import json

    t = get_test(name)
    params = json.loads(result.data.attrs["parameters"])
    obs = PAPER_OBSERVATIONS.get(t.name, {})
    cyc = result.cycles_to_limit
    alpha = result.data.attrs.get("alpha_deg")
    return ReproductionRow(
        test=t.name,
        parameter_set=parameter_set,
        A=float(params.get("A", math.nan)),
        B=float(params.get("B", math.nan)),
        C=float(params.get("C", math.nan)),
        mu=float(params["friction_coefficient"]),
        gamma_kn=float(result.data.attrs["submerged_unit_weight"]) / 1e3,
        alpha_deg=float(alpha) if isinstance(alpha, (int, float)) else None,
        cycles_model=cyc,
        cycles_paper=t.cycles_used,
        cycles_difference=None if cyc is None else cyc - t.cycles_used,
        initial_penetration=result.summary["initial_penetration"],
        initial_penetration_paper=obs.get("initial_penetration"),
        max_penetration=result.summary["max_penetration"],
        max_penetration_paper=obs.get("max_penetration"),
        final_displacement=result.summary["final_displacement"],
        final_displacement_paper_simulation=obs.get("final_displacement_simulation"),
        displacement_limit=t.displacement_limit,
        status=result.message,
        n_steps=result.n_steps,
    )


def run_reproduction(
    *,
    tests: Iterable[str] | None = None,
    parameter_sets: Sequence[str] = ("table2", "recommended"),
    gamma: float | None = None,
    progress: bool = False,
    **options: Any,
) -> list[tuple[ReproductionRow, SectionResult]]:
    """Run the tests; each run goes on past the limit to the end of the runaway.

    Parameters
    ----------
    tests : iterable of str or None
        Test names (None = all seven).
    parameter_sets : sequence of {"table2", "recommended"}
        Parameter sets to run.
    gamma : float or None
        γ' [N/m³] (None = :data:`SUBMERGED_UNIT_WEIGHT`).
    progress : bool
        tqdm over runs.
    **options
        Passed to :func:`run_centrifuge_test` (``time_basis``, ``shape``, ...).
    """
    names = list(TESTS) if tests is None else [get_test(n).name for n in tests]
    jobs = [(n, ps) for ps in parameter_sets for n in names]
    it: Iterable[tuple[str, str]] = jobs
    if progress:
        from tqdm.auto import tqdm

        it = tqdm(jobs, desc="centrifuge tests", unit="run")
    out = []
    for name, ps in it:
        res = run_centrifuge_test(
            name, parameters=ps, gamma=gamma, after_limit="runaway_end", **options
        )
        if not res.success:
            logger.warning("%s (%s): %s", name, ps, res.message)
        out.append((_row(name, ps, res), res))
    return out


def gamma_sensitivity(
    gammas: Sequence[float] = (6.0e3, 7.5e3, 9.0e3),
    *,
    tests: Iterable[str] | None = None,
    parameter_set: str = "table2",
) -> list[ReproductionRow]:
    """Rows for several submerged unit weights γ' [N/m³] (the paper does not give γ')."""
    rows = []
    for g in gammas:
        rows += [
            r for r, _ in run_reproduction(tests=tests, parameter_sets=(parameter_set,), gamma=g)
        ]
    return rows


def _fmt(x: Any, nd: int = 3) -> str:
    if x is None:
        return "–"
    if isinstance(x, float):
        if math.isnan(x):
            return "–"
        return f"{x:.{nd}f}"
    return str(x)


_COLUMNS = (
    ("test", "test", 0),
    ("parameter_set", "parameters", 0),
    ("A", "A", 2),
    ("B", "B", 2),
    ("C", "C", 2),
    ("mu", "μ", 2),
    ("gamma_kn", "γ' kN/m³", 1),
    ("alpha_deg", "α °", 0),
    ("cycles_model", "cycles to limit (model)", 2),
    ("cycles_paper", "cycles (Table 1)", 2),
    ("cycles_difference", "Δ cycles", 2),
    ("initial_penetration", "z_i model m", 3),
    ("initial_penetration_paper", "z_i test m", 3),
    ("max_penetration", "max w model m", 3),
    ("max_penetration_paper", "max w test m", 3),
    ("final_displacement", "final u model m", 2),
    ("final_displacement_paper_simulation", "final u paper sim m", 2),
    ("displacement_limit", "limit m", 1),
)


def write_markdown(rows: Sequence[ReproductionRow], path: str | Path, title: str = "") -> Path:
    """Write the rows as a Markdown table (units in the headers)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    lines = []
    if title:
        lines += [f"# {title}", ""]
    lines.append("| " + " | ".join(h for _, h, _ in _COLUMNS) + " |")
    lines.append("|" + "---|" * len(_COLUMNS))
    for r in rows:
        d = asdict(r)
        lines.append("| " + " | ".join(_fmt(d[k], nd) for k, _, nd in _COLUMNS) + " |")
    lines += [
        "",
        "cycles: load cycles (groups for Regular/Irregular) until |u| first reaches the box"
        " limit; final u: displacement where the runaway past the limit stops (velocity"
        " returns to zero); z_i/max w test and the paper's simulated final u (3.70 m) are"
        " given for Inclined 1 only (Fig. 9 and text); –: not given or not reached.",
        "",
    ]
    path.write_text("\n".join(lines), encoding="utf-8")
    return path


def write_csv(rows: Sequence[ReproductionRow], path: str | Path) -> Path:
    """Write the rows as CSV (SI lengths in m, γ' in kN/m³ as the column name says)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fields = list(ReproductionRow.__dataclass_fields__)
    with path.open("w", newline="", encoding="utf-8") as fh:
        w = csv.DictWriter(fh, fieldnames=fields)
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if v is None else v) for k, v in asdict(r).items()})
    return path


def reproduce(
    out: str | Path,
    *,
    figure: Callable[[ReproductionRow, SectionResult], Any] | None = None,
    netcdf: bool = True,
    sensitivity: bool = True,
    gamma: float | None = None,
    progress: bool = False,
) -> dict[str, Any]:
    """Run the reproduction and write everything under ``out``.

    Files: ``table.md``, ``table.csv`` (all runs), ``gamma_sensitivity.md/.csv``,
    ``netcdf/<test>_<set>.nc`` and, if ``figure`` is given, ``plots/<test>_<set>.png``.

    Parameters
    ----------
    out : path
        Output folder.
    figure : callable or None
        ``figure(row, result) -> matplotlib Figure`` for each run (study does not import
        plotting; the CLI passes :func:`onbottom.plotting.section.reproduction_figure`).
    netcdf, sensitivity : bool
        Write NetCDF files / the γ' sensitivity table.
    gamma : float or None
        γ' [N/m³].
    progress : bool
        tqdm over runs.

    Returns
    -------
    dict
        ``rows`` (list of :class:`ReproductionRow`), ``files`` (paths written).
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    runs = run_reproduction(gamma=gamma, progress=progress)
    rows = [r for r, _ in runs]
    files = [
        write_markdown(
            rows,
            out / "table.md",
            "Youssef & Cassidy (2014) centrifuge tests: onbottom reproduction",
        ),
        write_csv(rows, out / "table.csv"),
    ]
    if netcdf:
        for row, res in runs:
            files.append(res.save(out / "netcdf" / f"{slug(row.test)}_{row.parameter_set}.nc"))
    if figure is not None:
        for row, res in runs:
            fig = figure(row, res)
            p = out / "plots" / f"{slug(row.test)}_{row.parameter_set}.png"
            p.parent.mkdir(parents=True, exist_ok=True)
            fig.savefig(p, dpi=110)
            files.append(p)
            close = getattr(getattr(fig, "canvas", None), "manager", None)
            if close is not None:  # pyplot-managed figure: release it
                import matplotlib.pyplot as plt

                plt.close(fig)
    if sensitivity:
        base = SUBMERGED_UNIT_WEIGHT if gamma is None else gamma
        srows = gamma_sensitivity((0.8 * base, base, 1.2 * base))
        files.append(
            write_markdown(
                srows,
                out / "gamma_sensitivity.md",
                "Sensitivity to the submerged unit weight γ' (Table 2 parameters)",
            )
        )
        files.append(write_csv(srows, out / "gamma_sensitivity.csv"))
    return {"rows": rows, "files": files}
