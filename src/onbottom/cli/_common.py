"""Helpers shared by the CLI commands: JSON output, error reporting, checked numeric options.

Exit codes of every command:

* 0 — a valid result was produced;
* 1 — an input error (bad value, case file or checkpoint: :class:`~onbottom.errors.InputError`)
  or no solution (:class:`~onbottom.errors.SolutionError`), or a file that cannot be written;
  — an option value out of its range (:class:`Number`) included;
* 2 — a command-line usage error (unknown option, missing argument, a value click rejects);
* 3 — the command ran but its result is not valid (solver did not converge, a result left its
  model's validity, some runs of a sweep failed);
* 70 — an internal error (a bug: the traceback goes to stderr);
* 130 — interrupted (Ctrl-C): one line on stderr says what was kept and how to resume.

With ``--json`` every error is the JSON object ``{"error": {"type", "message", "field"}}`` on
stdout (``field`` is the option or key at fault, or null), so scripts never parse tracebacks.
"""

from __future__ import annotations

import json
import math
import re
import sys
import traceback
from collections.abc import Callable, Mapping, Sequence
from functools import wraps
from typing import Any, NoReturn

import click

from onbottom.errors import InputError, OnbottomError, RunInterrupted, SolutionError

__all__ = [
    "EXIT_INPUT",
    "EXIT_INTERNAL",
    "EXIT_INTERRUPTED",
    "EXIT_INVALID_RESULT",
    "EXIT_USAGE",
    "JsonErrorGroup",
    "Number",
    "emit_error",
    "emit_json",
    "error_payload",
    "handle_errors",
    "json_option",
    "log_to_stderr",
    "plain_numbers",
    "report_click_error",
]

EXIT_INPUT = 1
EXIT_USAGE = 2
EXIT_INVALID_RESULT = 3  # a solver status maps here: onbottom.dynamics.status.exit_code
EXIT_INTERNAL = 70
EXIT_INTERRUPTED = 130

json_option = click.option(
    "--json", "as_json", is_flag=True, help="Print machine-readable JSON instead of a table."
)


def _jsonable(obj: Any) -> Any:
    import numpy as np  # here, not at the top: `onbottom --help` does not load numpy

    if isinstance(obj, Mapping):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _jsonable(obj.tolist())
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, (np.floating, float)):
        x = float(obj)
        return x if math.isfinite(x) else None
    if isinstance(obj, np.integer):
        return int(obj)
    return obj


def _versioned(payload: Any) -> Any:
    """``payload`` with ``schema_version`` first (a JSON object; docs/json.md)."""
    from onbottom.cli.json_contract import SCHEMA_VERSION

    if isinstance(payload, Mapping):
        return {"schema_version": SCHEMA_VERSION, **{k: v for k, v in payload.items()}}
    return payload


def emit_json(payload: Mapping[str, Any] | Sequence[Any]) -> None:
    """Print ``payload`` as JSON (NaN/inf become null) with ``schema_version`` (the contract
    of every command's keys: :mod:`onbottom.cli.json_contract`, docs/json.md)."""
    click.echo(json.dumps(_jsonable(_versioned(payload)), indent=2))


# ---------------------------------------------------------------------------------------------
# errors
# ---------------------------------------------------------------------------------------------
_NP_SCALAR = re.compile(r"np\.(?:float|int|uint|bool_?|str_)\d*\(([^()]*)\)")
_OPTION = re.compile(r"^(--[a-z0-9][a-z0-9-]*)\b")
_FIELD = re.compile(r"^(?:[^:\n]*?: )?(--[a-z0-9][a-z0-9-]*|[A-Za-z_][\w.\[\]'\"-]*) (?:=|is )")


def plain_numbers(text: str) -> str:
    """``"np.float64(7.0)"`` → ``"7.0"`` (numpy 2 scalar reprs in messages)."""
    return _NP_SCALAR.sub(r"\1", text)


def _field_of(exc: BaseException) -> str | None:
    field = getattr(exc, "field", None)
    if isinstance(field, str) and field:
        return field
    option = getattr(exc, "option_name", None)  # click.NoSuchOption
    if isinstance(option, str) and option:
        return option
    param = getattr(exc, "param", None)
    if param is not None:
        opts = [o for o in getattr(param, "opts", []) if o.startswith("--")]
        return opts[0] if opts else getattr(param, "name", None)
    text = str(exc)
    m = _OPTION.match(text)
    if m:
        return m.group(1)
    m = _FIELD.match(text)
    return m.group(1) if m else None


def error_payload(exc: BaseException) -> dict[str, dict[str, Any]]:
    """``{"error": {"type", "message", "field"}}`` for any exception."""
    if isinstance(exc, click.ClickException) and exc.__cause__ is not None:
        if isinstance(exc.__cause__, (OnbottomError, OSError)):
            exc = exc.__cause__
    if isinstance(exc, click.ClickException):
        message = exc.format_message()
        if isinstance(exc, OptionValueError):
            kind = "InputError"
        elif isinstance(exc, click.UsageError):
            kind = "UsageError"
        else:
            kind = type(exc).__name__
    else:
        message = str(exc)
        kind = type(exc).__name__
    return {
        "error": {
            "type": kind,
            "message": plain_numbers(message),
            "field": _field_of(exc),
        }
    }


def emit_error(exc: BaseException, *, as_json: bool) -> None:
    """Report ``exc``: a JSON error object on stdout, or ``Error: message`` on stderr."""
    if as_json:
        click.echo(json.dumps(_versioned(error_payload(exc)), indent=2))
    elif isinstance(exc, click.ClickException):
        exc.show()
    else:
        click.echo(f"Error: {error_payload(exc)['error']['message']}", err=True)


class ReportedError(click.ClickException):
    """An error already reported by :func:`handle_errors` (nothing more to print)."""

    def show(self, file: Any = None) -> None:
        return None

    def with_exit(self, code: int) -> ReportedError:
        """Set the exit status (default 1); returns self."""
        self.exit_code = code
        return self


def _os_message(exc: OSError) -> str:
    name = exc.filename if exc.filename is not None else ""
    return f"{name}: {exc.strerror or exc}" if name else str(exc)


def handle_errors(fn: Callable) -> Callable:
    """Report errors of a command body cleanly and exit non-zero.

    Input errors and solution errors (and files that cannot be read or written) exit with
    status 1; with ``--json`` (the ``as_json`` keyword) the error is a JSON object on stdout.
    Any other exception is a bug: its traceback goes to stderr and the exit status is 70.
    """

    @wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        as_json = bool(kwargs.get("as_json", False))
        try:
            return fn(*args, **kwargs)
        except (click.exceptions.Exit, click.exceptions.Abort, click.ClickException):
            raise
        except (InputError, SolutionError, OnbottomError) as exc:
            emit_error(exc, as_json=as_json)
            raise ReportedError(plain_numbers(str(exc))) from exc
        except KeyboardInterrupt as exc:  # Ctrl-C: one line, no traceback, status 130
            msg = str(exc) if isinstance(exc, RunInterrupted) and str(exc) else "interrupted"
            report_interrupt(msg, as_json=as_json)
            raise ReportedError(msg).with_exit(EXIT_INTERRUPTED) from None
        except OSError as exc:
            err = InputError(plain_numbers(_os_message(exc)))
            err.field = exc.filename  # type: ignore[attr-defined]
            emit_error(err, as_json=as_json)
            raise ReportedError(str(err)) from exc
        except Exception as exc:  # a bug: keep the traceback, keep the contract
            traceback.print_exc(file=sys.stderr)
            emit_error(exc, as_json=as_json)
            raise ReportedError(str(exc)).with_exit(EXIT_INTERNAL) from exc

    return wrapper


def report_interrupt(message: str = "interrupted", *, as_json: bool) -> int:
    """Say that the run was interrupted (Ctrl-C): one line on stderr, or a JSON error object
    on stdout; returns the exit status, 130."""
    if as_json:
        payload = {"error": {"type": "Interrupted", "message": message, "field": None}}
        click.echo(json.dumps(_versioned(payload), indent=2))
    else:
        click.echo(message, err=True)
    return EXIT_INTERRUPTED


def report_click_error(exc: click.ClickException, argv: Sequence[str] | None) -> int:
    """Print a click error (JSON when ``--json`` is among ``argv``); return its exit code."""
    if not isinstance(exc, ReportedError):
        emit_error(exc, as_json="--json" in (argv or ()))
    return exc.exit_code


class JsonErrorGroup(click.Group):
    """Root group: usage errors (bad option values) follow ``--json`` too."""

    def main(  # type: ignore[override]
        self,
        args: Sequence[str] | None = None,
        prog_name: str | None = None,
        complete_var: str | None = None,
        standalone_mode: bool = True,
        **extra: Any,
    ) -> Any:
        if not standalone_mode:
            return super().main(args, prog_name, complete_var, False, **extra)
        argv = list(sys.argv[1:] if args is None else args)
        try:
            rv = super().main(argv, prog_name, complete_var, False, **extra)
        except click.ClickException as exc:
            sys.exit(report_click_error(exc, argv))
        except click.exceptions.Abort:
            click.echo("Aborted!", err=True)
            sys.exit(1)
        sys.exit(rv if isinstance(rv, int) else 0)


# ---------------------------------------------------------------------------------------------
# checked numeric options
# ---------------------------------------------------------------------------------------------
def _fmt(x: float) -> str:
    return f"{x:g}"


class OptionValueError(click.BadParameter):
    """An option value outside its range: an input error (exit status 1)."""

    exit_code = EXIT_INPUT


class Number(click.ParamType):
    """A finite number option with a range: ``type=Number(int, min=1)``.

    Refuses NaN and infinity, out-of-range values and (for ``int``) values with a fractional
    part (``16.7``), with a message naming the option, the value and the allowed range.
    ``1e3`` is accepted for an ``int`` option. ``unit`` is shown in the help and the message.
    """

    def __init__(
        self,
        kind: type = float,
        *,
        min: float | None = None,
        max: float | None = None,
        min_open: bool = False,
        max_open: bool = False,
        unit: str = "",
    ) -> None:
        if kind not in (int, float):
            raise TypeError("kind must be int or float")
        self.kind = kind
        self.min, self.max = min, max
        self.min_open, self.max_open = min_open, max_open
        self.unit = unit
        self.name = "integer" if kind is int else "number"

    def _range(self) -> str:
        lo = "-inf" if self.min is None else _fmt(self.min)
        hi = "inf" if self.max is None else _fmt(self.max)
        lb = "(" if self.min is None or self.min_open else "["
        hb = ")" if self.max is None or self.max_open else "]"
        return f"{lb}{lo}, {hi}{hb}" + (f" {self.unit}" if self.unit else "")

    def get_metavar(self, param: click.Parameter, ctx: click.Context | None = None) -> str:
        return ("INTEGER" if self.kind is int else "FLOAT") + " " + self._range()

    def fail(
        self, message: str, param: click.Parameter | None = None, ctx: click.Context | None = None
    ) -> NoReturn:
        raise OptionValueError(message, ctx=ctx, param=param)

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None) -> Any:
        if isinstance(value, bool):
            self.fail(f"{value!r} is not a {self.name}", param, ctx)
        import numpy as np

        if isinstance(value, (int, float, np.integer, np.floating)):
            x = float(value)
            text = repr(value)
        else:
            text = str(value).strip()
            try:
                x = float(text)
            except ValueError:
                self.fail(f"{text!r} is not a {self.name}", param, ctx)
        if not math.isfinite(x):
            self.fail(f"{text} is invalid: expected a finite {self.name}", param, ctx)
        if self.kind is int:
            if x != math.floor(x):
                self.fail(f"{text} is invalid: expected a whole number (no fraction)", param, ctx)
            if abs(x) > 2**62:
                self.fail(f"{text} is invalid: too large", param, ctx)
        lo_bad = self.min is not None and (x <= self.min if self.min_open else x < self.min)
        hi_bad = self.max is not None and (x >= self.max if self.max_open else x > self.max)
        if lo_bad or hi_bad:
            self.fail(f"{_fmt(x)} is invalid: must lie in {self._range()}", param, ctx)
        return int(x) if self.kind is int else x


def check_output_path(path: Any, *, field: str) -> None:
    """Create the parent folder of an output file; refuse a path that is an existing folder."""
    from pathlib import Path

    p = Path(path)
    if p.is_dir():
        err = InputError(f"{field} = {str(p)!r} is invalid: it is a folder, expected a file name")
        err.field = field  # type: ignore[attr-defined]
        raise err
    p.parent.mkdir(parents=True, exist_ok=True)


FIGURE_SUFFIXES = (".png", ".pdf", ".svg")


def check_output_names(case: Any, outputs: Sequence[tuple[str, Any, Sequence[str]]]) -> None:
    """Refuse output names that would overwrite the case file or each other, or a wrong kind.

    ``outputs`` holds ``(field, path or None, allowed suffixes)``, e.g. ``("--output", nc,
    (".nc",))``; the first offending entry raises :class:`InputError` naming its field
    (before any work is done, so a bad name never costs a run).
    """
    from pathlib import Path

    def fail(field: str, message: str) -> None:
        err = InputError(message)
        err.field = field  # type: ignore[attr-defined]
        raise err

    given = [(f, Path(p), tuple(s)) for f, p, s in outputs if p is not None]
    for field, p, suffixes in given:
        if suffixes and p.suffix.lower() not in suffixes:
            fail(
                field,
                f"{field} = {str(p)!r} is invalid: the file name must end in "
                + " or ".join(suffixes),
            )
    case_path = Path(case).resolve()
    for field, p, _ in given:
        if p.resolve() == case_path:
            fail(field, f"{field} = {str(p)!r} is invalid: it would overwrite the case file")
    for i, (field, p, _) in enumerate(given):
        for other, q, _ in given[i + 1 :]:
            if p.resolve() == q.resolve():
                fail(field, f"{field} = {str(p)!r} is invalid: the same file as {other}")


class log_to_stderr:
    """Show the INFO messages of the ``onbottom`` loggers on stderr ("resuming from t = …").

    Solvers never print: they log; a command shows what they log with this context manager
    (``enabled`` false: nothing is added, e.g. with ``--json``).
    """

    def __init__(self, enabled: bool = True) -> None:
        import logging

        self.enabled = enabled
        self.logger = logging.getLogger("onbottom")
        self.handler = logging.StreamHandler(sys.stderr)
        self.handler.setFormatter(logging.Formatter("%(message)s"))
        self.level = self.logger.level

    def __enter__(self) -> log_to_stderr:
        import logging

        if self.enabled:
            self.logger.addHandler(self.handler)
            if self.logger.getEffectiveLevel() > logging.INFO:
                self.logger.setLevel(logging.INFO)
        return self

    def __exit__(self, *exc: Any) -> None:
        if self.enabled:
            self.logger.removeHandler(self.handler)
            self.logger.setLevel(self.level)
