"""Unit tests: the ``onbottom penetration`` command (in-process)."""

from __future__ import annotations

import json

import pytest

from onbottom.cli.main import main

SAND = ["penetration", "--diameter", "0.5", "--gamma-kn", "16.7", "--phi-deg", "33"]


def test_sand_table_and_embedment(capsys):
    code = main([*SAND, "--n-gamma", "vesic", "--load-kn", "26.4"])
    out = capsys.readouterr().out
    assert code == 0
    assert "26.4" in out  # Q_v at 0.1D, vesic, spec §3.3
    assert "(z/D = 0.0998)" in out  # 26.4 kN/m is Q_v(0.1D) rounded (26.43)


def test_sand_json_with_bounds(capsys):
    code = main(
        [*SAND, "--phi-lower-deg", "33", "--phi-upper-deg", "40", "--load-kn", "40", "--json"]
    )
    assert code == 0
    data = json.loads(capsys.readouterr().out)
    assert data["model"] == "dnvgl_rp_f114_drained"
    assert data["table"]["z_over_D"] == pytest.approx([0.1, 0.2, 0.3, 0.4, 0.5])
    assert data["table"]["Q_v_lower"][0] == pytest.approx(10.6e3, rel=0.01)
    assert data["table"]["Q_v_upper"][-1] == pytest.approx(209.2e3, rel=0.01)
    assert data["embedment"]["Q_v"] == pytest.approx(40e3, rel=1e-8)
    assert data["embedment"]["success"] is True
    assert data["bounds"]["upper"]["friction_angle_deg"] == 40.0


def test_clay_model2_with_lay_factor_json(capsys):
    args = ["penetration", "--soil", "clay", "--diameter", "0.5", "--gamma-kn", "6"]
    args += ["--su-kpa", "2", "--su-gradient-kpa", "3", "--model", "2", "--at", "0.1,0.3"]
    args += ["--load-kn", "5", "--ei", "1e8", "--tension-kn", "500", "--json"]
    assert main(args) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["model"] == "dnvgl_rp_f114_undrained_model2"
    assert data["table"]["Q_v"][0] == pytest.approx(3719.07, abs=0.01)
    assert data["embedment"]["lay_factor"] > 1.0
    assert data["warnings"] == []


def test_plot_and_netcdf_outputs(tmp_path, capsys):
    png, nc = tmp_path / "v_w.png", tmp_path / "curve.nc"
    assert main([*SAND, "--load-kn", "30", "--plot", str(png), "--save", str(nc)]) == 0
    assert png.stat().st_size > 1000 and nc.stat().st_size > 1000


def test_errors_exit_1_and_name_the_field(capsys):
    assert main([*SAND[:2], "-0.5", *SAND[3:]]) == 1
    assert "diameter" in capsys.readouterr().err
    assert main([*SAND, "--load-kn", "1000"]) == 1
    assert "exceeds the resistance at full embedment" in capsys.readouterr().err
    assert main(["penetration", "--soil", "clay", "--diameter", "0.5", "--gamma-kn", "6"]) == 1
    assert "--su-kpa" in capsys.readouterr().err
    assert main([*SAND, "--ei", "1e8"]) == 1
    assert "--tension-kn" in capsys.readouterr().err


def test_out_of_range_warning_is_reported(capsys):
    assert main([*SAND[:-1], "47", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert any("friction_angle_deg" in w for w in data["warnings"])
