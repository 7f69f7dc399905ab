"""Conformance suite: every registered soil model against the kernel contract of
:mod:`onbottom.soil.base` (scipy's ``test_ivp`` runs every method of ``METHODS``; here every
entry of :data:`onbottom.soil.registry.SOIL_MODELS`).

A model registered with :func:`~onbottom.soil.registry.register_soil_model` gets every test
below with no test written (``tests/recipe_models.py``'s ``adhesive_coulomb`` is registered by
importing it, to show that). A model whose kernel is missing from the dispatch fails
``test_dispatch_entry_exists[<name>]``.

Rules checked (numbers of the contract): 1 and 2 (``params`` and ``state_old`` read only), 4
(zero resistance at lift-off), 5 (the same trial from the same committed state), 6 (every
``out`` slot finite; dissipated energy never decreasing on a path at constant V), 7 (sign and
mirror symmetry: from the initial state, the path −u gives −R), the plain-Python twin equal to
the kernel on a random path, NaN in gives NaN resistance out (the solvers' SOIL_NAN status), and
a case file naming the model through ``onbottom storm``.
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
from onbottom.cli.main import cli
from onbottom.inputs import Pipe
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.soil._dispatch import _KERNELS
from onbottom.soil.base import OUT_DISSIPATED, OUT_R, OUT_SIZE
from onbottom.soil.registry import SOIL_MODELS

PIPE = Pipe(outer_diameter=0.4, submerged_weight=1500.0)
SEABEDS = {
    Sand: Sand(submerged_unit_weight=10.0e3, friction_coefficient=0.6),
    Clay: Clay(undrained_shear_strength=5.0e3, submerged_unit_weight=6.0e3, unit_weight=16.0e3),
    Rock: Rock(friction_coefficient=0.6),
}
SEABED_TABLES = {
    Sand: 'model = "sand"\nsubmerged_unit_weight = 10.0e3\nfriction_coefficient = 0.6\n',
    Clay: 'model = "clay"\nundrained_shear_strength = 5.0e3\nsubmerged_unit_weight = 6.0e3\n'
    "unit_weight = 16.0e3\n",
    Rock: 'model = "rock"\nfriction_coefficient = 0.6\n',
}
NAMES = SOIL_MODELS.names()
V = 1200.0  # vertical load [N/m], below W_s (the models' as-laid state is at W_s)


def _model(name):
    entry = SOIL_MODELS[name]
    return entry.build(PIPE, SEABEDS[entry.seabeds[0]], **entry.example)


def _path(seed: int, n: int = 300) -> np.ndarray:
    """A random lateral path [m]: steps of a few mm, reversals, out to a few cm."""
    rng = np.random.default_rng(seed)
    return np.cumsum(rng.normal(0.0, 3.0e-3, n))


def _run(kernel, model, us, vs):
    """Drive ``kernel`` along (u, V), committing every step; outputs and states per step."""
    params = model.packed_parameters()
    state = model.initial_state().copy()
    outs, states = [], []
    for u, v in zip(us, vs, strict=True):
        new = np.zeros_like(state)
        out = np.zeros(OUT_SIZE)
        kernel(params, state, u, v, new, out)
        outs.append(out.copy())
        states.append(new.copy())
        state = new
    return np.array(outs), np.array(states)


@pytest.mark.parametrize("name", NAMES)
def test_dispatch_entry_exists(name):
    model = _model(name)
    assert model.model_id in _KERNELS, f"{name}: model_id {model.model_id} not in the dispatch"
    assert _KERNELS[model.model_id] is model.kernel


@pytest.mark.parametrize("name", NAMES)
def test_kernel_equals_twin_on_a_random_path(name):
    model = _model(name)
    us = _path(1)
    vs = V * (1.0 + 0.2 * np.sin(np.arange(us.size) / 7.0))
    k_out, k_state = _run(model.kernel, model, us, vs)
    t_out, t_state = _run(model.python_kernel, model, us, vs)
    assert np.all(np.isfinite(k_out)) and np.all(np.isfinite(k_state))  # rule 6
    np.testing.assert_allclose(k_out, t_out, rtol=1e-10, atol=1e-9)
    np.testing.assert_allclose(k_state, t_state, rtol=1e-10, atol=1e-12)


@pytest.mark.parametrize("name", NAMES)
def test_inputs_read_only_and_trials_repeatable(name):
    model = _model(name)
    params = model.packed_parameters()
    state = model.initial_state().copy()
    p0, s0 = params.copy(), state.copy()
    results = []
    for _ in range(2):  # rule 5: the same trial from the same committed state
        new, out = np.zeros_like(state), np.zeros(OUT_SIZE)
        model.kernel(params, state, 4.0e-3, V, new, out)
        results.append((new.copy(), out.copy()))
    np.testing.assert_array_equal(params, p0)  # rule 1
    np.testing.assert_array_equal(state, s0)  # rule 2
    np.testing.assert_array_equal(results[0][0], results[1][0])
    np.testing.assert_array_equal(results[0][1], results[1][1])


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("v", [0.0, -500.0])
def test_zero_resistance_at_lift_off(name, v):
    model = _model(name)
    us = _path(2, 40)
    outs, _ = _run(model.kernel, model, us, np.r_[np.full(20, V), np.full(20, v)])
    assert np.all(outs[20:, OUT_R] == 0.0)  # rule 4: zero, not NaN


@pytest.mark.parametrize("name", NAMES)
def test_dissipation_never_decreases_at_constant_v(name):
    model = _model(name)
    us = _path(3)
    outs, _ = _run(model.kernel, model, us, np.full(us.size, V))
    d = outs[:, OUT_DISSIPATED]
    scale = max(1.0, float(np.max(np.abs(d))))
    assert np.all(np.diff(d) >= -1e-9 * scale), f"{name}: dissipated energy decreased"


@pytest.mark.parametrize("name", NAMES)
def test_mirror_symmetry(name):
    model = _model(name)
    us = _path(4, 120)
    vs = np.full(us.size, V)
    plus, _ = _run(model.kernel, model, us, vs)
    minus, _ = _run(model.kernel, model, -us, vs)
    np.testing.assert_allclose(minus[:, OUT_R], -plus[:, OUT_R], rtol=1e-9, atol=1e-6)
    assert np.any(plus[:, OUT_R] > 0.0)  # rule 7: R resists positive motion


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("which", ["u", "v"])
def test_nan_in_gives_nan_resistance(name, which):
    model = _model(name)
    state = model.initial_state().copy()
    new, out = np.zeros_like(state), np.zeros(OUT_SIZE)
    u, v = (np.nan, V) if which == "u" else (1.0e-3, np.nan)
    model.kernel(model.packed_parameters(), state, u, v, new, out)
    assert not np.isfinite(out[OUT_R]), f"{name}: NaN {which} gave R = {out[OUT_R]}"


@pytest.mark.long  # one storm-kernel compile per model on a cold cache
@pytest.mark.parametrize("name", NAMES)
def test_case_file_round_trip(name, tmp_path):
    entry = SOIL_MODELS[name]
    opts = "".join(f"{k} = {v!r}\n" for k, v in entry.example.items())
    case = tmp_path / "case.toml"
    case.write_text(
        "[pipe]\nouter_diameter = 0.4\nsubmerged_weight = 1500.0\n"
        f"[seabed]\n{SEABED_TABLES[entry.seabeds[0]]}"
        "[environment]\nwater_depth = 13.0\n"
        "[current]\nvelocity = 0.3\nreference_height = 1.0\ndirection_deg = 90.0\n"
        '[storm]\nkind = "regular"\nheight = 4.0\nperiod = 10.0\ndirection_deg = 90.0\n'
        "build_up_hours = 0.005\npeak_hours = 0.01\ntime_step = 0.1\n"
        "[solver]\nrecord_interval = 1.0\n"
        f'[soil]\nmodel = "{name}"\n' + (f"[soil.{name}]\n{opts}" if opts else ""),
        encoding="utf-8",
    )
    out = tmp_path / "case.nc"
    res = CliRunner().invoke(cli, ["storm", str(case), "--workers", "0", "--quiet", "-o", str(out)])
    assert res.exit_code == 0, res.output
    with xr.open_dataset(out) as ds:
        assert ds.attrs["run_status"] == "complete"
        assert np.all(np.isfinite(ds["y"].values))
        assert f'"soil_model": "{_model(name).name}"' in ds.attrs["parameters"]
