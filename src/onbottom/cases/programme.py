"""Load-programme tables and files (TOML, CSV): ``onbottom simulate``'s ``[programme]`` table.

A programme table (in a section case file, :mod:`onbottom.cases.section`, or a TOML file of
its own) names a builder of :mod:`onbottom.dynamics.programmes` by ``kind`` and gives its
arguments with loads in **kN/m** (keys ending in ``_kn``); :func:`programme_from_toml` turns it
into a :class:`~onbottom.dynamics.programmes.LoadProgramme` (SI). ``kind = "csv"`` reads the
loads from a CSV file (:func:`read_programme_csv`) named relative to the TOML file.
"""

from __future__ import annotations

import os
import re
import warnings
from collections.abc import Mapping
from typing import Any

import numpy as np

from onbottom._casefile import contained, read_toml
from onbottom._validate import integer, one_of
from onbottom.dynamics.programmes import (
    LoadProgramme,
    from_arrays,
    inclined_cyclic,
    irregular_wave_current_groups,
    regular_wave_current_groups,
)
from onbottom.errors import InputError

__all__ = ["programme_from_toml", "read_programme_csv"]

_KN = 1.0e3

WAVE_GROUP_ONLY: dict[str, tuple[str, ...]] = {
    "regular": ("sub_cycles",),
    "irregular": ("hs", "tp", "depth", "seed", "waves_per_group"),
}
"""Keys of a wave-group programme that only one of its two kinds takes (the builders of
:mod:`onbottom.dynamics.programmes`)."""


def read_programme_csv(path: str) -> np.ndarray:
    """Columns time [s], H [kN/m], V [kN/m] of a programme CSV (one header line)."""
    if not os.path.isfile(path):
        raise InputError(f"programme.file = {path!r} is invalid: file not found")
    try:
        with warnings.catch_warnings():  # an empty file is reported below, not warned
            warnings.simplefilter("ignore", UserWarning)
            data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    except (ValueError, UnicodeDecodeError) as exc:
        # never echo the file's contents (numpy quotes the offending text): row/column only
        m = re.search(r"at row (\d+), column (\d+)", str(exc))
        where = f" (row {int(m.group(1)) + 2}, column {m.group(2)})" if m else ""
        raise InputError(
            f"programme.file = {path!r} is invalid: expected numeric CSV columns time [s],"
            f" H [kN/m], V [kN/m] after one header line{where}"
        ) from None
    if data.ndim != 2 or data.shape[1] < 3 or data.shape[0] < 2:
        raise InputError(
            f"programme.file = {path!r} is invalid: expected at least 2 rows of 3 columns"
            f" (time, H, V), got shape {tuple(data.shape)}"
        )
    if not np.all(np.isfinite(data[:, :3])):
        raise InputError(f"programme.file = {path!r} is invalid: contains NaN or inf")
    return data


def programme_from_toml(source: str | os.PathLike | Mapping[str, Any]) -> LoadProgramme:
    """Build a programme from a TOML file (its ``[programme]`` table) or an equivalent mapping.

    Loads in the TOML file are in **kN/m** (keys end in ``_kn``); times in s; see
    ``examples/section_case.toml`` for every kind. ``kind`` selects the builder:

    * ``"inclined_cyclic"``: ``vertical_load_kn``, ``amplitude_step_kn``, ``period``,
      ``alpha_deg``, ``n_cycles``, optional ``shape``, ``points_per_cycle``.
    * ``"regular"``: ``vertical_load_kn``, ``n_groups``, optional ``group_period``,
      ``sub_cycles``, ``h_peak_kn``, ``h_trough_kn``, ``v_peak_kn``, ``increment``.
    * ``"irregular"``: as regular plus ``hs``, ``tp``, ``depth``, ``seed``,
      ``waves_per_group``.
    * ``"arrays"``: ``time`` [s], ``horizontal_load_kn``, ``vertical_load_kn`` lists, optional
      ``cycle_period``.
    * ``"csv"``: ``file`` (relative to the TOML file) with columns time [s], H [kN/m],
      V [kN/m] (one header line), optional ``cycle_period``.

    All kinds accept ``installation_load_kn`` (V_peak) and ``name``.
    """
    base = None
    if isinstance(source, Mapping):
        table = dict(source.get("programme", source))
    else:
        doc, _ = read_toml(source)
        if "programme" not in doc:
            raise InputError(f"{source}: no [programme] table")
        table = dict(doc["programme"])
        base = os.path.dirname(os.fspath(source))
    kind = one_of(
        "programme.kind",
        table.pop("kind", None),
        ("inclined_cyclic", "regular", "irregular", "arrays", "csv"),
    )
    v_peak = table.pop("installation_load_kn", None)
    v_peak = None if v_peak is None else float(v_peak) * _KN
    name = str(table.pop("name", kind))

    def take(key: str, *, kn: bool = False, default: Any = ...) -> Any:
        if key not in table:
            if default is ...:
                raise InputError(f"programme.{key} is missing (required for kind = {kind!r})")
            return default
        val = table.pop(key)
        return float(val) * _KN if kn else val

    if kind == "inclined_cyclic":
        prog = inclined_cyclic(
            take("vertical_load_kn", kn=True),
            take("amplitude_step_kn", kn=True),
            float(take("period")),
            float(take("alpha_deg")),
            integer("programme.n_cycles", take("n_cycles"), 1),
            shape=str(take("shape", default="sine")),
            points_per_cycle=integer(
                "programme.points_per_cycle", take("points_per_cycle", default=200), 8
            ),
            installation_load=v_peak,
            name=name,
        )
    elif kind in ("regular", "irregular"):
        other = WAVE_GROUP_ONLY["irregular" if kind == "regular" else "regular"]
        wrong = sorted(k for k in other if k in table)
        if wrong:
            raise InputError(
                f"programme.{wrong[0]} is invalid with kind = {kind!r}: it is a key of kind ="
                f" {'irregular' if kind == 'regular' else 'regular'!r}"
            )
        kwargs: dict[str, Any] = {}
        for key in ("h_peak_kn", "h_trough_kn", "v_peak_kn"):
            if key in table:
                kwargs[key[:-3]] = take(key, kn=True)
        for key in ("group_period", "increment", "hs", "tp", "depth", "waves_per_group"):
            if key in table:
                kwargs[key] = float(take(key))
        for key in ("sub_cycles", "seed"):
            if key in table:
                kwargs[key] = integer(f"programme.{key}", take(key), 0)
        builder = (
            regular_wave_current_groups if kind == "regular" else irregular_wave_current_groups
        )
        prog = builder(
            take("vertical_load_kn", kn=True),
            integer("programme.n_groups", take("n_groups"), 1),
            installation_load=v_peak,
            name=name,
            **kwargs,
        )
    else:
        if kind == "arrays":
            t = np.asarray(take("time"), dtype=float)
            h = np.asarray(take("horizontal_load_kn"), dtype=float) * _KN
            v = np.asarray(take("vertical_load_kn"), dtype=float) * _KN
        else:
            path = str(take("file"))
            if base is not None:
                value = path
                if not os.path.isabs(path):
                    path = os.path.join(base, path)
                contained(value, path, folder=base, field="programme.file")
            data = read_programme_csv(path)
            t, h, v = data[:, 0], data[:, 1] * _KN, data[:, 2] * _KN
        period = table.pop("cycle_period", None)
        prog = from_arrays(
            t,
            h,
            v,
            installation_load=v_peak,
            cycle_period=None if period is None else float(period),
            name=name,
        )
    if table:
        raise InputError(f"programme has unknown keys {sorted(table)} for kind = {kind!r}")
    return prog
