"""DEM figures from synthetic result datasets."""

from __future__ import annotations

import numpy as np
import xarray as xr

from onbottom.plotting.dem import (
    plot_force_chains,
    plot_resistance_with_bounds,
    plot_rotation_field,
    plot_velocity_field,
)


def _result():
    rng = np.random.default_rng(0)
    n = 50
    w = np.linspace(0, 0.01, 20)
    return xr.Dataset(
        {
            "w_over_D": ("record", w / 0.02),
            "V": ("record", 1e3 * w),
            "V_prototype": ("record", 25e3 * w),
            "x": (("snapshot", "particle"), rng.random((1, n)) * 0.1),
            "y": (("snapshot", "particle"), rng.random((1, n)) * 0.05),
            "vx": (("snapshot", "particle"), rng.standard_normal((1, n))),
            "vy": (("snapshot", "particle"), rng.standard_normal((1, n))),
            "rotation": (("snapshot", "particle"), rng.standard_normal((1, n))),
            "chain_i": ("chain", np.arange(10)),
            "chain_j": ("chain", np.arange(10) + 1),
            "chain_fn": ("chain", np.linspace(0, 500, 10)),
            "chain_snapshot": ("chain", np.zeros(10, int)),
            "snapshot_w": ("snapshot", [0.01]),
        },
        coords={"snapshot": ("snapshot", [0.5])},
        attrs={"preset": "test", "pipe_diameter": 0.02, "surface0_at_pipe": 0.05},
    )


def test_bounds_plot_has_three_curves():
    ds = _result()
    wd = np.linspace(0, 0.5, 6)
    fig = plot_resistance_with_bounds(ds, wd, 50e3 * wd, 200e3 * wd)
    assert len(fig.axes[0].lines) == 3


def test_field_plots():
    ds = _result()
    fig = plot_force_chains(ds, 0.5, threshold=200.0)
    assert "contacts > 200 N" in fig.axes[0].texts[0].get_text()
    assert fig.axes[0].texts[0].get_text().startswith("6 ")
    assert plot_rotation_field(ds, 0.5, threshold_deg=20.0).axes
    assert plot_velocity_field(ds, 0.5).axes


def _summary(preset="SM"):
    from onbottom.dem.summary import summarize_run

    x = np.linspace(0.001, 0.259, 130)
    run = xr.Dataset(
        {
            "w_over_D": ("record", np.linspace(0, 0.5, 400)),
            "V": ("record", np.linspace(0, 5e3, 400)),
            "surface0": ("x_bin", np.full(130, 0.1)),
            "surface": ("x_bin", 0.1 + 0.003 * np.exp(-(((x - 0.13) / 0.04) ** 2))),
        },
        coords={"x_bin": x},
        attrs={"preset": preset, "pipe_diameter": 0.02, "gravity_factor": 25.0},
    )
    return summarize_run(run)


def test_summary_resistance_plot_draws_band_and_published_points():
    from onbottom.dem.published import PUBLISHED
    from onbottom.plotting.dem import plot_resistance, plot_surface

    paper = {k: c.resistance for k, c in PUBLISHED.items()}
    ax = plot_resistance([_summary("SM"), _summary("SM-reduced")], reference=paper).axes[0]
    # SM: mean line + 3 paper markers; SM-reduced: mean line only (not the paper's case)
    assert len(ax.lines) == 3
    marks = ax.lines[1]
    np.testing.assert_allclose(marks.get_xdata(), [50.0, 120.0, 125.0])
    assert len(ax.collections) == 2  # the min–max bands
    heave = plot_surface(_summary()).axes[0]
    assert len(heave.lines) == 3  # smoothed, raw, zero line
