"""Unit tests: V–w penetration plots (structure of the figure, not pixels)."""

from __future__ import annotations

import numpy as np
import pytest

from onbottom import InputError
from onbottom.plotting.penetration import overlay_penetration_data, plot_penetration_curve
from onbottom.soil.penetration_f114 import penetration_curve, solve_embedment
from onbottom.soil.penetration_sand import DrainedBounds, DrainedPenetration


def test_curve_bounds_embedment_and_overlay(tmp_path):
    model = DrainedPenetration(diameter=0.5, unit_weight=16.7e3, friction_angle_deg=36)
    bounds = DrainedBounds.from_friction_angles(
        diameter=0.5, unit_weight=16.7e3, lower_friction_angle_deg=33, upper_friction_angle_deg=40
    )
    emb = solve_embedment(model, 40e3)
    fig, ax = plot_penetration_curve(penetration_curve(model, bounds=bounds, embedment=emb))
    assert ax.yaxis_inverted()
    labels = [line.get_label() for line in ax.get_lines()]
    assert "lower estimate" in labels and "upper estimate" in labels
    marker = next(line for line in ax.get_lines() if line.get_label().startswith("embedment"))
    assert marker.get_xdata()[0] == pytest.approx(40.0)  # kN/m
    assert marker.get_ydata()[0] == pytest.approx(emb.z_over_d)
    w = np.linspace(0.0, 0.25, 20)
    overlay_penetration_data(ax, w, 3e5 * w, diameter=0.5, label="DEM", color="k")
    dem = next(line for line in ax.get_lines() if line.get_label() == "DEM")
    assert dem.get_ydata()[-1] == pytest.approx(0.5)
    assert dem.get_xdata()[-1] == pytest.approx(75.0)
    fig.savefig(tmp_path / "f.png")
    with pytest.raises(InputError, match="lengths"):
        overlay_penetration_data(ax, w, w[:-1])
