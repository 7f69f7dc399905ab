"""Small route documents for the ``onbottom assess`` tests (short storms, few seeds)."""

from __future__ import annotations

import copy

PIPE = {
    "steel_outer_diameter": 0.2191,
    "wall_thickness": 0.0127,
    "condition": "operation",
    "contents": {"installation": 0.0, "flooded": 1025.0, "hydrotest": 1025.0, "operation": 180.0},
    "layers": [
        {"name": "corrosion", "thickness": 0.0055, "density": 1335.0},
        {"name": "concrete", "thickness": 0.04, "density": 3043.5},
    ],
}

SECTION = {
    "name": "mid-route",
    "kp_start_km": 2.0,
    "kp_end_km": 10.0,
    "water_depth": 30.0,
    "seabed": {"model": "sand", "submerged_unit_weight": 10.0e3, "friction_coefficient": 0.6},
    "waves": {"hs": 4.5, "tp": 10.5, "direction_deg": 90.0},
    "current": {"velocity": 0.4, "reference_height": 1.0, "direction_deg": 90.0},
    "combinations": [
        {"name": "100-yr wave + 10-yr current"},
        {"name": "installation", "hs": 3.0, "tp": 9.0, "condition": "installation"},
    ],
}


def route_document(*, sections: int = 1, seeds: int = 2, peak_hours: float = 0.1) -> dict:
    """A route of ``sections`` sections (KP 2-10 km, then 8 km each deeper), short storms."""
    secs = []
    for k in range(sections):
        s = copy.deepcopy(SECTION)
        s["name"] = f"section {k}"
        s["kp_start_km"], s["kp_end_km"] = 2.0 + 8.0 * k, 10.0 + 8.0 * k
        s["water_depth"] = 30.0 + 10.0 * k
        secs.append(s)
    return {
        "route": {"name": "test route", "sections": secs},
        "pipe": copy.deepcopy(PIPE),
        "design": {"thickness_min": 0.0, "thickness_max": 0.2},
        "levels": {"generalized": False},
        "dynamic": {
            "seeds": seeds,
            "build_up_hours": 0.02,
            "peak_hours": peak_hours,
            "time_step": 0.1,
            "thickness_tolerance_m": 0.004,
        },
    }


def route_toml(doc: dict) -> str:
    """A route document as TOML (the value types of :func:`route_document`)."""
    import json

    def val(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return json.dumps(v)
        return repr(v)

    lines: list[str] = []

    def table(prefix: str, d: dict, array: bool = False) -> None:
        lines.append(f"[[{prefix}]]" if array else f"[{prefix}]")
        subs = []
        for k, v in d.items():
            if isinstance(v, dict):
                subs.append((k, v, False))
            elif isinstance(v, list) and v and isinstance(v[0], dict):
                subs.append((k, v, True))
            else:
                lines.append(f"{k} = {val(v)}")
        for k, v, arr in subs:
            for item in v if arr else [v]:
                table(f"{prefix}.{k}", item, arr)

    for k, v in doc.items():
        if k == "route":
            lines.append(f"[route]\nname = {val(v['name'])}")
            for s in v["sections"]:
                table("route.sections", s, True)
        else:
            table(k, v)
    return "\n".join(lines) + "\n"
