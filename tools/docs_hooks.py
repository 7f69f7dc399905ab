"""MkDocs hooks of the onbottom site (``mkdocs.yml: hooks``).

At build time this hook

* expands nav entries that name a folder (``theory/``) into that folder's pages, titled by
  their first heading, so a new theory or validation page appears without editing mkdocs.yml;
* runs every ``examples/ex*.py`` in a scratch folder and adds a gallery page per example
  (docstring, source, printed output, the figures it wrote) — an example that fails breaks
  the build;
* runs ``onbottom report`` (the validation report) and adds it under ``validation-report/``;
* writes one API reference page per subpackage (mkdocstrings renders the docstrings).

Environment: ``ONBOTTOM_DOCS_REPORT`` = ``full`` (default), ``fast`` (leave out the slow
sections) or ``skip`` (a page saying the report was not built); ``ONBOTTOM_DOCS_GALLERY`` =
``run`` (default) or ``skip``.
"""

from __future__ import annotations

import ast
import logging
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from mkdocs.structure.files import File, Files

log = logging.getLogger("mkdocs.hooks.onbottom")

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
REPORT_DIR = "validation/validation-report"
REPORT_LINK = "validation-report"  # relative to validation/report.md
API_PACKAGES = (
    ("onbottom", "Top-level API: the names exported by `import onbottom`."),
    ("onbottom.inputs", ""),
    ("onbottom.hydro", ""),
    ("onbottom.soil", ""),
    ("onbottom.checks", ""),
    ("onbottom.dynamics", ""),
    ("onbottom.dem", ""),
    ("onbottom.calibration", ""),
    ("onbottom.study", ""),
    ("onbottom.metocean", ""),
    ("onbottom.reliability", ""),
    ("onbottom.assess", "Route assessment (`onbottom assess`): docs/assess.md."),
    ("onbottom.plotting", ""),
    ("onbottom.report", ""),
    ("onbottom.cases", "Case files: every TOML/JSON schema and case → model builder."),
    ("onbottom.results", ""),
    ("onbottom.errors", ""),
)
EXAMPLE_TIMEOUT_S = None
"""No kill timer on the gallery (issue 31: a slow or loaded machine must not fail the build)."""
GENERATED_PAGES = {"validation/": (("Validation report", "validation/report.md"),)}
"""Pages this hook generates, listed first in the nav folder they belong to."""

_scratch: Path | None = None
timings: dict[str, float] = {}


# ---------------------------------------------------------------------------------------------
# nav: folders expand into their pages


def _title(path: Path) -> str:
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("# "):
            return line[2:].strip()
    return path.stem.replace("_", " ")


def _expand(items, docs_dir: Path):
    out = []
    for item in items:
        if isinstance(item, dict):
            (key, value), *_ = item.items()
            if value == "api/":
                value = [{"Overview": "api/index.md"}] + [
                    {mod: f"api/{mod.replace('.', '_')}.md"} for mod, _ in API_PACKAGES
                ]
            elif value == "gallery/":
                value = [{"Gallery": "gallery/index.md"}] + [
                    {p.stem: f"gallery/{p.stem}.md"} for p in sorted(EXAMPLES.glob("ex*.py"))
                ]
            elif isinstance(value, str) and value.endswith("/"):
                pages = sorted((docs_dir / value).glob("*.md"))
                value = [
                    *({t: u} for t, u in GENERATED_PAGES.get(value, ())),
                    *({_title(p): p.relative_to(docs_dir).as_posix()} for p in pages),
                ]
            elif isinstance(value, list):
                value = _expand(value, docs_dir)
            out.append({key: value})
        else:
            out.append(item)
    return out


# Docstrings state units in brackets after a bracketed expression ("in [a, b] [-]", "x [m]"):
# Markdown reads "[a, b] [-]" as a reference link to "-" and autorefs warns that the target is
# missing. Those are units, not references: such warnings (only they) are dropped; a missing
# target that is not a unit still fails the strict build.
_UNITS = {"-", "–", "m", "s", "N", "J", "W", "Pa", "kPa", "kN", "kg", "rad", "deg", "°", "%", "Hz"}
_UNRESOLVED = re.compile(r"Could not find cross-reference target '([^']*)'")


def _is_unit(target: str) -> bool:
    return target in _UNITS or any(c in target for c in "/²³·⁻")


class _UnitBrackets(logging.Filter):
    def filter(self, record: logging.LogRecord) -> bool:
        m = _UNRESOLVED.search(record.getMessage())
        return not (m and _is_unit(m.group(1)))


def on_config(config):
    """Expand folder entries of the nav; stop autorefs reading units as references."""
    for name in list(logging.root.manager.loggerDict):
        if name.startswith("mkdocs.plugins.mkdocs_autorefs"):
            logging.getLogger(name).addFilter(_UnitBrackets())
    if config.nav:
        config.nav = _expand(config.nav, Path(config.docs_dir))
    return config


# ---------------------------------------------------------------------------------------------
# generated pages


def _add(files: Files, config, uri: str, *, content: str | None = None, src: Path | None = None):
    if files.get_file_from_path(uri) is not None:
        files.remove(files.get_file_from_path(uri))
    if content is not None:
        files.append(File.generated(config, uri, content=content))
    else:
        files.append(File.generated(config, uri, abs_src_path=str(src)))


def _docstring(path: Path) -> str:
    doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""
    # keep the prose; drop the indented "python examples/..." usage line
    return "\n".join(line for line in doc.splitlines() if not line.startswith("    "))


def _run_example(script: Path, workdir: Path) -> tuple[str, float]:
    env = dict(os.environ, MPLBACKEND="Agg")
    env.setdefault("NUMBA_NUM_THREADS", "1")
    t0 = time.perf_counter()
    proc = subprocess.run(
        [sys.executable, str(script)],
        cwd=workdir,
        capture_output=True,
        text=True,
        env=env,
        timeout=EXAMPLE_TIMEOUT_S,
        check=False,
    )
    dt = time.perf_counter() - t0
    if proc.returncode != 0:
        raise RuntimeError(f"example {script.name} failed:\n{proc.stderr[-3000:]}")
    return proc.stdout, dt


def _gallery(files: Files, config, scratch: Path) -> None:
    scripts = sorted(EXAMPLES.glob("ex*.py"))
    index = [
        "# Examples gallery",
        "",
        "Every script in `examples/` was run when this site was built; the output and figures",
        "below are from that run (`python examples/<name>.py` reproduces them).",
        "",
    ]
    mode = os.environ.get("ONBOTTOM_DOCS_GALLERY", "run")
    runs = {}
    if mode != "skip":
        # the examples are independent processes: run them two at a time (CI has 2 cores)
        from concurrent.futures import ThreadPoolExecutor

        for script in scripts:
            (scratch / "gallery" / script.stem).mkdir(parents=True, exist_ok=True)
        with ThreadPoolExecutor(max_workers=max(1, min(2, os.cpu_count() or 1))) as pool:
            futures = {
                s: pool.submit(_run_example, s, scratch / "gallery" / s.stem) for s in scripts
            }
            runs = {s: f.result() for s, f in futures.items()}
    for script in scripts:
        stem = script.stem
        title = _docstring(script).splitlines()[0] if _docstring(script) else stem
        page = [f"# {stem}: {title}", "", *_docstring(script).splitlines()[1:], ""]
        figures: list[str] = []
        if mode == "skip":
            page += ["!!! note", "    Not run in this build (ONBOTTOM_DOCS_GALLERY=skip).", ""]
        else:
            work = scratch / "gallery" / stem
            stdout, dt = runs[script]
            timings[f"example {stem}"] = dt
            log.info("gallery: %s ran in %.1f s", script.name, dt)
            for png in sorted(work.rglob("*.png")):
                uri = f"gallery/{stem}/{png.relative_to(work).as_posix()}"
                _add(files, config, uri, src=png)
                figures.append(uri.removeprefix("gallery/"))
            page += [f"Output (ran in {dt:.1f} s at build time):", "", "```text", stdout, "```", ""]
            for fig in figures:
                page += [f"![{Path(fig).stem}]({fig})", ""]
        page += [
            "Source:",
            "",
            "```python",
            script.read_text(encoding="utf-8").rstrip(),
            "```",
            "",
        ]
        _add(files, config, f"gallery/{stem}.md", content="\n".join(page))
        thumb = f"![{stem}]({figures[0]}){{ width=240 }}" if figures else ""
        index += [f"## [{stem}]({stem}.md)", "", title, "", thumb, ""]
    _add(files, config, "gallery/index.md", content="\n".join(index))


def _report(files: Files, config, scratch: Path) -> None:
    mode = os.environ.get("ONBOTTOM_DOCS_REPORT", "full")
    page = [
        "# Validation report",
        "",
        "Every comparison with the papers and the standards on one page, rebuilt by one",
        "command: `onbottom report --out DIR`. Each check states its tolerance, fixed before",
        "the run; a failure the project knows says where it is documented.",
        "",
    ]
    if mode == "skip":
        page += ["!!! note", "    Not built with this site (ONBOTTOM_DOCS_REPORT=skip).", ""]
    else:
        from onbottom.report import build_report

        out = scratch / "report"
        t0 = time.perf_counter()
        res = build_report(out, fast=(mode == "fast"))
        timings["report"] = time.perf_counter() - t0
        for s in res.sections:  # a section that raised is a bug: fail the strict build
            if s.state == "error":
                log.warning("validation report: section %s raised:\n%s", s.name, s.reason)
        for path in sorted(p for p in out.rglob("*") if p.is_file()):
            _add(files, config, f"{REPORT_DIR}/{path.relative_to(out).as_posix()}", src=path)
        page += [
            f"**[Open the validation report]({REPORT_LINK}/index.html)** — built with this site:"
            f" {res.n_pass} checks pass, {res.n_fail} fail"
            f" (commit `{res.provenance['git_commit'] or 'unknown'}`,"
            f" {res.provenance['run_time']} s).",
            "",
            "| section | result |",
            "|---|---|",
        ]
        for s in res.sections:
            state = {
                "ok": f"{s.n_pass} pass, {s.n_fail} fail",
                "unavailable": "not available in this build",
                "skipped": "not run",
                "error": "error",
            }[s.state]
            page.append(f"| [{s.title}]({REPORT_LINK}/index.html#{s.name}) | {state} |")
        page.append("")
    _add(files, config, "validation/report.md", content="\n".join(page))


def _exports() -> str:
    import onbottom

    lines = ["| name | defined in |", "|---|---|"]
    for name in sorted(onbottom.__all__):
        obj = getattr(onbottom, name, None)
        mod = getattr(obj, "__module__", None) or "onbottom"
        lines.append(f"| `{name}` | `{mod}` |")
    return "\n".join(lines)


def _api(files: Files, config) -> None:
    index = [
        "# API reference",
        "",
        "Generated from the docstrings. Units are SI unless a parameter name says otherwise.",
        "",
    ]
    for mod, blurb in API_PACKAGES:
        slug = mod.replace(".", "_")
        body = f"# `{mod}`\n\n{blurb}\n\n::: {mod}\n"
        if mod == "onbottom":  # its names are documented where they are defined
            body += "    options:\n      members: false\n      show_submodules: false\n"
            body += "\n" + _exports() + "\n"
        _add(files, config, f"api/{slug}.md", content=body)
        index.append(f"- [`{mod}`]({slug}.md)")
    _add(files, config, "api/models.md", content=_models())
    index.append("- [Models by name: the registries](models.md)")
    _add(files, config, "api/index.md", content="\n".join(index) + "\n")


def _models() -> str:
    """The registered soil models, force models and design checks (the names case files use),
    from the registries themselves (`onbottom.registry.Registry.table`)."""
    from onbottom.checks.registry import CHECKS
    from onbottom.hydro.registry import FORCE_REGISTRY
    from onbottom.soil.registry import SOIL_MODELS

    parts = ["# Models by name", "", "Generated from the registries at build time."]
    for title, key, reg in (
        ("Soil models", "`[soil] model`, options in `[soil.<name>]`", SOIL_MODELS),
        ("Force models", "`[hydro] model`, options in `[hydro.<name>]`", FORCE_REGISTRY),
        ("Design checks", "`[design] checks`", CHECKS),
    ):
        parts += ["", f"## {title}", "", f"Case-file key: {key}.", "", reg.table()]
    return "\n".join(parts) + "\n"


def on_files(files: Files, config) -> Files:
    """Add the generated pages: gallery, validation report, API reference."""
    global _scratch
    _scratch = Path(tempfile.mkdtemp(prefix="onbottom-docs-"))
    _gallery(files, config, _scratch)
    _report(files, config, _scratch)
    _api(files, config)
    return files


def on_post_build(config) -> None:
    """Remove the scratch folder and log the build-time runs."""
    for what, dt in timings.items():
        log.info("build-time run: %s %.1f s", what, dt)
    if _scratch is not None:
        shutil.rmtree(_scratch, ignore_errors=True)
