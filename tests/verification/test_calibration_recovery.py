"""Verification: synthetic recovery of A, B, C, μ with the real section solver.

A record of the Inclined 1 centrifuge test is simulated with known parameters (the paper's
Table 2 values), resampled to 1 s and perturbed with seeded Gaussian noise of 1 % of each
channel's scale. The calibration starts far away (A, B, C, μ = 0.6, 0.8, 1.3, 1.0) and must
recover the truth within absolute tolerances of 0.02 (A, B) and 0.01 (C, μ) — about a tenth of
the spread of the paper's Table 2 — and the ±3 s.e. intervals must cover the truth.
"""

from __future__ import annotations

import pytest

from onbottom.calibration.fit import calibrate
from onbottom.calibration.objective import HISTORY_ONLY, evaluate_misfit
from onbottom.calibration.paper import PAPER_TABLE2, default_parameters, virtual_record
from onbottom.calibration.simulators import CentrifugeSimulator

TOLERANCE = {"A": 0.02, "B": 0.02, "C": 0.01, "mu": 0.01}


@pytest.mark.verification
@pytest.mark.slow
@pytest.mark.long
def test_recover_table2_parameters_of_inclined_1_from_noisy_record():
    truth = PAPER_TABLE2["Inclined 1"]
    sim = CentrifugeSimulator()
    rec = virtual_record("Inclined 1", truth, noise=0.01, seed=1, simulator=sim)
    start = {"A": 0.6, "B": 0.8, "C": 1.3, "mu": 1.0}
    res = calibrate(
        rec,
        default_parameters(start=start),
        simulator=sim,
        weights=HISTORY_ONLY,
        method="global",
        seed=0,
    )
    assert res.success, res.message
    for name, tol in TOLERANCE.items():
        assert res.values[name] == pytest.approx(truth[name], abs=tol), name
        lo, hi = res.interval(name, z=3.0)
        assert lo <= truth[name] <= hi, (name, res.values[name], res.std_errors[name])
    # the optimum is at least as good as the truth (to 1 %): the search found the minimum
    truth_misfit = evaluate_misfit(rec, sim(rec, truth), HISTORY_ONLY).total
    assert res.misfit <= 1.01 * truth_misfit
