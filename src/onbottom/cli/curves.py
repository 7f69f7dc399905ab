"""placeholder"""

import click


@click.command("curves")
def command() -> None:
    """Stability curves (in progress)."""
