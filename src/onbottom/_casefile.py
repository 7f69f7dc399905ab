"""Strict case files: one pydantic schema per file type, errors that name the key and its place.

Every TOML/JSON file onbottom reads goes through :func:`load_case_file` (or :func:`read_toml`
then :func:`parse_case`) with a schema derived from :class:`StrictModel`:

* unknown tables or keys are errors naming the key, its place (file, table, line) and the
  allowed keys, with a did-you-mean suggestion;
* wrong types (strict: no silent ``"1"`` → 1.0, no ``16.7`` → 16), missing keys, NaN/inf and
  values outside a declared range are errors naming the field and the value;
* a malformed file is an error naming the file and the line the parser stopped at.

All of these raise :class:`CaseFileError`, an :class:`~onbottom.errors.InputError`, so the CLI
reports them like any other input error (exit code >= 1, ``--json`` error object).

Only :mod:`onbottom.cases` (every case-file schema and case → model builder) and
:mod:`onbottom.cli` import this module (``tests/unit/test_architecture.py``); the library's
API takes the built objects, never a case file.

pydantic (v2) is used rather than hand-written checks: it is well kept, validates nested
tables with exact locations, and its strict mode refuses the silent coercions that made wrong
results possible.
"""

from __future__ import annotations

import difflib
import json
import os
import re
import tomllib
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any, TypeVar

import pydantic
from pydantic import BaseModel, ConfigDict

from onbottom.errors import InputError

__all__ = [
    "MAX_CASE_FILE_BYTES",
    "MAX_NESTING",
    "CaseFileError",
    "StrictModel",
    "allow_outside_paths",
    "contained",
    "find_key_line",
    "find_line",
    "load_case_file",
    "outside_paths_allowed",
    "parse_case",
    "read_json",
    "read_toml",
    "resolve_path",
]

M = TypeVar("M", bound=BaseModel)


class CaseFileError(InputError):
    """A case file is malformed or does not match its schema.

    Attributes
    ----------
    field : str or None
        Dotted path of the offending key (``"solver.dt_max"``), or None for the whole file.
    file : str or None
        Path of the file.
    line : int or None
        1-based line of the key in the file, where it could be located.
    """

    def __init__(
        self,
        message: str,
        *,
        field: str | None = None,
        file: str | None = None,
        line: int | None = None,
    ) -> None:
        super().__init__(message)
        self.field = field
        self.file = file
        self.line = line


class StrictModel(BaseModel):
    """Base of every case-file schema: unknown keys forbidden, strict types, finite floats.

    Subclasses declare fields with ``pydantic.Field(gt=..., le=..., description="... [unit]")``;
    the description is the field's documentation and must state its unit.
    """

    model_config = ConfigDict(
        extra="forbid",
        frozen=True,
        strict=True,
        allow_inf_nan=False,
        validate_default=True,
    )


# ---------------------------------------------------------------------------------------------
# reading
# ---------------------------------------------------------------------------------------------
_TOML_LINE = re.compile(r"at line (\d+), column (\d+)")


def read_toml(path: str | os.PathLike) -> tuple[dict[str, Any], str]:
    """Read a TOML file; return ``(document, text)``.

    Raises :class:`CaseFileError` if the file is missing, unreadable, not UTF-8 or not TOML
    (naming the line and column the parser stopped at).
    """
    p = Path(path)
    text = _read_text(p)
    try:
        return _check_nesting(p, tomllib.loads(text)), text
    except RecursionError:
        raise _too_deep(p) from None
    except tomllib.TOMLDecodeError as exc:
        m = _TOML_LINE.search(str(exc))
        line = int(m.group(1)) if m else None
        raise CaseFileError(
            f"{p}: not valid TOML: {exc}", field=None, file=str(p), line=line
        ) from None


def read_json(path: str | os.PathLike) -> tuple[Any, str]:
    """Read a JSON file; return ``(document, text)`` (errors as :func:`read_toml`)."""
    p = Path(path)
    text = _read_text(p)
    try:
        return _check_nesting(p, json.loads(text)), text
    except RecursionError:
        raise _too_deep(p) from None
    except json.JSONDecodeError as exc:
        raise CaseFileError(
            f"{p}: not valid JSON: {exc.msg} (at line {exc.lineno}, column {exc.colno})",
            file=str(p),
            line=exc.lineno,
        ) from None


MAX_CASE_FILE_BYTES = 10_000_000
"""Largest case file read (10 MB): case files are a few kB; a larger file is not a case file
(a result, a device such as /dev/zero) and is refused before it is read into memory."""

MAX_NESTING = 32
"""Deepest nesting of tables and arrays in a case file (the schemas need 4)."""


def _read_text(p: Path) -> str:
    if not p.exists():
        raise CaseFileError(f"{p}: file not found", field="path", file=str(p))
    if p.is_dir():
        raise CaseFileError(f"{p}: is a folder, expected a file", field="path", file=str(p))
    if not p.is_file():
        raise CaseFileError(
            f"{p}: is not a regular file (a device, pipe or socket), expected a case file",
            field="path",
            file=str(p),
        )
    try:
        size = p.stat().st_size
        if size > MAX_CASE_FILE_BYTES:
            raise _too_large(p, size)
        with p.open("rb") as fh:
            raw = fh.read(MAX_CASE_FILE_BYTES + 1)
        if len(raw) > MAX_CASE_FILE_BYTES:
            raise _too_large(p, len(raw))
        return raw.decode("utf-8")
    except UnicodeDecodeError:
        raise CaseFileError(f"{p}: not a UTF-8 text file", field="path", file=str(p)) from None
    except OSError as exc:
        raise CaseFileError(f"{p}: cannot be read ({exc.strerror})", file=str(p)) from None


def _too_large(p: Path, size: int) -> CaseFileError:
    return CaseFileError(
        f"{p}: is {size / 1e6:.3g} MB or more, larger than the {MAX_CASE_FILE_BYTES / 1e6:g} MB"
        " limit of a case file (is it a case file?)",
        field="path",
        file=str(p),
    )


def _nesting(doc: Any) -> int:
    """Deepest nesting of mappings and lists in ``doc`` (iterative: no recursion limit)."""
    deepest = 0
    stack: list[tuple[Any, int]] = [(doc, 0)]
    while stack:
        obj, depth = stack.pop()
        if isinstance(obj, Mapping):
            children: Any = obj.values()
        elif isinstance(obj, list):
            children = obj
        else:
            continue
        depth += 1
        deepest = max(deepest, depth)
        if depth > MAX_NESTING:
            return depth
        stack.extend((c, depth) for c in children)
    return deepest


def _check_nesting(p: Path, doc: Any) -> Any:
    if _nesting(doc) > MAX_NESTING:
        raise _too_deep(p)
    return doc


def _too_deep(p: Path) -> CaseFileError:
    return CaseFileError(
        f"{p}: tables or arrays nested deeper than {MAX_NESTING} levels: not a case file",
        field="path",
        file=str(p),
    )


_OUTSIDE = {"allowed": False}

OUTSIDE_OPTION = "onbottom --allow-outside-paths <command> ..."
"""How a user lets a case file name files outside its folder (the global CLI option)."""


def allow_outside_paths(allowed: bool = True) -> None:
    """Let case files name files outside their own folder tree (``allowed``) or not (the
    default). Set by the global option ``onbottom --allow-outside-paths`` for one command."""
    _OUTSIDE["allowed"] = bool(allowed)


def outside_paths_allowed() -> bool:
    """Whether case files may name files outside their folder (:func:`allow_outside_paths`)."""
    return _OUTSIDE["allowed"]


def resolve_path(
    value: str,
    *,
    relative_to: str | os.PathLike | None,
    field: str,
    must_exist: bool = True,
) -> Path:
    """Resolve a file named in a case file (relative to the case file's folder).

    The one containment rule of every path a case file names (:func:`contained`): absolute or
    relative, the file must lie inside the case file's folder tree unless
    :func:`allow_outside_paths`; with ``must_exist`` it must exist. Errors name ``field``
    and never the file's content.
    """
    p = Path(value).expanduser()
    if not p.is_absolute() and relative_to is not None:
        p = Path(relative_to).resolve().parent / p
    if relative_to is not None:
        p = contained(value, p, folder=Path(relative_to).resolve().parent, field=field)
    if must_exist and not p.is_file():
        raise CaseFileError(
            f"{field} = {value!r} is invalid: file {p} not found", field=field, file=str(p)
        )
    return p


def contained(
    value: str, path: str | os.PathLike, *, folder: str | os.PathLike, field: str
) -> Path:
    """``path`` resolved; a :class:`CaseFileError` naming ``field`` unless it lies inside
    ``folder`` (the case file's folder) or :func:`outside_paths_allowed`.

    Absolute paths, ``~`` and ``..`` get the same rule, after symbolic links are resolved:
    a case file someone sends cannot make onbottom read (and echo) files elsewhere on the
    disk, such as ``/etc/passwd``.
    """
    base = Path(folder).resolve()
    full = Path(path).expanduser().resolve()
    if outside_paths_allowed():
        return full
    if full != base and base not in full.parents:
        raise CaseFileError(
            f"{field} = {value!r} is invalid: it leaves the case file's folder {base} (a file"
            " named in a case file must lie in that folder or below it, absolute or relative;"
            " give a path inside it, or allow files elsewhere with"
            f" {OUTSIDE_OPTION})",
            field=field,
        )
    return full


# ---------------------------------------------------------------------------------------------
# validation and error messages
# ---------------------------------------------------------------------------------------------
def parse_case(
    model: type[M],
    data: Any,
    *,
    file: str | os.PathLike | None = None,
    text: str | None = None,
    root: str = "",
) -> M:
    """Validate ``data`` against the schema ``model``; raise :class:`CaseFileError` on the
    first problem (with every other problem listed after it).

    Parameters
    ----------
    model
        A :class:`StrictModel` subclass.
    data
        The parsed document (mapping).
    file, text
        The file path and its text, used to name the place of an error (line numbers).
    root
        Dotted prefix of ``data`` inside the document (when validating one table of a file).
    """
    if not isinstance(data, Mapping):
        raise CaseFileError(
            f"{_where(file, root or None, None)}expected a table of keys, got"
            f" {type(data).__name__}",
            field=root or None,
            file=None if file is None else str(file),
        )
    try:
        return model.model_validate(dict(data))
    except pydantic.ValidationError as exc:
        raise _case_error(model, exc, file=file, text=text, root=root) from None


def load_case_file(path: str | os.PathLike, model: type[M]) -> M:
    """Read a TOML (``.toml``) or JSON (``.json``) case file and validate it against ``model``."""
    p = Path(path)
    if p.suffix.lower() == ".json":
        doc, text = read_json(p)
    else:
        doc, text = read_toml(p)
    return parse_case(model, doc, file=p, text=text)


_UNION_TAG = re.compile(r"^[\w-]+\[.*\]$|^(?:int|float|str|bool|none)$")


def _without_tags(loc: Sequence[Any]) -> tuple[Any, ...]:
    """``loc`` without pydantic's union-member tags (``literal['a','b']``,
    ``function-after[...]``, ``list[...]``, ``float``): they are no case-file keys."""
    return tuple(k for k in loc if isinstance(k, int) or not _UNION_TAG.match(str(k)))


def _dotted(loc: Sequence[Any], root: str) -> str:
    loc = _without_tags(loc)
    parts = [root] if root else []
    for item in loc:
        if isinstance(item, int):
            parts[-1:] = [f"{parts[-1]}[{item}]"] if parts else [f"[{item}]"]
        else:
            parts.append(str(item))
    return ".".join(parts)


def _submodel(model: type[BaseModel], loc: Sequence[Any]) -> type[BaseModel] | None:
    """The schema of the table that contains the last key of ``loc`` (None if unknown)."""
    current: Any = model
    for item in loc[:-1]:
        if isinstance(item, int):
            continue
        if not (isinstance(current, type) and issubclass(current, BaseModel)):
            return None
        info = current.model_fields.get(str(item))
        if info is None:
            return None
        current = _model_in(info.annotation)
    return current if isinstance(current, type) and issubclass(current, BaseModel) else None


def _model_in(annotation: Any) -> Any:
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    for arg in getattr(annotation, "__args__", ()) or ():
        found = _model_in(arg)
        if found is not None:
            return found
    return None


def _plain(value: Any) -> str:
    if isinstance(value, float):
        return repr(float(value))
    if isinstance(value, Mapping):
        return "{...}"
    return repr(value)


def _message(model: type[BaseModel], err: Mapping[str, Any], root: str) -> str:
    loc = _without_tags(err.get("loc", ()))
    field = _dotted(loc, root)
    kind = err.get("type", "")
    if kind == "extra_forbidden":
        key = str(loc[-1]) if loc else "?"
        parent = _submodel(model, loc)
        allowed = sorted(parent.model_fields) if parent is not None else []
        table = _dotted(loc[:-1], root)
        place = f"[{table}]" if table else "the top level"
        msg = f"unknown key {key!r} in {place}"
        if allowed:
            msg += f" (allowed: {', '.join(allowed)})"
            close = difflib.get_close_matches(key, allowed, n=1, cutoff=0.6)
            if close:
                msg += f"; did you mean {close[0]!r}?"
        return msg
    if kind == "missing":
        return f"{field} is missing (required)"
    value = _plain(err.get("input"))
    text = str(err.get("msg", "invalid"))
    return f"{field} = {value} is invalid: {text[0].lower() + text[1:] if text else text}"


def _case_error(
    model: type[BaseModel],
    exc: pydantic.ValidationError,
    *,
    file: str | os.PathLike | None,
    text: str | None,
    root: str,
) -> CaseFileError:
    errors = exc.errors(include_url=False)
    # an unknown key first: a misspelled required key is also reported missing, and the
    # misspelling (with its did-you-mean) is the useful message
    errors.sort(key=lambda e: e.get("type") != "extra_forbidden")
    first = errors[0]
    loc = _without_tags(first.get("loc", ()))
    field = _dotted(loc, root) or None
    line = find_line(text, tuple(root.split(".")) + loc if root else loc) if text else None
    msg = _where(file, None, line) + _message(model, first, root)
    if len(errors) > 1:
        others = "; ".join(_message(model, e, root) for e in errors[1:4])
        more = f" (and {len(errors) - 4} more)" if len(errors) > 4 else ""
        msg += f" [also: {others}{more}]"
    return CaseFileError(msg, field=field, file=None if file is None else str(file), line=line)


def _where(file: str | os.PathLike | None, field: str | None, line: int | None) -> str:
    if file is None:
        return ""
    return f"{file}{f', line {line}' if line else ''}: "


def find_key_line(text: str | None, field: str) -> int | None:
    """Best-effort 1-based line of the dotted key ``field`` (``"route.sections[1].name"``) in
    TOML ``text`` (None if not found or no text): :func:`find_line` of its path."""
    if not text:
        return None
    loc: list[Any] = []
    for part in field.split("."):
        name, _, idx = part.partition("[")
        loc.append(name)
        if idx:
            loc.append(int(idx.rstrip("]")))
    return find_line(text, loc)


def find_line(text: str, loc: Sequence[Any]) -> int | None:
    """Best-effort 1-based line of the key at ``loc`` in TOML ``text`` (None if not found):
    the n-th ``[[array.of.tables]]`` where ``loc`` holds an index, else the first match."""
    if any(isinstance(k, int) for k in loc):
        found = _find_indexed(text, [k if isinstance(k, int) else str(k) for k in loc if k != ""])
        if found is not None:
            return found
    return _find_first(text, loc)


def _find_indexed(text: str, target: list[Any]) -> int | None:
    """The line of ``target`` (names and array indices) counting ``[[...]]`` headers."""
    header = re.compile(r"^\s*(\[\[?)\s*([^\]]+?)\s*\]\]?\s*(#.*)?$")
    assign = re.compile(r"^\s*([A-Za-z0-9_\-\"'. ]+?)\s*=")
    arrays: dict[tuple[Any, ...], int] = {}

    def resolve(names: list[str]) -> list[Any]:
        out: list[Any] = []
        for n in names:
            out.append(n)
            k = tuple(out)
            if k in arrays:
                out.append(arrays[k])
        return out

    table: list[Any] = []
    for i, raw in enumerate(text.splitlines(), start=1):
        m = header.match(raw)
        if m:
            names = [p.strip().strip("\"'") for p in m.group(2).split(".")]
            if m.group(1) == "[[":
                key = (*resolve(names[:-1]), names[-1])
                arrays[key] = arrays.get(key, -1) + 1
                # the nested arrays of the previous element start again
                for k in [k for k in arrays if len(k) > len(key) and k[: len(key)] == key]:
                    del arrays[k]
                table = [*key, arrays[key]]
            else:
                table = resolve(names)
            if table == target or (table[:-1] == target and isinstance(table[-1], int)):
                return i
            continue
        m = assign.match(raw)
        if m:
            key = [p.strip().strip("\"'") for p in m.group(1).split(".")]
            if table + key == target:
                return i
            if table + key == target[: len(table) + len(key)] and ("{" in raw or "[" in raw):
                return i
    return None


def _find_first(text: str, loc: Sequence[Any]) -> int | None:
    keys = [str(k) for k in loc if not isinstance(k, int) and k != ""]
    if not keys:
        return None
    table: list[str] = []
    header = re.compile(r"^\s*\[\[?\s*([^\]]+?)\s*\]\]?\s*(#.*)?$")
    assign = re.compile(r"^\s*([A-Za-z0-9_\-\"'. ]+?)\s*=")
    for i, raw in enumerate(text.splitlines(), start=1):
        m = header.match(raw)
        if m:
            table = [p.strip().strip("\"'") for p in m.group(1).split(".")]
            if table == keys:
                return i
            continue
        m = assign.match(raw)
        if m:
            key = [p.strip().strip("\"'") for p in m.group(1).split(".")]
            if table + key == keys or (not table and key == keys):
                return i
            # inline table at this line: key of a parent table
            if table + key == keys[: len(table) + len(key)] and "{" in raw:
                return i
    return None
