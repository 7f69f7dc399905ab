"""FourierModel: validation named, parameter row layout, stage table, provenance."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from onbottom.errors import InputError, OutOfRangeWarning
from onbottom.hydro import _fourier_kernel as FK
from onbottom.hydro._force_contract import FO_SIZE, N_FORCE_STATE
from onbottom.hydro.fourier import FORCE_FOURIER, FourierModel
from onbottom.hydro.fourier_table import FourierTable


def test_example_model_and_parameter_row_layout():
    model = FourierModel.example()
    assert model.name == "fourier" and model.model_id == FORCE_FOURIER == 2
    assert model.added_mass_coefficient == pytest.approx(2.29)
    assert model.harmonic_order == 5 and model.memory_weight == 0.25
    tab = model.table
    row = model.params()
    nk, nm = tab.k_grid.size, tab.m_grid.size
    assert row[FK.P_NHARM] == 5 and row[FK.P_NK] == nk and row[FK.P_NM] == nm
    assert row[FK.P_MEMORY] == 0.25 and row[FK.P_CD] == 0.7 and row[FK.P_CM] == 3.29
    assert model.phase == "flow" and row[FK.P_PHASE] == 1.0
    assert FourierModel.example(phase="time").params()[FK.P_PHASE] == 0.0
    np.testing.assert_array_equal(row[FK.P_HEADER : FK.P_HEADER + nk], tab.k_grid)
    coef = row[FK.P_HEADER + nk + nm :].reshape(nk, nm, 2, 11)
    np.testing.assert_array_equal(coef, tab.coefficients[0])
    assert (N_FORCE_STATE, FO_SIZE) == (16, 4)


def test_truncated_harmonics_and_added_mass():
    model = FourierModel.example(harmonics=2, added_mass=1.0)
    tab = model.table
    nk, nm = tab.k_grid.size, tab.m_grid.size
    coef = model.params()[FK.P_HEADER + nk + nm :].reshape(nk, nm, 2, 5)
    np.testing.assert_array_equal(coef, tab.coefficients[0][..., :5])
    assert model.added_mass_coefficient == 1.0


def test_parameter_table_rows_identical_and_warns_outside_grid():
    model = FourierModel.example()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        table = model.parameter_table(np.array([5.0, 20.0]), np.array([0.0, -0.5]))
    assert table.shape == (2, model.params().size) and table.flags.c_contiguous
    np.testing.assert_array_equal(table[0], table[1])
    with pytest.warns(OutOfRangeWarning, match="stage 0: K = 100"):
        model.parameter_table(np.array([100.0]), np.array([0.0]))
    with pytest.raises(InputError, match="shape"):
        model.parameter_table(np.array([1.0, 2.0]), np.array([0.0]))


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"memory_weight": 1.0}, "FourierModel.memory_weight"),
        ({"memory_weight": -0.1}, "FourierModel.memory_weight"),
        ({"harmonics": 6}, "FourierModel.harmonics"),
        ({"harmonics": 0}, "FourierModel.harmonics"),
        ({"drag_coefficient": 11.0}, "FourierModel.drag_coefficient"),
        ({"inertia_coefficient": 0.5}, "C_a = C_M − 1"),
        ({"added_mass": -1.0}, "FourierModel.added_mass"),
        ({"roughness": 0.01}, "no roughness axis"),
        ({"model_id": 1}, "model_id"),
        ({"phase": "elapsed"}, "FourierModel.phase"),
    ],
)
def test_validation_names_the_field(kwargs, match):
    with pytest.raises(InputError, match=match):
        FourierModel.example(**kwargs)


def test_table_type_and_roughness_required():
    with pytest.raises(InputError, match="expected a FourierTable"):
        FourierModel(table="table.csv")
    t = FourierTable.example()
    rough = FourierTable(
        t.k_grid,
        t.m_grid,
        np.stack((t.coefficients[0], 2.0 * t.coefficients[0])),
        np.array([0.0, 0.01]),
        "two slices",
    )
    with pytest.raises(InputError, match="roughness axis"):
        FourierModel(table=rough)
    model = FourierModel(table=rough, roughness=0.005)
    np.testing.assert_allclose(model.resolved_table.coefficients, 1.5 * t.coefficients)
    assert model.describe()["roughness_k_over_D"] == 0.005


def test_describe_provenance():
    d = FourierModel.example().describe()
    assert d["force_model"] == "fourier" and d["reconstruction"] == 1
    assert "Bryndum" in d["force_model_source"]
    assert "SYNTHETIC" in d["fourier_table_source"]
    assert d["fourier_harmonics"] == 5
