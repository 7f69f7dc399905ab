"""The committed curve sweeps (docs/validation/stability_curves/) and the numbers the storm
section theory page quotes from them."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from onbottom.results import load_dataset

FOLDER = Path(__file__).resolve().parents[2] / "docs" / "validation" / "stability_curves"

# docs/theory/storm_section.md, "Committed curve sweeps": sand, L_stable/(2+M)², N = 0.003
QUOTED = {
    ("wake", 0.0): (3.87, 3.10, 2.08, 1.27),
    ("morison", 0.0): (1.82, 1.22, 0.97, 0.89),
    ("wake", 1.0): (2.15, 1.72, 1.32, 0.96),
    ("morison", 1.0): (1.01, 1.05, 0.92, 0.88),
    ("wake", 10.0): (0.91, 0.80, 0.70, 0.59),
    ("morison", 10.0): (0.76, 0.73, 0.64, 0.56),
}


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
    for (name, m), values in QUOTED.items():
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
    assert ratio.min() == pytest.approx(1.14, abs=0.01)
    assert ratio.max() == pytest.approx(2.55, abs=0.01)
