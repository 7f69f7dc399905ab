"""Unit tests: F114 bounds at the prototype scale of a DEM run (spec dnv-reference.md §3.3)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from onbottom import InputError
from onbottom.plotting.dem_f114 import f114_bounds_for_dem, plot_dem_against_f114


def _fake_run() -> xr.Dataset:
    # model D = 20 mm at 25 g → prototype D = 0.5 m; a made-up linear V–w record
    w = np.linspace(0.0, 0.01, 11)
    v = 4e3 * w / 0.01  # model scale [N/m]
    ds = xr.Dataset(
        {"V": ("w", v), "V_prototype": ("w", 25.0 * v), "w_over_D": ("w", w / 0.02)},
        coords={"w": w},
    )
    ds.attrs.update(pipe_diameter=0.02, gravity_factor=25.0, preset="SD")
    return ds


def test_bounds_match_the_spec_table_at_prototype_scale():
    w, lower, upper = f114_bounds_for_dem(_fake_run(), unit_weight=16.7e3)
    i = np.argmin(abs(w - 0.1))
    # spec §3.3: γ' = 16.7 kN/m³; D&B smooth φ=33° → 10.6 kN/m, D&B rough φ=40° → 64.5 kN/m
    assert lower[i] == pytest.approx(10.6e3, rel=0.01)
    assert upper[i] == pytest.approx(64.5e3, rel=0.01)
    assert np.all(upper >= lower)


def test_bad_unit_weight_is_rejected():
    with pytest.raises(InputError, match="unit_weight"):
        f114_bounds_for_dem(_fake_run(), unit_weight=-1.0)


def test_plot_has_bounds():
    fig = plot_dem_against_f114(_fake_run(), unit_weight=16.7e3)
    labels = [ln.get_label() for ln in fig.axes[0].get_lines()]
    assert any("lower" in lb for lb in labels) and any("upper" in lb for lb in labels)
