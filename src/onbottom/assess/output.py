"""Outputs of ``onbottom assess``: ``results.json``, ``dynamic.nc``, ``report.html`` (+ PDF).

Every file is written under a temporary name and renamed when complete
(:mod:`onbottom.results`); the case file is only read.

``results.json`` keys (:data:`RESULTS_KEYS`): ``schema`` ("onbottom.assess/1"),
``provenance`` (onbottom version, git commit, date, machine, case source and SHA-256 of its
text, run identity), ``route`` (name, sections count), ``summary`` (one row per section:
section, kp_start_m, kp_end_m, water_depth_m, seabed, governing_check, max_utilisation at
the given design, variable, vertical_value / absolute_value / generalized_value /
dynamic_value — the minimum of the design variable per level, m or N/m, null where the level
has no solution or was not run — governing_level, design_value, saved_submerged_weight_n_per_m),
``sections`` (everything per section: checks with details, levels, per-seed dynamic results
and the search trials (key ``bisection``), notes, the section's ``onbottom stability`` case
document),
``comparison`` (per section: which of the absolute and dynamic designs is heavier, and why),
``validity`` (notes on reconstructed models), ``clauses`` (equation → clause reference),
``pipeline`` (the pipeline FE run of the governing section, ``[levels] pipeline_fe``: section,
combination, seed, design value, max_displacement_m / _over_D, max_strain, strain_limit,
strain_check, worst_node_x_m, status, envelopes {x, max_abs_y, max_strain, max_abs_moment}
[m, m, -, N·m], wall_time_s, netcdf; null when not run). The FE results are NetCDF files
(:func:`onbottom.assess.pipeline.fe_dataset`): ``pipeline.nc`` of the governing section, or with
``[pipeline] sections = "every"`` one per section checked, ``pipeline/NN-<section>.nc``, each
named by its check's ``netcdf`` key (``sections[i].pipeline_fe.netcdf``) and listed in the
files written.

Figures are embedded (inline SVG, PNG as data URIs): the report is one self-contained file.
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import hashlib
import json
import math
import os
import platform
import socket
import subprocess
from pathlib import Path
from typing import Any

from onbottom._version import __version__, content_hash
from onbottom.assess._report import render, report_context
from onbottom.assess._wording import (
    CLAUSES,
    VALIDITY,
    WHY_LIGHTER,
    format_value,
    level_name,
)
from onbottom.assess.core import Assessment
from onbottom.errors import InputError
from onbottom.results import atomic_write, save_dataset, write_text_atomic

__all__ = [
    "CLAUSES",
    "LOCK_NAME",
    "MARK_NAME",
    "RELIABILITY_NAMES",
    "RESULTS_KEYS",
    "VALIDITY",
    "OutputFolder",
    "claim_output_folder",
    "comparison",
    "fe_files",
    "format_value",
    "level_name",
    "provenance_block",
    "results_payload",
    "write_outputs",
]

RESULTS_KEYS = (
    "schema",
    "provenance",
    "route",
    "summary",
    "sections",
    "comparison",
    "validity",
    "clauses",
    "pipeline",
)


def _git_commit() -> str:
    try:
        r = subprocess.run(
            ["git", "rev-parse", "HEAD"],
            cwd=Path(__file__).resolve().parent,
            capture_output=True,
            text=True,
            timeout=5,
            check=False,
        )
        return r.stdout.strip() if r.returncode == 0 and r.stdout.strip() else "unknown"
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def provenance_block(a: Assessment, case_text: str | None) -> dict[str, Any]:
    """Version, commit, date, machine, case source and hash, run identity."""
    return {
        "onbottom_version": __version__,
        "git_commit": _git_commit(),
        "date": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "machine": f"{platform.node()} ({platform.platform()}, {platform.processor() or '?'})",
        "python": platform.python_version(),
        "case_source": a.source,
        "case_sha256": None
        if case_text is None
        else hashlib.sha256(case_text.encode("utf-8")).hexdigest(),
        "run_identity": a.identity,
        "onbottom_content_hash": content_hash(),
        "wall_time_s": a.wall_time_s,
        "sections_reused": a.reused,
        "sections_recomputed": [{"section": n, "reason": r} for n, r in a.recomputed],
    }


def comparison(a: Assessment) -> list[dict[str, Any]]:
    """Per section: absolute vs dynamic design, which is heavier, and the reason stated."""
    out = []
    for s in a.sections:
        lv = s["levels"]
        xa = (lv.get("absolute") or {}).get("value")
        xd = (lv.get("dynamic") or {}).get("value")
        if "absolute" not in lv or "dynamic" not in lv:
            continue
        if xa is None and xd is None:
            verdict, why = "neither", "no design in the range at either level"
        elif xa is None:
            verdict = "absolute"
            why = (
                "the absolute method finds no design in the range while storms on the section"
                " stay within the allowable: it requires zero movement under the single design"
                " oscillation (U*, T*) with peak load coefficients, whereas the dynamic level"
                " lets the soil resistance build up with penetration and allows the"
                " displacement"
            )
        elif xd is None:
            verdict = "dynamic"
            why = (
                "the dynamic level finds no design in the range: some seed exceeds the"
                " allowable even at the upper bound (check the storm and the soil model)"
            )
        elif xd < xa:
            verdict = "absolute"
            why = WHY_LIGHTER
        elif xd > xa:
            verdict = "dynamic"
            why = (
                "the dynamic level asks for more weight than the absolute method here: the"
                " absolute method is meant to be conservative, so this points at the dynamic"
                " model's assumptions (the force model and its calibration, the soil model's"
                " range, every seed rather than the mean must pass) or at a small number of"
                " seeds — treat it as a finding to review"
            )
        else:
            verdict, why = "equal", "both levels give the same design"
        out.append({"section": s["name"], "absolute_value": xa, "dynamic_value": xd,
                    "heavier": verdict, "reason": why})  # fmt: skip
    return out


def _json_safe(x: Any) -> Any:
    if isinstance(x, dict):
        return {str(k): _json_safe(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_json_safe(v) for v in x]
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if hasattr(x, "item") and not isinstance(x, (str, bytes)):
        try:
            return _json_safe(x.item())
        except (TypeError, ValueError):
            return str(x)
    return x


def results_payload(a: Assessment, case_text: str | None) -> dict[str, Any]:
    """The ``results.json`` document (keys: :data:`RESULTS_KEYS`)."""
    summary = a.summary
    return _json_safe({
        "schema": "onbottom.assess/1",
        "provenance": provenance_block(a, case_text),
        "route": {"name": a.route.name, "sections": len(a.sections),
                  "variable": a.route.variable,
                  "allowable": a.route.dynamic.allowable
                  if a.route.dynamic.allowable != "user"
                  else f"{a.route.dynamic.allowable_displacement_m} m"},
        "summary": summary.astype(object).where(summary.notna(), None).to_dict("records"),
        "sections": a.sections,
        "comparison": comparison(a),
        "validity": VALIDITY,
        "clauses": CLAUSES,
        "pipeline": a.pipeline,
    })  # fmt: skip


def report_html(a: Assessment, payload: dict[str, Any]) -> str:
    """The design report (self-contained HTML: the shared report style, inline figures)."""
    return render(report_context(a, payload))


def write_outputs(
    a: Assessment,
    out: str | Path,
    *,
    case_text: str | None = None,
    pdf: bool = True,
    notes: list[str] | tuple[str, ...] = (),
) -> dict[str, Any]:
    """Write results.json, dynamic.nc, report.html and (WeasyPrint installed) report.pdf into
    ``out``; return ``{"files": [...], "pdf": str | None (why not)}``, the files listing also
    the pipeline FE results the run wrote (:func:`fe_files`). ``notes``: warnings raised while
    the route was read and run, listed in the report with the sections' own."""
    outp = Path(out)
    payload = results_payload(a, case_text)
    files = [write_text_atomic(outp / "results.json", json.dumps(payload, indent=1))]
    ds = a.dynamic_dataset()
    if ds.data_vars:
        files.append(save_dataset(ds, outp / "dynamic.nc"))
    files += fe_files(a)
    ctx = report_context(a, payload, notes=notes)
    for tb in ctx["tables"]:
        files.append(write_text_atomic(outp / tb["csv"], tb["csv_text"]))
    text = render(ctx)
    files.append(write_text_atomic(outp / "report.html", text))
    why = None
    if pdf:
        try:
            from weasyprint import HTML  # optional: onbottom[pdf]
        except (ImportError, OSError) as exc:
            why = f"report.pdf not written: WeasyPrint is not available ({type(exc).__name__})"
        else:
            atomic_write(
                outp / "report.pdf",
                lambda tmp: HTML(string=text, base_url=str(outp)).write_pdf(tmp),
            )
            files.append(outp / "report.pdf")
    else:
        why = "report.pdf not asked for"
    return {"files": [str(f) for f in files], "pdf": why}


def fe_files(a: Assessment) -> list[Path]:
    """The pipeline FE results (NetCDF) of the route: each section's check with
    ``[pipeline] sections = "every"`` (``pipeline/NN-<section>.nc``), else the governing
    section's ``pipeline.nc``; those on disk, in section order."""
    docs = [s.get("pipeline_fe") for s in a.sections] + [a.pipeline]
    found = [Path(d["netcdf"]) for d in docs if d and d.get("netcdf")]
    return [f for f in dict.fromkeys(found) if f.is_file()]


# ---- the output folder: whose files, which run -----------------------------------------------
MARK_NAME = ".onbottom-assess"
"""The file that marks a folder as written by ``onbottom assess`` (its files may be replaced)."""

LOCK_NAME = ".onbottom-assess.lock"
"""The lock file of the run writing a folder (its process id and host)."""

_OWN_NAMES = frozenset(
    {
        "results.json",
        "dynamic.nc",
        "report.html",
        "report.pdf",
        "sections",
        "pipeline.nc",
        "pipeline",
    }
)

RELIABILITY_NAMES = frozenset(
    {
        "campaign.zarr",
        "design.zarr",
        "reliability.json",
        "exceedance.png",
        "convergence.png",
        "importance.png",
        "design.png",
        "report.html",
        "tables",
    }
)
"""What ``onbottom reliability`` writes into its ``--out``."""
_GENERATOR = '<meta name="generator" content="onbottom'


class OutputFolder:
    """The ``--out`` folder of ``onbottom assess``, held for one run (:func:`claim_output_folder`;
    a context manager: the lock file is removed on exit). ``notes``: what was found (a stale
    lock taken over)."""

    def __init__(self, path: Path, notes: list[str], lock: Path | None = None) -> None:
        self.path = path
        self.notes = notes
        self.lock = path / LOCK_NAME if lock is None else lock

    def __enter__(self) -> OutputFolder:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.release()

    def release(self) -> None:
        """Remove the lock file if it is still this process's."""
        lock = self.lock
        try:
            if _lock_owner(lock)[0] == os.getpid():
                lock.unlink()
        except OSError:
            pass


def _refuse(message: str) -> InputError:
    err = InputError(message)
    err.field = "--out"  # type: ignore[attr-defined]
    return err


def _foreign(out: Path, mark: str, own: frozenset[str]) -> list[str]:
    """Entries of ``out`` that the command did not write (empty: the folder is its own or
    empty). With the ``mark`` file every entry is taken as the tool's; without it (a folder of
    an older run) only the tool's names ``own``, and a report.html carrying its mark."""
    entries = sorted(out.iterdir(), key=lambda q: q.name)
    if (out / mark).is_file():
        return []
    names = own | {mark, mark + ".lock"}
    foreign = [
        q.name
        for q in entries
        if q.name not in names
        and not any(q.name.startswith(n) for n in names)  # its partial and temporary files
        and not (q.name.startswith(".") and q.name.endswith(".tmp"))
    ]
    page = out / "report.html"
    if page.is_file():
        try:
            with page.open("rb") as fh:
                head = fh.read(4096).decode("utf-8", "replace")
        except OSError:
            head = ""
        if _GENERATOR not in head:
            foreign.append("report.html")
    return foreign


def _lock_owner(lock: Path) -> tuple[int | None, str]:
    """(process id, host) written in a lock file; (None, "") if unreadable."""
    try:
        pid, _, host = lock.read_text(encoding="utf-8").strip().partition(" ")
        return int(pid), host
    except (OSError, ValueError):
        return None, ""


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True  # a process of another user
    except OSError:
        return True
    return True


def claim_output_folder(
    out: str | Path,
    *,
    force: bool = False,
    command: str = "assess",
    own: frozenset[str] = _OWN_NAMES,
) -> OutputFolder:
    """Check and lock ``--out`` for one ``onbottom assess`` run (or ``command``'s, writing the
    names ``own``: ``onbottom reliability`` with :data:`RELIABILITY_NAMES`).

    * the filesystem root and the home folder: refused (as ``onbottom report``'s
      :func:`onbottom.report.build.check_report_folder`; an assessment writes report.html,
      results.json, dynamic.nc and sections/ into the folder);
    * a folder holding files that onbottom did not write (no :data:`MARK_NAME`, and a name
      that is not the tool's, or a report.html without its generator mark): refused unless
      ``force``;
    * a folder that another run is writing (:data:`LOCK_NAME` of a live process on this
      host): refused, naming the process; a lock left by a process that is gone (killed) is
      taken over, with a note.

    Returns the held :class:`OutputFolder` (use it in ``with``); every refusal is an
    :class:`~onbottom.errors.InputError` with ``field = "--out"``.
    """
    p = Path(out).expanduser()
    full = p.resolve()
    if full.parent == full or full == Path.home().resolve():
        where = "the filesystem root" if full.parent == full else "the home folder"
        raise _refuse(
            f"--out = {str(p)!r} is invalid: onbottom {command} needs a folder of its own,"
            f" not {where} (e.g. --out {command}_results)"
        )
    if p.exists() and not p.is_dir():
        raise _refuse(f"--out = {str(p)!r} is invalid: it is a file, expected a folder")
    notes: list[str] = []
    if p.is_dir() and not force:
        foreign = _foreign(p, f".onbottom-{command}", own)
        if foreign:
            shown = ", ".join(foreign[:5]) + (
                f" and {len(foreign) - 5} more" if len(foreign) > 5 else ""
            )
            raise _refuse(
                f"--out = {str(p)!r} is invalid: it holds files that onbottom did not write"
                f" ({shown}); choose another folder or pass --force to write there anyway"
            )
    p.mkdir(parents=True, exist_ok=True)
    lock = p / f".onbottom-{command}.lock"
    me = f"{os.getpid()} {socket.gethostname()}"
    for _ in range(2):
        try:
            fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
        except FileExistsError:
            pid, host = _lock_owner(lock)
            if pid is not None and host == socket.gethostname() and not _alive(pid):
                notes.append(
                    f"{lock} was left by process {pid}, which is gone (killed?): taken over"
                )
                with contextlib.suppress(OSError):
                    lock.unlink()
                continue
            who = f"process {pid} on {host or 'an unknown host'}" if pid else "another run"
            raise _refuse(
                f"--out = {str(p)!r} is in use: {who} is writing it (lock file {lock}); wait"
                " for it to finish or choose another --out (if no such run exists, delete the"
                " lock file)"
            ) from None
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(me + "\n")
        break
    else:  # pragma: no cover - two takeovers raced
        raise _refuse(f"--out = {str(p)!r} is in use: its lock file {lock} keeps reappearing")
    mark = p / f".onbottom-{command}"
    if not mark.is_file():
        write_text_atomic(mark, f"written by onbottom {command}: its files may be replaced\n")
    return OutputFolder(p, notes, lock)
