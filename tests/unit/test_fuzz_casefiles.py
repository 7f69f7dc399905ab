"""Property-based fuzzing of case files and numeric options (hypothesis; issue #10).

Invariant for every generated input: either a valid result (no NaN in it), or an onbottom
error — :class:`~onbottom.errors.InputError` / :class:`~onbottom.errors.SolutionError` in the
API, exit status >= 1 with a JSON error object naming the field on the command line — and
never another exception type (no ``KeyError``, ``TypeError``, numpy or h5py traceback).
"""

from __future__ import annotations

import copy
import json
import math
import os
import tempfile
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from onbottom.cli.main import cli
from onbottom.errors import OnbottomError

# out-of-range warnings are part of a valid result here (the suite turns them into errors)
pytestmark = pytest.mark.filterwarnings("default::onbottom.errors.OutOfRangeWarning")

FUZZ = settings(
    # ONBOTTOM_FUZZ_EXAMPLES=1000 for a longer hunt (CI keeps the suite to seconds)
    max_examples=int(os.environ.get("ONBOTTOM_FUZZ_EXAMPLES", "40")),
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)

# values of any TOML/JSON type, weighted towards the troublesome ones
NUMBERS = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True, width=64),
    st.sampled_from([0.0, -0.0, -1.0, 1e-300, 1e300, 0.5, 16.7, 1e7, -1e7]),
    st.integers(min_value=-(2**63), max_value=2**63 - 1),
)
SCALARS = st.one_of(NUMBERS, st.booleans(), st.text(max_size=8))
VALUES = st.one_of(
    SCALARS,
    st.lists(SCALARS, max_size=3),
    st.dictionaries(st.text(max_size=5), SCALARS, max_size=2),
)


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{json.dumps(k)} = {_toml_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(v)


def _toml(doc: dict) -> str:
    lines = []
    for table, body in doc.items():
        if isinstance(body, dict):
            lines.append(f"[{table}]")
            lines.extend(f"{json.dumps(k)} = {_toml_value(v)}" for k, v in body.items())
        else:
            lines.insert(0, f"{json.dumps(table)} = {_toml_value(body)}")
    return "\n".join(lines) + "\n"


def _mutate(base: dict, data) -> dict:
    """Change, add or delete one to three keys of a two-level document."""
    doc = copy.deepcopy(base)
    for _ in range(data.draw(st.integers(1, 3), label="n_mutations")):
        table = data.draw(st.sampled_from([*doc.keys(), "extra_table"]), label="table")
        body = doc.setdefault(table, {})
        if not isinstance(body, dict):
            doc[table] = data.draw(VALUES, label="value")
            continue
        keys = [*body.keys(), "extra_key"]
        key = data.draw(st.sampled_from(keys), label="key")
        action = data.draw(st.sampled_from(["set", "set", "delete"]), label="action")
        if action == "delete":
            body.pop(key, None)
        else:
            body[key] = data.draw(VALUES, label="value")
    return doc


def _run(args: list[str]):
    r = CliRunner().invoke(cli, [*args, "--json"])
    assert r.exit_code != 70 and "Traceback" not in r.output, r.output
    assert not isinstance(r.exception, Exception) or isinstance(r.exception, SystemExit), repr(
        r.exception
    )
    return r


def _assert_error(r) -> None:
    assert r.exit_code >= 1
    err = json.loads(r.stdout)["error"]
    assert err["message"] and "np.float" not in err["message"]
    assert err["type"] not in {"KeyError", "TypeError", "IndexError", "AttributeError"}


def _assert_no_nan(obj) -> None:
    if isinstance(obj, dict):
        for v in obj.values():
            _assert_no_nan(v)
    elif isinstance(obj, list):
        for v in obj:
            _assert_no_nan(v)
    elif isinstance(obj, float):
        assert math.isfinite(obj)


# --------------------------------------------------------------------------------------------
# simulate case files: schema + solver, end to end
# --------------------------------------------------------------------------------------------
CASE = {
    "pipe": {"outer_diameter": 1.0, "submerged_weight_kn": 10.52},
    "soil": {
        "model": "verley_sotberg_calcareous",
        "friction_coefficient": 0.48,
        "submerged_unit_weight_kn": 7.5,
    },
    "programme": {
        "kind": "inclined_cyclic",
        "vertical_load_kn": 10.52,
        "amplitude_step_kn": 0.25,
        "period": 40.0,
        "alpha_deg": 30.0,
        "n_cycles": 2,
        "points_per_cycle": 40,
    },
    "solver": {"displacement_limit": 3.0},
}


@FUZZ
@given(data=st.data())
def test_fuzz_simulate_case_file(data):
    doc = _mutate(CASE, data)
    with tempfile.TemporaryDirectory() as tmp:
        case = Path(tmp) / "case.toml"
        case.write_text(_toml(doc), encoding="utf-8")
        r = _run(["simulate", str(case), "--quiet"])
        if r.exit_code == 0 or r.exit_code == 3:  # a result (3: valid file, invalid result)
            out = json.loads(r.stdout)
            assert out["success"] is (r.exit_code == 0)
            if r.exit_code == 0:
                from onbottom.results import load_dataset

                ds = load_dataset(out["netcdf"])
                for name in ("u", "w", "H", "V", "F_soil"):
                    assert np.all(np.isfinite(ds[name].values)), name
                _assert_no_nan({k: v for k, v in out.items() if k != "cycles_to_limit"})
        else:
            _assert_error(r)
            assert r.exit_code == 1


@FUZZ
@given(
    d=NUMBERS,
    w=NUMBERS,
    gamma=NUMBERS,
    mu=NUMBERS,
    n=NUMBERS,
)
def test_fuzz_simulate_numbers(d, w, gamma, mu, n):
    """Only numbers change: a finite result, or an error naming the changed key."""
    doc = copy.deepcopy(CASE)
    doc["pipe"].update(outer_diameter=d, submerged_weight_kn=w)
    doc["soil"].update(submerged_unit_weight_kn=gamma, friction_coefficient=mu)
    doc["programme"]["n_cycles"] = n
    with tempfile.TemporaryDirectory() as tmp:
        case = Path(tmp) / "case.toml"
        case.write_text(_toml(doc), encoding="utf-8")
        r = _run(["simulate", str(case), "--quiet"])
        if r.exit_code in (0, 3):
            assert json.loads(r.stdout)["success"] is (r.exit_code == 0)
            return
        _assert_error(r)
        field = json.loads(r.stdout)["error"]["field"] or ""
        known = ("outer_diameter", "submerged_weight", "unit_weight", "friction", "n_cycles")
        assert any(k in field for k in known) or "mass" in field, field


# --------------------------------------------------------------------------------------------
# sweep grid files (read and checked; the runs themselves are tested elsewhere)
# --------------------------------------------------------------------------------------------
GRID = {
    "sweep": {"function": "centrifuge_response", "seed": 1},
    "grid": {"A": [0.2, 0.3]},
    "fixed": {"test": "Inclined 1"},
}


@FUZZ
@given(data=st.data())
def test_fuzz_sweep_grid_file(data):
    from onbottom.cli.sweep import read_grid

    doc = _mutate(GRID, data)
    with tempfile.TemporaryDirectory() as tmp:
        grid = Path(tmp) / "grid.toml"
        grid.write_text(_toml(doc), encoding="utf-8")
        try:
            spec = read_grid(grid)
        except OnbottomError as exc:
            assert str(exc) and "np.float" not in str(exc)
            return
        assert callable(spec["function"]) and spec["grid"]
        for values in spec["grid"].values():
            assert len(values) >= 1


# --------------------------------------------------------------------------------------------
# DEM config files (JSON)
# --------------------------------------------------------------------------------------------
@FUZZ
@given(data=st.data())
def test_fuzz_dem_config(data):
    from onbottom.dem.config import SD_REDUCED, DEMConfig

    base = json.loads(SD_REDUCED.to_json())
    doc = _mutate(base, data)
    try:
        cfg = DEMConfig.from_json(json.dumps(doc, allow_nan=True))
    except OnbottomError as exc:
        assert str(exc) and "np.float" not in str(exc)
        return
    assert cfg.estimated_particle_count() >= 0
    assert DEMConfig.from_json(cfg.to_json()) == cfg


# --------------------------------------------------------------------------------------------
# calibration records (CSV)
# --------------------------------------------------------------------------------------------
CELLS = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.sampled_from(["", "x", "1e400", "-0", " 1 ", "nan"]),
    st.integers(-5, 5).map(str),
)


@FUZZ
@given(
    header=st.lists(st.sampled_from(["time", "u", "w", "H", "V", "x", ""]), max_size=6),
    units=st.lists(st.sampled_from(["s", "m", "mm", "kN/m", "N/m", "furlong", ""]), max_size=6),
    rows=st.lists(st.lists(CELLS, max_size=6), max_size=5),
    meta=st.lists(st.tuples(st.sampled_from(["diameter", "V_i", "name", "zz"]), CELLS), max_size=3),
)
def test_fuzz_record_csv(header, units, rows, meta):
    from onbottom.calibration.records import load_record

    text = "".join(f"# {k}: {v} m\n" for k, v in meta)
    text += ",".join(header) + "\n" + ",".join(units) + "\n"
    text += "".join(",".join(r) + "\n" for r in rows)
    with tempfile.TemporaryDirectory() as tmp:
        f = Path(tmp) / "rec.csv"
        f.write_text(text, encoding="utf-8")
        try:
            rec = load_record(f)
        except OnbottomError as exc:
            assert str(exc) and "np.float" not in str(exc)
            return
        t = np.asarray(rec.time)
        assert np.all(np.isfinite(t)) and np.all(np.diff(t) > 0)


# --------------------------------------------------------------------------------------------
# numeric options
# --------------------------------------------------------------------------------------------
OPTION_TEXT = st.one_of(
    NUMBERS.map(str),
    st.sampled_from(["", "abc", "1,5", "0x10", "1e", "--", "nan", "-inf", "1_000"]),
)


@FUZZ
@given(d=OPTION_TEXT, w=OPTION_TEXT, gamma=OPTION_TEXT, mu=OPTION_TEXT, cycles=OPTION_TEXT)
def test_fuzz_backbone_options(d, w, gamma, mu, cycles):
    args = ["backbone", "--diameter", d, "--weight-kn", w, "--gamma-kn", gamma, "--mu", mu]
    args += ["--cycles", cycles, "--amplitude", "0.01"]
    r = _run(args)
    if r.exit_code in (0, 3):  # 3: a result outside the model's validity (z > D/2)
        out = json.loads(r.stdout)
        assert out["success"] is (r.exit_code == 0)
        _assert_no_nan(out["backbone"])
        _assert_no_nan(out.get("path", {}))
    else:
        _assert_error(r)
        assert json.loads(r.stdout)["error"]["field"], r.stdout


@FUZZ
@given(d=OPTION_TEXT, gamma=OPTION_TEXT, phi=OPTION_TEXT, load=OPTION_TEXT)
def test_fuzz_penetration_options(d, gamma, phi, load):
    args = ["penetration", "--diameter", d, "--gamma-kn", gamma, "--phi-deg", phi]
    args += ["--load-kn", load]
    r = _run(args)
    if r.exit_code in (0, 3):
        out = json.loads(r.stdout)
        _assert_no_nan(out["table"])
        assert out["embedment"]["success"] is (r.exit_code == 0)
    else:
        _assert_error(r)
        assert json.loads(r.stdout)["error"]["field"], r.stdout


@pytest.mark.parametrize("value", ["0", "-1", "2.5", "nan", "1e30", "x"])
@pytest.mark.parametrize("option", ["--popsize", "--maxiter", "--workers", "--seed"])
def test_calibrate_integer_options(tmp_path, option, value):
    rec = tmp_path / "r.csv"
    rec.write_text("time,u,w\ns,m,m\n0,0,0\n1,0,0\n")
    if option in ("--workers", "--seed") and value == "0":
        pytest.skip("0 is valid for this option")
    r = _run(["calibrate", str(rec), option, value])
    _assert_error(r)
    assert json.loads(r.stdout)["error"]["field"] == option
