"""Force models by name (hydro/registry.py) and in case files ([hydro] model = ...)."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from onbottom.errors import InputError
from onbottom.hydro import _force_dispatch as fd
from onbottom.hydro.force_model import MorisonLift
from onbottom.hydro.fourier import FourierModel
from onbottom.hydro.registry import (
    FORCE_MODELS,
    build_force_model,
    force_model_class,
    force_model_from_case,
    model_options,
)
from onbottom.hydro.wake import WakeModel

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_registry_names_and_classes_match_the_dispatch_ids():
    assert FORCE_MODELS == ("morison", "wake", "fourier")
    assert force_model_class("morison") is MorisonLift
    assert force_model_class("wake") is WakeModel
    assert force_model_class("fourier") is FourierModel
    assert MorisonLift().model_id == fd.FORCE_MORISON
    assert WakeModel().model_id == fd.FORCE_WAKE
    assert build_force_model("fourier", {"table": "example"}).model_id == fd.FORCE_FOURIER


def test_unknown_name_lists_the_choices():
    with pytest.raises(InputError, match=r"hydro.model = 'wak' is invalid: choose one of"):
        force_model_class("wak")


def test_unknown_option_is_named_with_the_allowed_ones():
    with pytest.raises(InputError, match=r"hydro.wake.drag_exess is not an option.*drag_excess"):
        build_force_model("wake", {"drag_exess": 0.5})
    assert "name" not in model_options("wake") and "model_id" not in model_options("wake")


def test_bad_value_names_the_table_and_field():
    with pytest.raises(InputError, match=r"\[hydro.wake\] WakeModel.wake_ratio = 5"):
        build_force_model("wake", {"wake_ratio": 5.0})


def test_fourier_table_path_missing_or_absent(tmp_path):
    with pytest.raises(InputError, match="hydro.fourier.table is missing"):
        build_force_model("fourier", {})
    with pytest.raises(InputError, match="no such file"):
        build_force_model("fourier", {"table": "nope.csv"}, base_dir=tmp_path)


class _Hydro:
    cd, cm, cl, added_mass_coefficient = 0.8, 3.29, 0.9, 2.29

    def __init__(self, model, wake=None, fourier=None):
        self.model, self.wake, self.fourier = model, wake or {}, fourier or {}


def test_from_case_morison_takes_the_hydro_coefficients():
    fm = force_model_from_case(_Hydro("morison"))
    assert isinstance(fm, MorisonLift) and fm.cd == 0.8


def test_options_for_a_model_not_selected_are_an_error():
    with pytest.raises(InputError, match=r"\[hydro.wake\] is given but hydro.model = 'morison'"):
        force_model_from_case(_Hydro("morison", wake={"wake_ratio": 0.3}))


def _case(tmp_path: Path, extra: str) -> Path:
    text = (EXAMPLES / "storm_case.toml").read_text(encoding="utf-8")
    text = text.replace("peak_hours = 3.0", "peak_hours = 0.25").replace(
        "build_up_hours = 0.5", "build_up_hours = 0.05"
    )
    text = text.replace("reductions = true", "reductions = true\n" + extra, 1)
    p = tmp_path / "case.toml"
    p.write_text(text, encoding="utf-8")
    return p


@pytest.mark.parametrize(
    ("extra", "cls"),
    [
        ('model = "wake"', WakeModel),
        ('model = "wake"\n[hydro.wake]\nwake = false', WakeModel),
        ('model = "fourier"\n[hydro.fourier]\ntable = "example"', FourierModel),
    ],
)
def test_storm_case_runs_each_force_model(tmp_path, extra, cls):
    from onbottom.dynamics.storm_case import load_storm_case
    from onbottom.dynamics.storm_section import simulate_storm_section

    setup = load_storm_case(_case(tmp_path, extra))
    assert isinstance(setup.force_model, cls)
    res = simulate_storm_section(setup.pipe, setup.soil, setup.storm, **setup.kwargs())
    assert res.success
    assert res.data.attrs["force_model"] == cls.__dataclass_fields__["name"].default
    assert np.isfinite(res.data["y"].values).all()


def test_wake_switched_off_in_a_case_equals_morison_with_the_same_coefficients(tmp_path):
    """WakeModel(wake=False) with C_D∞, C_M, C_L∞ = the Morison case's C_D, C_M, C_L: same run."""
    from onbottom.dynamics.storm_case import load_storm_case
    from onbottom.dynamics.storm_section import simulate_storm_section

    off = load_storm_case(
        _case(
            tmp_path,
            'model = "wake"\n[hydro.wake]\nwake = false\ncd_steady = 0.7\ncl_steady = 0.9\n'
            "cm = 3.29\nadded_mass = 2.29",
        )
    )
    shutil.move(tmp_path / "case.toml", tmp_path / "wake.toml")
    mor = load_storm_case(_case(tmp_path, ""))
    a = simulate_storm_section(off.pipe, off.soil, off.storm, **off.kwargs()).data
    b = simulate_storm_section(mor.pipe, mor.soil, mor.storm, **mor.kwargs()).data
    np.testing.assert_array_equal(a["y"].values, b["y"].values)
