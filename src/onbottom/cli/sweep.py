"""``onbottom sweep``: run a parametric sweep described by a grid TOML file.

Grid file format, the registered functions and the checks: :mod:`onbottom.cases.sweep`
(example: ``examples/sweep_grid.toml``). The command exits with status 3 when some runs
failed (the results, with ``failed`` and ``error``, are still written), unless
``--allow-failures``; always when every run failed.
"""

from __future__ import annotations

import click
import numpy as np

from onbottom.cli._common import (
    EXIT_INVALID_RESULT,
    Number,
    check_output_path,
    emit_json,
    handle_errors,
    json_option,
)


@click.command("sweep")
@click.argument("grid_file", type=click.Path(exists=True, dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), required=True, help="NetCDF out.")
@click.option("--scheduler", help="Address of a running Dask scheduler.")
@click.option(
    "--workers",
    type=Number(int, min=0, max=1024),
    default=None,
    help="Local worker processes (default one per core; 0 = serial, no Dask).",
)
@click.option(
    "--allow-failures",
    is_flag=True,
    help="Exit 0 when some (not all) runs failed (default: exit status 3).",
)
@click.option("--no-progress", is_flag=True, help="Hide the progress bar.")
@click.option(
    "--force",
    is_flag=True,
    help="Run even when the estimated time or memory exceeds the budget"
    " (onbottom.study.budget: 12 h, 8 GB).",
)
@json_option
@handle_errors
def command(grid_file, output, scheduler, workers, allow_failures, no_progress, force, as_json):
    """Run the sweep of GRID_FILE (TOML) and write the results to NetCDF.

    The grid's run time and memory are estimated first (about 1 s per point on one core);
    beyond the budget (12 h, 8 GB) the sweep is refused unless --force.
    """
    import math

    from onbottom.cases.sweep import read_grid
    from onbottom.results import save_dataset
    from onbottom.study import budget
    from onbottom.study.sweep import sweep

    check_output_path(output, field="--output")
    spec = read_grid(grid_file)
    n_points = math.prod(len(v) for v in spec["grid"].values())
    budget.check(budget.sweep_points(n_points, workers=workers), force=force, field="[grid]")
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
    n_points = int(ds.attrs["n_points"])
    n_failed = int(ds.attrs["n_failed"])
    errors = sorted({str(e) for e in np.ravel(ds["error"].values) if str(e)})
    summary = {
        "success": n_failed == 0,
        "output": str(output),
        "dims": {k: int(v) for k, v in ds.sizes.items()},
        "variables": [str(v) for v in ds.data_vars],
        "n_points": n_points,
        "n_failed": n_failed,
        "errors": errors[:10],
        "wall_time": float(ds.attrs["wall_time"]),
    }
    failed = n_failed == n_points or (n_failed > 0 and not allow_failures)
    if as_json:
        emit_json(summary)
    else:
        click.echo(
            f"{n_points} runs ({n_failed} failed) in {summary['wall_time']:.1f} s → {output}"
        )
        for e in errors[:5]:
            click.echo(f"  failure: {e}", err=True)
        if failed:
            click.echo(
                "Error: "
                + (
                    "every run failed"
                    if n_failed == n_points
                    else f"{n_failed} of {n_points} runs failed (--allow-failures to accept)"
                ),
                err=True,
            )
    if failed:
        raise click.exceptions.Exit(EXIT_INVALID_RESULT)
