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

from case_helpers import toml_value as _toml_value
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
                for name in ("y", "z", "H", "V", "F_soil"):
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
    from onbottom.cases.sweep import read_grid

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
    from onbottom.cases.dem import dem_config_from_json
    from onbottom.dem.config import SD_REDUCED

    base = json.loads(SD_REDUCED.to_json())
    doc = _mutate(base, data)
    try:
        cfg = dem_config_from_json(json.dumps(doc, allow_nan=True))
    except OnbottomError as exc:
        assert str(exc) and "np.float" not in str(exc)
        return
    assert cfg.estimated_particle_count() >= 0
    assert dem_config_from_json(cfg.to_json()) == cfg


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
    header=st.lists(st.sampled_from(["time", "y", "z", "u", "w", "H", "V", "x", ""]), max_size=6),
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


# --------------------------------------------------------------------------------------------
# issue #31: the stability commands' case files and API, seeded with the campaign's classes
# (physical inconsistency, unit slips, path escapes); never exit 0 with a verdict on nonsense
# --------------------------------------------------------------------------------------------
STABILITY = {
    "pipe": {"outer_diameter": 0.512, "submerged_weight": 1500.0},
    "seabed": {"model": "sand", "submerged_unit_weight": 10.0e3},
    "environment": {"water_depth": 30.0},
    "waves": {"hs": 4.0, "tp": 11.0, "direction_deg": 90.0},
    "current": {"velocity": 0.4, "reference_height": 1.0, "direction_deg": 90.0},
}
BUILDUP = {
    "steel_outer_diameter": 0.2191,
    "wall_thickness": 0.0127,
    "youngs_modulus": 207.0e9,
    "layers": [{"name": "concrete", "thickness": 0.04, "density": 3043.5}],
}
# (table, key, value): the campaign's classes as seeds of the mutations
CAMPAIGN = [
    ("environment", "water_depth", 0.4),  # shallower than D = 0.512 m
    ("environment", "water_depth", 0.5),
    ("waves", "hs", 30.0),  # breaking in 30 m
    ("waves", "tp", 0.011),  # ms typed as s
    ("waves", "direction_deg", 1.5708),  # radians typed as degrees
    ("current", "velocity", 9.5),  # knots? cm/s?
    ("pipe", "outer_diameter", 512.0),  # mm typed as m
    ("pipe", "submerged_weight", 1.5),  # kN/m typed as N/m
    ("seabed", "submerged_unit_weight", 10.0),  # kN/m³ typed as N/m³
    ("storm", "peak_hours", 1e-9),
    ("storm", "build_up_hours", 1e-9),
    ("solver", "max_displacement_over_d", 1e-6),
]
SEEDED = st.one_of(
    st.sampled_from(CAMPAIGN),
    st.tuples(
        st.sampled_from(["environment", "waves", "current", "pipe"]), st.text(max_size=4), VALUES
    ),
)


def _seeded(base: dict, data) -> dict:
    doc = copy.deepcopy(base)
    for _ in range(data.draw(st.integers(1, 2), label="n_campaign")):
        table, key, value = data.draw(SEEDED, label="campaign")
        doc.setdefault(table, {})
        if isinstance(doc[table], dict) and key:
            doc[table][key] = value
    return _mutate(doc, data) if data.draw(st.booleans(), label="also_mutate") else doc


def _diameter(doc: dict) -> float | None:
    p = doc.get("pipe", {})
    d = p.get("outer_diameter")
    return float(d) if isinstance(d, (int, float)) and not isinstance(d, bool) else None


@FUZZ
@given(data=st.data(), command=st.sampled_from(["stability", "loads"]))
def test_fuzz_stability_and_loads_case_files(data, command):
    doc = _seeded(STABILITY, data)
    with tempfile.TemporaryDirectory() as tmp:
        case = Path(tmp) / "case.toml"
        case.write_text(_toml(doc), encoding="utf-8")
        args = [command, str(case)] + (["--duration-hours", "0.1"] if command == "loads" else [])
        r = _run(args)
        if r.exit_code in (0, 3):
            out = json.loads(r.stdout)
            assert out["schema_version"] >= 1
            depth = doc["environment"]["water_depth"]
            d = _diameter(doc)
            if d is not None:  # a verdict only on a pipe under water
                assert depth > d, (depth, d)
            hs = doc["waves"]["hs"]
            assert hs <= 0.78 * depth
        else:
            _assert_error(r)
            assert r.exit_code in (1, 2)


@FUZZ
@given(data=st.data())
def test_fuzz_storm_case_files_load(data):
    """Section storm case files, loaded only (the storm is not run): a setup whose depth,
    peak duration and stop limit make sense, or a named error."""
    from onbottom.cases.storm import load_storm_setup

    base = copy.deepcopy(STABILITY)
    base["storm"] = {"build_up_hours": 0.0, "peak_hours": 0.02}
    base["solver"] = {"max_displacement_over_d": 10.0}
    doc = _seeded(base, data)
    with tempfile.TemporaryDirectory() as tmp:
        case = Path(tmp) / "case.toml"
        case.write_text(_toml(doc), encoding="utf-8")
        try:
            setup = load_storm_setup(case)
        except OnbottomError as exc:
            assert str(exc) and "np.float" not in str(exc) and "Traceback" not in str(exc)
            return
        assert setup.depth > setup.pipe.outer_diameter
        assert setup.settings.stop_displacement_over_d >= 10.0
        peak = max(s.tp for s in setup.storm.stages)
        assert setup.storm.duration_s >= 3.0 * peak


PIPELINE_TABLE = {
    "length": 200.0,
    "element_length": 4.0,
    "end_conditions": "fixed",
    "record_interval": 2.0,
}
PIPELINE_CAMPAIGN = [
    ("length", 4.0),  # one element, fixed-fixed
    ("element_length", 100.0),
    ("chunk_duration", 0.001),
    ("animation", "../../x.gif"),  # path escapes
    ("animation", "/tmp/x.gif"),
    ("animation", "sub/../../x.gif"),
    ("end_conditions", ["fixed", "free"]),
]


@FUZZ
@given(
    data=st.data(),
    change=st.one_of(
        st.sampled_from(PIPELINE_CAMPAIGN), st.tuples(st.sampled_from(list(PIPELINE_TABLE)), VALUES)
    ),
)
def test_fuzz_pipeline_case_files_build(data, change):
    """Pipeline case files, built only: at least 3 free nodes, paths inside the case folder."""
    from onbottom.cases.pipeline import load_pipeline_run

    base = copy.deepcopy(STABILITY)
    base["pipe"] = dict(BUILDUP)
    base["storm"] = {"build_up_hours": 0.0, "peak_hours": 0.02}
    base["pipeline"] = dict(PIPELINE_TABLE)
    base["pipeline"][change[0]] = change[1]
    doc = _seeded(base, data) if data.draw(st.booleans(), label="seeded") else base
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "a" / "b"
        folder.mkdir(parents=True)
        case = folder / "case.toml"
        case.write_text(_toml_nested(doc), encoding="utf-8")
        try:
            run = load_pipeline_run(case)
        except OnbottomError as exc:
            assert str(exc) and "np.float" not in str(exc)
            return
        if run.animation is not None:
            assert folder.resolve() in run.animation.resolve().parents
        assert run.model.x.size >= 3


def _toml_nested(doc: dict) -> str:
    """Like :func:`_toml` with arrays of tables (``[[pipe.layers]]``)."""
    lines = []
    for table, body in doc.items():
        if not isinstance(body, dict):
            lines.insert(0, f"{json.dumps(table)} = {_toml_value(body)}")
            continue
        lines.append(f"[{table}]")
        subs = []
        for k, v in body.items():
            if isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
                subs.extend((k, x) for x in v)
            else:
                lines.append(f"{json.dumps(k)} = {_toml_value(v)}")
        for k, x in subs:
            lines.append(f"[[{table}.{k}]]")
            lines.extend(f"{json.dumps(kk)} = {_toml_value(vv)}" for kk, vv in x.items())
    return "\n".join(lines) + "\n"


CURVES_CASE = {
    "curves": {
        "K": [5.0],
        "M": [0.0],
        "seeds": 1,
        "build_up_hours": 0.0,
        "peak_hours": 0.01,
        "tolerance": 0.5,
        "diameter": 0.5,
    }
}
CURVES_CAMPAIGN = [
    ("peak_hours", 1e-9),
    ("K", [float(k) for k in range(1, 200)]),
    ("seeds", 1000),
    ("diameter", 500.0),
    ("time_step", 100.0),
    ("tolerance", 1e-9),
]


@FUZZ
@given(
    data=st.data(),
    change=st.one_of(
        st.sampled_from(CURVES_CAMPAIGN),
        st.tuples(st.sampled_from(list(CURVES_CASE["curves"])), VALUES),
    ),
)
def test_fuzz_curves_case_files(data, change):
    """Curves case files, checked only (settings, peak duration, budget)."""
    from onbottom.cases.curves import build_curve_settings, check_budget, load_curves_case

    doc = copy.deepcopy(CURVES_CASE)
    doc["curves"][change[0]] = change[1]
    if data.draw(st.booleans(), label="mutate"):
        doc = _mutate(doc, data)
    with tempfile.TemporaryDirectory() as tmp:
        case = Path(tmp) / "c.toml"
        case.write_text(_toml(doc), encoding="utf-8")
        try:
            cfg = load_curves_case(case)
            settings = build_curve_settings(cfg, case)
            check_budget(cfg.curves, workers=2, force=False)
        except OnbottomError as exc:
            assert str(exc) and "np.float" not in str(exc)
            return
        assert settings.peak_hours > 0 and cfg.curves.peak_hours * 3600.0 >= 3.0 * 8.0


API_VALUES = st.one_of(
    NUMBERS,
    st.sampled_from([np.array([8.0, 9.0]), [8.0], (1.0, 2.0), np.array(3.0), "3", None, True]),
    st.lists(st.floats(0.1, 10.0), min_size=2, max_size=3).map(np.array),
)


@FUZZ
@given(
    hs=API_VALUES,
    tp=API_VALUES,
    depth=st.one_of(API_VALUES, st.sampled_from([0.4, 0.512, 0.6, 1.0])),
    current=API_VALUES,
    direction=st.one_of(API_VALUES, st.just(1.5708)),
)
def test_fuzz_absolute_lateral_stability_arguments(hs, tp, depth, current, direction):
    """Arrays where scalars are expected, the reverse, units slipped, depth below D: a finite
    utilisation or an onbottom error — never numpy's TypeError."""
    import warnings

    from onbottom.checks.absolute import absolute_lateral_stability
    from onbottom.inputs.pipe import Pipe
    from onbottom.inputs.soil import Sand

    pipe = Pipe(outer_diameter=0.512, submerged_weight=1500.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            r = absolute_lateral_stability(
                pipe,
                Sand(submerged_unit_weight=10e3),
                hs=hs,
                tp=tp,
                depth=depth,
                current_velocity=current,
                wave_direction_deg=direction,
            )
        except OnbottomError as exc:
            assert str(exc) and "np.float" not in str(exc)
            return
    assert math.isfinite(r.utilisation) or r.utilisation == math.inf
    assert float(depth) > 0.512


@FUZZ
@given(depth=st.one_of(API_VALUES, st.sampled_from([0.1, 0.4, 0.512])))
def test_fuzz_simulate_storm_section_depth(depth):
    """A depth that is no scalar, not finite or not above D is refused before the run."""
    from onbottom.dynamics.storm_section import simulate_storm_section
    from onbottom.inputs.pipe import Pipe
    from onbottom.inputs.soil import Sand
    from onbottom.inputs.storm import SeaState, Storm
    from onbottom.soil.verley_sotberg import VerleySotberg

    ok = (
        isinstance(depth, (int, float))
        and not isinstance(depth, bool)
        and math.isfinite(depth)
        and depth > 0.512
    )
    if ok:  # a valid depth runs a 36-s storm: a result (deep water: no flow at the seabed)
        pipe = Pipe(outer_diameter=0.512, submerged_weight=1500.0)
        soil = VerleySotberg.silica(pipe, Sand(submerged_unit_weight=10e3))
        storm = Storm.standard(SeaState(hs=0.2, tp=4.0), build_up_hours=0.0, peak_hours=0.01)
        import warnings

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            r = simulate_storm_section(pipe, soil, storm, depth=depth)
        assert math.isfinite(r.max_displacement)
        return
    pipe = Pipe(outer_diameter=0.512, submerged_weight=1500.0)
    soil = VerleySotberg.silica(pipe, Sand(submerged_unit_weight=10e3))
    storm = Storm.standard(SeaState(hs=0.2, tp=4.0), build_up_hours=0.0, peak_hours=0.01)
    with pytest.raises(OnbottomError):
        simulate_storm_section(pipe, soil, storm, depth=depth)
