"""Unit tests: parametric sweep (serial and on a real local Dask cluster)."""

from __future__ import annotations

import numpy as np
import pytest

from onbottom import InputError
from onbottom.results import load_dataset, save_dataset
from onbottom.study.sweep import sweep


def _paraboloid(a, b, c=0.0):
    if a < 0:
        raise ValueError("a must be >= 0")
    return {"f": (a - 1.0) ** 2 + (b + 2.0) ** 2 + c, "g": a * b}


def test_serial_sweep_values_dims_and_failures():
    ds = sweep(
        _paraboloid,
        {"a": [-1.0, 0.0, 1.0], "b": [-2.0, 0.5]},
        fixed={"c": 3.0},
        n_workers=0,
        progress=False,
    )
    assert ds["f"].dims == ("a", "b")
    assert ds["f"].sel(a=1.0, b=-2.0) == 3.0
    assert ds["g"].sel(a=1.0, b=0.5) == 0.5
    assert bool(ds["failed"].sel(a=-1.0).all())
    assert np.isnan(ds["f"].sel(a=-1.0)).all()
    assert "ValueError: a must be >= 0" in str(ds["error"].sel(a=-1.0, b=0.5).item())
    assert str(ds["error"].sel(a=0.0, b=0.5).item()) == ""
    assert ds.attrs["n_failed"] == 2 and ds.attrs["n_points"] == 6


def test_seeded_streams_are_reproducible_and_independent():
    def noisy(x, rng):
        return float(rng.normal())

    one = sweep(noisy, {"x": np.arange(5.0)}, seed=42, n_workers=0, progress=False)
    two = sweep(noisy, {"x": np.arange(5.0)}, seed=42, n_workers=0, progress=False)
    other = sweep(noisy, {"x": np.arange(5.0)}, seed=43, n_workers=0, progress=False)
    np.testing.assert_array_equal(one["value"], two["value"])
    assert not np.allclose(one["value"], other["value"])
    assert len(np.unique(one["value"])) == 5


def test_non_scalar_output_is_recorded_as_failure(tmp_path):
    def vector(x):
        return {"y": np.array([x, x])}

    ds = sweep(vector, {"x": [1.0, 2.0]}, n_workers=0, progress=False)
    assert bool(ds["failed"].all())
    assert "not a scalar" in str(ds["error"].values[0])
    back = load_dataset(save_dataset(ds, tmp_path / "s.nc"))
    assert str(back["error"].values[0]) == str(ds["error"].values[0])


def test_invalid_grid_rejected():
    with pytest.raises(InputError, match="repeat"):
        sweep(_paraboloid, {"a": [1.0, 1.0], "b": [0.0]}, n_workers=0, progress=False)
    with pytest.raises(InputError, match="both give"):
        sweep(_paraboloid, {"a": [1.0], "b": [0.0]}, fixed={"a": 1}, n_workers=0)


@pytest.mark.dask
def test_dask_cluster_two_workers_matches_serial():
    """A real LocalCluster (2 worker processes on 127.0.0.1) gives the serial results."""
    from onbottom.study.engine import dask_client

    def f(a, b, rng):
        if a == b:
            raise RuntimeError("diagonal")
        return {"s": a * 10 + b + rng.uniform()}

    grid = {"a": np.arange(6.0), "b": np.arange(7.0)}
    serial = sweep(f, grid, seed=5, n_workers=0, progress=False)
    trim = __import__("os").environ.get("MALLOC_TRIM_THRESHOLD_")  # before a nanny sets it
    with dask_client(n_workers=2) as client:
        env = client.run(lambda: __import__("os").environ.get("NUMBA_NUM_THREADS"))
        assert set(env.values()) == {"1"} and len(env) == 2
        # glibc's allocator defaults: Dask's MALLOC_TRIM_THRESHOLD_ is not set in the workers
        malloc = client.run(lambda: __import__("os").environ.get("MALLOC_TRIM_THRESHOLD_"))
        assert set(malloc.values()) == {trim}
        assert all("127.0.0.1" in addr for addr in env)
        parallel = sweep(f, grid, seed=5, client=client, batch_size=4, progress=False)
        # the same cluster reached by address, as a remote scheduler would be
        remote = sweep(f, grid, seed=5, scheduler_address=client.scheduler.address, progress=False)
    np.testing.assert_array_equal(remote["s"].values, serial["s"].values)
    np.testing.assert_array_equal(parallel["s"].values, serial["s"].values)
    np.testing.assert_array_equal(parallel["failed"].values, serial["failed"].values)
    assert parallel.attrs["n_failed"] == 6 and parallel.attrs["engine"] == "dask"
    assert "RuntimeError: diagonal" in str(parallel["error"].sel(a=2.0, b=2.0).item())


# --------------------------------------------------------------------------------------------
# registry and failures (issue #10)
# --------------------------------------------------------------------------------------------
def _fails_above(*, x: float, limit: float = 1.5) -> dict[str, float]:
    if x > limit:
        raise ValueError(f"x = {x} above {limit}")
    return {"y": 2.0 * x}


def test_registry_runs_only_registered_names():
    from onbottom.errors import InputError
    from onbottom.study.functions import get_function, register, registered

    register("test_fails_above", _fails_above, replace=True)
    assert get_function("test_fails_above") is _fails_above
    assert "centrifuge_response" in registered()
    for bad in ("subprocess:getoutput", "os.system", "test_fails_abov"):
        with pytest.raises(InputError, match="not a registered function"):
            get_function(bad)
    with pytest.raises(InputError, match="no ':'"):
        register("pkg.mod:fn", _fails_above)
    with pytest.raises(InputError, match="already registered"):
        register("test_fails_above", lambda **_: 0.0)


@pytest.mark.parametrize(
    ("values", "flags", "code", "n_failed"),
    [
        ("[1.0]", [], 0, 0),
        ("[1.0, 2.0]", [], 3, 1),
        ("[1.0, 2.0]", ["--allow-failures"], 0, 1),
        ("[2.0, 3.0]", ["--allow-failures"], 3, 2),  # every run failed: never a success
    ],
)
def test_sweep_command_exit_status_follows_failures(tmp_path, values, flags, code, n_failed):
    import json

    from click.testing import CliRunner

    from onbottom.cli.main import cli
    from onbottom.study.functions import register

    register("test_fails_above", _fails_above, replace=True)
    grid = tmp_path / "g.toml"
    grid.write_text(f'[sweep]\nfunction = "test_fails_above"\n[grid]\nx = {values}\n')
    out = tmp_path / "o.nc"
    args = ["sweep", str(grid), "-o", str(out), "--workers", "0", "--json", *flags]
    r = CliRunner().invoke(cli, args)
    assert r.exit_code == code, r.output
    summary = json.loads(r.stdout)
    assert summary["n_failed"] == n_failed and out.exists()  # results kept for diagnosis
    assert summary["success"] is (n_failed == 0)
