"""Build the validation report: run the sections, render the Jinja2 template, write the files.

Output folder layout::

    DIR/index.html         the report (self-contained apart from the figures beside it)
    DIR/report.json        the same content, machine-readable (checks, tables, provenance)
    DIR/figures/*.png      figures
    DIR/tables/*.csv       every table as CSV

Provenance recorded: onbottom version, git commit (and whether the tree had uncommitted
changes), date (UTC), machine (host name, platform, processor count, Python and NumPy
versions), the run time of every section and of the whole report.
"""

from __future__ import annotations

import csv
import datetime as _dt
import io
import json
import os
import platform
import subprocess
import time
import traceback
import warnings
from collections.abc import Iterable, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from onbottom._version import __version__
from onbottom.errors import InputError
from onbottom.report.content import SectionContent, SectionContext
from onbottom.report.registry import (
    ReportSection,
    UnavailableSection,
    load_sections,
    missing_requirements,
)

__all__ = ["RenderedSection", "ReportResult", "build_report", "provenance", "repo_root"]


def repo_root() -> Path | None:
    """The source checkout this onbottom runs from (holding ``docs/validation``), or None."""
    here = Path(__file__).resolve()
    for parent in here.parents:
        if (parent / "docs" / "validation").is_dir() and (parent / "pyproject.toml").is_file():
            return parent
    return None


def _git(root: Path | None, *args: str) -> str | None:
    if root is None or not (root / ".git").exists():
        return None
    try:
        out = subprocess.run(
            ["git", *args],
            cwd=root,
            capture_output=True,
            text=True,
            timeout=20,
            check=True,
        )
    except (OSError, subprocess.SubprocessError):
        return None
    return out.stdout.strip()


def provenance(root: Path | None = None) -> dict[str, Any]:
    """Version, git commit, date and machine of this build (strings; None where unknown)."""
    import numpy as np

    root = repo_root() if root is None else root
    commit = _git(root, "rev-parse", "HEAD")
    dirty = _git(root, "status", "--porcelain", "--untracked-files=no")
    return {
        "onbottom_version": __version__,
        "git_commit": commit,
        "git_dirty": None if dirty is None else bool(dirty),
        "date_utc": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "machine": platform.node() or "unknown",
        "platform": platform.platform(),
        "processors": os.cpu_count(),
        "python": platform.python_version(),
        "numpy": np.__version__,
    }


@dataclass(slots=True)
class RenderedSection:
    """One section as shown: its outcome, run time and content.

    ``state`` is ``"ok"`` (ran), ``"unavailable"`` (module missing: ``reason`` says which),
    ``"skipped"`` (left out by ``only``/``fast``) or ``"error"`` (raised: ``reason`` holds the
    traceback; counts as a failure).
    """

    name: str
    title: str
    order: int
    state: str
    run_time: float = 0.0
    reason: str = ""
    content: SectionContent = field(default_factory=SectionContent)
    table_files: list[str] = field(default_factory=list)

    @property
    def n_pass(self) -> int:
        """Checks that pass."""
        return sum(c.status == "pass" for c in self.content.checks)

    @property
    def n_fail(self) -> int:
        """Checks that fail (an error counts as one failure)."""
        return sum(c.status == "fail" for c in self.content.checks) + (self.state == "error")


@dataclass(slots=True)
class ReportResult:
    """What :func:`build_report` wrote.

    Attributes
    ----------
    index : Path
        ``index.html``.
    json_path : Path
        ``report.json``.
    sections : list of RenderedSection
        In page order.
    provenance : dict
        See :func:`provenance`; includes ``run_time`` [s].
    files : list of Path
        Every file written.
    """

    index: Path
    json_path: Path
    sections: list[RenderedSection]
    provenance: dict[str, Any]
    files: list[Path]

    @property
    def n_pass(self) -> int:
        """Checks that pass, over all sections."""
        return sum(s.n_pass for s in self.sections)

    @property
    def n_fail(self) -> int:
        """Checks that fail (and sections that raised), over all sections."""
        return sum(s.n_fail for s in self.sections)

    def summary(self) -> dict[str, Any]:
        """A JSON-able summary (for ``onbottom report --json``)."""
        return {
            "index": str(self.index),
            "json": str(self.json_path),
            "n_pass": self.n_pass,
            "n_fail": self.n_fail,
            "run_time": self.provenance["run_time"],
            "sections": [
                {
                    "name": s.name,
                    "state": s.state,
                    "n_pass": s.n_pass,
                    "n_fail": s.n_fail,
                    "run_time": round(s.run_time, 3),
                    "reason": s.reason.splitlines()[-1] if s.reason else "",
                }
                for s in self.sections
            ],
        }


def _select(
    sections: Sequence[ReportSection | UnavailableSection], only: Iterable[str] | None
) -> set[str] | None:
    if only is None:
        return None
    only = list(only)
    if not only or any(not o.strip() for o in only):
        raise InputError(
            "only = '' is invalid: a section name is required (onbottom report --list shows"
            " the names)"
        )
    wanted = {o.strip() for o in only}
    names = {s.name for s in sections}
    unknown = sorted(wanted - names)
    if unknown:
        raise InputError(
            f"only = {unknown[0]!r} is invalid: allowed sections are {', '.join(sorted(names))}"
        )
    return wanted


def _run(sec: ReportSection, ctx: SectionContext) -> RenderedSection:
    rs = RenderedSection(name=sec.name, title=sec.title, order=sec.order, state="ok")
    t0 = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # warnings belong to the runs, not the report
            content = sec.build(ctx)
        if not isinstance(content, SectionContent):
            raise TypeError(f"section {sec.name} returned {type(content).__name__}")
        rs.content = content
    except ImportError as exc:  # a part of onbottom (or a package) missing from this build
        rs.state = "unavailable"
        rs.reason = (
            f"module {exc.name} is not in this build"
            if isinstance(exc, ModuleNotFoundError)
            else f"{exc} (that part of onbottom is not complete in this build)"
        )
    except Exception:
        rs.state = "error"
        rs.reason = traceback.format_exc(limit=8)
    rs.run_time = time.perf_counter() - t0
    return rs


def _write_tables(rs: RenderedSection, out: Path) -> list[Path]:
    files = []
    for i, table in enumerate(rs.content.tables, start=1):
        rel = Path("tables") / f"{rs.name}_{i}.csv"
        path = out / rel
        from onbottom.results import write_text_atomic

        buf = io.StringIO(newline="")
        w = csv.writer(buf)
        w.writerow(table.columns)
        w.writerows(["" if c is None else c for c in row] for row in table.rows)
        write_text_atomic(path, buf.getvalue())  # kill-safe: whole or absent
        rs.table_files.append(rel.as_posix())
        files.append(path)
    return files


def _environment():
    import jinja2

    env = jinja2.Environment(
        loader=jinja2.PackageLoader("onbottom.report", "templates"),
        autoescape=jinja2.select_autoescape(["html", "j2"]),
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
    )
    from onbottom.report.content import format_cell

    env.filters["cell"] = format_cell
    return env


def _finite(obj: Any) -> Any:
    """Replace NaN/inf by None so that report.json is valid JSON."""
    import math

    if isinstance(obj, dict):
        return {k: _finite(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_finite(v) for v in obj]
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    if hasattr(obj, "item") and callable(obj.item):  # numpy scalar
        return _finite(obj.item())
    return obj


def _jsonable(rs: RenderedSection) -> dict[str, Any]:
    d = {
        "name": rs.name,
        "title": rs.title,
        "state": rs.state,
        "run_time": rs.run_time,
        "reason": rs.reason,
        "n_pass": rs.n_pass,
        "n_fail": rs.n_fail,
        "table_files": rs.table_files,
    }
    d.update(asdict(rs.content))
    return d


GENERATOR_MARK = '<meta name="generator" content="onbottom'
"""How an ``index.html`` written by :func:`build_report` begins to identify itself."""


def check_report_folder(out: str | os.PathLike, *, force: bool = False) -> Path:
    """The output folder of a report, refused when writing there would do harm.

    * a filesystem root or the home folder: always refused (a report writes index.html,
      report.json, figures/ and tables/ into the folder);
    * a folder holding an ``index.html`` that :func:`build_report` did not write (no
      onbottom generator mark): refused unless ``force`` — a report never silently
      overwrites someone else's page; an earlier onbottom report there is replaced.
    """
    p = Path(out).expanduser()
    full = p.resolve()
    if full.parent == full or full == Path.home().resolve():
        err = InputError(
            f"out = {str(p)!r} is invalid: a report needs a folder of its own, not"
            f" {'the filesystem root' if full.parent == full else 'the home folder'}"
            " (e.g. --out onbottom-report)"
        )
        err.field = "--out"  # type: ignore[attr-defined]
        raise err
    if p.exists() and not p.is_dir():
        err = InputError(f"out = {str(p)!r} is invalid: it is a file, expected a folder")
        err.field = "--out"  # type: ignore[attr-defined]
        raise err
    index = p / "index.html"
    if index.is_file() and not force:
        try:
            with index.open("rb") as fh:
                head = fh.read(4096).decode("utf-8", "replace")
        except OSError:
            head = ""
        if GENERATOR_MARK not in head:
            err = InputError(
                f"out = {str(p)!r} is invalid: it holds an index.html that onbottom did not"
                " write; choose another folder or pass --force to overwrite it"
            )
            err.field = "--out"  # type: ignore[attr-defined]
            raise err
    return p


def build_report(
    out: str | os.PathLike,
    *,
    only: Iterable[str] | None = None,
    fast: bool = False,
    title: str = "onbottom validation report",
    force: bool = False,
) -> ReportResult:
    """Run the report's sections and write ``index.html``, ``report.json``, figures, tables.

    Parameters
    ----------
    out : path
        Output folder (created; files of an earlier onbottom report are overwritten; see
        :func:`check_report_folder`).
    only : iterable of str or None
        Section names to run (others are listed as "not run"); None runs all.
    fast : bool
        Leave out the sections marked slow (the calibration recovery, …).
    title : str
        Page title.
    force : bool
        Overwrite an ``index.html`` in ``out`` that onbottom did not write
        (:func:`check_report_folder`; an earlier onbottom report is replaced without it).

    Returns
    -------
    ReportResult

    Raises
    ------
    InputError
        A name in ``only`` is not a section.
    """
    t_start = time.perf_counter()
    sections = load_sections()
    wanted = _select(sections, only)
    out_dir = check_report_folder(out, force=force)
    out_dir.mkdir(parents=True, exist_ok=True)
    root = repo_root()
    import matplotlib

    matplotlib.use("Agg", force=False)

    rendered: list[RenderedSection] = []
    files: list[Path] = []
    for sec in sections:
        rs, written = _section_outcome(sec, wanted, fast, out_dir, root)
        rendered.append(rs)
        files += written

    prov = provenance(root)
    prov["run_time"] = round(time.perf_counter() - t_start, 2)
    index, json_path = _write_page(out_dir, title, rendered, prov)
    return ReportResult(
        index=index,
        json_path=json_path,
        sections=rendered,
        provenance=prov,
        files=[index, json_path, *files],
    )


def _section_outcome(
    sec: ReportSection | UnavailableSection,
    wanted: set[str] | None,
    fast: bool,
    out_dir: Path,
    root: Path | None,
) -> tuple[RenderedSection, list[Path]]:
    """One section of the report: unavailable, skipped, or run (its figures and tables
    written into ``out_dir``); the files it wrote."""
    if isinstance(sec, UnavailableSection):
        rs = RenderedSection(
            name=sec.name, title=sec.title, order=sec.order, state="unavailable", reason=sec.reason
        )
        return rs, []
    missing = missing_requirements(sec)
    if missing:
        rs = RenderedSection(
            name=sec.name,
            title=sec.title,
            order=sec.order,
            state="unavailable",
            reason=f"module {', '.join(missing)} is not in this build",
        )
        return rs, []
    if (wanted is not None and sec.name not in wanted) or (fast and sec.slow):
        why = "left out by --fast (slow section)" if wanted is None else "not in --only"
        rs = RenderedSection(
            name=sec.name, title=sec.title, order=sec.order, state="skipped", reason=why
        )
        return rs, []
    ctx = SectionContext(name=sec.name, out_dir=out_dir, repo_root=root)
    rs = _run(sec, ctx)
    return rs, [out_dir / f.path for f in rs.content.figures] + _write_tables(rs, out_dir)


def _write_page(
    out_dir: Path, title: str, rendered: list[RenderedSection], prov: dict[str, Any]
) -> tuple[Path, Path]:
    """Write ``report.json`` and, last (a whole index.html means a whole report),
    ``index.html``; return their paths."""
    n_pass = sum(s.n_pass for s in rendered)
    n_fail = sum(s.n_fail for s in rendered)
    html = (
        _environment()
        .get_template("report.html.j2")
        .render(
            title=title,
            sections=rendered,
            provenance=prov,
            n_pass=n_pass,
            n_fail=n_fail,
            n_info=sum(sum(c.status == "info" for c in s.content.checks) for s in rendered),
        )
    )
    from onbottom.results import write_text_atomic

    json_path = out_dir / "report.json"
    write_text_atomic(
        json_path,
        json.dumps(
            _finite(
                {
                    "title": title,
                    "provenance": prov,
                    "n_pass": n_pass,
                    "n_fail": n_fail,
                    "sections": [_jsonable(s) for s in rendered],
                }
            ),
            indent=2,
            default=str,
            allow_nan=False,
        ),
    )
    index = out_dir / "index.html"
    write_text_atomic(index, html)
    return index, json_path
