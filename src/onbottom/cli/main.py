"""``onbottom`` command-line entry point.

Each command group lives in its own module of this package and exposes ``command`` (a click
command or group); :data:`COMMANDS` names them with their short help, and a command's module
is imported only when it runs (``onbottom --help`` imports none).
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import time
from typing import Any, TextIO

import click
from click.utils import make_default_short_help

from onbottom._version import __version__
from onbottom.cli._common import JsonErrorGroup, report_click_error, report_interrupt

COMMANDS: dict[str, tuple[str, str]] = {
    "reproduce": (
        "reproduce",
        "Reproduce the seven Youssef (2012) centrifuge tests (Youssef & Cassidy 2014).",
    ),
    "simulate": ("simulate", "Simulate a pipe section under a load programme (CASE: TOML file)."),
    "calibrate": (
        "calibrate",
        "Fit the calcareous Verley & Sotberg parameters to test RECORDS (CSV or NetCDF).",
    ),
    "sweep": ("sweep", "Run the sweep of GRID_FILE (TOML) and write the results to NetCDF."),
    "backbone": (
        "backbone",
        "Backbone of the Verley & Sotberg model: region limits, forces, penetrations.",
    ),
    "penetration": (
        "penetration",
        "DNVGL-RP-F114 vertical penetration resistance Q_v(z) and the embedment for a load.",
    ),
    "dem": ("dem", "2D DEM of a pipe pushed into sand (model scale SI; prototype = ×N)."),
    "dem-lammps": (
        "dem_lammps",
        "Run the pipe-penetration experiment with LAMMPS (cross-check of 'onbottom dem').",
    ),
    "report": (
        "report",
        "Validation report: every comparison with the papers and the standards on one page.",
    ),
    "stability": (
        "stability",
        "DNV-RP-F109 design checks of CASE (TOML): flotation (Eq 3.1), absolute lateral static"
        " stability (Eqs 3.38/3.39) per load combination, and the minimum concrete thickness or"
        " submerged weight ([design] solve_for).",
    ),
    "loads": (
        "loads",
        "Peak hydrodynamic loads of every wave cycle of each load combination of CASE (TOML),"
        " in V–H space (H = |F_Y|, V = w_s − F_Z), and the fraction of cycles whose load angle"
        " from the V axis lies between 20° and 45° (Youssef & Cassidy 2014, Fig.",
    ),
    "storm": ("storm", "Simulate a pipe section on the seabed through a storm (CASE: TOML file)."),
    "curves": (
        "curves",
        "Stability curves L_stable, L_10 from dynamic storms (CASE: TOML with [curves]).",
    ),
    "fourier-fit": (
        "fourier_fit",
        "Fit a Fourier coefficient table from regular-wave RUNS (CSV: t,U,F_Y,F_Z).",
    ),
    "metocean": (
        "metocean",
        "Metocean statistics of HINDCAST (CSV or NetCDF: time, hs, tp, "
        "wave_direction_deg, current_speed, current_direction_deg; see "
        "docs/theory/metocean.md): declustered storms, return values per direction sector "
        "with confidence intervals (POT/GPD, pyextremes), the DNV-RP-C205 H_s–T_p model "
        "and IFORM contours (virocon), and the DNV-RP-F109 design table per sector.",
    ),
    "assess": (
        "assess",
        "On-bottom stability of a whole route (CASE: route TOML; none: the embedded example).",
    ),
    "reliability": (
        "reliability",
        "Long-term reliability of CASE (a storm case with a [reliability] table; see "
        "examples/reliability_case.toml and docs/theory/reliability.md): P[max lateral "
        "displacement in a storm > limit] per storm, year and design life, with its CV "
        "and the importance of the inputs; the response-based design on an environmental "
        "contour.",
    ),
    "warmup": (
        "warmup",
        "Compile the numba kernels of storm, assess, pipeline and section runs into the cache.",
    ),
}
"""Command name → (module of ``onbottom.cli`` defining it as ``command``, its short help).

The short help is the command's own (``command.get_short_help_str()``), kept here so that
``onbottom --help`` lists every command without importing any; a command's module is imported
only when that command runs. ``tests/unit/test_cli_lazy.py`` checks the table against the
commands.
"""

COMMAND_MODULES: tuple[str, ...] = tuple(module for module, _ in COMMANDS.values())
"""Modules of ``onbottom.cli`` that each define ``command``."""


class LazyGroup(JsonErrorGroup):
    """Root group whose commands (:data:`COMMANDS`) are imported when they are invoked."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(set(COMMANDS) | set(self.commands))

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name in self.commands or cmd_name not in COMMANDS:
            return super().get_command(ctx, cmd_name)
        module = importlib.import_module(f"onbottom.cli.{COMMANDS[cmd_name][0]}")
        command = module.command
        self.add_command(command, cmd_name)
        return command

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        """The command list of ``--help`` from :data:`COMMANDS` (no command imported)."""
        names = self.list_commands(ctx)
        if not names:
            return
        limit = formatter.width - 6 - max(len(name) for name in names)
        rows = []
        for name in names:
            if name in COMMANDS:
                rows.append((name, make_default_short_help(COMMANDS[name][1], limit)))
            else:
                cmd = self.commands[name]
                if not cmd.hidden:
                    rows.append((name, cmd.get_short_help_str(limit)))
        with formatter.section("Commands"):
            formatter.write_dl(rows)


@click.group(
    cls=LazyGroup,
    context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100},
)
@click.version_option(__version__, prog_name="onbottom")
@click.option(
    "--allow-outside-paths",
    is_flag=True,
    help="Let case files name files outside their own folder tree (absolute paths, '..').",
)
def cli(allow_outside_paths: bool = False) -> None:
    """onbottom — on-bottom stability of subsea pipelines (DNV-RP-F109), from the sea states
    to a design report.

    \b
    Start here:
      onbottom assess --out DIR    a whole route: every F109 level per KP section (flotation,
                                   absolute, generalized, dynamic storms over seeds, pipeline
                                   FE of the governing section) and the design report
      onbottom assess --example    the example route case, to copy and edit
    \b
    Design inputs and single studies:
      metocean      return values and the F109 design table from a hindcast
      stability     F109 static checks and the minimum concrete of one section
      storm         a pipe section (or pipeline FE) through a storm, over seeds
      reliability   long-term probability of failure of a section
      curves        the tool's own generalized stability curves from dynamic storms
    \b
    Models and research: backbone, penetration, simulate, reproduce, calibrate, sweep, dem.
    Setup: warmup (compile the kernels once, ~1 min). Validation: report.

    Inputs are SI (m, N, N/m, Pa) unless an option name carries a unit (e.g. --gamma-kn).
    Every command accepts --json for scripting. Input errors exit with status 1 and a message
    naming the field, its value and the allowed range. docs/quickstart.md walks through it.
    """
    import sys

    if allow_outside_paths or "onbottom._casefile" in sys.modules:  # pydantic only when needed
        from onbottom._casefile import allow_outside_paths as _allow

        _allow(allow_outside_paths)


class CompileNotice:
    """Says on ``stream`` when numba starts compiling, and how long it took (first run only).

    numba compiles each kernel on its first call and caches it (``cache=True``), so the first
    run of a command after an install pays tens of seconds of compiling with no other sign of
    life. Registered as a listener of numba's ``numba:compile`` events.
    """

    def __init__(self, stream: TextIO) -> None:
        self.stream = stream
        self.depth = 0
        self.count = 0
        self.seconds = 0.0
        self._t0 = 0.0

    def on_start(self, event: Any) -> None:
        if self.depth == 0:
            if self.count == 0:
                self.stream.write(
                    "onbottom: compiling the numba kernels (first run after an install or an"
                    " update; later runs load them from the cache; `onbottom warmup` compiles"
                    " them all once ahead) ...\n"
                )
                self.stream.flush()
            self._t0 = time.perf_counter()
        self.depth += 1
        self.count += 1

    def on_end(self, event: Any) -> None:
        self.depth -= 1
        if self.depth == 0:
            self.seconds += time.perf_counter() - self._t0

    def summary(self) -> str | None:
        """``"compiled N kernels in T s"``, or None when nothing was compiled."""
        if self.count == 0:
            return None
        return f"onbottom: compiled {self.count} kernel specialisations in {self.seconds:.1f} s"


class _NumbaWatch(importlib.abc.MetaPathFinder):
    """Registers a :class:`CompileNotice` once numba is imported (no cost if it never is)."""

    def __init__(self, notice: CompileNotice) -> None:
        self.notice = notice

    def find_spec(self, fullname: str, path: Any = None, target: Any = None) -> Any:
        if fullname != "numba":
            return None
        sys.meta_path.remove(self)
        spec = importlib.util.find_spec("numba")
        if spec is None or spec.loader is None:
            return spec
        exec_module = spec.loader.exec_module
        notice = self.notice

        def exec_and_listen(module: Any) -> None:
            exec_module(module)
            try:
                from numba.core import event

                event.register("numba:compile", _listener(notice))
            except Exception:  # an older or newer numba without the event API: no notice
                pass

        spec.loader.exec_module = exec_and_listen  # type: ignore[method-assign]
        return spec


def _listener(notice: CompileNotice) -> Any:
    from numba.core import event

    class Listener(event.Listener):
        def on_start(self, ev: Any) -> None:
            notice.on_start(ev)

        def on_end(self, ev: Any) -> None:
            notice.on_end(ev)

    return Listener()


def main(argv: list[str] | None = None) -> int:
    """Run the CLI; returns the exit code (for tests, ``main([...])``).

    On a terminal (and without ``--quiet``) a line on stderr says when numba compiles. A Ctrl-C
    at any moment (also before or after the command's own handling) ends with one line on
    stderr (a JSON error object with ``--json``) and status 130, never a traceback.
    """
    try:
        return _main_with_notice(argv, list(sys.argv[1:] if argv is None else argv))
    except KeyboardInterrupt:
        return report_interrupt(as_json="--json" in (sys.argv[1:] if argv is None else argv))


def _main_with_notice(argv: list[str] | None, args: list[str]) -> int:
    if "--quiet" in args or not sys.stderr.isatty() or "numba" in sys.modules or _warmup(args):
        return _main(argv)
    notice = CompileNotice(sys.stderr)
    watch = _NumbaWatch(notice)
    sys.meta_path.insert(0, watch)
    try:
        return _main(argv)
    finally:
        if watch in sys.meta_path:
            sys.meta_path.remove(watch)
        if notice.summary():
            click.echo(notice.summary(), err=True)


def _warmup(args: list[str]) -> bool:
    """``onbottom warmup`` says what it compiles itself (no first-run notice)."""
    return bool(args) and args[0] == "warmup"


def _main(argv: list[str] | None) -> int:
    try:
        rv = cli.main(args=argv, prog_name="onbottom", standalone_mode=False)
    except click.exceptions.Abort as exc:
        if isinstance(exc.__context__, KeyboardInterrupt):  # Ctrl-C outside a command's body
            return report_interrupt(as_json="--json" in (sys.argv[1:] if argv is None else argv))
        click.echo("Aborted!", err=True)
        return 1
    except click.ClickException as exc:
        return report_click_error(exc, argv if argv is not None else sys.argv[1:])
    except SystemExit as exc:  # --help / --version
        return int(exc.code or 0)
    return rv if isinstance(rv, int) else 0


if __name__ == "__main__":
    sys.exit(main())
