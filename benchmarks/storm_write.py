"""Output cheaper than the physics: a storm's NetCDF write against its integration, by engine.

One 3.5-h storm on a pipe section (0.5 h build-up + 3 h peak, the sand and pipe of
``storm_section.py``), recorded every ``--record-interval`` seconds (default 0.5 s, the storm
case's), integrated ``--repeat`` times (best process CPU time kept), then its records written
``--repeat`` times by each writer, best CPU time kept (CPU time: the machine is shared):

- ``save_dataset`` — what every onbottom result goes through (the direct NetCDF-4 writer,
  deflate by ISA-L when ``isal`` is installed), plain and at compression level 4;
- xarray's h5netcdf store (what ``save_dataset`` used before the direct writer), plain and
  zlib level 4;
- xarray's netCDF4 engine, when the ``netCDF4`` package is installed (it is not a
  dependency; the line says so otherwise);
- zarr (a folder store; not NetCDF), with no compressor and with zarr's default.

Each line prints the write / integration ratio against the target ≤ 0.5 (issue: "a storm's
NetCDF write ≤ 0.5× its integration, compressed too"), the file size, and the load average.

Run: ``PYTHONPATH=src python benchmarks/storm_write.py [--repeat 5] [--smoke]``
(``--smoke``: a 10-minute storm, one repeat: checks that it runs and prints).
"""

from __future__ import annotations

import argparse
import os
import shutil
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import xarray as xr

from onbottom.dynamics.storm_section import StormSolverSettings, simulate_storm_section
from onbottom.hydro.storm_kinematics import storm_kinematics
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.inputs.storm import Current, SeaState, Storm
from onbottom.results import netcdf_encoding, save_dataset
from onbottom.results._nc4write import deflate_name
from onbottom.soil.verley_sotberg import VerleySotberg

TARGET = 0.5


def _best_cpu(fn: Callable[[], object], repeat: int) -> float:
    times = []
    for _ in range(repeat):
        c0 = time.process_time()
        fn()
        times.append(time.process_time() - c0)
    return min(times)


def _size(path: Path) -> float:
    if path.is_dir():
        return sum(p.stat().st_size for p in path.rglob("*") if p.is_file()) / 1e6
    return path.stat().st_size / 1e6


def _writers(ds: xr.Dataset, tmp: Path) -> list[tuple[str, Path, Callable[[], object] | str]]:
    def h5netcdf_store(path: Path, level: int) -> Callable[[], object]:
        from xarray.backends import H5NetCDFStore

        enc = netcdf_encoding(ds, level)

        def write() -> None:
            store = H5NetCDFStore.open(str(path), mode="w", lock=False)
            try:
                ds.dump_to_store(store, encoding=enc)
            finally:
                store.close()

        return write

    def netcdf4(path: Path, level: int) -> Callable[[], object] | str:
        try:
            import netCDF4  # noqa: F401
        except ImportError:
            return "netCDF4 not installed (not a dependency of onbottom)"
        enc = netcdf_encoding(ds, level)
        return lambda: ds.to_netcdf(path, engine="netcdf4", encoding=enc)

    def zarr(path: Path, default_compressor: bool) -> Callable[[], object] | str:
        try:
            import zarr as _zarr  # noqa: F401
        except ImportError:
            return "zarr not installed"
        enc = {} if default_compressor else {k: {"compressors": None} for k in ds.data_vars}

        def write() -> None:
            shutil.rmtree(path, ignore_errors=True)
            ds.to_zarr(path, mode="w", encoding=enc, consolidated=False)

        return write

    return [
        ("save_dataset, plain", tmp / "a0.nc", lambda: save_dataset(ds, tmp / "a0.nc")),
        (
            f"save_dataset, level 4 ({deflate_name()})",
            tmp / "a4.nc",
            lambda: save_dataset(ds, tmp / "a4.nc", compression_level=4),
        ),
        ("xarray h5netcdf store, plain", tmp / "h0.nc", h5netcdf_store(tmp / "h0.nc", 0)),
        ("xarray h5netcdf store, zlib 4", tmp / "h4.nc", h5netcdf_store(tmp / "h4.nc", 4)),
        ("xarray netCDF4 engine, plain", tmp / "n0.nc", netcdf4(tmp / "n0.nc", 0)),
        ("xarray netCDF4 engine, zlib 4", tmp / "n4.nc", netcdf4(tmp / "n4.nc", 4)),
        ("zarr, no compressor", tmp / "z0.zarr", zarr(tmp / "z0.zarr", False)),
        ("zarr, default compressor", tmp / "z1.zarr", zarr(tmp / "z1.zarr", True)),
    ]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--record-interval", type=float, default=0.5, help="output rows [s]")
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    pipe = Pipe(outer_diameter=0.3951, submerged_weight=1500.0)
    soil = VerleySotberg.silica(pipe, Sand(submerged_unit_weight=10e3))
    storm = Storm.standard(SeaState(hs=4.68, tp=10.8, gamma=1.009, spreading_s=8.0))
    if args.smoke:
        args.repeat = 1
        storm = Storm(stages=(SeaState(hs=4.68, tp=10.8, duration_s=600.0),))
    current = Current(velocity=0.91, z0=5.2e-6)
    kin = storm_kinematics(storm.with_seed(0), 13.0, diameter=0.3951, current=current)
    settings = StormSolverSettings(dt_max=0.1, record_interval=args.record_interval)
    simulate_storm_section(pipe, soil, kin, settings=settings)  # compiled or loaded
    result: list = []
    integration = _best_cpu(
        lambda: result.append(simulate_storm_section(pipe, soil, kin, settings=settings)),
        args.repeat,
    )
    ds = result[-1].data
    load0 = os.getloadavg()[0]
    print(
        f"storm {storm.duration_s / 3600:.2f} h, records every {args.record_interval:g} s:"
        f" {ds.sizes['time']} rows x {len(ds.data_vars)} variables ({ds.nbytes / 1e6:.2f} MB);"
        f" integration {integration:.4f} CPU-s (best of {args.repeat})"
    )
    with tempfile.TemporaryDirectory(prefix="onbottom-write-") as tmp:
        for name, path, write in _writers(ds, Path(tmp)):
            if isinstance(write, str):
                print(f"  {name:<36} not measured: {write}")
                continue
            write()  # first call: imports, file creation
            cpu = _best_cpu(write, args.repeat)
            ratio = cpu / integration
            verdict = "met" if ratio <= TARGET else "NOT met"
            print(
                f"  {name:<36} {cpu:7.4f} CPU-s  {_size(path):6.2f} MB"
                f"  write/integration {ratio:5.2f}  target <= {TARGET}: {verdict}"
            )
    la = os.getloadavg()
    print(f"load average {load0:.2f} at the start; now {la[0]:.2f} {la[1]:.2f} {la[2]:.2f}")


if __name__ == "__main__":
    main()
