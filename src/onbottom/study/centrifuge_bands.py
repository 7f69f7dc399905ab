"""Sensitivity bands of the centrifuge reproduction over every choice the paper leaves open.

Youssef & Cassidy (2014) do not state several inputs the cycle counts of Table 1 depend on.
For each of the seven tests (Table 2 parameters) this module runs the full factorial grid of
those choices (:data:`CHOICES`), on Dask (:class:`onbottom.study.engine.ParallelMap`) or in
this process, and reports the *band* of cycles to the displacement limit: its minimum and
maximum, the run with the defaults, whether Table 1 lies inside, and the range each choice
spans alone (all others at their defaults). A verdict that holds across the band does not
depend on a guess; the validation tests assert only such verdicts
(``tests/validation/test_centrifuge_bands.py``).

The choices, their values and the default (with the reason) are in :data:`CHOICES`; the
discussion is in ``docs/validation/youssef_cassidy_2014.md``. The committed result is
``docs/validation/bands/centrifuge_bands.{csv,md}`` (``onbottom reproduce --bands``).
"""

from __future__ import annotations

import csv
import itertools
import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from onbottom.dynamics.centrifuge import SUBMERGED_UNIT_WEIGHT, TESTS, get_test, run_centrifuge_test

__all__ = [
    "ALPHA_CHOICES",
    "CHOICES",
    "BandRow",
    "BandSummary",
    "band_cases",
    "bands",
    "compute_bands",
    "read_csv",
    "run_case",
    "summarise",
    "write_csv",
    "write_markdown",
]

CHOICES: dict[str, dict[str, Any]] = {
    "shape": {
        "values": ("sine", "triangle"),
        "default": "sine",
        "why": "Table 1's fractions (.27, .75, .25, .29, .25) sit at or just past a load peak",
        "applies": "inclined",
    },
    "time_basis": {
        "values": ("paper", "prototype"),
        "default": "paper",
        "why": "the paper's durations (40/60/50 s) used as simulation time; its Inclined 1"
        " simulation stopped its runaway at 3.70 m, which needs the short time scale",
        "applies": "all",
    },
    "gamma_kn": {
        "values": (6.9, 7.5, 8.1),
        "default": 7.5,
        "why": "γ' = (G_s − 1)γ_w/(1 + e), G_s ≈ 2.75, e = 1.12–1.48 (Airey et al. 1988):"
        " 6.9–8.1 kN/m³, middle 7.5",
        "applies": "all",
    },
    "b_placement": {
        "values": ("outside", "inside"),
        "default": "outside",
        "why": "B stands before the bracket of Eqs 13–14 in the extracted text; 'inside' is"
        " the other reading the text allows",
        "applies": "all",
    },
    "max_penetration_law": {
        "values": ("reconstruction", "reconstruction_no_half"),
        "default": "reconstruction",
        "why": "Eq 8/14 reconstructed with the factor 0.5 (spec [R]); the reading without it"
        " is the alternative",
        "applies": "all",
    },
    "work_integrand": {
        "values": ("total", "passive"),
        "default": "total",
        "why": "V&S Eq 6 integrates the total resistance F_h; passive F_r only is the alternative",
        "applies": "all",
    },
    "alpha_deg": {
        "values": None,  # per test: ALPHA_CHOICES
        "default": "30° (tests 1–4), 65° (test 5)",
        "why": "tests 1–3: 30° (stated); 4: the 20°–45° hydrodynamic envelope the paper"
        " discusses, default 30° (limit-equilibrium inference, the angle of tests 1–3);"
        " 5: 60°–70° around the inferred 65° (no 20°–45° path reaches 29 cycles)",
        "applies": "inclined 4-5",
    },
}
"""Each unstated choice: its values, the default and why, and which tests it applies to."""

ALPHA_CHOICES: dict[str, tuple[float, ...]] = {
    "Inclined 1": (30.0,),
    "Inclined 2": (30.0,),
    "Inclined 3": (30.0,),
    "Inclined 4": (20.0, 25.0, 30.0, 35.0, 45.0),
    "Inclined 5": (60.0, 65.0, 70.0),
}
"""Load-path inclination α [deg] of each inclined test in the band (tests 1–3: stated)."""

_ORDER = ("shape", "time_basis", "gamma_kn", "b_placement", "max_penetration_law",
          "work_integrand", "alpha_deg")  # fmt: skip


@dataclass(frozen=True, kw_only=True, slots=True)
class BandRow:
    """One run of the band grid (Table 2 parameters)."""

    test: str
    shape: str
    time_basis: str
    gamma_kn: float
    b_placement: str
    max_penetration_law: str
    work_integrand: str
    alpha_deg: float | None
    is_default: bool
    cycles_model: float | None
    max_penetration: float
    status: str


@dataclass(frozen=True, kw_only=True, slots=True)
class BandSummary:
    """Band of one test: cycles to the limit over the grid."""

    test: str
    n_runs: int
    cycles_paper: float
    cycles_default: float | None
    cycles_min: float | None
    cycles_max: float | None
    paper_inside: bool
    n_not_reached: int
    one_at_a_time: dict[str, tuple[float | None, float | None]]


def _defaults(test: str) -> dict[str, Any]:
    t = get_test(test)
    d = {k: v["default"] for k, v in CHOICES.items() if k != "alpha_deg"}
    d["alpha_deg"] = t.alpha_deg if t.kind == "inclined" else None
    if t.kind != "inclined":
        d["shape"] = "n/a"
    return d


def band_cases(test: str, *, reduced: bool = False) -> list[dict[str, Any]]:
    """All choice combinations of ``test`` (dicts of :data:`_ORDER` keys plus ``test``).

    ``reduced=True`` keeps only the defaults and the one-at-a-time variations (each choice
    alone), a small subset for quick checks.
    """
    t = get_test(test)
    vals: dict[str, Sequence[Any]] = {k: v["values"] for k, v in CHOICES.items()}
    vals["alpha_deg"] = ALPHA_CHOICES.get(t.name, (None,))
    if t.kind != "inclined":
        vals["shape"] = ("n/a",)
    default = _defaults(t.name)
    cases = []
    for combo in itertools.product(*(vals[k] for k in _ORDER)):
        case = dict(zip(_ORDER, combo, strict=True))
        n_diff = sum(case[k] != default[k] for k in _ORDER)
        if reduced and n_diff > 1:
            continue
        cases.append({"test": t.name, **case})
    return cases


def run_case(case: dict[str, Any]) -> BandRow:
    """Run one grid point (stops at the displacement limit)."""
    t = get_test(case["test"])
    options = {
        "b_placement": case["b_placement"],
        "max_penetration_law": case["max_penetration_law"],
        "work_integrand": case["work_integrand"],
    }
    res = run_centrifuge_test(
        t.name,
        parameters="table2",
        gamma=float(case["gamma_kn"]) * 1e3,
        time_basis=case["time_basis"],
        shape=case["shape"] if t.kind == "inclined" else "sine",
        alpha_deg=case["alpha_deg"],
        after_limit="stop",
        soil_options=options,
    )
    default = _defaults(t.name)
    return BandRow(
        test=t.name,
        shape=case["shape"],
        time_basis=case["time_basis"],
        gamma_kn=float(case["gamma_kn"]),
        b_placement=case["b_placement"],
        max_penetration_law=case["max_penetration_law"],
        work_integrand=case["work_integrand"],
        alpha_deg=case["alpha_deg"],
        is_default=all(case[k] == default[k] for k in _ORDER),
        cycles_model=res.cycles_to_limit,
        max_penetration=float(res.summary["max_penetration"]),
        status=res.message,
    )


def compute_bands(
    tests: Iterable[str] | None = None,
    *,
    mapper: Callable[[Callable[[Any], Any], Iterable[Any]], list[Any]] | None = None,
    reduced: bool = False,
) -> list[BandRow]:
    """Run the band grid of ``tests`` (None = all seven).

    Parameters
    ----------
    tests : iterable of str or None
        Test names.
    mapper : callable or None
        ``map``-like callable (:class:`onbottom.study.engine.ParallelMap` for Dask); None
        runs in this process.
    reduced : bool
        Defaults and one-at-a-time variations only (see :func:`band_cases`).
    """
    names = list(TESTS) if tests is None else [get_test(n).name for n in tests]
    cases = [c for n in names for c in band_cases(n, reduced=reduced)]
    if mapper is None:
        return [run_case(c) for c in cases]
    return list(mapper(run_case, cases))


def _range(xs: Iterable[float | None]) -> tuple[float | None, float | None]:
    v = [x for x in xs if x is not None]
    return (min(v), max(v)) if v else (None, None)


def summarise(rows: Sequence[BandRow]) -> list[BandSummary]:
    """Band of each test (in :data:`TESTS` order) from the grid rows."""
    out = []
    for name in TESTS:
        rs = [r for r in rows if r.test == name]
        if not rs:
            continue
        t = get_test(name)
        default = _defaults(name)
        d = [r for r in rs if r.is_default]
        lo, hi = _range(r.cycles_model for r in rs)
        n_none = sum(r.cycles_model is None for r in rs)
        inside = lo is not None and hi is not None and lo <= t.cycles_used <= hi
        if n_none and hi is not None:
            # a run that never reached the limit holds longer than any counted one
            inside = lo is not None and lo <= t.cycles_used
        oat = {}
        for k in _ORDER:
            sub = [r for r in rs if all(getattr(r, j) == default[j] for j in _ORDER if j != k)]
            oat[k] = _range(r.cycles_model for r in sub)
        out.append(
            BandSummary(
                test=name,
                n_runs=len(rs),
                cycles_paper=t.cycles_used,
                cycles_default=d[0].cycles_model if d else None,
                cycles_min=lo,
                cycles_max=hi,
                paper_inside=bool(inside),
                n_not_reached=n_none,
                one_at_a_time=oat,
            )
        )
    return out


def write_csv(rows: Sequence[BandRow], path: str | Path) -> Path:
    """Write the grid rows (cycles with 6 decimals; γ' in kN/m³, α in degrees)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fields = list(BandRow.__dataclass_fields__)
    with path.open("w", newline="", encoding="utf-8") as fh:
        w = csv.DictWriter(fh, fieldnames=fields, lineterminator="\n")
        w.writeheader()
        for r in rows:
            d = asdict(r)
            if d["cycles_model"] is not None:
                d["cycles_model"] = f"{d['cycles_model']:.6f}"
            d["max_penetration"] = f"{d['max_penetration']:.6f}"
            w.writerow({k: ("" if v is None else v) for k, v in d.items()})
    return path


def read_csv(path: str | Path) -> list[BandRow]:
    """Read rows written by :func:`write_csv`."""
    rows = []
    with Path(path).open(encoding="utf-8") as fh:
        for d in csv.DictReader(fh):
            rows.append(
                BandRow(
                    test=d["test"],
                    shape=d["shape"],
                    time_basis=d["time_basis"],
                    gamma_kn=float(d["gamma_kn"]),
                    b_placement=d["b_placement"],
                    max_penetration_law=d["max_penetration_law"],
                    work_integrand=d["work_integrand"],
                    alpha_deg=float(d["alpha_deg"]) if d["alpha_deg"] else None,
                    is_default=d["is_default"] == "True",
                    cycles_model=float(d["cycles_model"]) if d["cycles_model"] else None,
                    max_penetration=float(d["max_penetration"]),
                    status=d["status"],
                )
            )
    return rows


def _f(x: float | None, nd: int = 2) -> str:
    return "–" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.{nd}f}"


_LABELS = {
    "shape": "cycle shape",
    "time_basis": "time basis",
    "gamma_kn": "γ'",
    "b_placement": "B placement",
    "max_penetration_law": "Eq 8 reading",
    "work_integrand": "work integrand",
    "alpha_deg": "α",
}


def write_markdown(summaries: Sequence[BandSummary], path: str | Path) -> Path:
    """Write the band table and the one-at-a-time ranges as Markdown."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    lines = [
        "# Centrifuge tests: sensitivity bands over the unstated choices",
        "",
        "Generated by `onbottom reproduce --bands` (`onbottom.study.centrifuge_bands`);"
        " Table 2 parameters, passive rule `elastoplastic`. Cycles: load cycles (groups for"
        " Regular/Irregular) until |u| first reaches the box limit.",
        "",
        "| test | runs | cycles Table 1 | cycles default | band min | band max |"
        " Table 1 inside band |",
        "|---|---|---|---|---|---|---|",
    ]
    for s in summaries:
        extra = f" ({s.n_not_reached} runs never reach the limit)" if s.n_not_reached else ""
        lines.append(
            f"| {s.test} | {s.n_runs} | {_f(s.cycles_paper)} | {_f(s.cycles_default)} |"
            f" {_f(s.cycles_min)} | {_f(s.cycles_max)} |"
            f" {'yes' if s.paper_inside else 'no'}{extra} |"
        )
    lines += [
        "",
        "## Each choice alone (all others at their defaults): cycles min – max",
        "",
        "| test | " + " | ".join(_LABELS[k] for k in _ORDER) + " |",
        "|---|" + "---|" * len(_ORDER),
    ]
    for s in summaries:
        cells = []
        for k in _ORDER:
            lo, hi = s.one_at_a_time[k]
            cells.append("–" if lo is None else f"{_f(lo)} – {_f(hi)}")
        lines.append(f"| {s.test} | " + " | ".join(cells) + " |")
    lines += ["", "## Choices, values and defaults", ""]
    for k in _ORDER:
        c = CHOICES[k]
        vals = c["values"] if c["values"] is not None else ALPHA_CHOICES
        if isinstance(vals, dict):
            vals = "; ".join(f"{t}: {', '.join(f'{a:g}°' for a in v)}" for t, v in vals.items())
        else:
            vals = ", ".join(str(v) for v in vals)
        lines.append(f"- **{_LABELS[k]}** (`{k}`): {vals}; default {c['default']}: {c['why']}.")
    lines += [
        f"- γ' default {SUBMERGED_UNIT_WEIGHT / 1e3:.1f} kN/m³ is"
        " `onbottom.dynamics.centrifuge.SUBMERGED_UNIT_WEIGHT`.",
        "",
    ]
    path.write_text("\n".join(lines), encoding="utf-8")
    return path


def bands(
    out: str | Path,
    *,
    tests: Iterable[str] | None = None,
    scheduler_address: str | None = None,
    n_workers: int | None = None,
    progress: bool = False,
) -> dict[str, Any]:
    """Compute the bands (on Dask unless ``n_workers == 0``) and write them under ``out``.

    Files: ``centrifuge_bands.csv`` (every run) and ``centrifuge_bands.md`` (the bands).

    Parameters
    ----------
    out : path
        Output folder (the committed copy lives in ``docs/validation/bands/``).
    tests : iterable of str or None
        Test names (None = all seven).
    scheduler_address : str or None
        Running Dask scheduler to use; None = an embedded local cluster.
    n_workers : int or None
        Local worker processes (None = one per core; 0 = serial in this process, no Dask).
    progress : bool
        tqdm bar.

    Returns
    -------
    dict
        ``rows``, ``summaries``, ``files``.
    """
    from onbottom.study.engine import ParallelMap, dask_client

    out = Path(out)
    if n_workers == 0 and scheduler_address is None:
        rows = compute_bands(tests)
    else:
        with dask_client(scheduler_address=scheduler_address, n_workers=n_workers) as client:
            rows = compute_bands(tests, mapper=ParallelMap(client, progress=progress))
    summaries = summarise(rows)
    files = [
        write_csv(rows, out / "centrifuge_bands.csv"),
        write_markdown(summaries, out / "centrifuge_bands.md"),
    ]
    return {"rows": rows, "summaries": summaries, "files": files}
