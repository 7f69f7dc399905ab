"""``onbottom sweep``: run a parametric sweep described by a grid TOML file.

Grid file (see ``examples/sweep_grid.toml``)::

    [sweep]
    function = "centrifuge_response"   # built-in name, or "package.module:callable"
    seed = 1                           # optional: per-point random streams
    batch_size = 2                     # optional: runs per Dask task

    [grid]                             # one dimension per entry, in this order
    A = [0.15, 0.25, 0.35]
    B = { start = 0.2, stop = 0.5, num = 4 }     # numpy.linspace
    mu = { values = [0.48, 0.85] }

    [fixed]                            # keyword arguments passed to every run
    test = "inclined_1"

Built-in functions: ``centrifuge_response`` (:func:`onbottom.study.functions.centrifuge_response`)
and ``misfit`` (:func:`onbottom.calibration.fit.record_misfit`; ``[fixed] record = "path"`` is
loaded as a :class:`~onbottom.calibration.records.TestRecord`, relative to the grid file).
"""

from __future__ import annotations

import importlib
import tomllib
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import click
import numpy as np

from onbottom.cli._common import emit_json, handle_errors, json_option
from onbottom.errors import InputError

BUILTINS = {
    "centrifuge_response": "onbottom.study.functions:centrifuge_response",
    "misfit": "onbottom.calibration.fit:record_misfit",
}


def resolve_function(spec: str) -> Callable[..., Any]:
    """``"module:attr"`` (or a built-in name) → the callable."""
    target = BUILTINS.get(spec, spec)
    if ":" not in target:
        raise InputError(
            f"sweep.function = {spec!r} is invalid: use a built-in ({', '.join(BUILTINS)})"
            " or 'package.module:callable'"
        )
    mod_name, attr = target.split(":", 1)
    try:
        fn = getattr(importlib.import_module(mod_name), attr)
    except (ImportError, AttributeError) as exc:
        raise InputError(f"sweep.function = {spec!r} cannot be imported: {exc}") from exc
    if not callable(fn):
        raise InputError(f"sweep.function = {spec!r} is not callable")
    return fn


def _axis(name: str, spec: Any) -> list[Any]:
    if isinstance(spec, list):
        return spec
    if isinstance(spec, Mapping):
        if "values" in spec:
            return list(spec["values"])
        if {"start", "stop", "num"} <= set(spec):
            return np.linspace(float(spec["start"]), float(spec["stop"]), int(spec["num"])).tolist()
    raise InputError(
        f"grid.{name} = {spec!r} is invalid: expected a list, {{values = [...]}} or"
        " {start, stop, num}"
    )


def read_grid(path: str | Path) -> dict[str, Any]:
    """Parse a grid TOML file into ``function``, ``grid``, ``fixed`` and options."""
    p = Path(path)
    try:
        doc = tomllib.loads(p.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{p}: invalid TOML: {exc}") from exc
    sw = doc.get("sweep", {})
    if "function" not in sw:
        raise InputError(f"{p}: [sweep] function is missing")
    if not doc.get("grid"):
        raise InputError(f"{p}: [grid] is missing or empty")
    fn_spec = str(sw["function"])
    fixed = dict(doc.get("fixed", {}))
    if fn_spec == "misfit":
        from onbottom.calibration.records import load_record

        if "record" not in fixed:
            raise InputError(f"{p}: function 'misfit' needs [fixed] record = 'path'")
        rec_path = Path(fixed["record"])
        if not rec_path.is_absolute():
            rec_path = p.parent / rec_path
        fixed["record"] = load_record(rec_path)
    return {
        "function": resolve_function(fn_spec),
        "function_name": fn_spec,
        "grid": {k: _axis(k, v) for k, v in doc["grid"].items()},
        "fixed": fixed,
        "seed": sw.get("seed"),
        "batch_size": sw.get("batch_size"),
    }


@click.command("sweep")
@click.argument("grid_file", type=click.Path(exists=True, dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), required=True, help="NetCDF out.")
@click.option("--scheduler", help="Address of a running Dask scheduler.")
@click.option(
    "--workers",
    type=int,
    default=None,
    help="Local worker processes (default one per core; 0 = serial, no Dask).",
)
@click.option("--no-progress", is_flag=True, help="Hide the progress bar.")
@json_option
@handle_errors
def command(grid_file, output, scheduler, workers, no_progress, as_json):
    """Run the sweep of GRID_FILE (TOML) and write the results to NetCDF."""
    from onbottom.results import save_dataset
    from onbottom.study.sweep import sweep

    spec = read_grid(grid_file)
    ds = sweep(
        spec["function"],
        spec["grid"],
        fixed=spec["fixed"],
        scheduler_address=scheduler,
        n_workers=workers,
        seed=spec["seed"],
        batch_size=spec["batch_size"],
        progress=not (no_progress or as_json),
    )
    ds.attrs["grid_file"] = str(grid_file)
    ds.attrs["function"] = spec["function_name"]
    save_dataset(ds, output)
    summary = {
        "output": str(output),
        "dims": {k: int(v) for k, v in ds.sizes.items()},
        "variables": [str(v) for v in ds.data_vars],
        "n_points": int(ds.attrs["n_points"]),
        "n_failed": int(ds.attrs["n_failed"]),
        "wall_time": float(ds.attrs["wall_time"]),
    }
    if as_json:
        emit_json(summary)
        return
    click.echo(
        f"{summary['n_points']} runs ({summary['n_failed']} failed) in"
        f" {summary['wall_time']:.1f} s → {output}"
    )
