"""The committed curve sweeps (package data, src/onbottom/data/stability_curves/) and the
numbers the storm section theory page quotes from them.

Nothing here is a hard-coded result: every number the page states is parsed from the page and
recomputed from the committed NetCDF files, so a regenerated sweep that changes a number fails
with the value to write on the page instead.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from onbottom.results import load_dataset

ROOT = Path(__file__).resolve().parents[2]
FOLDER = ROOT / "src" / "onbottom" / "data" / "stability_curves"
PAGE = ROOT / "docs" / "theory" / "storm_section.md"
MODELS = {"wake": "wake", "Morison": "morison"}
LOW_M, HIGH_M = [0.0, 0.2, 0.4], [2.0, 5.0, 10.0]
ALL_N = [0.003, 0.006, 0.01]


@pytest.fixture(scope="module")
def sweeps():
    return {name: load_dataset(FOLDER / f"{name}.nc") for name in ("wake", "morison")}


@pytest.fixture(scope="module")
def section() -> str:
    text = PAGE.read_text(encoding="utf-8")
    start = text.index("## Committed curve sweeps")
    return text[start : text.index("\n## ", start + 1)]


def _table_after(text: str, marker: str) -> tuple[list[str], list[list[str]]]:
    """Header cells and body rows of the first Markdown table after ``marker``."""
    lines = text[text.index(marker) :].splitlines()
    first = next(i for i, ln in enumerate(lines) if ln.startswith("|"))
    rows = []
    for ln in lines[first:]:
        if not ln.startswith("|"):
            break
        rows.append([c.strip() for c in ln.strip().strip("|").split("|")])
    return rows[0], rows[2:]


def _range(values: np.ndarray) -> str:
    return f"{np.nanmin(values):.2f}–{np.nanmax(values):.2f}"


def test_the_sweeps_used_the_force_models_their_names_say(sweeps):
    import json

    for name, ds in sweeps.items():
        params = json.loads(ds.attrs["parameters"])
        assert params["force_model"]["force_model"] == (
            "wake" if name == "wake" else "morison_lift"
        )
        assert params["seeds"] == 10


def test_run_figures_quoted_on_the_page(section, sweeps):
    for label, name in MODELS.items():
        ds = sweeps[name]
        want = (
            f"{label}: {int(ds.attrs['total_storms']):,}"
            f" storms, {ds.attrs['cpu_time_s']:.0f} CPU-s, {ds.attrs['wall_time_s'] / 60:.1f} min"
            " wall"
        )
        assert want in " ".join(section.split()), f"the page should say: {want!r}"


def test_l_over_2_plus_m_squared_table_on_the_page(section, sweeps):
    header, rows = _table_after(section, "Sand, L_stable/(2 + M)², N = 0.003")
    assert header[0] == "K" and len(rows) == sweeps["wake"].sizes["K"]
    for row in rows:
        k = float(row[0])
        for cell, text in zip(header[1:], row[1:], strict=True):
            label, m = re.fullmatch(r"(\w+), M = ([\d.]+)", cell).groups()
            ds, m = sweeps[MODELS[label]], float(m)
            got = float(ds["L_stable"].sel(soil="sand", N=0.003, M=m, K=k)) / (2.0 + m) ** 2
            assert text == f"{got:.2f}", f"K = {k}, {cell}: the files give {got:.2f}"


def test_wake_over_morison_ratio_table_on_the_page(section, sweeps):
    header, rows = _table_after(section, "Ratio wake / Morison of L")
    columns = {  # header cell -> (M values, N values)
        "M ≤ 0.4, all N": (LOW_M, ALL_N),
        "M ≤ 0.4, N = 0.003": (LOW_M, [0.003]),
        "M ≥ 2, all N": (HIGH_M, ALL_N),
    }
    assert header[1:] == list(columns)
    assert len(rows) == 4
    for row in rows:
        soil, criterion = (s.strip() for s in row[0].split(","))
        for cell, text in zip(header[1:], row[1:], strict=True):
            m, n = columns[cell]
            sel = {"soil": soil, "M": m, "N": n}
            ratio = (
                sweeps["wake"][criterion].sel(sel) / sweeps["morison"][criterion].sel(sel)
            ).values
            assert text == _range(ratio), f"{row[0]}, {cell}: the files give {_range(ratio)}"


def test_statements_of_the_page_hold_in_the_files(sweeps):
    """The bullet points' claims (heavier where waves dominate, L falls with K at M = 0, the
    rise toward M = 1 at K = 10 with the wake model, the clay L_10 exception, where
    out_of_range points are)."""
    w, m = sweeps["wake"], sweeps["morison"]
    for soil, floor in (("sand", 0.95), ("clay", 1.0)):  # waves dominate: N = 0.003
        sel = {"soil": soil, "M": LOW_M, "N": 0.003}
        # sand: no point more than one 5 % bracket below 1; clay: every point above 1
        assert float((w["L_stable"].sel(sel) / m["L_stable"].sel(sel)).min()) > floor, soil
    for name, ds in sweeps.items():
        sand = ds["L_stable"].sel(soil="sand", N=0.003)
        assert np.all(np.diff(sand.sel(M=0.0).values) < 0.0), name  # falls with K at M = 0
        oor = ds["out_of_range"].where(ds["out_of_range"] > 0, drop=True)
        assert set(oor["soil"].values) <= {"sand"} and float(oor["M"].min()) >= 0.8, name
    norm = w["L_stable"].sel(soil="sand", N=0.003) / (2.0 + w["M"]) ** 2
    k10 = norm.sel(K=10.0)
    assert float(k10.sel(M=1.0)) > float(k10.sel(M=0.8))  # rises again toward M = 1 at K = 10
    peak = {
        float(k): float(norm["M"][int(np.nanargmax(norm.sel(K=k).values))]) for k in (20.0, 40.0)
    }
    assert peak == {20.0: 0.4, 40.0: 2.0}, peak
    sel = {"soil": "clay", "M": LOW_M}
    ratio = w["L_10"].sel(sel) / m["L_10"].sel(sel)
    where = ratio.where(ratio == ratio.min(), drop=True)
    assert float(where["K"][0]) == 5.0 and float(where["M"][0]) == 0.0
