"""The committed curve sweeps (docs/validation/stability_curves/) and the numbers the storm
section theory page quotes from them."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from onbottom.results import load_dataset

FOLDER = Path(__file__).resolve().parents[2] / "docs" / "validation" / "stability_curves"
PAGE = FOLDER.parents[1] / "theory" / "storm_section.md"


def _quoted() -> dict[tuple[str, float], tuple[float, ...]]:
    """The table of docs/theory/storm_section.md, "Committed curve sweeps": sand,
    L_stable/(2+M)², N = 0.003, columns "wake, M = m" / "Morison, M = m", rows K = 5…40."""
    lines = PAGE.read_text(encoding="utf-8").splitlines()
    head = next(i for i, ln in enumerate(lines) if ln.startswith("| K | wake, M = "))
    cols = [c.strip() for c in lines[head].strip("|").split("|")][1:]
    rows = []
    for ln in lines[head + 2 :]:
        if not ln.startswith("|"):
            break
        rows.append([float(c) for c in ln.strip("|").split("|")[1:]])
    out = {}
    for j, col in enumerate(cols):
        name, m = col.split(", M = ")
        out[(name.lower(), float(m))] = tuple(r[j] for r in rows)
    return out


def _quoted_ratio() -> tuple[float, float]:
    """ "… (a–b at N = 0.003 …" of the page's "Heavier pipes" finding."""
    text = PAGE.read_text(encoding="utf-8")
    m = re.search(r"\(([\d.]+)–([\d.]+) at N = 0\.003", text)
    assert m is not None
    return float(m.group(1)), float(m.group(2))


@pytest.fixture(scope="module")
def sweeps():
    return {name: load_dataset(FOLDER / f"{name}.nc") for name in ("wake", "morison")}


def test_the_sweeps_used_the_force_models_their_names_say(sweeps):
    import json

    for name, ds in sweeps.items():
        params = json.loads(ds.attrs["parameters"])
        assert params["force_model"]["force_model"] == (
            "wake" if name == "wake" else "morison_lift"
        )
        assert params["seeds"] == 5


def test_numbers_quoted_on_the_theory_page(sweeps):
    quoted = _quoted()
    assert len(quoted) == 6
    for (name, m), values in quoted.items():
        ds = sweeps[name]
        got = ds["L_stable"].sel(soil="sand", N=0.003, M=m).values / (2.0 + m) ** 2
        np.testing.assert_allclose(got, values, atol=0.006)


def test_low_m_curves_fall_with_k_and_the_wake_model_is_heavier(sweeps):
    for name in sweeps:
        at0 = sweeps[name]["L_stable"].sel(soil="sand", N=0.003, M=0.0).values
        assert np.all(np.diff(at0) < 0.0), name
    ratio = (
        sweeps["wake"]["L_stable"].sel(soil="sand", N=0.003, M=[0.0, 0.2, 0.4])
        / sweeps["morison"]["L_stable"].sel(soil="sand", N=0.003, M=[0.0, 0.2, 0.4])
    ).values
    low, high = _quoted_ratio()
    assert ratio.min() == pytest.approx(low, abs=0.006)
    assert ratio.max() == pytest.approx(high, abs=0.006)
