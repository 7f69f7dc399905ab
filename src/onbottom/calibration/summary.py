"""Multi-test calibration summary: per-test fits (a Table 2) and recommended values (a Table 3).

Youssef & Cassidy (2014) fitted A, B, C and μ to each of seven centrifuge tests (their Table 2)
and recommended one set for calcareous sand (their Table 3) with these rules, quoted from the
paper: A — "an average value of 0.28 ... however, a conservative value of 0.25 is suggested",
i.e. the *lowest* fitted value (lower passive resistance is conservative for stability);
B — "the average value (0.35)"; C — the average (0.98); μ — not recommended from the tests
(site-specific, "from the project's geotechnical report"); only its range is reported.
:data:`PAPER_RULES` encodes these rules; pass your own ``rules`` to change them.

Tables are lists of dicts (no pandas), written as Markdown or CSV.
"""

from __future__ import annotations

import csv
import io
import math
import os
from collections.abc import Mapping, Sequence
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np

from onbottom._validate import one_of
from onbottom.calibration.fit import CalibrationResult, calibrate
from onbottom.calibration.parameters import Parameter
from onbottom.calibration.records import TestRecord
from onbottom.study.engine import ParallelMap, dask_client

__all__ = [
    "PAPER_RULES",
    "RULES",
    "fit_each",
    "parameter_table",
    "recommend",
    "to_csv",
    "to_markdown",
    "write_fits",
]

RULES = ("min", "max", "mean", "median", "range")
"""Recommendation rules: the lowest, highest, mean or median fitted value, or only the range."""

PAPER_RULES: Mapping[str, str] = {"A": "min", "B": "mean", "C": "mean", "mu": "range"}
"""Rules of Youssef & Cassidy (2014, Table 3 and the text before it)."""


def fit_each(
    records: Sequence[TestRecord],
    parameters: Sequence[Parameter],
    *,
    client: Any = None,
    scheduler_address: str | None = None,
    n_workers: int | None = 0,
    progress: bool = False,
    **calibrate_kwargs: Any,
) -> list[CalibrationResult]:
    """Calibrate ``parameters`` to each record alone (one result per record, same order).

    ``calibrate_kwargs`` go to :func:`~onbottom.calibration.fit.calibrate` (simulator,
    weights, method, seed, ...). With a Dask client, a scheduler address or ``n_workers`` >= 1
    the *records* are fitted in parallel, one task each (each fit runs serially inside its
    task): coarse tasks suit simulations of a few milliseconds better than spreading each
    population over the cluster.
    """
    fit_one = partial(calibrate, parameters=tuple(parameters), **calibrate_kwargs)
    if client is None and scheduler_address is None and n_workers == 0:
        return [fit_one(rec) for rec in records]
    with dask_client(client, scheduler_address=scheduler_address, n_workers=n_workers) as c:
        return ParallelMap(c, batch_size=1, progress=progress)(fit_one, list(records))


def parameter_table(results: Sequence[CalibrationResult]) -> list[dict[str, Any]]:
    """One row per fit: ``case``, each parameter value and ``<name>_se``, misfit, success."""
    rows = []
    for res in results:
        row: dict[str, Any] = {"case": ", ".join(res.record_names)}
        for p in res.parameters:
            row[p.name] = p.value
            if p.vary:
                row[f"{p.name}_se"] = res.std_errors.get(p.name, math.nan)
        row["misfit"] = res.misfit
        row["success"] = res.success
        rows.append(row)
    return rows


def recommend(
    rows: Sequence[Mapping[str, Any]],
    names: Sequence[str] = ("A", "B", "C", "mu"),
    rules: Mapping[str, str] | None = None,
) -> list[dict[str, Any]]:
    """Recommended values from per-test fits (a Table 3).

    Parameters
    ----------
    rows : sequence of mapping
        Output of :func:`parameter_table` (or rows with the same keys).
    names : sequence of str
        Parameters to summarise.
    rules : mapping or None
        name → one of :data:`RULES`; default :data:`PAPER_RULES` (``"mean"`` for names it does
        not list).

    Returns
    -------
    list of dict
        ``parameter``, ``n``, ``min``, ``mean``, ``median``, ``max``, ``std``, ``rule``,
        ``recommended`` (NaN for the ``"range"`` rule).
    """
    rules = dict(PAPER_RULES if rules is None else rules)
    out = []
    for name in names:
        vals = np.array([float(r[name]) for r in rows if name in r and r[name] is not None])
        vals = vals[np.isfinite(vals)]
        rule = one_of(f"rules[{name!r}]", rules.get(name, "mean"), RULES)
        stats = {
            "parameter": name,
            "n": int(vals.size),
            "min": float(vals.min()) if vals.size else math.nan,
            "mean": float(vals.mean()) if vals.size else math.nan,
            "median": float(np.median(vals)) if vals.size else math.nan,
            "max": float(vals.max()) if vals.size else math.nan,
            "std": float(vals.std(ddof=1)) if vals.size > 1 else math.nan,
            "rule": rule,
        }
        stats["recommended"] = math.nan if rule == "range" else stats[rule]
        out.append(stats)
    return out


def _fmt(value: Any, floatfmt: str) -> str:
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, (float, np.floating)):
        return "–" if not math.isfinite(value) else format(float(value), floatfmt)
    return str(value)


def _columns(rows: Sequence[Mapping[str, Any]], columns: Sequence[str] | None) -> list[str]:
    if columns is not None:
        return list(columns)
    cols: list[str] = []
    for r in rows:
        cols.extend(k for k in r if k not in cols)
    return cols


def to_markdown(
    rows: Sequence[Mapping[str, Any]],
    columns: Sequence[str] | None = None,
    floatfmt: str = ".3g",
) -> str:
    """A Markdown pipe table of ``rows`` (missing cells empty, NaN shown as "–")."""
    cols = _columns(rows, columns)
    lines = ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    for r in rows:
        lines.append("| " + " | ".join(_fmt(r.get(c, ""), floatfmt) for c in cols) + " |")
    return "\n".join(lines) + "\n"


def to_csv(
    rows: Sequence[Mapping[str, Any]],
    path: str | os.PathLike | None = None,
    columns: Sequence[str] | None = None,
) -> str:
    """``rows`` as CSV text (full precision); also written to ``path`` if given."""
    cols = _columns(rows, columns)
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=cols, lineterminator="\n", extrasaction="ignore")
    writer.writeheader()
    for r in rows:
        writer.writerow({c: r.get(c, "") for c in cols})
    text = buf.getvalue()
    if path is not None:
        Path(path).write_text(text, encoding="utf-8")
    return text


def write_fits(results: Sequence[CalibrationResult], path: str | os.PathLike) -> list[Path]:
    """Write each fit as TOML (:meth:`CalibrationResult.to_toml`), atomically.

    One result goes to ``path`` itself; several (``onbottom calibrate --each``) to
    ``<stem>_<record><suffix>`` beside it, the record name with every character other than a
    letter or digit made ``_``, and ``_<n>`` (its 1-based position) added when two records give
    one name, so that no fit overwrites another. Returns the paths written, in order.
    """
    from onbottom.results import write_text_atomic

    out = Path(path)
    if len(results) == 1:
        return [write_text_atomic(out, results[0].to_toml())]
    written = []
    used: set[str] = set()
    for i, res in enumerate(results):
        tag = "".join(ch if ch.isalnum() else "_" for ch in res.record_names[0])
        if tag in used:  # two records of one name: never overwrite a fit
            tag = f"{tag}_{i + 1}"
        used.add(tag)
        written.append(
            write_text_atomic(out.with_name(f"{out.stem}_{tag}{out.suffix}"), res.to_toml())
        )
    return written
