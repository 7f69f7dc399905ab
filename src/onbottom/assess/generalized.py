"""Generalized level of a route section: the tool's own dynamic curves, where they cover it.

DNV-RP-F109 (2017) §3.5 tabulates the weight parameter L = w_s/(½ ρ_w D U_s²) at which a pipe
moves 0.5D (L_stable) or 10D (L_10), against K = U_s T_u/D, M = V/U_s and N = U_s/(g T_u) (Eqs
3.31–3.37). Those tables are DNV content and are not reproduced here. Instead the level reads
the curve sweeps the tool computes itself (``onbottom curves``, NetCDF of
:mod:`onbottom.study.stability_curves`): a combination is **covered** when a sweep has the
section's soil (``sand`` — Verley & Sotberg silica — or ``clay``) and its N, M and K lie inside
the sweep's grid; L at the point is then interpolated linearly in (N, M, K) and the
utilisation is L_required / L_actual. Outside, the row says "not covered" and why; nothing is
extrapolated. The sweeps use their own soil parameters (γ'_s, G_c) and a long-crested storm
with γ = 3.3: the report shows the sweep's source with every covered point.

U_s and T_u are the significant flow velocity and zero-up-crossing period at the pipe of the
absolute check (F109 §3.4.3, its ``us``/``tu``); V is its steady current V* (F109 Eq 3.4,
mean over D, normal to the pipe).
"""

from __future__ import annotations

import functools
import math
from pathlib import Path
from typing import Any

from onbottom.constants import GRAVITY

__all__ = ["default_curve_files", "generalized_rows"]

CRITERION = {"0.5D": "L_stable", "10D": "L_10"}


def default_curve_files() -> list[str]:
    """Committed sweeps: ``onbottom/data/stability_curves/*.nc`` (package data) and, in a
    source checkout, ``docs/validation/stability_curves/*.nc``."""
    here = Path(__file__).resolve().parent.parent
    folders = [here / "data" / "stability_curves"]
    repo = here.parent.parent / "docs" / "validation" / "stability_curves"
    folders.append(repo)
    return [str(p) for f in folders if f.is_dir() for p in sorted(f.glob("*.nc"))]


@functools.lru_cache(maxsize=16)
def _load(path: str) -> Any:
    """A sweep read once per process (None if unreadable: reported as not covered)."""
    from onbottom.results import load_dataset

    try:
        return load_dataset(path)
    except Exception:
        return None


def _soil_label(model: str) -> str | None:
    return {"sand": "sand", "clay": "clay"}.get(model)


def generalized_rows(
    rows: list[Any],
    files: list[str],
    allowable: str = "0.5D",
    *,
    seabed_model: str,
    water_density: float,
) -> list:
    """One row per absolute-lateral row of ``rows`` (:func:`onbottom.checks.design.run_checks`
    on the section): level ``generalized``, ``covered`` and ``message``; where covered,
    ``utilisation`` and the point (K, M, N, L). ``seabed_model``: the section's soil model name
    (curves exist for ``sand`` and ``clay``); ``water_density``: ρ_w [kg/m³] of L."""
    out = []
    lat = [r for r in rows if r.name == "absolute_lateral" and "us" in r.details]
    sweeps = [(f, ds) for f in files if (ds := _load(f)) is not None]
    crit = CRITERION.get(allowable)
    rho = water_density
    for r in lat:
        det = r.details
        d, us, tu, v = det["diameter"], det["us"], det["tu"], det.get("v_star", 0.0)
        base = {"name": "generalized_lateral", "combination": r.combination,
                "condition": r.condition, "level": "generalized", "covered": False,
                "utilisation": None, "pass": None}  # fmt: skip
        if us <= 0.0 or tu <= 0.0:
            out.append(base | {"message": "no wave flow at the pipe (U_s = 0)", "details": {}})
            continue
        k, n, m = us * tu / d, us / (GRAVITY * tu), v / us
        lact = det["submerged_weight"] / (0.5 * rho * d * us**2)
        point = {"K": k, "M": m, "N": n, "L_actual": lact}
        soil = _soil_label(seabed_model)
        msg = None
        if crit is None:
            msg = f"allowable {allowable!r}: the curves give 0.5D and 10D only"
        elif not sweeps:
            msg = (
                "no committed stability-curve sweep (onbottom curves NetCDF in"
                " onbottom/data/stability_curves/ or docs/validation/stability_curves/)"
            )
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
        u = lreq / lact
        out.append(
            base
            | {
                "covered": True,
                "utilisation": u,
                "pass": u <= 1.0,
                "message": f"{crit} interpolated in {Path(f).name}",
                "details": point | {"L_required": lreq, "source": f},
            }
        )
    return out
