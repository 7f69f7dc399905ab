"""Bad inputs of every file type and option class give a named error, never a traceback.

Table-driven (issue #10): each case runs the command line end to end with ``--json`` and
checks the contract of every command — exit status 1 (input) or 2 (usage), a JSON object
``{"error": {"type", "message", "field"}}`` on stdout whose ``field`` names the key or option
at fault, plain numbers in the message (no ``np.float64(...)``), and no internal error (70).
Tables: simulate case files (TOML), programme CSV files, sweep grid files (TOML), DEM config
files (JSON), calibration records (CSV/NetCDF), DEM run files, numeric and text options of
every command, and the plausibility of the Python inputs.
"""

from __future__ import annotations

import json
import math
import warnings

import pytest
from click.testing import CliRunner

from onbottom.cli.main import cli
from onbottom.dem.config import SD_REDUCED
from onbottom.errors import InputError, OutOfRangeWarning
from onbottom.status import Status

# --------------------------------------------------------------------------------------------
# the contract
# --------------------------------------------------------------------------------------------


def _check(args: list[str], field: str | None, *, message: str | None = None) -> dict:
    """Run ``onbottom ARGS --json``; assert the error contract; return the error object."""
    r = CliRunner().invoke(cli, [*args, "--json"])
    assert r.exit_code in (1, 2), (r.exit_code, r.output, r.exception)
    assert "Traceback" not in r.output
    err = json.loads(r.stdout)["error"]
    assert set(err) == {"type", "message", "field"}
    assert err["message"] and "np.float" not in err["message"] and "np.int" not in err["message"]
    if field is None:
        assert err["field"] is None or isinstance(err["field"], str)
    else:
        assert err["field"] is not None and field.lower() in err["field"].lower(), err
    if message is not None:
        assert message in err["message"], err
    return err


# --------------------------------------------------------------------------------------------
# simulate: case files (TOML) and programme CSV files
# --------------------------------------------------------------------------------------------
CASE = """\
[pipe]
outer_diameter = 1.0
submerged_weight_kn = 10.52

[soil]
model = "verley_sotberg_calcareous"
friction_coefficient = 0.48
submerged_unit_weight_kn = 7.5

[programme]
kind = "inclined_cyclic"
vertical_load_kn = 10.52
amplitude_step_kn = 0.25
period = 40.0
alpha_deg = 30.0
n_cycles = 2

[solver]
displacement_limit = 3.0
"""

SIMULATE_CASES = [
    # (id, old text, new text, field expected in the error)
    ("misspelled-table", "[solver]", "[solvr]", "solvr"),
    ("misspelled-key", "outer_diameter = 1.0", "outer_diamter = 1.0", "pipe.outer_diamter"),
    ("unknown-key-solver", "displacement_limit", "displacement_limt", "solver.displacement"),
    ("string-number", "period = 40.0", 'period = "40"', "programme.period"),
    ("bool-number", "period = 40.0", "period = true", "programme.period"),
    ("array-number", "outer_diameter = 1.0", "outer_diameter = [1.0]", "pipe.outer_diameter"),
    ("table-number", "outer_diameter = 1.0", "outer_diameter = {a = 1}", "pipe.outer_diameter"),
    ("n_cycles-fraction", "n_cycles = 2", "n_cycles = 16.7", "programme.n_cycles"),
    ("n_cycles-zero", "n_cycles = 2", "n_cycles = 0", "programme.n_cycles"),
    ("n_cycles-huge", "n_cycles = 2", "n_cycles = 10000000", "programme.n_cycles"),
    ("nan", "period = 40.0", "period = nan", "programme.period"),
    ("inf", "alpha_deg = 30.0", "alpha_deg = inf", "programme.alpha_deg"),
    ("alpha-range", "alpha_deg = 30.0", "alpha_deg = 120.0", "programme.alpha_deg"),
    ("negative-D", "outer_diameter = 1.0", "outer_diameter = -1.0", "pipe.outer_diameter"),
    ("D-in-mm", "outer_diameter = 1.0", "outer_diameter = 500.0", "outer_diameter"),
    ("zero-weight", "submerged_weight_kn = 10.52", "submerged_weight_kn = 0", "submerged_weight"),
    (
        "gamma-in-MN",
        "submerged_unit_weight_kn = 7.5",
        "submerged_unit_weight_kn = 0.0075",
        "soil.submerged_unit_weight_kn",
    ),
    (
        "gamma-in-N",
        "submerged_unit_weight_kn = 7.5",
        "submerged_unit_weight_kn = 7500.0",
        "soil.submerged_unit_weight_kn",
    ),
    (
        "mu-3",
        "friction_coefficient = 0.48",
        "friction_coefficient = 3.0",
        "soil.friction_coefficient",
    ),
    (
        "mu-negative",
        "friction_coefficient = 0.48",
        "friction_coefficient = -0.1",
        "soil.friction_coefficient",
    ),
    ("unknown-model", 'model = "verley_sotberg_calcareous"', 'model = "clay"', "soil.model"),
    (
        "coulomb-with-gamma",
        'model = "verley_sotberg_calcareous"',
        'model = "coulomb"',
        "soil.submerged_unit_weight_kn",
    ),
    (
        "silica-with-A",
        'model = "verley_sotberg_calcareous"',
        'model = "verley_sotberg_silica"\nA = 0.3',
        "soil.A",
    ),
    (
        "A-negative",
        "submerged_unit_weight_kn = 7.5",
        "submerged_unit_weight_kn = 7.5\nA = -0.2",
        "soil.A",
    ),
    ("gamma-missing", "submerged_unit_weight_kn = 7.5", "", "soil.submerged_unit_weight_kn"),
    ("required-key-missing", "vertical_load_kn = 10.52\n", "", "programme.vertical_load_kn"),
    ("unknown-kind", 'kind = "inclined_cyclic"', 'kind = "inclined"', "programme.kind"),
    ("kind-missing", 'kind = "inclined_cyclic"\n', "", "programme.kind"),
    ("kind-list", 'kind = "inclined_cyclic"', "kind = []", "programme.kind"),  # found by fuzzing
    ("key-of-other-kind", "n_cycles = 2", "n_cycles = 2\nn_groups = 3", "programme.n_groups"),
    ("bad-shape", "n_cycles = 2", 'n_cycles = 2\nshape = "square"', "programme.shape"),
    ("bad-integrator", "displacement_limit = 3.0", 'integrator = "rk4"', "solver.integrator"),
    ("bad-after-limit", "displacement_limit = 3.0", 'after_limit = "never"', "solver.after_limit"),
    (
        "negative-limit",
        "displacement_limit = 3.0",
        "displacement_limit = -3.0",
        "solver.displacement_limit",
    ),
    ("zero-iterations", "displacement_limit = 3.0", "max_iterations = 0", "solver.max_iterations"),
    ("table-missing", "[soil]", "[soil_x]", "soil_x"),
    (
        "mass-below-weight",
        "submerged_weight_kn = 10.52",
        "submerged_weight_kn = 10.52\nmass = 1.0",
        "mass",
    ),
    ("preset-and-pipe", "[pipe]", '[preset]\ntest = "Inclined 1"\n\n[pipe]', "preset"),
    ("malformed-toml", "period = 40.0", "period = = 40", None),
    ("duplicate-key", "period = 40.0", "period = 40.0\nperiod = 41.0", None),
    ("unclosed-table", "[solver]", "[solver", None),
    ("table-as-value", "[solver]\ndisplacement_limit = 3.0", "solver = 3", "solver"),
    ("array-of-tables", "[solver]", "[[solver]]", "solver"),
    (
        "points-per-cycle-low",
        "n_cycles = 2",
        "n_cycles = 2\npoints_per_cycle = 2",
        "programme.points_per_cycle",
    ),
    (
        "ca-negative",
        "submerged_weight_kn = 10.52",
        "submerged_weight_kn = 10.52\nadded_mass_coefficient = -1",
        "pipe.added_mass_coefficient",
    ),
    (
        "installation-negative",
        "n_cycles = 2",
        "n_cycles = 2\ninstallation_load_kn = -5",
        "programme.installation_load_kn",
    ),
    ("dt-max-zero", "displacement_limit = 3.0", "dt_max = 0.0", "solver.dt_max"),
    (
        "increment-tiny",
        "displacement_limit = 3.0",
        "max_displacement_increment = 1e-12",
        "solver.max_displacement_increment",
    ),
]


@pytest.mark.parametrize(
    ("old", "new", "field"), [c[1:] for c in SIMULATE_CASES], ids=[c[0] for c in SIMULATE_CASES]
)
def test_simulate_case_file(tmp_path, old, new, field):
    assert old in CASE
    case = tmp_path / "case.toml"
    case.write_text(CASE.replace(old, new, 1), encoding="utf-8")
    err = _check(["simulate", str(case), "--quiet"], field)
    if field is None:
        assert "case.toml" in err["message"]
    assert not (tmp_path / "case.nc").exists()  # nothing written


PRESET_CASES = [
    ("unknown-preset-key", 'test = "Inclined 1"\ngama_kn = 7.5', "preset.gama_kn"),
    ("preset-gamma-range", 'test = "Inclined 1"\ngamma_kn = 0.0075', "preset.gamma_kn"),
    ("preset-test-missing", 'parameters = "table2"', "preset.test"),
    ("preset-bad-parameters", 'test = "Inclined 1"\nparameters = "table9"', "preset.parameters"),
    ("preset-dt-negative", 'test = "Inclined 1"\ndt = -0.1', "preset.dt"),
    ("preset-dt-tiny", 'test = "Inclined 1"\ndt = 1e-9', "preset.dt"),  # would run for days
    ("preset-dt-huge", 'test = "Inclined 1"\ndt = 1e6', "preset.dt"),
    ("preset-unknown-test", 'test = "Inclined 9"', "test"),
]


@pytest.mark.parametrize(
    ("body", "field"), [c[1:] for c in PRESET_CASES], ids=[c[0] for c in PRESET_CASES]
)
def test_simulate_preset_file(tmp_path, body, field):
    case = tmp_path / "preset.toml"
    case.write_text(f"[preset]\n{body}\n", encoding="utf-8")
    _check(["simulate", str(case), "--quiet"], field)


CSV_CASES = [
    ("non-numeric", "time,H,V\n0,0,10\n1,x,10\n"),
    ("two-columns", "time,H\n0,0\n1,1\n"),
    ("one-row", "time,H,V\n0,0,10\n"),
    ("empty", ""),
    ("time-decreasing", "time,H,V\n0,0,10\n2,1,10\n1,0,10\n"),
    ("nan", "time,H,V\n0,0,10\n1,nan,10\n"),
    ("ragged", "time,H,V\n0,0,10\n1,1\n"),
]


@pytest.mark.parametrize("text", [c[1] for c in CSV_CASES], ids=[c[0] for c in CSV_CASES])
def test_programme_csv_file(tmp_path, text):
    (tmp_path / "prog.csv").write_text(text, encoding="utf-8")
    head = CASE.split("[programme]")[0]
    case = tmp_path / "case.toml"
    case.write_text(head + '[programme]\nkind = "csv"\nfile = "prog.csv"\n', encoding="utf-8")
    _check(["simulate", str(case), "--quiet"], None)


def test_programme_csv_missing_and_not_utf8(tmp_path):
    head = CASE.split("[programme]")[0]
    case = tmp_path / "case.toml"
    case.write_text(head + '[programme]\nkind = "csv"\nfile = "nope.csv"\n', encoding="utf-8")
    _check(["simulate", str(case), "--quiet"], "programme.file")
    case.write_bytes(b"\xff\xfe[pipe]\n")
    _check(["simulate", str(case), "--quiet"], "path", message="UTF-8")


# --------------------------------------------------------------------------------------------
# sweep grid files (TOML)
# --------------------------------------------------------------------------------------------
GRID = """\
[sweep]
function = "centrifuge_response"
seed = 1

[grid]
A = [0.2, 0.3]

[fixed]
test = "Inclined 1"
"""

SWEEP_CASES = [
    ("misspelled-fixed", "[fixed]", "[fixd]", "fixd"),
    ("code-from-data", '"centrifuge_response"', '"subprocess:getoutput"', "sweep.function"),
    ("module-path", '"centrifuge_response"', '"os:system"', "sweep.function"),
    ("misspelled-function", '"centrifuge_response"', '"centrifuge_respons"', "sweep.function"),
    ("function-number", '"centrifuge_response"', "3", "sweep.function"),
    ("function-missing", 'function = "centrifuge_response"\n', "", "sweep.function"),
    ("unknown-sweep-key", "seed = 1", "sed = 1", "sweep.sed"),
    ("seed-negative", "seed = 1", "seed = -1", "sweep.seed"),
    ("seed-fraction", "seed = 1", "seed = 1.5", "sweep.seed"),
    ("batch-zero", "seed = 1", "batch_size = 0", "sweep.batch_size"),
    ("grid-empty", "A = [0.2, 0.3]", "", "grid"),
    ("axis-empty", "A = [0.2, 0.3]", "A = []", "grid.A"),
    ("axis-string", "A = [0.2, 0.3]", 'A = "0.2"', "grid.A"),
    ("axis-nested", "A = [0.2, 0.3]", "A = [[0.2, 0.3]]", "grid.A[0]"),
    ("axis-nan", "A = [0.2, 0.3]", "A = [0.2, nan]", "grid.A[1]"),
    ("linspace-no-num", "A = [0.2, 0.3]", "A = { start = 0.1, stop = 0.3 }", "grid.A.num"),
    (
        "linspace-num-fraction",
        "A = [0.2, 0.3]",
        "A = { start = 0.1, stop = 0.3, num = 2.5 }",
        "grid.A.num",
    ),
    ("linspace-typo", "A = [0.2, 0.3]", "A = { start = 0.1, stp = 0.3, num = 2 }", "grid.A.stp"),
    ("values-empty", "A = [0.2, 0.3]", "A = { values = [] }", "grid.A.values"),
    (
        "grid-too-large",
        "A = [0.2, 0.3]",
        "A = { start = 0.1, stop = 0.3, num = 100000 }\n"
        "B = { start = 0.1, stop = 0.3, num = 100000 }",
        "grid",
    ),
    ("unknown-argument", "A = [0.2, 0.3]", "Z = [0.2, 0.3]", "grid.Z"),
    ("misspelled-fixed-key", 'test = "Inclined 1"', 'tset = "Inclined 1"', "fixed.tset"),
    ("fixed-table", 'test = "Inclined 1"', "test = { a = 1 }", "fixed.test"),
    ("misfit-without-record", '"centrifuge_response"', '"misfit"', "fixed.record"),
    ("misfit-record-missing", '"centrifuge_response"', '"misfit"\n[x]', "x"),
    ("malformed", "seed = 1", "seed = ", None),
]


@pytest.mark.parametrize(
    ("old", "new", "field"), [c[1:] for c in SWEEP_CASES], ids=[c[0] for c in SWEEP_CASES]
)
def test_sweep_grid_file(tmp_path, old, new, field):
    assert old in GRID
    grid = tmp_path / "grid.toml"
    grid.write_text(GRID.replace(old, new, 1), encoding="utf-8")
    out = tmp_path / "out.nc"
    _check(["sweep", str(grid), "-o", str(out), "--workers", "0", "--no-progress"], field)
    assert not out.exists()


def test_sweep_misfit_record_file_missing(tmp_path):
    grid = tmp_path / "grid.toml"
    grid.write_text('[sweep]\nfunction = "misfit"\n[grid]\nA = [0.2]\n[fixed]\nrecord = "no.csv"\n')
    _check(["sweep", str(grid), "-o", str(tmp_path / "o.nc"), "--workers", "0"], "fixed.record")


# --------------------------------------------------------------------------------------------
# DEM config files (JSON)
# --------------------------------------------------------------------------------------------
def _cfg(**edits):
    d = json.loads(SD_REDUCED.to_json())
    for path, value in edits.items():
        *parents, key = path.split("__")
        node = d
        for p in parents:
            node = node[p]
        if value is _DELETE:
            del node[key]
        else:
            node[key] = value
    return json.dumps(d, allow_nan=True)


_DELETE = object()

DEM_JSON_CASES = [
    ("unknown-top-key", _cfg(sed=1), "sed"),
    ("misspelled-nested", _cfg(loading__pipe_velocty=0.1), "loading.pipe_velocty"),
    ("seed-fraction", _cfg(seed=1.5), "seed"),
    ("seed-string", _cfg(seed="1"), "seed"),
    ("seed-negative", _cfg(seed=-1), "seed"),
    ("name-number", _cfg(name=5), "name"),
    ("width-negative", _cfg(geometry__width=-1.0), "width"),
    ("d50-nan", _cfg(psd__d50=math.nan), "psd.d50"),
    ("d50-inf", _cfg(psd__d50=math.inf), "psd.d50"),
    ("geometry-missing", _cfg(geometry=_DELETE), "geometry"),
    ("section-not-table", _cfg(loading=3), "loading"),
    ("velocity-zero", _cfg(loading__pipe_velocity=0.0), "pipe_velocity"),
    ("friction-negative", _cfg(contacts__soil__mu=-1.0), "mu"),
    ("layers-fraction", _cfg(preparation__n_layers=2.5), "preparation.n_layers"),
    ("top-level-list", "[1, 2]", None),
    ("truncated", SD_REDUCED.to_json()[:60], None),
    ("empty", "", None),
]


@pytest.mark.parametrize(
    ("text", "field"), [c[1:] for c in DEM_JSON_CASES], ids=[c[0] for c in DEM_JSON_CASES]
)
def test_dem_config_file(tmp_path, text, field):
    cfg = tmp_path / "cfg.json"
    cfg.write_text(text, encoding="utf-8")
    out = tmp_path / "s.nc"
    _check(["dem", "prepare", "--config", str(cfg), "--out", str(out), "--no-progress"], field)
    assert not out.exists()


@pytest.mark.parametrize("command", ["plot", "summarize"])
@pytest.mark.parametrize("content", ["garbage", "record-file"], ids=["garbage", "not-a-run"])
def test_dem_run_files(tmp_path, command, content):
    f = tmp_path / "run.nc"
    if content == "garbage":
        f.write_bytes(b"\x89HDF\r\n\x1a\n" + b"0" * 100)
    else:
        import xarray as xr

        from onbottom.results import save_dataset

        save_dataset(xr.Dataset({"x": ("i", [1.0])}), f)
    _check(["dem", command, str(f), "--outdir", str(tmp_path / "o")], "results")


# --------------------------------------------------------------------------------------------
# calibration records (CSV, NetCDF)
# --------------------------------------------------------------------------------------------
RECORD_CASES = [
    ("empty", ".csv", b""),
    ("garbage", ".csv", b"garbage"),
    ("non-numeric", ".csv", b"time,u,w\ns,m,m\n0,0,0\n1,x,0\n"),
    ("time-repeats", ".csv", b"time,u,w\ns,m,m\n0,0,0\n0,0,0\n"),
    ("bad-header-number", ".csv", b"# diameter: abc m\ntime,u,w\ns,m,m\n0,0,0\n1,0,0\n"),
    ("unknown-unit", ".csv", b"time,u,w\ns,furlong,m\n0,0,0\n1,0,0\n"),
    ("column-missing", ".csv", b"time,u\ns,m\n0,0\n1,0\n"),
    ("nan", ".csv", b"time,u,w\ns,m,m\n0,0,0\n1,nan,0\n"),
    ("ragged", ".csv", b"time,u,w\ns,m,m\n0,0,0\n1,0\n"),
    ("not-utf8", ".csv", b"\xff\xfe\x00garbage"),
    ("netcdf-garbage", ".nc", b"\x89HDF\r\n\x1a\n" + b"1" * 64),
    ("wrong-suffix", ".txt", b"time,u,w\ns,m,m\n0,0,0\n1,0,0\n"),
    ("units-line-missing", ".csv", b"time,u,w\n0,0,0\n1,0,0\n"),
    ("negative-diameter", ".csv", b"# diameter: -1 m\ntime,u,w\ns,m,m\n0,0,0\n1,0,0\n"),
    ("inf", ".csv", b"time,u,w\ns,m,m\n0,0,0\n1,inf,0\n"),
]


@pytest.mark.parametrize(
    ("suffix", "data"), [c[1:] for c in RECORD_CASES], ids=[c[0] for c in RECORD_CASES]
)
def test_calibration_record_file(tmp_path, suffix, data):
    rec = tmp_path / f"rec{suffix}"
    rec.write_bytes(data)
    _check(["calibrate", str(rec), "--maxiter", "1"], "records")


# --------------------------------------------------------------------------------------------
# options of every command
# --------------------------------------------------------------------------------------------
BACKBONE = ["backbone", "--diameter", "1.0", "--weight-kn", "10.5", "--gamma-kn", "7.5"]
SAND = ["penetration", "--diameter", "0.5", "--gamma-kn", "16.7", "--phi-deg", "35"]
CLAY = ["penetration", "--soil", "clay", "--diameter", "0.5", "--gamma-kn", "6"]

OPTION_CASES = [
    # (id, arguments, field)
    ("bb-diameter-zero", [*BACKBONE, "--diameter", "0"], "--diameter"),
    ("bb-diameter-negative", [*BACKBONE, "--diameter", "-1"], "--diameter"),
    ("bb-diameter-nan", [*BACKBONE, "--diameter", "nan"], "--diameter"),
    ("bb-diameter-inf", [*BACKBONE, "--diameter", "inf"], "--diameter"),
    ("bb-diameter-text", [*BACKBONE, "--diameter", "one"], "--diameter"),
    ("bb-diameter-mm", [*BACKBONE, "--diameter", "500"], "outer_diameter"),
    (
        "bb-weight-zero",
        ["backbone", "--diameter", "1", "--weight-kn", "0", "--gamma-kn", "7.5"],
        "--weight-kn",
    ),
    (
        "bb-gamma-MN",
        ["backbone", "--diameter", "1", "--weight-kn", "10", "--gamma-kn", "0.0075"],
        "--gamma-kn",
    ),
    (
        "bb-gamma-N",
        ["backbone", "--diameter", "1", "--weight-kn", "10", "--gamma-kn", "7500"],
        "--gamma-kn",
    ),
    ("bb-mu-3", [*BACKBONE, "--mu", "3"], "--mu"),
    ("bb-A-negative", [*BACKBONE, "--A", "-0.1"], "--A"),
    ("bb-z2-range", [*BACKBONE, "--z2-over-d", "2"], "--z2-over-d"),
    ("bb-cycles-memory", [*BACKBONE, "--cycles", "1e7"], "--cycles"),
    ("bb-cycles-zero", [*BACKBONE, "--cycles", "0"], "--cycles"),
    ("bb-amplitude-negative", [*BACKBONE, "--cycles", "1", "--amplitude", "-1"], "--amplitude"),
    ("bb-unknown-option", [*BACKBONE, "--diamter", "1"], "--diamter"),
    ("bb-bad-model", [*BACKBONE, "--model", "clay"], "--model"),
    (
        "pen-diameter-mm",
        ["penetration", "--diameter", "500", "--gamma-kn", "10", "--phi-deg", "35"],
        "diameter",
    ),
    ("pen-diameter-negative", [*SAND[:2], "-0.5", *SAND[3:]], "--diameter"),
    (
        "pen-gamma-low",
        ["penetration", "--diameter", "0.5", "--gamma-kn", "0.5", "--phi-deg", "35"],
        "--gamma-kn",
    ),
    ("pen-phi-80", [*SAND[:-1], "80"], "--phi-deg"),
    ("pen-phi-missing", SAND[:-2], "--phi-deg"),
    ("pen-su-missing", CLAY, "--su-kpa"),
    ("pen-su-negative", [*CLAY, "--su-kpa", "-1"], "--su-kpa"),
    ("pen-roughness", [*CLAY, "--su-kpa", "2", "--roughness", "2"], "--roughness"),
    ("pen-levels-text", [*SAND, "--at", "a,b"], "--at"),
    ("pen-levels-range", [*SAND, "--at", "2"], "--at"),
    ("pen-ei-alone", [*SAND, "--ei", "1e8"], "--ei"),
    ("pen-load-zero", [*SAND, "--load-kn", "0"], "--load-kn"),
    ("pen-load-too-large", [*SAND, "--load-kn", "1000"], "--load-kn"),
    ("cal-popsize-zero", ["calibrate", "R.csv", "--popsize", "0"], "--popsize"),
    ("cal-maxiter-negative", ["calibrate", "R.csv", "--maxiter", "-1"], "--maxiter"),
    ("cal-maxiter-fraction", ["calibrate", "R.csv", "--maxiter", "2.5"], "--maxiter"),
    ("cal-workers-negative", ["calibrate", "R.csv", "--workers", "-1"], "--workers"),
    ("cal-seed-negative", ["calibrate", "R.csv", "--seed", "-1"], "--seed"),
    ("cal-gamma-kN", ["calibrate", "R.csv", "--gamma", "7.5"], "--gamma"),
    ("cal-gamma-nan", ["calibrate", "R.csv", "--gamma", "nan"], "--gamma"),
    ("cal-vary-empty", ["calibrate", "R.csv", "--vary", ","], "--vary"),
    ("cal-vary-unknown", ["calibrate", "R.csv", "--vary", "A,Z"], "--vary"),
    ("cal-bounds-reversed", ["calibrate", "R.csv", "--bounds", "A=0.5:0.1"], "--bounds"),
    ("cal-bounds-text", ["calibrate", "R.csv", "--bounds", "A=x:1"], "--bounds"),
    ("cal-bounds-form", ["calibrate", "R.csv", "--bounds", "A=0.5"], "--bounds"),
    ("cal-start-nan", ["calibrate", "R.csv", "--start", "A=nan"], "--start"),
    ("cal-start-unknown", ["calibrate", "R.csv", "--start", "Q=1"], "--start"),
    ("cal-weights-unknown", ["calibrate", "R.csv", "--weights", "foo=1"], "--weights"),
    ("cal-method", ["calibrate", "R.csv", "--method", "magic"], "--method"),
    ("sweep-workers-negative", ["sweep", "G", "-o", "x.nc", "--workers", "-1"], "--workers"),
    ("dem-seed-negative", ["dem", "prepare", "--seed", "-1", "--out", "x.nc"], "--seed"),
    ("dem-seed-fraction", ["dem", "prepare", "--seed", "1.5", "--out", "x.nc"], "--seed"),
    ("dem-preset", ["dem", "prepare", "--preset", "XX", "--out", "x.nc"], "--preset"),
    (
        "dem-threads-zero",
        ["dem", "penetrate", "--sample", "s.nc", "--out", "r.nc", "--threads", "0"],
        "--threads",
    ),
    (
        "dem-checkpoint-every-zero",
        ["dem", "penetrate", "--sample", "s.nc", "--out", "r.nc", "--checkpoint-every", "0"],
        "--checkpoint-every",
    ),
    (
        "dem-max-steps-negative",
        ["dem", "penetrate", "--sample", "s.nc", "--out", "r.nc", "--max-steps", "-1"],
        "--max-steps",
    ),
    (
        "dem-event-drop-fraction-one",
        ["dem", "penetrate", "--sample", "s.nc", "--out", "r.nc", "--event-drop-fraction", "1"],
        "--event-drop-fraction",
    ),
    (
        "dem-event-drop-fraction-nan",
        ["dem", "penetrate", "--sample", "s.nc", "--out", "r.nc", "--event-drop-fraction", "nan"],
        "--event-drop-fraction",
    ),
    (
        "dem-max-event-snapshots-one",
        ["dem", "penetrate", "--sample", "s.nc", "--out", "r.nc", "--max-event-snapshots", "1"],
        "--max-event-snapshots",
    ),
    (
        "dem-max-event-snapshots-fraction",
        ["dem", "penetrate", "--sample", "s.nc", "--out", "r.nc", "--max-event-snapshots", "8.5"],
        "--max-event-snapshots",
    ),
    ("dem-plot-gamma", ["dem", "plot", "R", "--gamma-kn", "0.1"], "--gamma-kn"),
    (
        "dem-plot-band-deg",
        ["dem", "plot", "R", "--band-threshold-deg", "200"],
        "--band-threshold-deg",
    ),
    ("dem-plot-phi", ["dem", "plot", "R", "--phi-lower-deg", "5"], "--phi-lower-deg"),
    ("dem-summarize-step", ["dem", "summarize", "R", "--step", "0"], "--step"),
    ("dem-summarize-drop", ["dem", "summarize", "R", "--drop-fraction", "1"], "--drop-fraction"),
    (
        "dem-summarize-band-deg",
        ["dem", "summarize", "R", "--band-threshold-deg", "0"],
        "--band-threshold-deg",
    ),
    ("reproduce-gamma", ["reproduce", "--gamma-kn", "0", "--out", "o"], "--gamma-kn"),
    ("sim-missing-case", ["simulate", "nope.toml"], "case"),
    ("sweep-missing-grid", ["sweep", "nope.toml", "-o", "x.nc"], "grid_file"),
    ("sweep-output-missing", ["sweep", "G"], "--output"),
    ("cal-records-missing", ["calibrate"], "records"),
    ("dem-out-missing", ["dem", "prepare"], "--out"),
    ("lammps-np", ["dem-lammps", "--np", "0"], "--np"),
]


@pytest.mark.parametrize(
    ("args", "field"), [c[1:] for c in OPTION_CASES], ids=[c[0] for c in OPTION_CASES]
)
def test_command_option(tmp_path, monkeypatch, args, field):
    monkeypatch.chdir(tmp_path)
    for name in ("R", "R.csv"):
        (tmp_path / name).write_text("time,u,w\ns,m,m\n0,0,0\n1,0,0\n")
    (tmp_path / "G").write_text(GRID)
    _check(args, field)


def test_output_paths_that_are_folders_are_named(tmp_path):
    case = tmp_path / "case.toml"
    case.write_text(CASE)
    (tmp_path / "d").mkdir()
    _check(["simulate", str(case), "-o", str(tmp_path / "d"), "--quiet"], "--output")
    _check([*BACKBONE, "--plot", str(tmp_path / "d")], "--plot")


# --------------------------------------------------------------------------------------------
# the on-bottom stability case files (stability, loads, storm, curves share one layout)
# --------------------------------------------------------------------------------------------
STABILITY_FILES = [
    (
        "misspelled-table",
        "[pipe]\nouter_diameter = 0.4\nsubmerged_weight = 1500.0\n[seabd]\n",
        "seabd",
    ),
    (
        "diameter-in-mm",
        "[pipe]\nouter_diameter = 400.0\nsubmerged_weight = 1500.0\n",
        "pipe.outer_diameter",
    ),
    (
        "string-number",
        '[pipe]\nouter_diameter = "0.4"\nsubmerged_weight = 1500.0\n',
        "pipe.outer_diameter",
    ),
    ("malformed", "garbage = = 1\n", None),
]


@pytest.mark.parametrize("command", ["stability", "loads", "storm", "curves"])
@pytest.mark.parametrize(
    ("text", "field"), [c[1:] for c in STABILITY_FILES], ids=[c[0] for c in STABILITY_FILES]
)
def test_stability_case_files(tmp_path, command, text, field):
    case = tmp_path / "case.toml"
    case.write_text(text, encoding="utf-8")
    if command == "curves" and field and field.startswith("pipe."):
        field = "curves"  # `curves` names its missing [curves] table first
    _check([command, str(case)], field)


# --------------------------------------------------------------------------------------------
# plausibility of the Python inputs
# --------------------------------------------------------------------------------------------
def _pipe(d=1.0, w=1.0e4):
    from onbottom.inputs import Pipe

    return Pipe(outer_diameter=d, submerged_weight=w)


def _sand(g=8e3, mu=0.6):
    from onbottom.inputs import Sand

    return Sand(submerged_unit_weight=g, friction_coefficient=mu)


def _clay(g=6e3):
    from onbottom.inputs import Clay

    return Clay(undrained_shear_strength=5e3, submerged_unit_weight=g, unit_weight=2.0e4)


def _drained(d=0.5, g=9e3):
    from onbottom.soil.penetration_sand import DrainedPenetration

    return DrainedPenetration(diameter=d, unit_weight=g, friction_angle_deg=35.0)


def _undrained(d=0.5, su=5e3):
    from onbottom.soil.penetration_clay import UndrainedModel2

    return UndrainedModel2(diameter=d, su_mudline=su, unit_weight=6e3)


PLAUSIBILITY_ERRORS = [
    ("pipe-500m", lambda: _pipe(d=500.0), "Pipe.outer_diameter"),
    ("pipe-1mm", lambda: _pipe(d=0.001), "Pipe.outer_diameter"),
    ("pipe-weight", lambda: _pipe(w=5e7), "Pipe.submerged_weight"),
    ("sand-gamma-low", lambda: _sand(g=7.5), "Sand.submerged_unit_weight"),
    ("sand-gamma-high", lambda: _sand(g=3e4), "Sand.submerged_unit_weight"),
    ("sand-mu", lambda: _sand(mu=2.5), "Sand.friction_coefficient"),
    ("clay-gamma", lambda: _clay(g=100.0), "Clay.submerged_unit_weight"),
    ("f114-diameter", lambda: _drained(d=500.0), "DrainedPenetration.diameter"),
    ("f114-gamma", lambda: _drained(g=9.0), "DrainedPenetration.unit_weight"),
    ("f114-clay-diameter", lambda: _undrained(d=20.0), "UndrainedModel2.diameter"),
    ("f114-clay-su", lambda: _undrained(su=5e9), "UndrainedModel2.su_mudline"),
]


@pytest.mark.parametrize(
    ("make", "field"),
    [c[1:] for c in PLAUSIBILITY_ERRORS],
    ids=[c[0] for c in PLAUSIBILITY_ERRORS],
)
def test_implausible_inputs_are_errors(make, field):
    with pytest.raises(InputError) as info:
        make()
    assert str(info.value).startswith(field) and "np.float" not in str(info.value)


PLAUSIBILITY_WARNINGS = [
    ("pipe-3m", lambda: _pipe(d=3.0), "Pipe.outer_diameter"),
    ("sand-gamma-2kN", lambda: _sand(g=2.0e3), "Sand.submerged_unit_weight"),
    ("sand-mu-1.5", lambda: _sand(mu=1.5), "Sand.friction_coefficient"),
    ("f114-gamma-20kN", lambda: _drained(g=2.0e4), "DrainedPenetration.unit_weight"),
]


@pytest.mark.parametrize(
    ("make", "field"),
    [c[1:] for c in PLAUSIBILITY_WARNINGS],
    ids=[c[0] for c in PLAUSIBILITY_WARNINGS],
)
def test_unusual_inputs_warn(make, field):
    with pytest.warns(OutOfRangeWarning, match=field):
        make()


def test_usual_inputs_do_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error", OutOfRangeWarning)
        _pipe(), _sand(), _clay(), _drained(), _undrained()


def test_number_of_cases_is_reported():
    """The suite's size (issue #10 asks for it): keep this count in the closing note."""
    n = (
        len(SIMULATE_CASES)
        + len(PRESET_CASES)
        + len(CSV_CASES)
        + 2
        + len(SWEEP_CASES)
        + 1
        + len(DEM_JSON_CASES)
        + 4
        + len(RECORD_CASES)
        + len(OPTION_CASES)
        + 2
        + len(PLAUSIBILITY_ERRORS)
        + len(PLAUSIBILITY_WARNINGS)
        + 4 * len(STABILITY_FILES)
    )
    assert n >= 200


# --------------------------------------------------------------------------------------------
# results outside their model's validity say so (status, message, JSON) and exit 3
# --------------------------------------------------------------------------------------------
def _result(args: list[str]) -> dict:
    r = CliRunner().invoke(cli, [*args, "--json"])
    assert r.exit_code == 3, (r.exit_code, r.output)
    return json.loads(r.stdout)


def test_backbone_penetration_beyond_half_diameter():
    out = _result(
        ["backbone", "--diameter", "1", "--weight-kn", "50", "--gamma-kn", "1.0", "--cycles", "2"]
    )
    assert out["success"] is False and "exceeds D/2" in out["message"]


def test_f114_embedment_outside_the_model_range():
    out = _result([*CLAY[:-1], "5", "--model", "2", "--su-kpa", "1", "--load-kn", "4"])
    emb = out["embedment"]
    assert emb["z_over_D"] > 0.5 and emb["success"] is False
    assert emb["status"] == Status.OUTSIDE_VALIDITY == -3 and "converged" not in emb["message"]


def test_section_lift_off(tmp_path):
    head = CASE.split("[soil]")[0]
    case = tmp_path / "lift.toml"
    case.write_text(
        head + '[soil]\nmodel = "coulomb"\nfriction_coefficient = 0.5\n'
        '[programme]\nkind = "arrays"\ntime = [0.0, 10.0, 20.0]\n'
        "horizontal_load_kn = [0.0, 1.0, 0.0]\nvertical_load_kn = [10.0, -1.0, 10.0]\n"
    )
    out = _result(["simulate", str(case), "--quiet"])
    assert out["success"] is False and out["status"] == -3 and "lift-off" in out["message"]


@pytest.mark.parametrize(
    ("model", "keys"),
    [
        ("sand", {"submerged_unit_weight": 1.0e4, "unit_weight": 2.0e4}),
        ("calcareous", {"submerged_unit_weight": 1.0e4, "unit_weight": 2.0e4}),
        ("clay", {"undrained_shear_strength": 5e3, "submerged_unit_weight": 6e3,
                  "unit_weight": 1.6e4, "d50": 2e-4}),
    ],
)  # fmt: skip
def test_a_seabed_key_the_model_does_not_read_is_refused(model, keys):
    """The clay total unit weight on a sand (a key name inside another key's name) is refused,
    naming the key, like d50 on clay."""
    from onbottom.cases.tables import SeabedTable

    with pytest.raises(ValueError, match="unit_weight does not apply|d50 does not apply"):
        SeabedTable(model=model, **keys)
