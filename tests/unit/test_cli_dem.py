"""``onbottom dem`` command line (tiny configuration; seconds)."""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner

from onbottom.cli.main import cli
from onbottom.dem.config import SD_REDUCED, Geometry, Loading, Preparation

TINY = SD_REDUCED.replace(
    name="tiny",
    geometry=Geometry(width=0.06, height=0.02, pipe_diameter=0.02),
    preparation=Preparation(n_layers=2, max_settle_time=0.05),
    loading=Loading(gravity_factor=25.0, pipe_velocity=0.1, final_embedment_ratio=0.05),
)


def test_dem_prepare_penetrate_resume_plot(tmp_path):
    runner = CliRunner()
    cfg = tmp_path / "tiny.json"
    cfg.write_text(TINY.to_json())
    sample = tmp_path / "s.nc"
    out = tmp_path / "r.nc"
    r = runner.invoke(cli, ["dem", "prepare", "--config", str(cfg), "--out", str(sample), "--json"])
    assert r.exit_code == 0, r.output
    assert json.loads(r.output)["n_particles"] > 100
    assert not (tmp_path / "s.nc.prep-checkpoint.nc").exists()  # removed once saved
    args = ["dem", "penetrate", "--config", str(cfg), "--sample", str(sample), "--out", str(out)]
    r = runner.invoke(cli, [*args, "--json", "--max-steps", "2000"])
    assert r.exit_code == 0, r.output
    first = json.loads(r.output)
    assert not first["complete"]
    assert (tmp_path / "r.checkpoint.nc").exists()
    r = runner.invoke(cli, [*args, "--json"])
    assert r.exit_code == 0, r.output
    done = json.loads(r.output)
    assert done["complete"]
    assert done["steps"] > first["steps"]
    assert done["inertial_number"] > 0
    assert not (tmp_path / "r.checkpoint.nc").exists()
    r = runner.invoke(cli, ["dem", "plot", str(out), "--outdir", str(tmp_path / "f"), "--json"])
    assert r.exit_code == 0, r.output
    figs = json.loads(r.output)["figures"]
    assert any("V_w" in f for f in figs)
    assert not any("f114" in f for f in figs)  # preset "tiny" has no default unit weight
    r = runner.invoke(
        cli,
        ["dem", "plot", str(out), "--outdir", str(tmp_path / "g"), "--gamma-kn", "16.7", "--json"],
    )
    assert r.exit_code == 0, r.output
    assert any(f.endswith("dem_V_w_f114.png") for f in json.loads(r.output)["figures"])
    assert done["w_over_D_reached"] >= 0.05 - 1e-3
    assert done["V_prototype_kN_per_m (bin mean)"]["0.05D"] is not None
    assert done["V_prototype_kN_per_m (bin mean)"]["0.5D"] is None  # not reached
    summ = tmp_path / "summ"
    r = runner.invoke(cli, ["dem", "summarize", str(out), "--outdir", str(summ), "--json"])
    assert r.exit_code == 0, r.output
    (rep,) = json.loads(r.output)
    assert rep["preset"] == "tiny" and rep["complete"]
    for name in ("tiny_summary.nc", "tiny_V_w.csv", "tiny_surface.csv"):
        assert (summ / name).stat().st_size > 0
    header = (summ / "tiny_V_w.csv").read_text().splitlines()[0]
    assert header == (
        "w_over_D,V_prototype_mean_kN_per_m,V_prototype_min_kN_per_m,V_prototype_max_kN_per_m"
    )
    # kB-sized, whatever the run's size (a full-size run file is ~40 MB; this tiny run, with
    # no field snapshot reached and few records, is smaller than its summary)
    assert (summ / "tiny_summary.nc").stat().st_size < 200_000
    r = runner.invoke(
        cli, ["dem", "plot", str(summ / "tiny_summary.nc"), "--outdir", str(summ), "--json"]
    )
    assert r.exit_code == 0, r.output
    names = {Path(f).name for f in json.loads(r.output)["figures"]}
    assert {"dem_V_w_prototype.png", "dem_heave.png", "dem_initial_state.png"} <= names


def test_dem_bad_preset_is_reported():
    r = CliRunner().invoke(cli, ["dem", "prepare", "--preset", "XX", "--out", "x.nc"])
    assert r.exit_code != 0
    assert "XX" in r.output


def test_dem_prepare_not_at_rest_exits_3(tmp_path):
    """A specimen whose N g equilibrium stops at its time cap is written but is no valid result."""
    cfg = tmp_path / "unsettled.json"
    unsettled = TINY.replace(preparation=Preparation(n_layers=2, max_settle_time=1e-4))
    cfg.write_text(unsettled.to_json())
    sample = tmp_path / "s.nc"
    r = CliRunner().invoke(
        cli, ["dem", "prepare", "--config", str(cfg), "--out", str(sample), "--json"]
    )
    assert r.exit_code == 3, r.output
    payload = json.loads(r.output)
    assert payload["success"] is False
    assert payload["equilibrium_Ng_converged"] is False
    assert "not at rest" in payload["message"]
    assert sample.exists()  # kept for inspection


def test_dem_event_snapshots_cli(tmp_path):
    """Event snapshots on by default, off with --no-event-snapshots; bands CSV and figures."""
    import dataclasses

    import xarray as xr

    runner = CliRunner()
    cfg = tmp_path / "deeper.json"
    deeper = TINY.replace(loading=dataclasses.replace(TINY.loading, final_embedment_ratio=0.2))
    cfg.write_text(deeper.to_json())
    sample = tmp_path / "s.nc"
    base = ["dem", "penetrate", "--config", str(cfg), "--sample", str(sample), "--json"]
    r = runner.invoke(cli, [*base, "--out", str(tmp_path / "on.nc")])
    assert r.exit_code == 0, r.output
    on = json.loads(r.output)
    assert on["event_snapshots"] >= 2 and not on["event_snapshots_capped"]
    r = runner.invoke(cli, [*base, "--out", str(tmp_path / "off.nc"), "--no-event-snapshots"])
    assert r.exit_code == 0, r.output
    assert json.loads(r.output)["event_snapshots"] == 0
    with xr.open_dataset(tmp_path / "off.nc", engine="h5netcdf") as ds:
        assert set(ds["snapshot_kind"].values.astype(str)) == {"fixed"}
    summ = tmp_path / "summ"
    r = runner.invoke(cli, ["dem", "summarize", str(tmp_path / "on.nc"), "--outdir", str(summ)])
    assert r.exit_code == 0, r.output
    rows = (summ / "tiny_bands.csv").read_text().splitlines()
    assert rows[0] == (
        "band_episode,w_peak,w_trough,drop_percent,reaches_surface,outcrop_x_over_D,cluster_size"
    )
    assert len(rows) == 1 + on["event_snapshots"] // 2
    r = runner.invoke(
        cli, ["dem", "plot", str(tmp_path / "on.nc"), "--outdir", str(tmp_path / "f"), "--json"]
    )
    assert r.exit_code == 0, r.output
    names = {Path(f).name for f in json.loads(r.output)["figures"]}
    assert "dem_band_tiny_episode0.png" in names
    assert not any(n.startswith("dem_rotation_tiny_0.0") for n in names)  # fixed ones only
    # two runs of one preset plotted together: one set of per-run figures each, by file stem
    r = runner.invoke(
        cli,
        [
            "dem", "plot", str(tmp_path / "on.nc"), str(tmp_path / "off.nc"),
            "--outdir", str(tmp_path / "two"), "--json",
        ],
    )  # fmt: skip
    assert r.exit_code == 0, r.output
    names = {Path(f).name for f in json.loads(r.output)["figures"]}
    assert "dem_band_tiny_on_episode0.png" in names
    assert not any(n.startswith("dem_band_tiny_off") for n in names)  # no events in "off"
    assert not any(n.startswith("dem_band_tiny_episode") for n in names)
