"""Unit tests: simulators and virtual records of the centrifuge tests."""

from __future__ import annotations

import numpy as np
import pytest

from onbottom import InputError
from onbottom.calibration.objective import evaluate_misfit
from onbottom.calibration.paper import PAPER_TABLE2, virtual_record
from onbottom.calibration.simulators import CentrifugeSimulator, RecordedLoadSimulator

TRUTH = PAPER_TABLE2["Inclined 1"]


def test_virtual_record_metadata_and_noise_level():
    clean = virtual_record("Inclined 1", TRUTH, noise=0.0)
    noisy = virtual_record("Inclined 1", TRUTH, noise=0.02, seed=3)
    assert clean.V_peak == pytest.approx(42.98e3) and clean.V_i == pytest.approx(10.52e3)
    assert clean.displacement_limit == 3.0 and clean.cycle_period == 40.0
    assert clean.programme == "Inclined 1" and clean.diameter == 1.0
    np.testing.assert_allclose(np.diff(clean.time)[:-1], 1.0)
    # noise: standard deviation 2 % of the displacement limit (3 m) on u
    assert np.std(noisy.y - clean.y) == pytest.approx(0.02 * 3.0, rel=0.15)
    again = virtual_record("Inclined 1", TRUTH, noise=0.02, seed=3)
    np.testing.assert_array_equal(again.y, noisy.y)


def test_recorded_load_simulator_reproduces_preset_run():
    """Driven by the record's own H(t), V(t) sampled at the preset's 0.2 s, the section
    solver gives the preset's response again."""
    rec = virtual_record("Inclined 1", TRUTH, noise=0.0, sample_interval=0.2)
    res = RecordedLoadSimulator()(rec, TRUTH)
    assert res.success
    m = evaluate_misfit(rec, res)
    assert max(m.terms.values()) < 1e-3
    assert res.cycles_to_limit == pytest.approx(rec.time[-1] / 40.0, rel=1e-3)


def test_simulators_reject_unknown_parameters_and_missing_programme():
    rec = virtual_record("Inclined 1", TRUTH, noise=0.0)
    with pytest.raises(InputError, match="phi"):
        CentrifugeSimulator()(rec, {"phi": 1.0})
    bare = rec.__class__(name="x", data=rec.data[["y", "z"]], diameter=1.0)
    with pytest.raises(InputError, match="programme"):
        CentrifugeSimulator()(bare, TRUTH)
    with pytest.raises(InputError, match="'H'"):
        RecordedLoadSimulator()(bare, TRUTH)


def test_record_from_section_result_takes_metadata_from_attributes():
    from onbottom.calibration.records import record_from_result
    from onbottom.dynamics.centrifuge import run_centrifuge_test

    res = run_centrifuge_test("Inclined 2")
    rec = record_from_result(res, name="sim")
    assert rec.diameter == 1.0 and rec.programme == "Inclined 2"
    assert rec.V_peak == pytest.approx(23.30e3) and rec.V_i == pytest.approx(9.60e3)
    assert rec.displacement_limit == 2.0 and rec.cycle_period == 40.0
    assert "source_parameters" in rec.metadata
