"""Generalized and dynamic-curves levels of a route section.

* **generalized** — DNV-RP-F109 (2010/2017) §3.5 from F109's own tables
  (:mod:`onbottom.checks.f109_generalized`): the weight parameter L = w_s/(½ ρ_w D U_s²) at
  which a pipe moves 0.5D (L_stable) or 10D (L_10), against K = U_s T_u/D, M = V/U_s and
  N = U_s/(g T_u). The utilisation is L_required / L_actual. Where F109's tables do not give
  L (clay, calcareous or rock seabeds, a point outside the tables) the row says "not covered"
  and why; nothing is extrapolated.
* **dynamic curves** — the tool's own curve sweeps (``onbottom curves``, NetCDF of
  :mod:`onbottom.study.stability_curves`), read in the same groups: a separate level, never
  presented as F109's. A combination is covered when a sweep has the section's soil and its
  N, M and K lie inside the sweep's grid; L is then interpolated linearly in (N, M, K).
  The shipped sweeps are package data (``onbottom/data/stability_curves/*.nc``).

U_s and T_u are the significant flow velocity and zero-up-crossing period at the pipe of the
absolute check (F109 §3.4.3, its ``us``/``tu``); V is its steady current V* (F109 Eq 3.4,
mean over D, normal to the pipe).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any

__all__ = ["curve_files_at", "default_curve_files", "dynamic_curve_rows", "generalized_rows"]

CRITERION = {"0.5D": "L_stable", "10D": "L_10"}

F109_SOIL = {"sand": "sand", "clay": "clay"}
"""Seabed model → soil of F109's generalized tables (sand: silica sand; others not covered)."""


def default_curve_files() -> list[str]:
    """The shipped curve sweeps: package data ``onbottom/data/stability_curves/*.nc``."""
    from importlib.resources import files

    folder = Path(str(files("onbottom") / "data" / "stability_curves"))
    return [str(p) for p in sorted(folder.glob("*.nc"))] if folder.is_dir() else []


def curve_files_at(path: str | Path) -> list[str]:
    """The sweeps at ``path``: the file itself, or every ``*.nc`` of a folder."""
    p = Path(path)
    return [str(f) for f in sorted(p.glob("*.nc"))] if p.is_dir() else [str(p)]


@functools.lru_cache(maxsize=16)
def _load(path: str) -> Any:
    """A sweep read once per process (None if unreadable: reported as not covered)."""
    from onbottom.results import load_dataset

    try:
        return load_dataset(path)
    except Exception:
        return None


def _point(r: Any, rho: float) -> dict[str, float] | None:
    from onbottom.checks.f109_generalized import generalized_point

    return generalized_point(r.details, rho)


def _lateral(rows: list[Any]) -> list[Any]:
    return [r for r in rows if r.name == "absolute_lateral" and "us" in r.details]


def _flow_points(
    rows: list[Any], name: str, level: str, rho: float, out: list[dict[str, Any]]
) -> Iterator[tuple[dict[str, Any], dict[str, float]]]:
    """(row start, point K, M, N, L) of each absolute-lateral row with wave flow at the pipe;
    a row without flow (U_s = 0) is appended to ``out`` as not covered instead."""
    for r in _lateral(rows):
        base = {"name": name, "combination": r.combination, "condition": r.condition,
                "level": level, "covered": False, "utilisation": None, "pass": None}  # fmt: skip
        point = _point(r, rho)
        if point is None:
            out.append(base | {"message": "no wave flow at the pipe (U_s = 0)", "details": {}})
            continue
        yield base, point


def generalized_rows(
    rows: list[Any],
    allowable: str = "0.5D",
    *,
    seabed_model: str,
    water_density: float,
) -> list[dict[str, Any]]:
    """One row per absolute-lateral row of ``rows`` (:func:`onbottom.checks.design.run_checks`
    on the section): level ``generalized`` (F109 §3.5 tables), ``covered`` and ``message``;
    where covered, ``utilisation`` = L_required/L_actual and the point (K, M, N, L).
    ``seabed_model``: the section's soil model name; ``water_density``: ρ_w [kg/m³] of L."""
    from onbottom.checks.f109_generalized import generalized_requirement

    out = []
    soil = F109_SOIL.get(seabed_model)
    for base, point in _flow_points(rows, "generalized_lateral", "generalized", water_density, out):
        if soil is None:
            msg = (
                f"seabed model {seabed_model!r}: F109's generalized method (§3.5) covers sand"
                " and clay only"
            )
            out.append(base | {"message": msg, "details": point})
            continue
        req = generalized_requirement(soil, allowable, point["K"], point["M"], point["N"])
        if not req.covered or req.L is None:
            out.append(base | {"message": req.reason, "details": point})
            continue
        u = req.L / point["L_actual"]
        wreq = req.required_weight(point["diameter"], point["U_s"], water_density)
        out.append(
            base
            | {
                "covered": True,
                "utilisation": u,
                "pass": u <= 1.0,
                "message": f"{CRITERION[allowable]} from {req.reason}",
                "details": point
                | {"L_required": req.L, "required_submerged_weight": wreq, "source": req.source},
            }
        )
    return out


def dynamic_curve_rows(
    rows: list[Any],
    files: list[str],
    allowable: str = "0.5D",
    *,
    seabed_model: str,
    water_density: float,
) -> list[dict[str, Any]]:
    """As :func:`generalized_rows`, from the tool's own curve sweeps ``files`` (level
    ``dynamic_curves``: the dynamic model's curves, not F109's tables)."""
    out = []
    sweeps = [(f, ds) for f in files if (ds := _load(f)) is not None]
    crit = CRITERION.get(allowable)
    soil = F109_SOIL.get(seabed_model)
    for base, point in _flow_points(
        rows, "dynamic_curves_lateral", "dynamic_curves", water_density, out
    ):
        k, m, n = point["K"], point["M"], point["N"]
        msg = None
        if crit is None:
            msg = f"allowable {allowable!r}: the curves give 0.5D and 10D only"
        elif not sweeps:
            unread = ", ".join(Path(f).name for f in files) or "none given"
            msg = f"no readable curve sweep ({unread})"
        elif soil is None:
            msg = f"seabed model {seabed_model!r} has no curves (sand and clay only)"
        found = None
        if msg is None:
            reasons = []
            for f, ds in sweeps:
                if crit not in ds or soil not in [str(s) for s in ds["soil"].values]:
                    reasons.append(f"{Path(f).name}: no {soil}/{crit}")
                    continue
                ok = all(
                    float(ds[c].min()) <= val <= float(ds[c].max())
                    for c, val in (("N", n), ("M", m), ("K", k))
                )
                if not ok:
                    reasons.append(
                        f"{Path(f).name}: point K={k:.3g}, M={m:.3g}, N={n:.3g} outside the"
                        f" grid K [{float(ds.K.min()):g}, {float(ds.K.max()):g}], M"
                        f" [{float(ds.M.min()):g}, {float(ds.M.max()):g}], N"
                        f" [{float(ds.N.min()):g}, {float(ds.N.max()):g}]"
                    )
                    continue
                sel = ds[crit].sel(soil=soil)
                sel = sel.interp(N=n) if sel.sizes.get("N", 1) > 1 else sel.isel(N=0)
                lreq = float(sel.interp(M=m, K=k))
                if not math.isfinite(lreq):
                    reasons.append(f"{Path(f).name}: no converged L around the point")
                    continue
                found = (f, lreq)
                break
            if found is None:
                msg = "; ".join(reasons)
        if found is None:
            out.append(base | {"message": msg, "details": point})
            continue
        f, lreq = found
        u = lreq / point["L_actual"]
        out.append(
            base
            | {
                "covered": True,
                "utilisation": u,
                "pass": u <= 1.0,
                "message": f"{crit} interpolated in the dynamic curves {Path(f).name}",
                "details": point | {"L_required": lreq, "source": Path(f).name},
            }
        )
    return out
