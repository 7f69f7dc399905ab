"""The numbers the validation pages state are recomputed from the code, so pages cannot drift.

Tables marked *(checked)* in ``docs/validation/youssef_cassidy_2014.md`` and
``docs/validation/dem_penetration.md`` are parsed and each value is recomputed; a value printed
with n decimals must agree to half a unit of its last decimal. The committed band summary
``docs/validation/bands/centrifuge_bands.md`` must be what the committed CSV gives.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from onbottom.dynamics.centrifuge import get_test, run_centrifuge_test
from onbottom.soil._path import drive_path
from onbottom.soil.base import OUT_PASSIVE, OUT_SIZE
from onbottom.soil.penetration_sand import DrainedBounds
from onbottom.study.centrifuge_bands import read_csv, summarise, write_markdown

DOCS = Path(__file__).resolve().parents[2] / "docs"
YC = DOCS / "validation" / "youssef_cassidy_2014.md"
DEM = DOCS / "validation" / "dem_penetration.md"
BANDS = DOCS / "validation" / "bands"
SOIL_OPTIONS = ("passive_rule", "b_placement", "work_integrand", "max_penetration_law")


def _table(path: Path, heading: str) -> list[list[str]]:
    """Rows (cells stripped) of the first Markdown table after the line starting ``heading``."""
    lines = path.read_text(encoding="utf-8").splitlines()
    i = next(k for k, line in enumerate(lines) if line.startswith(heading))
    rows = []
    started = False
    for line in lines[i + 1 :]:
        if line.startswith("|"):
            started = True
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if not set(cells[0]) <= set("-"):
                rows.append(cells)
        elif started:
            break
    return rows[1:]  # without the header


def _close(value: float, printed: str) -> bool:
    text = printed.replace("−", "-").rstrip("*")
    nd = len(text.split(".")[1]) if "." in text else 0
    return abs(value - float(text)) <= 0.5 * 10.0**-nd + 1e-9


def test_results_table_of_the_validation_page():
    rows = _table(YC, "## Results with the default choices")
    assert len(rows) == 14
    for r in rows:
        name, ps = r[0], {"Table 2": "table2", "Table 3": "recommended"}[r[1]]
        res = run_centrifuge_test(name, parameters=ps, after_limit="runaway_end")
        cyc = res.cycles_to_limit
        checks = {
            "cycles": (cyc, r[7]),
            "delta": (cyc - get_test(name).cycles_used, r[9]),
            "z_i": (res.summary["initial_penetration"], r[10]),
            "max_w": (res.summary["max_penetration"], r[11]),
            "final_u": (res.summary["final_displacement"], r[12]),
        }
        for what, (value, printed) in checks.items():
            assert _close(value, printed), (name, ps, what, value, printed)


def _options(text: str) -> tuple[dict, dict]:
    run, soil = {}, {}
    for item in filter(None, (x.strip() for x in text.split(";"))):
        k, v = (x.strip() for x in item.split("="))
        if k in SOIL_OPTIONS:
            soil[k] = v
        elif k == "alpha_deg":
            run[k] = float(v)
        elif k == "gamma_kn":
            run["gamma"] = float(v) * 1e3
        else:
            run[k] = v
    return run, soil


def test_numbers_quoted_on_the_validation_page():
    rows = _table(YC, "## Numbers quoted on this page")
    assert len(rows) >= 20
    for name, opts, quantity, printed in rows:
        run, soil = _options(opts)
        res = run_centrifuge_test(name, soil_options=soil or None, **run)
        value = {"cycles": res.cycles_to_limit, "max_w": res.summary["max_penetration"]}[quantity]
        assert _close(value, printed), (name, opts, quantity, value, printed)


def test_band_table_of_the_validation_page_matches_the_committed_bands():
    rows = _table(YC, "## Sensitivity bands")
    summaries = {s.test: s for s in summarise(read_csv(BANDS / "centrifuge_bands.csv"))}
    assert [r[0] for r in rows] == list(summaries)
    for r in rows:
        s = summaries[r[0]]
        assert int(r[1]) == s.n_runs
        for printed, value in zip(
            r[2:6], (s.cycles_paper, s.cycles_default, s.cycles_min, s.cycles_max), strict=True
        ):
            assert _close(value, printed), (r[0], value, printed)
        assert r[6] == ("yes" if s.paper_inside else "no")


def test_committed_band_markdown_is_generated_from_the_committed_csv(tmp_path):
    md = write_markdown(summarise(read_csv(BANDS / "centrifuge_bands.csv")), tmp_path / "b.md")
    assert md.read_text(encoding="utf-8") == (BANDS / "centrifuge_bands.md").read_text(
        encoding="utf-8"
    )


def test_energy_paragraph_of_the_validation_page():
    text = YC.read_text(encoding="utf-8")
    m = re.search(r"it dissipates ([\d.]+), ([\d.]+) and ([\d.]+) J/m", text)
    assert m is not None
    from onbottom.dynamics.centrifuge import build_soil

    test = get_test("Inclined 1")
    # stated with every region-2 increment counting (work_counting="any_region2")
    soil = build_soil(test, parameters="table2", work_counting="any_region2")
    for amp, printed in zip((0.05, 0.1, 0.2), m.groups(), strict=True):
        u = amp * np.sin(np.linspace(0.0, 2.0 * np.pi, 4001)[1:])
        v = np.full(u.size, test.vertical_load)
        h = np.zeros((u.size, OUT_SIZE))
        drive_path(soil.model_id, soil.packed_parameters(), soil.initial_state(), u, v, h)
        uu = np.concatenate([[0.0], u])
        pp = np.concatenate([[0.0], h[:, OUT_PASSIVE]])
        work = float(np.sum(0.5 * (pp[1:] + pp[:-1]) * np.diff(uu)))
        assert _close(work, printed), (amp, work, printed)


@pytest.fixture(scope="module")
def f114_ratios():
    out = {}
    for sp, gamma in (("SM", 15.9e3), ("SD", 16.7e3)):
        ds = xr.open_dataset(DOCS / "validation" / "dem" / f"{sp}_summary.nc")
        d = float(ds.attrs["pipe_diameter"]) * float(ds.attrs["gravity_factor"])
        ds.close()
        df = pd.read_csv(DOCS / "validation" / "dem" / f"{sp}_V_w.csv")
        b = DrainedBounds.from_friction_angles(
            diameter=d,
            unit_weight=gamma,
            lower_friction_angle_deg=33.0,
            upper_friction_angle_deg=40.0,
        )
        w = df["w_over_D"].to_numpy()
        ratio = df["V_prototype_mean_kN_per_m"].to_numpy() * 1e3 / b.upper.resistance(w * d)
        out[sp] = (w, ratio)
    return out


def test_f114_comparison_table_of_the_dem_page(f114_ratios):
    rows = _table(DEM, "## F114 comparison")
    assert len(rows) >= 8
    for sp, where, printed in rows:
        w, ratio = f114_ratios[sp]
        m_max = re.fullmatch(r"max over w/D > ([\d.]+)", where)
        m_min = re.fullmatch(r"min over ([\d.]+)–([\d.]+)", where)
        if m_max:
            value = ratio[w > float(m_max.group(1)) + 1e-9].max()
        elif m_min:
            lo, hi = float(m_min.group(1)), float(m_min.group(2))
            value = ratio[(w >= lo - 1e-9) & (w <= hi + 1e-9)].min()
        else:
            (i,) = np.flatnonzero(np.isclose(w, float(where)))
            value = ratio[i]
        assert _close(float(value), printed), (sp, where, value, printed)


THEORY = DOCS / "theory" / "verley_sotberg.md"


def test_b_placement_effect_stated_on_the_theory_page():
    text = " ".join(THEORY.read_text(encoding="utf-8").split())
    m = re.search(
        r"z_max ([\d.]+) → ([\d.]+) m, cycles to the limit ([\d.]+) → ([\d.]+) \(with the former"
        r" elastic passive rule ([\d.]+) → ([\d.]+) m, ([\d.]+) → ([\d.]+)\)",
        text,
    )
    assert m is not None
    printed = m.groups()
    values = []
    for rule in ("elastoplastic", "legacy_elastic"):
        runs = [
            run_centrifuge_test(
                "Inclined 1", soil_options={"passive_rule": rule, "b_placement": bp}
            )
            for bp in ("outside", "inside")
        ]
        z = [r.summary["max_penetration"] for r in runs]
        c = [r.cycles_to_limit for r in runs]
        values += [z[0], z[1], c[0], c[1]] if rule == "elastoplastic" else [*z, *c]
    for value, p in zip(values, printed, strict=True):
        assert _close(value, p), (value, p)


def test_closed_cycle_energies_stated_on_the_theory_page():
    text = " ".join(THEORY.read_text(encoding="utf-8").split())
    old = re.search(r"did −([\d.]+), −([\d.]+) and −([\d.]+) J/m of net work", text)
    new = re.search(r"dissipates ([\d.]+), ([\d.]+) and ([\d.]+) J/m on the same cycles", text)
    assert old is not None and new is not None
    from onbottom.dynamics.centrifuge import build_soil

    test = get_test("Inclined 1")
    for rule, m, sign in (("legacy_elastic", old, -1.0), ("elastoplastic", new, 1.0)):
        soil = build_soil(test, parameters="table2", passive_rule=rule, work_counting="any_region2")
        for amp, printed in zip((0.05, 0.1, 0.2), m.groups(), strict=True):
            u = amp * np.sin(np.linspace(0.0, 2.0 * np.pi, 4001)[1:])
            v = np.full(u.size, test.vertical_load)
            h = np.zeros((u.size, OUT_SIZE))
            drive_path(soil.model_id, soil.packed_parameters(), soil.initial_state(), u, v, h)
            uu = np.concatenate([[0.0], u])
            pp = np.concatenate([[0.0], h[:, OUT_PASSIVE]])
            work = float(np.sum(0.5 * (pp[1:] + pp[:-1]) * np.diff(uu)))
            assert _close(sign * work, printed), (rule, amp, work, printed)
