"""Force models by name (hydro/registry.py) and in case files ([hydro] model = ...)."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from onbottom.cases.force import force_model_from_case
from onbottom.errors import InputError
from onbottom.hydro import _force_dispatch as fd
from onbottom.hydro.force_model import MorisonLift
from onbottom.hydro.fourier import FourierModel
from onbottom.hydro.registry import (
    FORCE_MODELS,
    build_force_model,
    force_model_class,
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
        build_force_model("fourier", {"table": str(tmp_path / "nope.csv")})
    with pytest.raises(InputError, match=r"hydro.fourier.table = 'nope.csv' is invalid: no such"):
        force_model_from_case(_Hydro("fourier", fourier={"table": "nope.csv"}), base_dir=tmp_path)


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


def test_case_fourier_table_is_read_relative_to_the_case_folder_and_stays_inside(tmp_path):
    """cases.force: a [hydro.fourier] table path is relative to the case file's folder and may
    not leave it; the registry (hydro/) takes the loaded table."""
    from onbottom.hydro.fourier_table import FourierTable

    FourierTable.example().to_csv(tmp_path / "table.csv")
    fm = force_model_from_case(_Hydro("fourier", fourier={"table": "table.csv"}), base_dir=tmp_path)
    assert isinstance(fm, FourierModel)
    assert fm.table.rows() == FourierTable.load(tmp_path / "table.csv").rows()
    inner = tmp_path / "case"
    inner.mkdir()
    with pytest.raises(InputError, match="hydro.fourier.table.*leaves the case file's folder"):
        force_model_from_case(_Hydro("fourier", fourier={"table": "../table.csv"}), base_dir=inner)


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
    from onbottom.cases.storm import load_storm_setup
    from onbottom.dynamics.storm_section import simulate_storm_section

    setup = load_storm_setup(_case(tmp_path, extra))
    assert isinstance(setup.force_model, cls)
    res = simulate_storm_section(setup.pipe, setup.soil, setup.storm, **setup.kwargs())
    assert res.success
    assert res.data.attrs["force_model"] == cls.__dataclass_fields__["name"].default
    assert np.isfinite(res.data["y"].values).all()


def test_wake_switched_off_in_a_case_equals_morison_with_the_same_coefficients(tmp_path):
    """WakeModel(wake=False) with C_D∞, C_M, C_L∞ = the Morison case's C_D, C_M, C_L: same run."""
    from onbottom.cases.storm import load_storm_setup
    from onbottom.dynamics.storm_section import simulate_storm_section

    off = load_storm_setup(
        _case(
            tmp_path,
            'model = "wake"\n[hydro.wake]\nwake = false\ncd_steady = 0.7\ncl_steady = 0.9\n'
            "cm = 3.29\nadded_mass = 2.29",
        )
    )
    shutil.move(tmp_path / "case.toml", tmp_path / "wake.toml")
    mor = load_storm_setup(_case(tmp_path, ""))
    a = simulate_storm_section(off.pipe, off.soil, off.storm, **off.kwargs()).data
    b = simulate_storm_section(mor.pipe, mor.soil, mor.storm, **mor.kwargs()).data
    np.testing.assert_array_equal(a["y"].values, b["y"].values)


def _table(tmp_path: Path, body: str) -> Path:
    p = tmp_path / "coefficients.csv"
    p.write_text(body, encoding="utf-8")
    return p


GOOD = (
    "# test table\nK,M,C_D,C_M,C_L\n-,-,-,-,-\n"
    "5,0,1.0,3.0,1.0\n5,1,0.8,3.0,0.8\n20,0,2.0,2.0,2.0\n20,1,1.6,2.0,1.6\n"
)
WIDE = (
    "K,M,C_D,C_M,C_L\n-,-,-,-,-\n"
    "1,0,1.0,3.0,1.0\n1,5,0.8,3.0,0.8\n500,0,2.0,2.0,2.0\n500,5,1.6,2.0,1.6\n"
)


def test_morison_coefficient_table_interpolates_bilinearly_and_warns_outside(tmp_path):
    from onbottom.errors import OutOfRangeWarning
    from onbottom.hydro.morison_table import MorisonCoefficientTable

    t = MorisonCoefficientTable.from_csv(_table(tmp_path, GOOD))
    # hand value: at K 12.5 (midway) and M 0.5 (midway) C_D = mean(1.0, 0.8, 2.0, 1.6) = 1.35
    cd, cm, cl = t(12.5, 0.5)
    assert cd == pytest.approx(1.35) and cm == pytest.approx(2.5) and cl == pytest.approx(1.35)
    with pytest.warns(OutOfRangeWarning, match="outside the Morison coefficient table"):
        assert t(40.0, 0.0)[0] == pytest.approx(2.0)


@pytest.mark.parametrize(
    ("body", "match"),
    [
        ("K,M,C_D,C_M\n-,-,-,-\n5,0,1,1\n", "header"),
        ("K,M,C_D,C_M,C_L\nm,-,-,-,-\n5,0,1,1,1\n", "units"),
        ("K,M,C_D,C_M,C_L\n-,-,-,-,-\n5,0,1,1,1\n5,1,1,1,1\n20,0,1,1,1\n", "missing"),
        ("K,M,C_D,C_M,C_L\n-,-,-,-,-\n20,0,1,1,1\n5,0,1,1,1\n", "sorted"),
        ("K,M,C_D,C_M,C_L\n-,-,-,-,-\n5,0,11,1,1\n", r"\[0, 10\]"),
        ("K,M,C_D,C_M,C_L\n-,-,-,-,-\n5,0,x,1,1\n", "not a number"),
    ],
)
def test_morison_coefficient_table_errors_are_named(tmp_path, body, match):
    from onbottom.hydro.morison_table import MorisonCoefficientTable

    with pytest.raises(InputError, match=match):
        MorisonCoefficientTable.from_csv(_table(tmp_path, body))


def test_storm_case_runs_morison_per_sea_state_from_a_table(tmp_path):
    """Per-sea-state Morison from a case file; a table constant at the [hydro] values gives the
    same run as the constant model, bit for bit."""
    from onbottom.cases.storm import load_storm_setup
    from onbottom.dynamics.storm_section import simulate_storm_section

    const = "K,M,C_D,C_M,C_L\n-,-,-,-,-\n1,0,0.7,3.29,0.9\n1,5,0.7,3.29,0.9\n"
    const += "500,0,0.7,3.29,0.9\n500,5,0.7,3.29,0.9\n"
    _table(tmp_path, const)
    tab = load_storm_setup(_case(tmp_path, 'coefficient_table = "coefficients.csv"'))
    assert tab.force_model.rule is not None
    mor = load_storm_setup(_case(tmp_path, ""))
    a = simulate_storm_section(tab.pipe, tab.soil, tab.storm, **tab.kwargs()).data
    b = simulate_storm_section(mor.pipe, mor.soil, mor.storm, **mor.kwargs()).data
    np.testing.assert_array_equal(a["y"].values, b["y"].values)
    _table(tmp_path, WIDE)
    var = load_storm_setup(_case(tmp_path, 'coefficient_table = "coefficients.csv"'))
    r = simulate_storm_section(var.pipe, var.soil, var.storm, **var.kwargs())
    assert r.success and r.max_displacement != pytest.approx(
        simulate_storm_section(mor.pipe, mor.soil, mor.storm, **mor.kwargs()).max_displacement
    )


def test_coefficient_table_outside_the_case_folder_or_with_another_model_is_refused(tmp_path):
    from onbottom.cases.storm import load_storm_setup

    with pytest.raises(InputError, match="leaves the case file's folder"):
        load_storm_setup(_case(tmp_path, 'coefficient_table = "../coefficients.csv"'))
    _table(tmp_path, GOOD)
    with pytest.raises(InputError, match="coefficient_table is given but hydro.model = 'wake'"):
        load_storm_setup(_case(tmp_path, 'model = "wake"\ncoefficient_table = "coefficients.csv"'))
