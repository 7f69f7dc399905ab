"""``onbottom`` command-line entry point.

Each command group lives in its own module of this package and exposes ``command`` (a click
command or group); :data:`COMMAND_MODULES` lists them in help order.
"""

from __future__ import annotations

import importlib
import sys

import click

from onbottom._version import __version__
from onbottom.cli._common import JsonErrorGroup, report_click_error

COMMAND_MODULES: tuple[str, ...] = (
    "reproduce",
    "simulate",
    "calibrate",
    "sweep",
    "backbone",
    "penetration",
    "dem",
    "dem_lammps",
    "report",
    "stability",
    "loads",
    "storm",
    "curves",
    "fourier_fit",
    "metocean",
    "reliability",
)
"""Modules of ``onbottom.cli`` that each define ``command``."""


@click.group(
    cls=JsonErrorGroup,
    context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100},
)
@click.version_option(__version__, prog_name="onbottom")
def cli() -> None:
    """onbottom — subsea pipeline–seabed interaction.

    Pipe–soil resistance models (Verley & Sotberg sand and its calcareous calibration,
    Verley & Lund clay, Coulomb), DNVGL-RP-F114 vertical penetration, load-controlled pipe
    section simulations of centrifuge tests, calibration, and a 2D DEM of pipe penetration.

    Inputs are SI (m, N, N/m, Pa) unless an option name carries a unit (e.g. --gamma-kn).
    Every command accepts --json for scripting. Input errors exit with status 1 and a message
    naming the field, its value and the allowed range.
    """


for _name in COMMAND_MODULES:
    _mod = importlib.import_module(f"onbottom.cli.{_name}")
    cli.add_command(_mod.command)


def main(argv: list[str] | None = None) -> int:
    """Run the CLI; returns the exit code (for tests, ``main([...])``)."""
    try:
        rv = cli.main(args=argv, prog_name="onbottom", standalone_mode=False)
    except click.exceptions.Abort:
        click.echo("Aborted!", err=True)
        return 1
    except click.ClickException as exc:
        return report_click_error(exc, argv if argv is not None else sys.argv[1:])
    except SystemExit as exc:  # --help / --version
        return int(exc.code or 0)
    return rv if isinstance(rv, int) else 0


if __name__ == "__main__":
    sys.exit(main())
