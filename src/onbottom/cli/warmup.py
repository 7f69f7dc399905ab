"""``onbottom warmup``: compile the numba kernels once, so that the first real run is warm.

Computation: :func:`onbottom.study.warmup.warm_kernels`; this module prints the progress
lines (stderr) and the totals, or writes JSON."""

from __future__ import annotations

import click

from onbottom.cli._common import emit_json, handle_errors, json_option
from onbottom.errors import RunInterrupted
from onbottom.study.warmup import TARGETS

__all__ = ["command"]


@click.command("warmup")
@click.option(
    "--only",
    "only",
    multiple=True,
    type=click.Choice([t.name for t in TARGETS]),
    help="Compile only this kernel group (repeatable; default: all).",
)
@click.option(
    "--processes",
    type=click.IntRange(min=1),
    default=None,
    help="Worker processes (default: one per core, at most one per kernel group).",
)
@click.option("--quiet", is_flag=True, help="No progress lines on stderr.")
@json_option
@handle_errors
def command(only: tuple[str, ...], processes: int | None, quiet: bool, as_json: bool) -> None:
    """Compile the numba kernels of storm, assess, pipeline and section runs into the cache.

    Run once after an install or an update (the README's set-up command does): numba compiles
    each kernel on its first call, which costs a first ``onbottom storm`` 5 s, a first
    ``assess`` 6 s and a first pipeline run 10 s of CPU; after the warm-up they load the
    kernels from numba's cache. Compiles the storm-section kernel for sand/calcareous, clay
    and rock seabeds and the pipeline FE kernel for sand and clay, each with the Morison and
    the wake force models, and the centrifuge-section kernel, each group by running a tiny
    problem, in parallel processes. A second run finds everything cached and takes a few
    seconds. Other models (Fourier forces, the V–H soil model, rock under a pipeline, mixed
    soils along a line) still compile on their first use.
    """
    from onbottom.study.warmup import estimate, warm_kernels

    def progress(k: int, n: int, target) -> None:
        if quiet:
            return
        if k == 1:  # what it will cost, before the first compile starts
            cpu, wall, workers = estimate(only or None, processes=processes)
            click.echo(
                f"onbottom warmup: compiling {n} kernel group{'s' if n != 1 else ''} on"
                f" {workers} process{'es' if workers > 1 else ''}: about {cpu:.0f} CPU-s,"
                f" {wall:.0f} s on free cores (longer on a busy machine; seconds for groups"
                " already cached) ...",
                err=True,
            )
        click.echo(f"onbottom warmup: compiling {target.title} ({k}/{n}) ...", err=True)

    try:
        report = warm_kernels(only or None, processes=processes, progress=progress)
    except KeyboardInterrupt:
        raise RunInterrupted(
            "interrupted: the kernels compiled so far stay in numba's cache; run onbottom"
            " warmup again to compile the rest"
        ) from None
    if as_json:
        emit_json(
            {
                "targets": [
                    {
                        "name": t.target.name,
                        "title": t.target.title,
                        "wall_s": t.wall_s,
                        "cpu_s": t.cpu_s,
                        "compiled": t.compiled,
                    }
                    for t in report.targets
                ],
                "wall_s": report.wall_s,
                "cpu_s": report.cpu_s,
                "compiled": report.compiled,
                "processes": report.processes,
            }
        )
        return
    n = len(report.targets)
    w = max((len(t.target.name) for t in report.targets), default=0)
    for t in report.targets:
        state = f"{t.compiled} compiled" if t.compiled else "already cached"
        click.echo(f"{t.target.name:<{w}} {t.wall_s:6.1f} s  ({t.cpu_s:.1f} CPU-s, {state})")
    click.echo(
        f"warm-up done: {n} kernel group{'s' if n != 1 else ''} in {report.wall_s:.1f} s"
        f" ({report.cpu_s:.1f} CPU-s on {report.processes} process"
        f"{'es' if report.processes > 1 else ''}); later runs load them from numba's cache"
    )
