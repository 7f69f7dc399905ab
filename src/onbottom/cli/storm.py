"""``onbottom storm``: dynamic on-bottom stability of a pipe section (or a pipeline) in a storm.

A case file with a ``[pipeline]`` table is built by :mod:`onbottom.cases.pipeline` and run by
the pipeline FE (:func:`onbottom.study.pipeline_seeds.run_pipeline_seeds`); otherwise
the rigid section is simulated (:func:`onbottom.dynamics.storm_section.simulate_storm_section`)
for one seed, or for ``--seeds N`` seeds on Dask with statistics of the maximum displacement.
"""

from __future__ import annotations

import warnings
from pathlib import Path
from typing import Any

import click

from onbottom.cli._common import (
    EXIT_INVALID_RESULT,
    FIGURE_SUFFIXES,
    Number,
    check_output_names,
    check_output_path,
    emit_json,
    handle_errors,
    json_option,
    log_to_stderr,
)
from onbottom.errors import InputError, OutOfRangeWarning


def _run_pipeline(
    case: Path,
    *,
    seeds: int | None,
    scheduler: str | None,
    workers: int | None,
    output: Path | None,
    plot: Path | None,
    progress: bool,
    restart: bool,
    force: bool,
) -> dict[str, Any]:
    """The pipeline FE: build the case, check the seeds' budget, run, draw."""
    from onbottom.cases.pipeline import load_pipeline_run
    from onbottom.study import budget
    from onbottom.study.pipeline_seeds import (
        estimate_pipeline_seeds,
        pipeline_seed_count,
        run_pipeline_seeds,
    )

    run = load_pipeline_run(case)
    if seeds is not None and seeds > 1 and not force:
        budget.check(estimate_pipeline_seeds(run, seeds, workers), force=False, field="--seeds")
    n = pipeline_seed_count(run, seeds)
    if n > 1 and plot is not None:
        raise InputError("--plot/animation are for one seed: run the seed of interest alone")
    study = run_pipeline_seeds(
        run,
        output=output if output is not None else case.with_suffix(".nc"),
        seeds=n,
        progress=progress,
        scheduler=scheduler,
        workers=workers,
        restart=restart,
    )
    res = study.result
    if res is None:  # several seeds: no figure
        return study.to_dict()
    plot_file = None
    if plot is not None:
        import matplotlib.pyplot as plt

        from onbottom.plotting.pipeline import plot_pipeline_result
        from onbottom.results import save_figure

        fig = plot_pipeline_result(res, title=f"{case.stem}: {res.message}")
        save_figure(fig, plot, dpi=110)
        plt.close(fig)
        plot_file = str(plot)
    anim_file = None
    if run.animation is not None:
        from onbottom.plotting.pipeline import animate_pipeline

        animate_pipeline(res, run.animation)
        anim_file = str(run.animation)
    return study.to_dict(plot=plot_file, animation=anim_file)


@click.command("storm")
@click.argument("case", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option(
    "--seeds",
    type=Number(int, min=1, max=100000),
    default=None,
    help="Number of storms (seeds storm.seed, storm.seed + 1, ...); default [run] seeds.",
)
@click.option(
    "--scheduler",
    default=None,
    metavar="ADDRESS",
    help="Dask scheduler address (tcp://host:8786); default a local cluster.",
)
@click.option(
    "--workers",
    type=Number(int, min=0, max=1024),
    default=None,
    help="Local Dask worker processes (default one per core; 0 = in this process).",
)
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="NetCDF file (default: CASE with suffix .nc): time series, or per-seed results.",
)
@click.option(
    "--plot",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="Figure (png, pdf, svg): y–t, z–t, H–y and V–H (one seed only).",
)
@click.option("--quiet", is_flag=True, help="No progress bar.")
@click.option(
    "--force",
    is_flag=True,
    help="Run even when the estimated time or memory of the seeds exceeds the budget"
    " (onbottom.study.budget: 12 h, 8 GB).",
)
@click.option(
    "--restart",
    is_flag=True,
    help="Discard what an interrupted run kept (seeds done, pipeline checkpoint) and start afresh.",
)
@json_option
@handle_errors
def command(
    case: Path,
    seeds: int | None,
    scheduler: str | None,
    workers: int | None,
    output: Path | None,
    plot: Path | None,
    quiet: bool,
    force: bool,
    restart: bool,
    as_json: bool,
) -> None:
    """Simulate a pipe section on the seabed through a storm (CASE: TOML file).

    The storm is [waves] as the peak after a 0.5 h build-up, 3 h at the peak (or
    [[storm.stages]]), or a regular wave ([storm] kind = "regular", height, period) or a
    measured velocity record ([storm] kind = "measured", series = CSV); [current], [seabed]
    (sand: Verley & Sotberg, clay: Verley & Lund, rock: Coulomb), [hydro] coefficients and
    F109 load reductions. Reports the maximum and final lateral displacement and the
    DNV-RP-F109 verdicts against 0.5D and 10D; a run whose penetration left the soil model's
    range (z > D/2) is flagged (status -3, exit code 3). See examples/storm_case.toml.


    Interrupted (Ctrl-C, a kill), the same command resumes: with --seeds the finished seeds
    are kept one file each in OUTPUT.tasks/, a pipeline run resumes from its checkpoint;
    --restart starts afresh. Results are written under a temporary name and renamed when
    complete.
    """
    with log_to_stderr(not as_json):
        _command(case, seeds, scheduler, workers, output, plot, quiet, force, restart, as_json)


def _command(
    case: Path,
    seeds: int | None,
    scheduler: str | None,
    workers: int | None,
    output: Path | None,
    plot: Path | None,
    quiet: bool,
    force: bool,
    restart: bool,
    as_json: bool,
) -> None:
    """Check the output names, then run the pipeline FE or the section (one seed or many)."""
    from onbottom.cases.pipeline import is_pipeline_case

    progress = not quiet and not as_json
    check_output_names(
        case,
        [
            ("--output", output if output is not None else case.with_suffix(".nc"), (".nc",)),
            ("--plot", plot, FIGURE_SUFFIXES),
        ],
    )
    if is_pipeline_case(case):
        _pipeline_command(
            case,
            seeds=seeds,
            scheduler=scheduler,
            workers=workers,
            output=output,
            plot=plot,
            progress=progress,
            restart=restart,
            force=force,
            as_json=as_json,
        )
        return

    from onbottom.cases.storm import load_storm_setup

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", OutOfRangeWarning)
        setup = load_storm_setup(case)
    notes = _split_warnings(caught, as_json)
    n = setup.seeds if seeds is None else int(seeds)
    if n > 1 and not hasattr(setup.storm, "with_seed"):
        raise _seeds_error(n)
    nc = output if output is not None else case.with_suffix(".nc")
    check_output_path(nc, field="--output")
    if n == 1:
        _one_seed(case, setup, nc, plot=plot, progress=progress, notes=notes, as_json=as_json)
    else:
        _many_seeds(
            setup,
            nc,
            n,
            scheduler=scheduler,
            workers=workers,
            progress=progress,
            restart=restart,
            force=force,
            notes=notes,
            as_json=as_json,
        )


def _pipeline_command(case: Path, *, as_json: bool, **options: Any) -> None:
    """The pipeline FE case: run it with its warnings caught, report, exit 3 if not valid."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", OutOfRangeWarning)
        payload = _run_pipeline(case, **options)
    notes = _split_warnings(caught, as_json)
    if isinstance(payload, dict):
        payload["warnings"] = notes
        _report(payload, as_json)
        if not payload.get("success", True):
            # as the section: a failed or flagged run (e.g. status −3, outside the soil
            # model's range) exits with EXIT_INVALID_RESULT
            raise click.exceptions.Exit(EXIT_INVALID_RESULT)


def _one_seed(
    case: Path,
    setup: Any,
    nc: Path,
    *,
    plot: Path | None,
    progress: bool,
    notes: list[str],
    as_json: bool,
) -> None:
    """One storm on the rigid section: simulate, save, draw, report; exit by its status."""
    from onbottom.dynamics.storm_section import simulate_storm_section

    res = simulate_storm_section(
        setup.pipe,
        setup.soil,
        setup.storm,
        progress=progress,
        attrs={"case_file": str(case)},
        **setup.kwargs(),
    )
    res.save(nc, compression_level=setup.compression_level)
    if plot is not None:
        import matplotlib.pyplot as plt

        from onbottom.plotting.storm import plot_storm_result
        from onbottom.results import save_figure

        check_output_path(plot, field="--plot")
        fig = plot_storm_result(res, title=f"{case.stem}: {res.message}")
        save_figure(fig, plot, dpi=110)
        plt.close(fig)
    payload = {
        **res.to_dict(),
        "mean_max_displacement_m": res.to_dict().get("max_displacement_m"),
        "seeds": 1,
        "seed": setup.storm.seed,
        "diameter_m": res.diameter,
        "netcdf": str(nc),
        "plot": None if plot is None else str(plot),
        "warnings": notes,
    }
    _report(payload, as_json)
    if res.exit_code:
        raise click.exceptions.Exit(res.exit_code)


def _many_seeds(
    setup: Any,
    nc: Path,
    n: int,
    *,
    scheduler: str | None,
    workers: int | None,
    progress: bool,
    restart: bool,
    force: bool,
    notes: list[str],
    as_json: bool,
) -> None:
    """``n`` storms on Dask: check the budget, run (resumable task store), save, report."""
    from onbottom.results import TaskStore, save_dataset
    from onbottom.study import budget
    from onbottom.study.storm_seeds import run_storm_seeds

    budget.check(
        budget.section_storms(
            n,
            float(setup.storm.duration_s),
            setup.settings.dt_max,
            tp=max(s.tp for s in setup.storm.stages),
            workers=workers,
        ),
        force=force,
        field="--seeds",
    )

    store = nc.with_name(nc.name + ".tasks")
    study = run_storm_seeds(
        setup.pipe,
        setup.soil,
        setup.storm,
        seeds=n,
        fractile=setup.fractile,
        n_workers=workers,
        scheduler=scheduler,
        progress=progress,
        store=store,
        restart=restart,
        **setup.kwargs(),
    )
    save_dataset(study.data, nc, compression_level=setup.compression_level)
    TaskStore.delete(store)  # the result holds every seed now
    payload = {**study.to_dict(), "netcdf": str(nc), "warnings": notes}
    _report(payload, as_json)
    if not study.success:
        raise click.exceptions.Exit(EXIT_INVALID_RESULT)


def _seeds_error(n: int) -> InputError:
    err = InputError(
        f"--seeds = {n} is invalid with a regular wave or a measured record ([storm] kind):"
        " the flow is deterministic, run one seed"
    )
    err.field = "--seeds"  # type: ignore[attr-defined]
    return err


def _split_warnings(caught: list[warnings.WarningMessage], as_json: bool) -> list[str]:
    """Messages of the :class:`OutOfRangeWarning` s caught (echoed to stderr without --json);
    other warnings are re-issued as usual."""
    notes = sorted({str(w.message) for w in caught if issubclass(w.category, OutOfRangeWarning)})
    for w in caught:
        if not issubclass(w.category, OutOfRangeWarning):
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    if not as_json:
        for note in notes:
            click.echo(f"warning: {note}", err=True)
    return notes


def _report(payload: dict[str, Any], as_json: bool) -> None:
    if as_json:
        emit_json(payload)
        return
    click.echo(payload.get("message", ""))
    d = payload.get("diameter_m")
    shown = [("max |y|", "max_displacement_m")]
    if (payload.get("seeds") or 1) > 1:  # the worst seed, then the seed mean
        shown = [("max |y| (worst)", "max_displacement_m")]
        shown.append(("mean of seed max", "mean_max_displacement_m"))
    for label, key in shown:
        if payload.get(key) is not None:
            tail = f" ({payload[key] / d:.3g}D)" if d else ""
            click.echo(f"  {label:<20} {payload[key]:.4g} m{tail}")
    if payload.get("final_displacement_m") is not None:
        click.echo(f"  final y (|y| mean)   {payload['final_displacement_m']:.4g} m")
    for k, v in (payload.get("criteria") or {}).items():
        click.echo(f"  F109 {k:>4} criterion  {'PASS' if v else 'FAIL'}")
    if payload.get("netcdf"):
        click.echo(
            f"  written: {payload['netcdf']}"
            + (f", {payload['plot']}" if payload.get("plot") else "")
        )
