"""What a report section returns: text, tables, figures and checks against stated tolerances.

A section function (see :mod:`onbottom.report.registry`) receives a :class:`SectionContext`
(where to save figures) and returns a :class:`SectionContent`. Nothing here formats HTML: the
templates do (:mod:`onbottom.report.build`).
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from onbottom.errors import InputError

__all__ = [
    "STATUSES",
    "Check",
    "FigureRef",
    "SectionContent",
    "SectionContext",
    "Table",
    "within",
]

STATUSES = ("pass", "fail", "info")
"""Check outcomes: ``pass``/``fail`` against a stated tolerance; ``info`` has no tolerance."""


def _slug(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", "_", text.lower()).strip("_") or "item"


@dataclass(frozen=True, slots=True)
class Check:
    """One comparison with a reference value and a tolerance fixed before the run.

    Attributes
    ----------
    name : str
        What is compared (e.g. ``"Q_v at 0.1D, φ' = 33°, Vesic"``).
    value : float or str or None
        The value onbottom computes (units in ``unit``).
    reference : float or str or None
        The published / reference value (units in ``unit``).
    tolerance : str
        The tolerance as a sentence (``"±1 %"``, ``"±1 cycle"``).
    status : {"pass", "fail", "info"}
        Outcome.
    unit : str
        Unit of ``value`` and ``reference`` (``""`` if dimensionless).
    note : str
        Why it fails, where the deviation is documented, or the source of the reference.
    """

    name: str
    value: float | str | None
    reference: float | str | None
    tolerance: str
    status: str
    unit: str = ""
    note: str = ""

    def __post_init__(self) -> None:
        if self.status not in STATUSES:
            raise InputError(f"status = {self.status!r} is invalid: expected one of {STATUSES}")


def within(
    name: str,
    value: float,
    reference: float,
    *,
    rtol: float = 0.0,
    atol: float = 0.0,
    unit: str = "",
    note: str = "",
    tolerance: str | None = None,
) -> Check:
    """A :class:`Check` that passes when ``|value − reference| ≤ atol + rtol·|reference|``.

    Parameters
    ----------
    name : str
        What is compared.
    value, reference : float
        Computed and reference values (same unit, ``unit``).
    rtol : float
        Relative tolerance [-].
    atol : float
        Absolute tolerance [unit].
    unit : str
        Unit of the values.
    note : str
        Source or remark.
    tolerance : str or None
        Text of the tolerance (default built from ``rtol``/``atol``).
    """
    ok = math.isfinite(value) and abs(value - reference) <= atol + rtol * abs(reference)
    if tolerance is None:
        parts = []
        if rtol:
            parts.append(f"±{100 * rtol:g} %")
        if atol:
            parts.append(f"±{atol:g} {unit}".rstrip())
        tolerance = " or ".join(parts) or "exact"
    return Check(
        name=name,
        value=float(value),
        reference=float(reference),
        tolerance=tolerance,
        status="pass" if ok else "fail",
        unit=unit,
        note=note,
    )


@dataclass(frozen=True, slots=True)
class Table:
    """A table: column headers carry their units (``"Q_v [kN/m]"``).

    Attributes
    ----------
    caption : str
        Caption shown above the table.
    columns : sequence of str
        Column headers.
    rows : sequence of sequence
        Cell values (numbers are formatted with ``digits`` decimals).
    digits : int
        Decimals for floats.
    """

    caption: str
    columns: Sequence[str]
    rows: Sequence[Sequence[Any]]
    digits: int = 3

    def __post_init__(self) -> None:
        n = len(self.columns)
        for i, row in enumerate(self.rows):
            if len(row) != n:
                raise InputError(
                    f"rows[{i}] of table {self.caption!r} is invalid: {len(row)} cells for"
                    f" {n} columns"
                )

    def formatted(self) -> list[list[str]]:
        """Rows as strings (floats to ``digits`` decimals, None/NaN as ``–``)."""
        return [[format_cell(c, self.digits) for c in row] for row in self.rows]


def format_cell(value: Any, digits: int = 3) -> str:
    """Format one cell: floats to ``digits`` decimals (tiny ones in e-notation), None/NaN ``–``."""
    if value is None:
        return "–"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        if not math.isfinite(value):
            return "–"
        if value != 0.0 and abs(value) < 0.5 * 10.0**-digits:  # would print as 0.000
            return f"{value:.2e}"
        return f"{value:.{digits}f}"
    return str(value)


@dataclass(frozen=True, slots=True)
class FigureRef:
    """A figure saved beside the page: ``path`` is relative to the report folder."""

    path: str
    caption: str


@dataclass(slots=True)
class SectionContent:
    """What a section shows, in order: summary text, checks, tables, figures, notes.

    Attributes
    ----------
    summary : str
        One paragraph (plain text) saying what was run and against what.
    checks : list of Check
        Comparisons with stated tolerances (pass/fail).
    tables : list of Table
        Result tables.
    figures : list of FigureRef
        Figures saved with :meth:`SectionContext.save_figure`.
    notes : list of str
        Assumptions, documented deviations, where to read more.
    sources : list of str
        The documents the reference values come from.
    """

    summary: str = ""
    checks: list[Check] = field(default_factory=list)
    tables: list[Table] = field(default_factory=list)
    figures: list[FigureRef] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    sources: list[str] = field(default_factory=list)


@dataclass(frozen=True, slots=True)
class SectionContext:
    """Where a section writes its files.

    Attributes
    ----------
    name : str
        The section's name (prefix of its figure files).
    out_dir : Path
        The report folder (``index.html`` lives here).
    repo_root : Path or None
        The source checkout holding ``docs/`` (committed summaries), if found.
    """

    name: str
    out_dir: Path
    repo_root: Path | None = None

    def save_figure(self, fig: Any, name: str, caption: str, *, dpi: int = 100) -> FigureRef:
        """Save a matplotlib figure as ``figures/<section>_<name>.png`` and close it.

        Parameters
        ----------
        fig : matplotlib.figure.Figure
            The figure.
        name : str
            Short file-name stem.
        caption : str
            Caption shown under the figure.
        dpi : int
            Resolution [dots per inch].
        """
        rel = Path("figures") / f"{_slug(self.name)}_{_slug(name)}.png"
        path = self.out_dir / rel
        from onbottom.results import save_figure

        save_figure(fig, path, dpi=dpi, bbox_inches="tight")
        import matplotlib.pyplot as plt

        plt.close(fig)
        return FigureRef(path=rel.as_posix(), caption=caption)

    def copy_figure(self, src: str | Path, caption: str) -> FigureRef:
        """Copy an existing PNG (e.g. a committed figure) beside the page."""
        import shutil

        src = Path(src)
        rel = Path("figures") / f"{_slug(self.name)}_{_slug(src.stem)}{src.suffix}"
        (self.out_dir / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(src, self.out_dir / rel)
        return FigureRef(path=rel.as_posix(), caption=caption)
