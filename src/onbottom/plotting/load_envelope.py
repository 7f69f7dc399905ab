"""V–H plot of the peak hydrodynamic loads per wave cycle (the seed paper's Fig. 4).

Vertical contact load V = w_s − F_Z on the horizontal axis, horizontal load H = |F_Y| on the
vertical axis, both in kN/m; lines at 20° and 45° from the V axis (H = V tan β) and, in the
legend, the fraction of cycles between them. Built on :class:`matplotlib.figure.Figure`
(no pyplot state), so it renders headless.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from matplotlib.figure import Figure

from onbottom.errors import InputError
from onbottom.hydro.load_envelope import LoadEnvelope

__all__ = ["plot_load_envelope"]

_KN = 1.0e-3


def plot_load_envelope(
    envelopes: Sequence[LoadEnvelope],
    labels: Sequence[str] | None = None,
    *,
    angles_deg: tuple[float, float] = (20.0, 45.0),
    title: str | None = None,
) -> Figure:
    """Scatter the cycle peaks of each envelope in V–H space with the two angle lines.

    Parameters
    ----------
    envelopes : sequence of LoadEnvelope
        One per sea state / load combination (at least one).
    labels : sequence of str or None
        Legend labels (default "sea state i").
    angles_deg : (float, float)
        Angles of the guide lines from the V axis [deg].
    title : str or None
        Figure title.
    """
    envs = list(envelopes)
    if not envs:
        raise InputError("envelopes = [] is invalid: give at least one LoadEnvelope")
    names = list(labels) if labels is not None else [f"sea state {i + 1}" for i in range(len(envs))]
    if len(names) != len(envs):
        raise InputError(f"labels = {names!r} is invalid: need one label per envelope")
    lo, hi = angles_deg
    fig = Figure(figsize=(6.0, 5.0), layout="constrained")
    ax = fig.add_subplot()
    vmax = hmax = 0.0
    for env, name in zip(envs, names, strict=True):
        frac = env.fraction_between(lo, hi)
        ax.scatter(
            env.vertical * _KN,
            env.horizontal * _KN,
            s=6,
            alpha=0.6,
            label=f"{name}: {100 * frac:.0f}% of {env.n_cycles} cycles in {lo:g}–{hi:g}°",
        )
        if env.n_cycles:
            vmax = max(vmax, float(np.max(env.vertical)), env.submerged_weight)
            hmax = max(hmax, float(np.max(env.horizontal)))
    v_line = np.array([0.0, max(vmax, 1.0) * 1.05]) * _KN
    for beta, style in ((lo, "--"), (hi, "-.")):
        ax.plot(v_line, v_line * math.tan(math.radians(beta)), "k" + style, lw=1.0,
                label=f"{beta:g}° from V axis")  # fmt: skip
    ax.set_xlim(min(0.0, float(min(np.min(e.vertical) for e in envs if e.n_cycles)) * _KN)
                if any(e.n_cycles for e in envs) else 0.0, v_line[1])  # fmt: skip
    ax.set_ylim(0.0, max(hmax * 1.1, 1.0) * _KN)
    ax.set_xlabel("Vertical contact load V = w_s − F_Z (kN/m)")
    ax.set_ylabel("Horizontal load H = |F_Y| (kN/m)")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper left", fontsize="small")
    if title:
        ax.set_title(title, fontsize="medium")
    return fig
