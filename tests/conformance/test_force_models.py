"""Conformance suite: every registered force model against the kernel contract of
:mod:`onbottom.hydro._force_dispatch` (every entry of
:data:`onbottom.hydro.registry.FORCE_REGISTRY`, as scipy's ``test_ivp`` runs every method).

A model registered with :func:`~onbottom.hydro.registry.register_force_model` gets every test
below with no test written (``tests/recipe_models.py``'s ``quadratic_drag`` is registered by
importing it). A model whose kernel is missing from the dispatch fails
``test_dispatch_entry_exists[<name>]``.

Rules checked: 1 (deterministic), 2 (``state_old`` read only, every ``out`` slot written), 3
(a zero state is valid), 4 (finite in, finite out; the Newton tangents ∂F/∂ẏ against central
differences; ∂F_Y/∂ẏ <= 0), 5 (mirror symmetry from the zero state), 6 (the plain-Python twin
equal to the kernel on a random record), 7 (the optional two-stage form: bit for bit the
kernel's state and outputs at several ẏ, or a no-op for a model without it), NaN in gives a
non-finite force (the step fails), and a case file naming the model through ``onbottom storm``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import recipe_models  # noqa: F401  (a model registered outside the package: it runs the suite too)
from onbottom._jit import pure_python
from onbottom.cli.main import cli
from onbottom.hydro._force_dispatch import _EVALUATE, _KERNELS, _PREPARE
from onbottom.hydro.kernel_contract import (
    FO_DFY_DYD,
    FO_DFZ_DYD,
    FO_FY,
    FO_FZ,
    FO_SIZE,
    N_FORCE_PREP,
    N_FORCE_STATE,
)
from onbottom.hydro.registry import FORCE_REGISTRY, build_force_model

NAMES = FORCE_REGISTRY.names()
D, RHO = 0.4, 1025.0


def _model(name):
    return build_force_model(name, FORCE_REGISTRY[name].example)


def _kernel(name):
    return _KERNELS[_model(name).model_id]


def _params(name):
    return np.ascontiguousarray(_model(name).parameter_table(np.array([12.0]), np.array([0.2]))[0])


def _call(fn, p, t, u, a, vc, yd, state=None):
    s_old = np.zeros(N_FORCE_STATE) if state is None else state
    s_new = np.zeros(N_FORCE_STATE)
    out = np.full(FO_SIZE, np.nan)
    fn(p, s_old, t, u, a, vc, yd, D, RHO, s_new, out)
    return out, s_new


def _record(seed: int, n: int = 400):
    """A random flow record: t, u, du/dt (a sum of three waves with random phases) and ẏ."""
    rng = np.random.default_rng(seed)
    t = np.arange(1, n + 1) * 0.1
    amp, om, ph = rng.uniform(0.2, 0.8, 3), rng.uniform(0.4, 1.2, 3), rng.uniform(0, 6.3, 3)
    u = (amp * np.sin(np.outer(t, om) + ph)).sum(axis=1)
    a = (amp * om * np.cos(np.outer(t, om) + ph)).sum(axis=1)
    yd = 0.05 * rng.normal(size=n)
    return t, u, a, yd


def _run(fn, p, vc, record):
    state = np.zeros(N_FORCE_STATE)
    outs = []
    for t, u, a, yd in zip(*record, strict=True):
        out, state = _call(fn, p, t, u, a, vc, yd, state)
        outs.append(out)
    return np.array(outs)


@pytest.mark.parametrize("name", NAMES)
def test_dispatch_entry_exists(name):
    model = _model(name)
    assert model.model_id in _KERNELS, f"{name}: model_id {model.model_id} not in the dispatch"


@pytest.mark.parametrize("name", NAMES)
def test_kernel_equals_twin_on_a_random_record(name):
    p, record = _params(name), _record(1)
    k = _run(_kernel(name), p, 0.3, record)
    t = _run(pure_python(_kernel(name)), p, 0.3, record)
    assert np.all(np.isfinite(k))  # rules 2 and 4: every slot written, finite
    np.testing.assert_allclose(k, t, rtol=1e-10, atol=1e-9)


@pytest.mark.parametrize("name", NAMES)
def test_state_read_only_and_deterministic(name):
    p = _params(name)
    state = np.zeros(N_FORCE_STATE)  # rule 3: the zero state is valid
    s0 = state.copy()
    a, sa = _call(_kernel(name), p, 1.0, 0.6, 0.2, 0.3, 0.01, state)
    b, sb = _call(_kernel(name), p, 1.0, 0.6, 0.2, 0.3, 0.01, state)
    np.testing.assert_array_equal(state, s0)  # rule 2
    np.testing.assert_array_equal(a, b)  # rule 1
    np.testing.assert_array_equal(sa, sb)
    assert np.all(np.isfinite(a))


@pytest.mark.parametrize("name", NAMES)
def test_tangents_against_central_differences(name):
    p, kernel, h = _params(name), _kernel(name), 1e-6
    for u, a, vc, yd in ((0.8, 0.1, 0.3, 0.02), (-0.5, -0.3, 0.2, -0.05), (1.2, 0.0, -0.4, 0.1)):
        out, _ = _call(kernel, p, 2.0, u, a, vc, yd)
        hi, _ = _call(kernel, p, 2.0, u, a, vc, yd + h)
        lo, _ = _call(kernel, p, 2.0, u, a, vc, yd - h)
        scale = max(1.0, abs(out[FO_DFY_DYD]), abs(out[FO_DFZ_DYD]))
        assert (hi[FO_FY] - lo[FO_FY]) / (2 * h) == pytest.approx(out[FO_DFY_DYD], abs=1e-4 * scale)
        assert (hi[FO_FZ] - lo[FO_FZ]) / (2 * h) == pytest.approx(out[FO_DFZ_DYD], abs=1e-4 * scale)
        assert out[FO_DFY_DYD] <= 0.0  # a drag law resists the pipe's own velocity


@pytest.mark.parametrize("name", NAMES)
def test_mirror_symmetry_from_the_zero_state(name):
    p, kernel = _params(name), _kernel(name)
    for u, a, vc, yd in ((0.8, 0.1, 0.3, 0.02), (0.5, -0.3, 0.0, -0.05)):
        plus, _ = _call(kernel, p, 2.0, u, a, vc, yd)
        minus, _ = _call(kernel, p, 2.0, -u, -a, -vc, -yd)
        assert minus[FO_FY] == pytest.approx(-plus[FO_FY], rel=1e-12, abs=1e-12)
        assert minus[FO_FZ] == pytest.approx(plus[FO_FZ], rel=1e-12, abs=1e-12)


@pytest.mark.parametrize("name", NAMES)
def test_nan_in_gives_non_finite_force(name):
    out, _ = _call(_kernel(name), _params(name), 2.0, np.nan, 0.0, 0.3, 0.0)
    assert not np.isfinite(out[FO_FY]), f"{name}: NaN velocity gave F_Y = {out[FO_FY]}"


@pytest.mark.long  # one storm-kernel compile per model on a cold cache
@pytest.mark.parametrize("name", NAMES)
def test_case_file_round_trip(name, tmp_path):
    entry = FORCE_REGISTRY[name]
    opts = "".join(f"{k} = {v!r}\n".replace("'", '"') for k, v in entry.example.items())
    case = tmp_path / "case.toml"
    case.write_text(
        "[pipe]\nouter_diameter = 0.4\nsubmerged_weight = 1500.0\n"
        '[seabed]\nmodel = "rock"\nfriction_coefficient = 0.6\n'
        "[environment]\nwater_depth = 13.0\n"
        "[current]\nvelocity = 0.3\nreference_height = 1.0\ndirection_deg = 90.0\n"
        '[storm]\nkind = "regular"\nheight = 4.0\nperiod = 10.0\ndirection_deg = 90.0\n'
        "build_up_hours = 0.005\npeak_hours = 0.01\ntime_step = 0.1\n"
        "[solver]\nrecord_interval = 1.0\n"
        f'[hydro]\nmodel = "{name}"\n' + (f"[hydro.{name}]\n{opts}" if opts else ""),
        encoding="utf-8",
    )
    out = tmp_path / "case.nc"
    res = CliRunner().invoke(cli, ["storm", str(case), "--workers", "0", "--quiet", "-o", str(out)])
    assert res.exit_code == 0, res.output
    with xr.open_dataset(out) as ds:
        assert ds.attrs["run_status"] == "complete"
        assert np.all(np.isfinite(ds["y"].values))
        assert ds.attrs["force_model"] == _model(name).name


@pytest.mark.parametrize("name", NAMES)
def test_two_stage_form_or_no_op(name):
    """Rule 7: a model with the two-stage form gives the kernel's state and outputs, bit for
    bit, from one prepare per step and one evaluation per ẏ; one without it returns False and
    touches nothing (the solver then calls the kernel)."""
    model_id = _model(name).model_id
    assert model_id in _PREPARE and model_id in _EVALUATE
    prepare, evaluate, kernel = _PREPARE[model_id], _EVALUATE[model_id], _kernel(name)
    p, (t, u, a, yd) = _params(name), _record(2, n=200)
    state = np.zeros(N_FORCE_STATE)
    s_new, s_one = np.full(N_FORCE_STATE, -7.0), np.zeros(N_FORCE_STATE)
    prep = np.full(N_FORCE_PREP, -7.0)
    out, one = np.zeros(FO_SIZE), np.zeros(FO_SIZE)
    for i in range(t.size):
        prepared = prepare(p, state, t[i], u[i], a[i], 0.3, D, RHO, s_new, prep)
        if not prepared:
            assert np.all(s_new == -7.0) and np.all(prep == -7.0)  # a no-op
            return
        for v in (yd[i], yd[i] + 0.2, -0.4):
            kernel(p, state, t[i], u[i], a[i], 0.3, v, D, RHO, s_one, one)
            evaluate(p, prep, u[i], 0.3, v, D, RHO, out)
            assert np.array_equal(out, one), (name, i, v)
        assert np.array_equal(s_new, s_one), (name, i)
        state = s_one.copy()
