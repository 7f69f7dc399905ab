"""Unit tests: fitting machinery on an analytic stand-in simulator (fast, exact truth)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from onbottom import InputError
from onbottom.calibration.fit import calibrate, grid_search, misfit_slices
from onbottom.calibration.objective import MisfitWeights
from onbottom.calibration.parameters import Parameter, parameters_from_mapping
from onbottom.calibration.records import TestRecord
from onbottom.calibration.summary import fit_each

T = np.linspace(0.0, 10.0, 41)


def toy(record, params):
    """u = a·t²/10 (drift), w = 0.05·c + 0.002·b·√t (penetration growth)."""
    if params["a"] > 0.9:
        raise RuntimeError("diverged")
    u = params["a"] * T**2 / 10.0
    w = 0.05 * params["c"] + 0.002 * params["b"] * np.sqrt(T)
    return xr.Dataset({"y": ("time", u), "z": ("time", w)}, coords={"time": T})


def _record(truth, noise=0.0, seed=1):
    ds = toy(None, truth)
    rng = np.random.default_rng(seed)
    ds["y"] = ds["y"] + noise * rng.standard_normal(T.size)
    ds["z"] = ds["z"] + 0.02 * noise * rng.standard_normal(T.size)
    return TestRecord(name="toy", data=ds, diameter=1.0, displacement_limit=3.0)


TRUTH = {"a": 0.3, "b": 2.0, "c": 1.1}


def _params(start=(0.8, 0.5, 0.6)):
    return (
        Parameter(name="a", value=start[0], lower=0.05, upper=1.0),
        Parameter(name="b", value=start[1], lower=0.0, upper=5.0),
        Parameter(name="c", value=start[2], lower=0.5, upper=1.5),
    )


def test_local_fit_recovers_truth_and_covers_it():
    rec = _record(TRUTH, noise=0.01)
    params = _params()
    # iid noise enters the history terms only: fit those, so that s² (JᵀJ)⁻¹ is consistent
    weights = MisfitWeights(
        initial_penetration=0.0, max_penetration=0.0, max_displacement=0.0, time_to_limit=0.0
    )
    res = calibrate(rec, params, simulator=toy, weights=weights, method="local", fd_step=0.01)
    assert res.success, res.message
    for name, true in TRUTH.items():
        lo, hi = res.interval(name, z=3.0)
        assert lo <= true <= hi, (name, res.values[name], res.std_errors[name])
        assert res.values[name] == pytest.approx(true, rel=0.05)
    assert res.correlation.shape == (3, 3)
    np.testing.assert_allclose(np.diag(res.correlation), 1.0)
    assert params[0].value == 0.8  # inputs untouched
    assert res.n_evaluations > 5
    with pytest.raises(ValueError):
        res.residuals[0] = 1.0


def test_global_fit_from_failing_region_and_fixed_parameter():
    rec = _record(TRUTH)
    params = (
        Parameter(name="a", value=0.95, lower=0.05, upper=1.0),  # start where the model fails
        Parameter(name="b", value=2.0, lower=0.0, upper=5.0, vary=False),
        Parameter(name="c", value=0.6, lower=0.5, upper=1.5),
    )
    res = calibrate(rec, params, simulator=toy, method="global", seed=3, maxiter=15)
    assert res.values["a"] == pytest.approx(0.3, rel=1e-3)
    assert res.values["c"] == pytest.approx(1.1, rel=1e-3)
    assert res.values["b"] == 2.0 and res.names == ("a", "c")
    assert res.misfit < 1e-8
    assert res.history["start"] > res.history["global"] >= res.history["local"]
    text = res.to_toml()
    import tomllib

    parsed = tomllib.loads(text)
    assert parsed["parameters"]["a"]["value"] == pytest.approx(0.3, rel=1e-3)
    assert parsed["parameters"]["b"]["vary"] is False


def test_grid_search_map_and_failures():
    rec = _record(TRUTH)
    ds = grid_search(
        rec,
        _params(),
        {"a": [0.1, 0.3, 0.95], "c": [1.0, 1.1]},
        simulator=toy,
        weights=MisfitWeights(time_to_limit=0.0),
    )
    assert ds["misfit"].dims == ("a", "c")
    assert ds.attrs["best_a"] == 0.3 and ds.attrs["best_c"] == 1.1
    # a = 0.95 raises inside the simulator: recorded, not fatal
    assert (ds["n_failed_simulations"].sel(a=0.95) == 1).all()
    assert not ds["failed"].any()


def test_slices_have_minimum_at_optimum():
    rec = _record(TRUTH)
    res = calibrate(rec, _params(start=(0.31, 2.1, 1.05)), simulator=toy, method="local")
    slices = misfit_slices(res, rec, simulator=toy, n=5)
    for name, ds in slices.items():
        assert float(ds[name][int(ds["misfit"].argmin(dim=name))]) == pytest.approx(
            res.values[name]
        )


def test_invalid_inputs():
    with pytest.raises(InputError, match="bounds"):
        Parameter(name="a", value=1.0, lower=2.0, upper=1.0)
    with pytest.raises(InputError, match="must lie"):
        Parameter(name="a", value=3.0, lower=0.0, upper=1.0)
    with pytest.raises(InputError, match="no bounds"):
        parameters_from_mapping({"a": 1.0}, {}, vary=["a"])
    rec = _record(TRUTH)
    fixed = tuple(
        Parameter(name=p.name, value=p.value, lower=p.lower, upper=p.upper, vary=False)
        for p in _params()
    )
    with pytest.raises(InputError, match="nothing to calibrate"):
        calibrate(rec, fixed, simulator=toy)
    with pytest.raises(InputError, match="unknown parameter"):

        def strict(record, params):
            raise InputError("unknown parameter 'q'")

        calibrate(rec, _params(), simulator=strict)
    with pytest.raises(InputError, match="fd_step"):
        calibrate(rec, _params(), simulator=toy, fd_step=0.5)


@pytest.mark.dask
def test_parallel_objective_evaluations_on_dask_equal_serial():
    """DE population and Jacobian columns evaluated on 2 local workers: same result."""
    from onbottom.study.engine import dask_client

    t = T.copy()

    def toy_local(record, params):  # a closure: cloudpickle sends it by value to workers
        u = params["a"] * t**2 / 10.0
        w = 0.05 * params["c"] + 0.002 * params["b"] * np.sqrt(t)
        return xr.Dataset({"y": ("time", u), "z": ("time", w)}, coords={"time": t})

    rec = _record(TRUTH, noise=0.01)
    kw = dict(simulator=toy_local, method="global", seed=4, maxiter=5, popsize=5)
    serial = calibrate(rec, _params(), **kw)
    other = _record({"a": 0.5, "b": 1.0, "c": 0.9}, noise=0.01, seed=2)
    with dask_client(n_workers=2) as client:
        parallel = calibrate(rec, _params(), client=client, **kw)
        each = fit_each([rec, other], _params(), client=client, **kw)
    assert parallel.values == serial.values
    assert parallel.n_evaluations == serial.n_evaluations
    # records fitted in parallel, one task each, in record order
    assert each[0].values == serial.values
    assert each[1].values == calibrate(other, _params(), **kw).values


def test_status_is_the_one_enumeration():
    """A fit reports its end with onbottom.status.Status: CONVERGED, NOT_CONVERGED when a
    least-squares stage hits its evaluation limit, NO_SOLUTION when every simulation fails at
    the fitted parameters; ``success`` is ``status.success`` (never a bare 0)."""
    from onbottom.status import Status

    rec = _record(TRUTH)
    ok = calibrate(rec, _params(start=(0.31, 2.1, 1.05)), simulator=toy, method="local")
    assert ok.status is Status.CONVERGED and ok.success and ok.to_dict()["status"] == 6
    short = calibrate(rec, _params(), simulator=toy, method="local", max_nfev=2)
    assert short.status is Status.NOT_CONVERGED and not short.success
    assert short.to_dict()["status"] == -5

    def broken(record, params):
        raise RuntimeError("diverged")

    none = calibrate(rec, _params(), simulator=broken, method="local", max_nfev=2)
    assert none.status is Status.NO_SOLUTION and not none.success
    assert "failed at the fitted parameters" in none.message
