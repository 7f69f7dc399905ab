"""Issue #31 (items 1, 3, 5): the reported bad-input cases of the 162-case campaign, each a test.

Every case below gave a silent wrong result (exit 0 with a verdict), a traceback or a write
outside the output folder before; now each gives a named error (exit status 1, a JSON error
object naming the key) or a named warning. No storm is run: the errors come before the run.
"""

from __future__ import annotations

import json
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from case_helpers import edit as _edit
from case_helpers import run_json as _run
from case_helpers import write_file as _write
from onbottom.errors import (
    BudgetError,
    InputError,
    OutOfRangeWarning,
    PhysicalConsistencyWarning,
    ShallowWaterWarning,
    UnitSlipWarning,
)
from onbottom.inputs import consistency

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"

# the reported case: D = 0.512 m (simple form) in 0.4 m of water, a small sea to stay below
# breaking (H_s <= 0.78 d) so that only the depth is wrong
SHALLOW = """
[pipe]
outer_diameter = 0.512
submerged_weight = 1500.0
[seabed]
model = "sand"
submerged_unit_weight = 10.0e3
[environment]
water_depth = 0.4
[waves]
hs = 0.2
tp = 4.0
[current]
velocity = 0.2
reference_height = 0.3
z0 = 5.2e-6
[storm]
build_up_hours = 0.0
peak_hours = 0.02
"""


def _error(args: list[str], capsys, field: str, code: int = 1) -> str:
    got, out = _run(args, capsys)
    assert got == code, out
    assert "error" in out, out
    assert out["error"]["field"] == field, out
    assert out["schema_version"] >= 1
    return out["error"]["message"]


# ---- 1. water depth against D -----------------------------------------------------------
@pytest.mark.parametrize("command", ["stability", "loads", "storm"])
def test_depth_below_the_pipe_is_refused_by_every_command(command, tmp_path, capsys):
    case = _write(tmp_path, SHALLOW)
    msg = _error([command, str(case)], capsys, "environment.water_depth")
    assert "0.4" in msg and "0.512" in msg


def test_depth_below_the_pipe_is_refused_by_the_pipeline(tmp_path, capsys):
    text = (EXAMPLES / "pipeline_case.toml").read_text(encoding="utf-8")
    text = _edit(text, "water_depth = 13.0", "water_depth = 0.25")  # D = 0.2701 m
    text = _edit(text, "hs = 5.0 ", "hs = 0.1 ")
    text = _edit(text, "tp = 11.0 ", "tp = 4.0 ")
    case = _write(tmp_path, text)
    msg = _error(["storm", str(case)], capsys, "environment.water_depth")
    assert "deeper than the pipe" in msg


def test_depth_below_the_pipe_is_refused_by_the_api():
    from onbottom.checks.absolute import absolute_lateral_stability
    from onbottom.dynamics.storm_section import simulate_storm_section
    from onbottom.inputs.pipe import Pipe
    from onbottom.inputs.soil import Sand
    from onbottom.inputs.storm import SeaState, Storm
    from onbottom.soil.verley_sotberg import VerleySotberg

    pipe = Pipe(outer_diameter=0.512, submerged_weight=1500.0)
    sand = Sand(submerged_unit_weight=10e3)
    with pytest.raises(InputError, match=r"depth = 0\.4 m is invalid") as exc:
        absolute_lateral_stability(pipe, sand, hs=0.2, tp=4.0, depth=0.4)
    assert exc.value.field == "depth"
    storm = Storm.standard(SeaState(hs=0.2, tp=4.0), build_up_hours=0.0, peak_hours=0.02)
    soil = VerleySotberg.silica(pipe, sand)
    with pytest.raises(InputError, match=r"depth = 0\.4 m is invalid"):
        simulate_storm_section(pipe, soil, storm, depth=0.4)


def test_shallow_water_and_near_breaking_warn():
    found = consistency.depth_and_diameter(1.0, 0.512)
    assert [f.category for f in found] == [ShallowWaterWarning] and not found[0].error
    assert consistency.depth_and_diameter(10.0, 0.512) == []
    # H_s/d in (0.5, 0.78]: near breaking (warning); above 0.78 (McCowan): error
    near = consistency.sea_state(6.0, 14.0, 10.0)
    assert [f.error for f in near] == [False] and "near breaking" in near[0].message
    assert consistency.sea_state(8.0, 14.0, 10.0)[0].error


def test_shallow_water_warns_in_the_case_file(tmp_path, capsys):
    case = _write(tmp_path, _edit(SHALLOW, "water_depth = 0.4", "water_depth = 1.2"))
    code, out = _run(["stability", str(case)], capsys)
    assert code == 0
    assert any("environment.water_depth = 1.2 m is shallow" in w for w in out["warnings"])


def test_shallow_water_warns_in_the_api():
    from onbottom.checks.absolute import absolute_lateral_stability
    from onbottom.inputs.pipe import Pipe
    from onbottom.inputs.soil import Sand

    pipe = Pipe(outer_diameter=0.512, submerged_weight=1500.0)
    with pytest.warns(ShallowWaterWarning, match="depth = 1.2 m is shallow"):
        absolute_lateral_stability(
            pipe, Sand(submerged_unit_weight=10e3), hs=0.2, tp=4.0, depth=1.2
        )


# ---- 1. stop limit, free nodes, materials, angles, durations, currents ------------------
SECTION = (
    (EXAMPLES / "storm_case.toml")
    .read_text(encoding="utf-8")
    .replace("build_up_hours = 0.5", "build_up_hours = 0.0")
    .replace("peak_hours = 3.0", "peak_hours = 0.02")
)


def test_stop_limit_below_the_largest_criterion_is_refused(tmp_path, capsys):
    case = _write(
        tmp_path,
        _edit(SECTION, "max_displacement_over_d = 10.0", "max_displacement_over_d = 1e-6"),
    )
    msg = _error(["storm", str(case)], capsys, "solver.max_displacement_over_d")
    assert "10 D" in msg


def test_one_element_fixed_fixed_pipeline_is_refused(tmp_path, capsys):
    text = (EXAMPLES / "pipeline_case.toml").read_text(encoding="utf-8")
    text = _edit(text, "length = 200.0 ", "length = 4.0 ")
    case = _write(tmp_path, text)
    msg = _error(["storm", str(case)], capsys, "pipeline.element_length")
    assert "0 free node(s)" in msg and "at least 3" in msg


def test_youngs_modulus_in_mpa_is_refused(tmp_path, capsys):
    text = (EXAMPLES / "stability_case.toml").read_text(encoding="utf-8")
    text = _edit(
        text, "steel_density = 7850.0 ", "youngs_modulus = 207000\nsteel_density = 7850.0 "
    )
    case = _write(tmp_path, text)
    msg = _error(["stability", str(case)], capsys, "pipe.youngs_modulus")
    assert "looks like MPa" in msg
    pipe_case = _write(
        tmp_path,
        _edit(
            (EXAMPLES / "pipeline_case.toml").read_text(encoding="utf-8"),
            "wall_thickness = 0.0127 ",
            "youngs_modulus = 207000\nwall_thickness = 0.0127 ",
        ),
        "pipe.toml",
    )
    _error(["storm", str(pipe_case)], capsys, "pipe.youngs_modulus")
    from onbottom.inputs.pipe_buildup import PipeBuildUp

    with pytest.raises(InputError, match="youngs_modulus = 207000"):
        PipeBuildUp(steel_outer_diameter=0.2191, wall_thickness=0.0127, youngs_modulus=207000)


def test_layer_lighter_than_water_warns_whatever_its_name(tmp_path, capsys):
    text = (EXAMPLES / "stability_case.toml").read_text(encoding="utf-8")
    case = _write(tmp_path, _edit(text, "density = 1335.0 ", "density = 900.0 "))
    code, out = _run(["stability", str(case)], capsys)
    assert code in (0, 3)
    assert any("pipe.layers[0].density = 900" in w and "lighter" in w for w in out["warnings"])


def test_radian_looking_angle_warns(tmp_path, capsys):
    text = (EXAMPLES / "stability_case.toml").read_text(encoding="utf-8")
    case = _write(tmp_path, _edit(text, "direction_deg = 90.0", "direction_deg = 1.5708"))
    code, out = _run(["stability", str(case)], capsys)
    assert code in (0, 3)
    assert any(
        "waves.direction_deg = 1.5708 looks like an angle in radians" in w for w in out["warnings"]
    )
    f = consistency.angle_deg(1.5708, field="direction_deg")
    assert f[0].category is UnitSlipWarning
    assert consistency.angle_deg(90.0, field="a") == consistency.angle_deg(3.0, field="a") == []
    assert consistency.angle_deg(30.0, field="a") == consistency.angle_deg(1.2, field="a") == []


def test_storm_peak_shorter_than_a_few_periods_is_refused(tmp_path, capsys):
    case = _write(tmp_path, _edit(SECTION, "peak_hours = 0.02", "peak_hours = 1e-9"))
    msg = _error(["storm", str(case)], capsys, "storm.peak_hours")
    assert "3 peak periods" in msg


def test_peak_duration_message_names_hours():
    (f,) = consistency.peak_duration(3.6, 20.0, field="storm.peak_hours")
    assert f.error and f.message.startswith("storm.peak_hours = 0.001 h is invalid")
    assert "T_p = 20 s" in f.message and ">= 0.0167 h" in f.message


def test_time_step_rule_by_hand():
    """One rule for the storm and curves cases: T_p = 10 s refuses a step above 2.5 s and
    warns above 0.5 s (docs/theory/storm_section.md)."""
    rule = consistency.time_step
    assert rule(0.5, 10.0, field="dt", source="waves.tp") == []
    (w,) = rule(2.5, 10.0, field="dt", source="waves.tp")
    assert not w.error and w.category is OutOfRangeWarning and w.field == "dt"
    assert w.message == (
        "dt = 2.5 s is coarse for T_p = 10 s (waves.tp): above T_p/20 = 0.5 s the result"
        " depends on the step; use <= T_p/20"
    )
    (e,) = rule(2.51, 10.0, field="dt", source="waves.tp")
    assert e.error and "dt = 2.51 s is invalid with T_p = 10 s (waves.tp)" in e.message
    assert "<= T_p/4 = 2.5 s" in e.message
    assert consistency.TIME_STEP_MAX_FRACTION == 0.25
    assert consistency.TIME_STEP_WARN_FRACTION == 0.05


def test_fast_current_warns(tmp_path, capsys):
    text = (EXAMPLES / "stability_case.toml").read_text(encoding="utf-8")
    case = _write(tmp_path, _edit(text, "velocity = 0.35 ", "velocity = 9.5 "))
    _, out = _run(["stability", str(case)], capsys)
    assert any("current.velocity = 9.5 m/s is unusual" in w for w in out["warnings"])


def test_report_only_empty_is_a_named_error(tmp_path, capsys):
    msg = _error(["report", "--only", "", "--out", str(tmp_path / "r")], capsys, "only")
    assert "section name is required" in msg
    assert not (tmp_path / "r").exists()


def test_backbone_diameter_is_required(capsys):
    code, out = _run(["backbone", "--weight-kn", "10.52", "--gamma-kn", "7.5"], capsys)
    assert code == 2 and out["error"]["field"] == "--diameter"


@pytest.mark.parametrize("bad", [np.array([8.0, 9.0]), [8.0], (8.0, 9.0)])
def test_arrays_where_scalars_are_expected_are_named_errors(bad):
    from onbottom.checks.absolute import absolute_lateral_stability
    from onbottom.inputs.pipe import Pipe
    from onbottom.inputs.soil import Sand

    pipe = Pipe(outer_diameter=0.512, submerged_weight=1500.0)
    with pytest.raises(InputError, match=r"hs = <array of shape") as exc:
        absolute_lateral_stability(
            pipe, Sand(submerged_unit_weight=10e3), hs=bad, tp=12.0, depth=50.0
        )
    assert exc.value.field == "hs"
    # a 0-d array is a scalar
    r = absolute_lateral_stability(
        pipe, Sand(submerged_unit_weight=10e3), hs=np.array(3.0), tp=10.0, depth=50.0
    )
    assert math.isfinite(r.utilisation)


def test_scalars_where_arrays_are_expected_are_named_errors():
    from onbottom.study.stability_curves import stability_curves

    with pytest.raises(InputError, match=r"k_values = 5\.0 is invalid: expected a sequence") as e:
        stability_curves(5.0, [0.0], n_workers=0)
    assert e.value.field == "k_values"
    with pytest.raises(InputError, match="m_values"):
        stability_curves([5.0], 0.0, n_workers=0)


# ---- 1. run-time and memory estimates --------------------------------------------------
@pytest.fixture
def no_runs(monkeypatch):
    """The many-storm functions fail the test if called: a refused run never starts."""

    def never(*args, **kwargs):
        raise AssertionError("the run started: the budget check did not refuse it")

    import onbottom.study.stability_curves as curves
    import onbottom.study.storm_seeds as seeds
    import onbottom.study.sweep as sweep

    monkeypatch.setattr(seeds, "run_storm_seeds", never)
    monkeypatch.setattr(curves, "stability_curves", never)
    monkeypatch.setattr(sweep, "sweep", never)


def test_storm_seeds_beyond_the_budget_are_refused(tmp_path, capsys, no_runs):
    text = (EXAMPLES / "storm_case.toml").read_text(encoding="utf-8")
    case = _write(tmp_path, _edit(text, "peak_hours = 3.0", "peak_hours = 30.0"))
    msg = _error(["storm", str(case), "--seeds", "100000", "--workers", "2"], capsys, "--seeds")
    assert "--force" in msg and "100000 storms" in msg


def test_pipeline_seeds_beyond_the_budget_are_refused(tmp_path, capsys, monkeypatch):
    import onbottom.study.pipeline_seeds as sp

    def never(*args, **kwargs):
        raise AssertionError("the run started: the budget check did not refuse it")

    monkeypatch.setattr(sp, "run_pipeline_seeds", never)
    text = (EXAMPLES / "pipeline_case.toml").read_text(encoding="utf-8")
    text = _edit(text, "length = 200.0 ", "length = 1000.0 ")
    text = _edit(text, "element_length = 4.0 ", "element_length = 2.0 ")
    text = _edit(text, "build_up_hours = 0.0167 ", "build_up_hours = 0.5 ")
    text = _edit(text, "peak_hours = 0.0667 ", "peak_hours = 3.0 ")
    case = _write(tmp_path, text)
    args = ["storm", str(case), "--seeds", "2000", "--workers", "2"]
    msg = _error(args, capsys, "--seeds")
    assert "2000 pipeline storms" in msg


def test_curves_grid_beyond_the_budget_is_refused(tmp_path, capsys, no_runs):
    ks = ", ".join(str(5.0 + 0.1 * i) for i in range(100))
    ms = ", ".join(str(0.01 * i) for i in range(100))
    text = (EXAMPLES / "curves_case.toml").read_text(encoding="utf-8")
    text = _edit(text, "K = [5.0, 20.0]", f"K = [{ks}]")
    text = _edit(text, "M = [0.0, 0.4]", f"M = [{ms}]")
    text = _edit(text, "peak_hours = 0.5", "peak_hours = 3.0")
    case = _write(tmp_path, text)
    msg = _error(["curves", str(case), "--workers", "2"], capsys, "[curves]")
    assert "curve points" in msg and "--force" in msg


def test_sweep_of_a_million_points_is_refused(tmp_path, capsys, no_runs):
    grid = _write(
        tmp_path,
        '[sweep]\nfunction = "centrifuge_response"\n[grid]\n'
        "A = { start = 0.1, stop = 0.5, num = 1000 }\n"
        "mu = { start = 0.3, stop = 0.9, num = 1000 }\n"
        '[fixed]\ntest = "Inclined 1"\n',
        "grid.toml",
    )
    msg = _error(
        ["sweep", str(grid), "-o", str(tmp_path / "s.nc"), "--workers", "2"], capsys, "[grid]"
    )
    assert "1e+06 sweep points" in msg
    assert not (tmp_path / "s.nc").exists()


def test_budget_estimates_and_force():
    from onbottom.study import budget

    est = budget.section_storms(10**6, 3.5 * 3600.0, 0.1, tp=10.0, workers=2)
    with pytest.raises(BudgetError, match="--force"):
        budget.check(est, force=False, field="--seeds")
    budget.check(est, force=True, field="--seeds")  # forced: no error
    small = budget.section_storms(10, 3.5 * 3600.0, 0.1, tp=10.0, workers=2)
    budget.check(small, force=False, field="--seeds")
    # 0.2 s per 3.5-h storm (126,000 steps at 2 µs + the synthesis), 5 rounds on 2 workers
    assert small.wall_s == pytest.approx(5 * (0.05 + 2e-6 * 126_000))


def test_pipeline_chunk_duration_is_bounded(tmp_path, capsys):
    text = (EXAMPLES / "pipeline_case.toml").read_text(encoding="utf-8")
    text = _edit(text, "record_interval = 2.0 ", "chunk_duration = 0.001\nrecord_interval = 2.0 ")
    case = _write(tmp_path, text)
    msg = _error(["storm", str(case)], capsys, "pipeline.chunk_duration")
    assert "chunks" in msg


# ---- 3. paths contained -----------------------------------------------------------------
@pytest.mark.parametrize("where", ["../../x.gif", "/tmp/onbottom-escape.gif", "sub/../../x.gif"])
def test_pipeline_animation_outside_the_case_folder_is_refused(where, tmp_path, capsys):
    text = (EXAMPLES / "pipeline_case.toml").read_text(encoding="utf-8")
    text = _edit(text, "record_interval = 2.0 ", f'animation = "{where}"\nrecord_interval = 2.0 ')
    folder = tmp_path / "a" / "b"
    folder.mkdir(parents=True)
    case = _write(folder, text)
    msg = _error(["storm", str(case)], capsys, "pipeline.animation")
    assert "leaves the case file's folder" in msg
    assert not (tmp_path / "x.gif").exists()


def test_simulate_file_outside_the_folder_is_refused_without_echo(tmp_path, capsys):
    head = (EXAMPLES / "section_case.toml").read_text(encoding="utf-8").split("[programme]")[0]
    tail = (
        "[solver]"
        + (EXAMPLES / "section_case.toml").read_text(encoding="utf-8").split("[solver]")[1]
    )
    case = _write(tmp_path, head + '[programme]\nkind = "csv"\nfile = "/etc/passwd"\n' + tail)
    msg = _error(["simulate", str(case), "--quiet"], capsys, "programme.file")
    assert "leaves the case file's folder" in msg and "root:" not in msg
    # a CSV inside the folder with text in it: the error names the row, never the text
    (tmp_path / "prog.csv").write_text("t,H,V\n0,1,2\nsecret-token,1,2\n", encoding="utf-8")
    case = _write(tmp_path, head + '[programme]\nkind = "csv"\nfile = "prog.csv"\n' + tail)
    code, out = _run(["simulate", str(case), "--quiet"], capsys)
    assert code == 1 and "secret-token" not in json.dumps(out)


def test_case_file_limits(tmp_path, capsys):
    from onbottom._casefile import MAX_CASE_FILE_BYTES, CaseFileError, read_json, read_toml

    deep = _write(tmp_path, "[" * 100_000 + "]" * 100_000, "deep.json")
    with pytest.raises(CaseFileError, match="nested deeper"):
        read_json(deep)
    msg = _error(["stability", str(deep)], capsys, "path")
    assert "nested deeper" in msg
    toml = _write(tmp_path, "a = " + "[" * 5000 + "]" * 5000 + "\n", "deep.toml")
    with pytest.raises(CaseFileError, match="nested deeper"):
        read_toml(toml)
    big = tmp_path / "big.toml"
    with big.open("wb") as fh:  # sparse: no disk used
        fh.truncate(MAX_CASE_FILE_BYTES + 1)
    assert "larger than the 10 MB limit" in _error(["stability", str(big)], capsys, "path")
    if Path("/dev/zero").exists():
        msg = _error(["stability", "/dev/zero"], capsys, "path")
        assert "not a regular file" in msg
        assert _error(["storm", "/dev/zero"], capsys, "path")


def test_report_out_is_refused_where_it_would_do_harm(tmp_path, capsys):
    from onbottom.report.build import GENERATOR_MARK, check_report_folder

    msg = _error(["report", "--only", "f114", "--out", "/"], capsys, "--out")
    assert "filesystem root" in msg
    foreign = tmp_path / "site"
    foreign.mkdir()
    (foreign / "index.html").write_text("<html>my page</html>", encoding="utf-8")
    msg = _error(["report", "--only", "f114", "--out", str(foreign)], capsys, "--out")
    assert "did not write" in msg and "--force" in msg
    assert (foreign / "index.html").read_text(encoding="utf-8") == "<html>my page</html>"
    assert check_report_folder(foreign, force=True) == foreign
    ours = tmp_path / "ours"
    ours.mkdir()
    (ours / "index.html").write_text(f'<html><head>{GENERATOR_MARK} 0.1">', encoding="utf-8")
    assert check_report_folder(ours) == ours


# ---- 5. curves: bracket, spread, converged ------------------------------------------------
def _row(k: float, *, converged: bool) -> dict:
    from onbottom.study.stability_curves import _seed_spread

    lo, hi = (4.16, 4.97) if converged else (1.0, 300.0)
    return {
        "soil": "sand",
        "K": k,
        "M": 0.0,
        "N": 0.003,
        "criterion": "L_stable",
        "L": math.sqrt(lo * hi) if converged else math.nan,
        "L_low": lo,
        "L_high": hi,
        "bracket_width": hi / lo - 1.0,
        "converged": converged,
        **_seed_spread("low", [0.4, 0.7]),
        **_seed_spread("high", [0.2, 0.45]),
        "evaluations": 6,
        "storms": 12,
        "runtime_s": 1.0,
        "cpu_s": 1.0,
        "success": converged,
        "error": False,
        "message": "converged" if converged else "no crossing",
    }


def test_curve_points_report_bracket_spread_and_convergence():
    from onbottom.study.stability_curves import (
        CurveSettings,
        _to_dataset,
        curves_table,
        point_summary,
    )

    s = CurveSettings(tolerance=0.2)
    rows = [_row(10.0, converged=True), _row(25.0, converged=False)]
    ds = _to_dataset(rows, ["sand"], [0.003], [0.0], [10.0, 25.0], ["L_stable"], s, 1.0, 1)
    assert list(ds["L_stable_converged"].values.ravel()) == [1, 0]
    assert ds["L_stable_bracket_low"].values.ravel()[0] == 4.16
    assert ds["L_stable_seed_max_low"].values.ravel()[0] == pytest.approx(0.7)
    table = curves_table(ds)
    assert table[0]["L_stable_L_low"] == 4.16 and table[0]["L_stable_L_high"] == 4.97
    assert table[0]["L_stable_converged"] is True and table[1]["L_stable_converged"] is False
    assert table[0]["L_stable_seed_min_high"] == pytest.approx(0.2)
    line = point_summary(table[0])
    assert "[4.16, 4.97]" in line and "0.4-0.7 at L_low" in line
    assert "NOT CONVERGED (bracket [1, 300])" in point_summary(table[1])


def test_consistency_findings_report_in_the_api():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        consistency.report(consistency.current_speed(9.5, field="v"))
    assert caught and issubclass(caught[0].category, PhysicalConsistencyWarning)
    assert issubclass(PhysicalConsistencyWarning, OutOfRangeWarning)
    with pytest.raises(InputError) as exc:
        consistency.report(consistency.stop_limit(1e-6, (0.5, 10.0), field="stop"))
    assert exc.value.field == "stop"
    with consistency.warnings_reported_by_case(), warnings.catch_warnings():
        warnings.simplefilter("error")
        consistency.report(consistency.current_speed(9.5, field="v"))  # left to the case
