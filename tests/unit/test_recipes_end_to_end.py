"""Unit tests: the recipes of docs/contributing.md followed end to end, own kernels included.

``tests/recipe_models.py`` adds a soil model (``adhesive_coulomb``) and a force model
(``quadratic_drag``), each with its own numba kernel and one registration call, in one file and
without editing the package. Here a storm case and a route case name them (``[soil] model``,
``[hydro] model`` and their option tables) and ``onbottom storm`` and ``onbottom assess`` run
them. Hand check: with no adhesion the soil is Coulomb friction and quadratic drag is Morison
with C_M = C_L = 0, so the storm equals the built-in models' storm to round-off.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import recipe_models  # registers adhesive_coulomb and quadratic_drag
from assess_cases import route_document
from onbottom.cases.assess import load_route
from onbottom.cli.main import cli

STORM = """
[pipe]
outer_diameter = 0.4
submerged_weight = 400.0

[seabed]
model = "rock"
friction_coefficient = 0.6

[environment]
water_depth = 13.0

[current]
velocity = 0.3
reference_height = 1.0
direction_deg = 90.0

[storm]
kind = "regular"
height = 6.0
period = 10.0
direction_deg = 90.0
build_up_hours = 0.01
peak_hours = 0.03
time_step = 0.1

[solver]
record_interval = 0.5
"""

OWN = """
[soil]
model = "adhesive_coulomb"

[soil.adhesive_coulomb]
adhesion = {adhesion}

[hydro]
model = "quadratic_drag"

[hydro.quadratic_drag]
cd = 0.9
"""

BUILTIN = """
[hydro]
model = "morison"
cd = 0.9
cm = 0.0
cl = 0.0
"""


def _toml(doc: dict, prefix: str = "") -> str:
    """A TOML text of ``doc`` (tables, arrays of tables, scalars and lists of scalars)."""
    lines, subs = [], []
    for k, v in doc.items():
        if isinstance(v, dict):
            subs.append(f"\n[{prefix}{k}]\n" + _toml(v, f"{prefix}{k}."))
        elif isinstance(v, list) and v and isinstance(v[0], dict):
            subs += [f"\n[[{prefix}{k}]]\n" + _toml(x, f"{prefix}{k}.") for x in v]
        else:
            lines.append(f"{k} = {json.dumps(v)}")
    return "\n".join(lines) + "\n" + "".join(subs)


def _storm(tmp_path: Path, name: str, extra: str) -> xr.Dataset:
    case = tmp_path / f"{name}.toml"
    case.write_text(STORM + extra, encoding="utf-8")
    out = tmp_path / f"{name}.nc"
    res = CliRunner().invoke(cli, ["storm", str(case), "--workers", "0", "--quiet", "-o", str(out)])
    assert res.exit_code == 0, res.output
    with xr.open_dataset(out) as ds:
        return ds.load()


def test_storm_case_names_models_with_their_own_kernels(tmp_path):
    own = _storm(tmp_path, "own", OWN.format(adhesion=0.0))
    ref = _storm(tmp_path, "builtin", BUILTIN)
    params = json.loads(own.attrs["parameters"])
    assert params["soil_model"] == "adhesive_coulomb" and params["adhesion"] == 0.0
    assert own.attrs["force_model"] == "quadratic_drag"
    assert np.max(np.abs(own["y"].values)) > 0.01  # the pipe slides: the kernels did the work
    np.testing.assert_allclose(own["y"].values, ref["y"].values, rtol=1e-7, atol=1e-9)
    # a large adhesion holds the pipe within the mobilisation displacement δ = 1 mm
    held = _storm(tmp_path, "held", OWN.format(adhesion=5.0e4))
    assert np.max(np.abs(held["y"].values)) <= 1.0e-3 + 1e-12


@pytest.mark.parametrize(
    ("extra", "key"),
    [
        ('[soil]\nmodel = "no_such_soil"\n', "soil.model"),
        ('[hydro]\nmodel = "no_such_force"\n', "hydro.model"),
        ('[soil]\nmodel = "coulomb"\n[soil.coulomb]\nstickiness = 1.0\n', "soil.coulomb"),
        ('[hydro]\nmodel = "morison"\n[hydro.quadratic_drag]\ncd = 1.0\n', "hydro.quadratic_drag"),
    ],
)
def test_unknown_names_are_named_errors(tmp_path, extra, key):
    case = tmp_path / "bad.toml"
    case.write_text(STORM + extra, encoding="utf-8")
    res = CliRunner().invoke(cli, ["storm", str(case), "--workers", "0", "--quiet"])
    assert res.exit_code != 0 and res.exc_info[0] is SystemExit, res.output
    assert key in res.output and "line" in res.output and "Traceback" not in res.output


def test_route_case_names_models_with_their_own_kernels(tmp_path):
    doc = route_document(sections=1, seeds=1, peak_hours=0.02)
    doc["soil"] = {"model": "adhesive_coulomb", "adhesive_coulomb": {"adhesion": 100.0}}
    doc["hydro"] = {"model": "quadratic_drag", "quadratic_drag": {"cd": 0.9}}
    case = tmp_path / "route.toml"
    case.write_text(_toml(doc), encoding="utf-8")
    out = tmp_path / "out"
    res = CliRunner().invoke(
        cli, ["assess", str(case), "--out", str(out), "--workers", "0", "--no-pdf", "--quiet"]
    )
    assert res.exit_code == 0, res.output
    with xr.open_dataset(out / "dynamic.nc") as ds:
        assert np.all(np.isfinite(ds["max_displacement"].values))
    # the storms the route ran are built with the two models and the case's options
    route = load_route(case)
    for storm in route.sections[0].storms:
        assert isinstance(storm.setup.soil, recipe_models.AdhesiveCoulomb)
        assert storm.setup.soil.adhesion == 100.0
        assert isinstance(storm.setup.force_model, recipe_models.QuadraticDrag)
        assert storm.setup.force_model.cd == 0.9
    # the design report's V–H diagram is drawn from those two models, not from defaults
    page = (out / "report.html").read_text(encoding="utf-8")
    assert "force model quadratic_drag (as built from the case&#39;s [hydro])" in page
    assert "as-laid penetration of the adhesive_coulomb soil model" in page
    assert "figure-not-drawn" not in page


# ---- an unknown model name is a named error in every case kind -----------------------------------
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
KINDS = {  # case kind: (example file, command, the tables that name a model)
    "section": ("section_case.toml", ["simulate"], ("soil",)),  # a load programme: no flow
    "stability": ("stability_case.toml", ["stability"], ("hydro",)),  # F109: no soil model
    "curves": ("curves_case.toml", ["curves"], ("hydro",)),  # soils: the F109 sand and clay
    "pipeline": ("pipeline_case.toml", ["storm", "--workers", "0"], ("soil", "hydro")),
    "reliability": ("reliability_case.toml", ["reliability", "--workers", "0"], ("soil", "hydro")),
    "route": ("assess_route.toml", ["assess", "--workers", "0"], ("soil", "hydro")),
}


def _with_model(text: str, table: str, name: str) -> str:
    """``text`` with ``[table] model = name`` (the table's own model line replaced)."""
    lines, out, inside, done = text.splitlines(), [], False, False
    for line in lines:
        head = line.split("#", 1)[0].strip()
        if head.startswith("["):
            inside = head == f"[{table}]"
            out.append(line)
            if inside:
                out.append(f'model = "{name}"')
                done = True
            continue
        if inside and head.startswith("model"):
            continue
        out.append(line)
    if not done:
        out += ["", f"[{table}]", f'model = "{name}"']
    return "\n".join(out) + "\n"


@pytest.mark.parametrize("table", ["soil", "hydro"])
@pytest.mark.parametrize("kind", list(KINDS))
def test_unknown_model_names_in_every_case_kind(tmp_path, kind, table):
    example, command, tables = KINDS[kind]
    if table not in tables:
        pytest.skip(f"the {kind} case has no [{table}] model")
    for csv in EXAMPLES.glob("*.csv"):
        (tmp_path / csv.name).write_bytes(csv.read_bytes())
    case = tmp_path / example
    bad = f"no_such_{table}"
    case.write_text(_with_model(EXAMPLES.joinpath(example).read_text("utf-8"), table, bad))
    args = [*command, str(case)]
    if kind == "route":
        args += ["--out", str(tmp_path / "out"), "--no-pdf", "--quiet"]
    res = CliRunner().invoke(cli, args)
    assert res.exit_code not in (0, 70) and res.exc_info[0] is SystemExit, res.output
    assert f"{table}.model = '{bad}' is invalid" in res.output, res.output
    assert "line" in res.output and "Traceback" not in res.output
    names = "coulomb" if table == "soil" else "morison"
    assert names in res.output  # the registered names are listed


def test_section_case_names_a_registered_model(tmp_path):
    case = tmp_path / "section.toml"
    case.write_text(
        "[pipe]\nouter_diameter = 0.4\nsubmerged_weight_kn = 1.5\n"
        '[soil]\nmodel = "adhesive_coulomb"\nfriction_coefficient = 0.5\n'
        "submerged_unit_weight_kn = 10.0\n[soil.adhesive_coulomb]\nadhesion = 300.0\n"
        '[programme]\nkind = "inclined_cyclic"\nname = "t"\ninstallation_load_kn = 1.5\n'
        "vertical_load_kn = 1.5\namplitude_step_kn = 0.2\nperiod = 20.0\nalpha_deg = 90.0\n"
        "n_cycles = 6\n",
        encoding="utf-8",
    )
    out = tmp_path / "section.nc"
    res = CliRunner().invoke(cli, ["simulate", str(case), "-o", str(out)])
    assert res.exit_code == 0, res.output
    with xr.open_dataset(out) as ds:
        params = json.loads(ds.attrs["parameters"])
        f_soil = ds["F_soil"].values
    assert params["soil_model"] == "adhesive_coulomb" and params["adhesion"] == 300.0
    # the resistance plateau is μV + a = 0.5 · 1500 + 300 N/m (hand calculation)
    assert np.max(np.abs(f_soil)) == pytest.approx(0.5 * 1500.0 + 300.0, rel=1e-9)
