"""Run identity of DEM checkpoints: resume only the run that wrote them (issue #10).

A synthetic specimen (disks on a lattice, no preparation) and a few hundred steps keep each
test to seconds; the preparation checkpoint is made by interrupting a tiny preparation after
its first layer.
"""

from __future__ import annotations

import json
import os
import stat

import numpy as np
import pytest
from click.testing import CliRunner

from onbottom.cli.main import cli
from onbottom.dem.config import SD_REDUCED, Geometry, Loading, Preparation
from onbottom.dem.experiment import penetrate
from onbottom.dem.identity import (
    CheckpointError,
    CheckpointMismatchError,
    dem_identity,
    differences,
    fingerprint,
)
from onbottom.dem.preparation import prepare_sample
from onbottom.dem.sample import Sample
from onbottom.errors import InputError

TINY = SD_REDUCED.replace(
    name="tiny",
    geometry=Geometry(width=0.06, height=0.02, pipe_diameter=0.02),
    preparation=Preparation(n_layers=2, max_settle_time=0.01),
    loading=Loading(gravity_factor=25.0, pipe_velocity=0.1, final_embedment_ratio=0.05),
)
MINI = TINY.replace(
    name="mini",
    geometry=Geometry(width=0.03, height=0.012, pipe_diameter=0.02),
    preparation=Preparation(n_layers=2, max_settle_time=0.005),
)
"""A specimen of about 80 disks for the preparation tests."""
STEPS = 400  # steps of the interrupted run (checkpoint written at the stop)


def _lattice_sample(jitter_seed: int = 0) -> Sample:
    """Disks of the PSD's median size on a slightly jittered square lattice filling the box."""
    g = TINY.geometry
    r = 0.5 * TINY.psd.d50
    s = 2.02 * r
    xs = np.arange(r * 1.01, g.width - r, s)
    ys = np.arange(r * 1.01, g.height - r, s)
    xx, yy = np.meshgrid(xs, ys)
    pos = np.stack([xx.ravel(), yy.ravel()], axis=1)
    rng = np.random.default_rng(jitter_seed)
    pos[:, 0] += rng.uniform(-0.005, 0.005, len(pos)) * r
    return Sample(pos, np.full(len(pos), r), (0.0, g.width, 0.0, g.height))


@pytest.fixture(scope="module")
def sample() -> Sample:
    return _lattice_sample()


@pytest.fixture
def checkpoint(tmp_path, sample):
    ck = tmp_path / "run.checkpoint.nc"
    part = penetrate(TINY, sample, checkpoint=ck, max_steps=STEPS, checkpoint_every=10**6)
    assert not part.attrs["complete"] and ck.exists()
    return ck


def test_identity_fingerprint_changes_with_every_determining_field(sample):
    base = dem_identity(TINY, "penetration", sample=sample).fields
    assert fingerprint(base) == fingerprint(dem_identity(TINY, "penetration", sample=sample).fields)
    changed = {
        "seed": TINY.replace(seed=9),
        "name": TINY.replace(name="other"),
        "velocity": TINY.replace(
            loading=Loading(gravity_factor=25.0, pipe_velocity=0.2, final_embedment_ratio=0.05)
        ),
    }
    for what, cfg in changed.items():
        other = dem_identity(cfg, "penetration", sample=sample).fields
        assert fingerprint(other) != fingerprint(base), what
        assert len(differences(base, other)) == 1, what
    other = dem_identity(TINY, "penetration", sample=_lattice_sample(jitter_seed=1)).fields
    assert differences(base, other)[0].startswith("sample:")


def test_resume_with_another_velocity_names_the_field_and_advises_restart(sample, checkpoint):
    faster = TINY.replace(
        loading=Loading(gravity_factor=25.0, pipe_velocity=0.2, final_embedment_ratio=0.05)
    )
    with pytest.raises(CheckpointMismatchError) as info:
        penetrate(faster, sample, checkpoint=checkpoint, max_steps=10)
    msg = str(info.value)
    assert "config.loading.pipe_velocity: 0.1 in the file, 0.2 now" in msg
    assert "--restart" in msg and isinstance(info.value, InputError)
    assert info.value.differing == ["config.loading.pipe_velocity: 0.1 in the file, 0.2 now"]
    assert checkpoint.exists()  # never deleted by a refused resume


def test_resume_with_another_seed_preset_or_specimen_is_refused(sample, checkpoint):
    with pytest.raises(CheckpointMismatchError, match="config.seed: 2 in the file, 7 now"):
        penetrate(TINY.replace(seed=7), sample, checkpoint=checkpoint, max_steps=10)
    with pytest.raises(CheckpointMismatchError, match="config.name: 'tiny' in the file"):
        penetrate(TINY.replace(name="SM-reduced"), sample, checkpoint=checkpoint, max_steps=10)
    with pytest.raises(CheckpointMismatchError, match="sample:"):
        penetrate(TINY, _lattice_sample(jitter_seed=3), checkpoint=checkpoint, max_steps=10)


def test_matching_resume_continues_and_result_carries_the_identity(sample, checkpoint):
    more = penetrate(TINY, sample, checkpoint=checkpoint, max_steps=200)
    assert int(more.attrs["steps"]) == STEPS + 200
    ident = json.loads(more.attrs["run_identity"])
    assert ident["file_format"] >= 2 and ident["kind"] == "penetration"
    assert more.attrs["run_fingerprint"] == fingerprint(
        dem_identity(TINY, "penetration", sample=sample).fields
    )


@pytest.mark.parametrize("damage", ["truncate", "garbage", "empty", "not_a_checkpoint"])
def test_corrupt_checkpoint_is_a_named_error_and_restart_recovers(
    tmp_path, sample, checkpoint, damage
):
    data = checkpoint.read_bytes()
    if damage == "truncate":
        checkpoint.write_bytes(data[: len(data) // 2])
    elif damage == "garbage":
        checkpoint.write_bytes(b"\x89HDF\r\n" + os.urandom(2000))
    elif damage == "empty":
        checkpoint.write_bytes(b"")
    else:
        sample.save(checkpoint)  # a valid NetCDF file, but a specimen
    with pytest.raises(CheckpointError) as info:
        penetrate(TINY, sample, checkpoint=checkpoint, max_steps=10)
    assert "cannot be read" in str(info.value) and "--restart" in str(info.value)
    assert info.value.field == "checkpoint"
    fresh = penetrate(TINY, sample, checkpoint=checkpoint, max_steps=10, restart=True)
    assert 0 < int(fresh.attrs["steps"]) <= TINY.numerics.record_every  # a fresh start


def test_checkpoint_without_identity_is_refused(sample, checkpoint):
    import xarray as xr

    from onbottom.results import save_dataset

    with xr.open_dataset(checkpoint, engine="h5netcdf") as ds:
        old = ds.load()
    meta = json.loads(old.attrs["checkpoint_meta"])
    del meta["identity"]
    old.attrs["checkpoint_meta"] = json.dumps(meta)
    save_dataset(old, checkpoint)
    with pytest.raises(CheckpointMismatchError, match="has no run identity"):
        penetrate(TINY, sample, checkpoint=checkpoint, max_steps=10)


@pytest.mark.parametrize(("key", "value"), [("checkpoint_every", 0), ("max_steps", -1)])
def test_bad_step_counts_are_named(sample, tmp_path, key, value):
    with pytest.raises(InputError, match=f"{key} = {value}"):
        penetrate(TINY, sample, checkpoint=tmp_path / "c.nc", **{key: value})


class _Stop(Exception):
    pass


@pytest.fixture(scope="module")
def prep_checkpoint(tmp_path_factory):
    """A preparation checkpoint of MINI written after its first compacted layer."""
    ck = tmp_path_factory.mktemp("prep") / "s.nc.prep-checkpoint.nc"

    def stop_after_first_layer(stage, fraction):
        if stage == "compaction" and fraction >= 0.5:
            raise _Stop

    with pytest.raises(_Stop):
        prepare_sample(MINI, progress=stop_after_first_layer, checkpoint=ck)
    assert ck.exists()
    return ck


def test_preparation_checkpoint_of_another_preset_is_refused(prep_checkpoint, tmp_path):
    ck = tmp_path / prep_checkpoint.name
    ck.write_bytes(prep_checkpoint.read_bytes())
    other = MINI.replace(name="SM-reduced", seed=7)
    with pytest.raises(CheckpointMismatchError) as info:
        prepare_sample(other, checkpoint=ck)
    msg = str(info.value)
    assert "config.name: 'mini' in the file, 'SM-reduced' now" in msg and "config.seed" in msg
    assert "--restart" in msg and ck.exists()


def test_cli_prepare_refuses_a_foreign_or_corrupt_checkpoint_and_restart_starts_afresh(
    prep_checkpoint, tmp_path
):
    runner = CliRunner()
    cfg = tmp_path / "other.json"
    cfg.write_text(MINI.replace(seed=7).to_json())
    out = tmp_path / "s.nc"
    ck = tmp_path / "s.nc.prep-checkpoint.nc"
    ck.write_bytes(prep_checkpoint.read_bytes())
    stale = tmp_path / "s.nc.prep-checkpoint.nc.abc123.tmp"  # left by a killed writer
    stale.write_bytes(b"partial")
    args = ["dem", "prepare", "--config", str(cfg), "--out", str(out), "--no-progress", "--json"]
    r = runner.invoke(cli, args)
    assert r.exit_code == 1
    err = json.loads(r.output)["error"]
    assert err["type"] == "CheckpointMismatchError" and err["field"] == "checkpoint"
    assert "config.seed: 2 in the file, 7 now" in err["message"]
    assert not out.exists() and not stale.exists()  # temporaries cleaned on the next start
    ck.write_bytes(prep_checkpoint.read_bytes()[:1000])  # truncated
    r = runner.invoke(cli, args)
    assert r.exit_code == 1 and "cannot be read" in json.loads(r.output)["error"]["message"]
    r = runner.invoke(cli, [*args, "--restart"])
    # MINI is too small a specimen to reach the N g criterion within its time cap: the run
    # completes, writes the specimen and says it is not at rest (exit 3) — consistently
    payload = json.loads(r.output)
    assert r.exit_code == (0 if payload["equilibrium_Ng_converged"] else 3), r.output
    assert payload["success"] is bool(payload["equilibrium_Ng_converged"])
    assert out.exists() and not ck.exists()
    assert json.loads(r.output)["run_fingerprint"] == fingerprint(
        dem_identity(MINI.replace(seed=7), "preparation").fields
    )
    # the specimen of that run is not overwritten by another run without --restart
    cfg2 = tmp_path / "mini.json"
    cfg2.write_text(MINI.to_json())
    r = runner.invoke(cli, ["dem", "prepare", "--config", str(cfg2), "--out", str(out), "--json"])
    err = json.loads(r.output)["error"]
    assert r.exit_code == 1 and err["field"] == "--out" and "config.seed: 7" in err["message"]
    mode = stat.S_IMODE(out.stat().st_mode)
    umask = os.umask(0)
    os.umask(umask)
    assert mode == 0o666 & ~umask  # not the 0600 of a temporary file


def test_cli_penetrate_mismatch_json_error_and_restart(sample, tmp_path):
    runner = CliRunner()
    spec = tmp_path / "spec.nc"
    s = _lattice_sample()
    s.attrs["config"] = TINY.to_json()
    s.save(spec)
    cfg = tmp_path / "tiny.json"
    cfg.write_text(TINY.to_json())
    out = tmp_path / "r.nc"
    base = ["dem", "penetrate", "--sample", str(spec), "--out", str(out), "--no-progress"]
    r = runner.invoke(cli, [*base, "--config", str(cfg), "--max-steps", "300", "--json"])
    assert r.exit_code == 0, r.output
    assert (tmp_path / "r.checkpoint.nc").exists()
    fast = tmp_path / "fast.json"
    fast.write_text(
        TINY.replace(
            loading=Loading(gravity_factor=25.0, pipe_velocity=0.3, final_embedment_ratio=0.05)
        ).to_json()
    )
    r = runner.invoke(cli, [*base, "--config", str(fast), "--max-steps", "10", "--json"])
    assert r.exit_code == 1
    err = json.loads(r.output)["error"]
    assert err["type"] == "CheckpointMismatchError" and "pipe_velocity" in err["message"]
    assert (tmp_path / "r.checkpoint.nc").exists()
    r = runner.invoke(
        cli, [*base, "--config", str(fast), "--max-steps", "10", "--restart", "--json"]
    )
    assert r.exit_code == 0, r.output
    assert 0 < json.loads(r.output)["steps"] <= TINY.numerics.record_every  # started afresh
    # a specimen prepared for another configuration is refused, naming the differing field
    other = tmp_path / "other.json"
    other.write_text(TINY.replace(seed=11).to_json())
    r = runner.invoke(cli, [*base, "--config", str(other), "--json"])
    assert r.exit_code == 1
    err = json.loads(r.output)["error"]
    assert err["field"] == "sample" and "config.seed" in err["message"]
    for bad in (["--checkpoint-every", "0"], ["--max-steps", "-1"], ["--threads", "0"]):
        r = runner.invoke(cli, [*base, "--config", str(cfg), *bad, "--json"])
        assert r.exit_code == 1, bad
        assert json.loads(r.output)["error"]["field"] == bad[0]


def test_summaries_of_two_runs_of_one_preset_do_not_overwrite_each_other(sample, tmp_path):
    from onbottom.results import save_dataset

    runner = CliRunner()
    ds = penetrate(TINY, sample, max_steps=STEPS)
    for name in ("a.nc", "b.nc"):
        save_dataset(ds, tmp_path / name)
    outdir = tmp_path / "summ"
    args = ["dem", "summarize", "--outdir", str(outdir), "--json"]
    r = runner.invoke(cli, [*args, str(tmp_path / "a.nc"), str(tmp_path / "b.nc")])
    assert r.exit_code == 0, r.output
    names = sorted(p.name for p in outdir.glob("*_summary.nc"))
    assert names == ["tiny_a_summary.nc", "tiny_b_summary.nc"]
    r = runner.invoke(cli, [*args, str(tmp_path / "a.nc")])  # one run: the preset name
    assert json.loads(r.output)[0]["summary"].endswith("tiny_summary.nc")
    r = runner.invoke(cli, [*args, str(tmp_path / "b.nc")])  # another run, same preset
    assert json.loads(r.output)[0]["summary"].endswith("tiny_b_summary.nc")
    assert (outdir / "tiny_summary.nc").exists()


def test_guard_output_refuses_a_file_of_another_run_unless_restart(tmp_path):
    """dem.identity.guard_output (the check of 'dem prepare/penetrate --out'), as a library call."""
    from onbottom.dem.identity import guard_output, recorded_identity

    ident = dem_identity(SD_REDUCED, "preparation").fields
    out = tmp_path / "out.nc"
    guard_output(out, ident, restart=False, field="--out")  # no file: nothing to refuse
    out.write_text("not a result", encoding="utf-8")
    assert recorded_identity(out) is None
    with pytest.raises(InputError, match=r"--out = .* already holds a file without a run identity"):
        guard_output(out, ident, restart=False, field="--out")
    guard_output(out, ident, restart=True, field="--out")  # --restart replaces it
