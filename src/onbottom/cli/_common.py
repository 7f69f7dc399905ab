"""Helpers shared by the CLI commands: JSON output, error reporting, unit display."""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Mapping
from functools import wraps
from typing import Any

import click
import numpy as np

from onbottom.errors import InputError, SolutionError

json_option = click.option(
    "--json", "as_json", is_flag=True, help="Print machine-readable JSON instead of a table."
)


def _jsonable(obj: Any) -> Any:
    if isinstance(obj, Mapping):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _jsonable(obj.tolist())
    if isinstance(obj, (np.floating, float)):
        x = float(obj)
        return x if math.isfinite(x) else None
    if isinstance(obj, np.integer):
        return int(obj)
    return obj


def emit_json(payload: Mapping[str, Any]) -> None:
    """Print ``payload`` as JSON (NaN/inf become null)."""
    click.echo(json.dumps(_jsonable(payload), indent=2))


def handle_errors(fn: Callable) -> Callable:
    """Turn input and solution errors into a clean message and exit code 2."""

    @wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            return fn(*args, **kwargs)
        except (InputError, SolutionError) as exc:
            raise click.ClickException(str(exc)) from exc

    return wrapper
