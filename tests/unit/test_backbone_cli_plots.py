"""Unit tests: `onbottom backbone` CLI, path response and backbone plots."""

from __future__ import annotations

import json

import numpy as np
import pytest
from matplotlib.figure import Figure

from onbottom import InputError, Pipe, Sand
from onbottom.cli.main import main
from onbottom.plotting.backbone import backbone_arrays, plot_backbone, plot_path_response
from onbottom.soil.response import cyclic_path, path_response
from onbottom.soil.verley_sotberg import VerleySotberg

ARGS = ["backbone", "--model", "calcareous", "--diameter", "1.0", "--weight-kn", "10.52"]
ARGS += ["--gamma-kn", "7.5", "--mu", "0.48"]


def test_cli_json_gives_the_worked_numbers(capsys):
    assert main([*ARGS, "--z2-over-d", "0.1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    bb = out["backbone"]
    assert bb["K_s"] == pytest.approx(0.712928, rel=1e-4)
    assert bb["z_i"] == pytest.approx(0.045487, rel=1e-4)
    assert bb["F_r2"] / 1e3 == pytest.approx(0.51592, rel=1e-4)
    assert bb["F_r1"] / 1e3 == pytest.approx(0.15478, rel=1e-4)
    assert bb["F_r3"] / 1e3 == pytest.approx(0.21692, rel=1e-4)
    assert (bb["y1"], bb["y2"], bb["y3"]) == pytest.approx((0.01, 0.25, 0.75))


def test_cli_table_path_and_plots(tmp_path, capsys):
    plot = tmp_path / "bb.png"
    assert main([*ARGS, "--cycles", "2", "--plot", str(plot)]) == 0
    text = capsys.readouterr().out
    assert "F_r2" in text and "cyclic path" in text
    assert plot.stat().st_size > 0
    assert (tmp_path / "bb_path.png").stat().st_size > 0


def test_cli_bad_input_names_the_field(capsys):
    assert main([*ARGS[:4], "-1", *ARGS[5:]]) == 1
    assert "--diameter" in capsys.readouterr().err  # the option at fault


def test_path_response_dataset_and_plot():
    m = VerleySotberg.silica(
        Pipe(outer_diameter=0.5, submerged_weight=2.0e3), Sand(submerged_unit_weight=1.0e4)
    )
    u = cyclic_path(0.05, 2.0, points_per_cycle=200)
    assert u.size == 400 and np.max(np.abs(u)) == pytest.approx(0.05, rel=1e-3)
    ds = path_response(m, u, 2.0e3)
    assert ds["F_soil"].attrs["units"] == "N/m" and ds.attrs["model"] == "verley_sotberg"
    assert float(ds["z"][-1]) > m.initial_penetration
    assert isinstance(plot_path_response(ds, diameter=0.5), Figure)
    pts = m.backbone_points(2.0e3)
    arr = backbone_arrays(pts)
    assert arr["passive"][arr["y"] == 0.0] == 0.0
    np.testing.assert_allclose(arr["passive"], arr["passive"][::-1])
    fig = plot_backbone(pts, diameter=0.5, title="t")
    assert len(fig.axes) == 2
    with pytest.raises(InputError, match="amplitude"):
        cyclic_path(0.0, 2.0)


def test_cli_reports_range_warnings(capsys):
    args = ["backbone", "--diameter", "1", "--weight-kn", "0.01", "--gamma-kn", "10", "--json"]
    assert main(args) == 0
    out = json.loads(capsys.readouterr().out)
    assert any("K_s" in w for w in out["warnings"])
