"""DEM run summaries: binning, softening detection, heave metrics (hand-made curves)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from onbottom.dem.summary import (
    binned_resistance,
    heave_metrics,
    softening_episodes,
    summarize_run,
)


def test_binned_resistance_mean_min_max_by_hand():
    w = np.array([-0.001, 0.001, 0.004, 0.006, 0.009, 0.012])
    f = np.array([99.0, 1.0, 3.0, 10.0, 20.0, 7.0])
    c, mean, lo, hi = binned_resistance(w, f, step=0.005)
    np.testing.assert_allclose(c, [0.0025, 0.0075, 0.0125])
    np.testing.assert_allclose(mean, [2.0, 15.0, 7.0])
    np.testing.assert_allclose(lo, [1.0, 10.0, 7.0])
    np.testing.assert_allclose(hi, [3.0, 20.0, 7.0])


def test_binned_resistance_empty_bin_is_nan_and_bad_step_names_the_field():
    _, mean, lo, _ = binned_resistance(np.array([0.001, 0.011]), np.array([1.0, 2.0]), 0.005)
    assert np.isnan(mean[1]) and np.isnan(lo[1])
    with pytest.raises(ValueError, match="step"):
        binned_resistance(np.array([0.1]), np.array([1.0]), 0.0)


def test_hardening_curve_has_no_softening_and_drops_are_found():
    w = np.linspace(0, 0.5, 101)
    assert softening_episodes(w, 50 + 150 * w) == []
    # two drops: 150 -> 100 at 0.35-0.40 and 10 % at 0.15
    f = 50 + 250 * w
    f[(w > 0.15) & (w < 0.2)] = 0.9 * f[w <= 0.15][-1]
    f[(w > 0.35) & (w <= 0.4)] = 100.0
    eps = softening_episodes(w, f, drop_fraction=0.05)
    assert len(eps) == 2
    assert eps[0].w_peak == pytest.approx(0.15, abs=0.006)
    assert eps[0].drop_fraction == pytest.approx(0.1)
    assert eps[1].w_peak == pytest.approx(0.35, abs=0.006) and eps[1].v_trough == 100.0
    # a 3 % wobble is below a 5 % threshold
    g = 50 + 250 * w
    g[50:53] *= 0.97
    assert softening_episodes(w, g, drop_fraction=0.05) == []


def test_heave_metrics_of_a_triangular_berm():
    D = 0.02
    x = np.linspace(0.001, 0.259, 130)
    xc = 0.13
    s0 = np.full_like(x, 0.1)
    d = np.abs(x - xc)
    berm = np.clip(0.004 * (1 - (d - D) / (2 * D)), 0, 0.004) * (d >= D)
    s1 = s0 + berm
    s1[d < 0.5 * D] = 0.09  # the pipe has gone in: not heave
    h = heave_metrics(x, s0, s1, xc, D, smooth_bins=1)
    assert h["peak_over_D"] == pytest.approx(0.2, rel=0.03)  # bins 2 mm apart
    assert abs(h["peak_x_over_D"]) == pytest.approx(1.0, abs=0.05)
    # falls to 25 % of the peak at d = D + 0.75·2D = 2.5D
    assert h["extent_over_D"] == pytest.approx(2.5, abs=0.1)
    assert np.all(np.isnan(h["change"][d < 0.75 * D]))


def _fake_run():
    D, N = 0.02, 25.0
    w = np.linspace(0, 0.01, 2001)
    V = 2000.0 + 4e5 * w
    x = np.linspace(0.001, 0.259, 130)
    return xr.Dataset(
        {
            "w_over_D": ("record", w / D),
            "V": ("record", V),
            "surface0": ("x_bin", np.full(130, 0.1)),
            "surface": ("x_bin", np.full(130, 0.101)),
        },
        coords={"x_bin": x},
        attrs={"pipe_diameter": D, "gravity_factor": N, "model": "dem.penetration"},
    )


def test_summarize_run_reports_prototype_values_and_provenance():
    s = summarize_run(_fake_run())
    # V(w = 0.4D = 0.008 m) = 2000 + 3200 = 5200 N/m model, ×25 prototype
    assert s.attrs["V_prototype_at_0.4D"] == pytest.approx(5200 * 25, rel=1e-3)
    assert s.attrs["softening_episodes"] == 0
    assert s.sizes["episode"] == 0
    assert s.attrs["heave_peak_over_D"] == pytest.approx(0.05)
    assert s.attrs["model"] == "dem.penetration.summary"
    assert s["V_prototype_mean"].attrs["units"] == "N/m"
    assert s.sizes["w_over_D"] == 100


def test_summarize_run_stores_softening_episodes_at_prototype_scale():
    ds = _fake_run()
    w = ds["w_over_D"].values
    V = ds["V"].values.copy()
    V[(w > 0.3) & (w < 0.35)] *= 0.8  # a 20 % drop from about 0.3D
    s = summarize_run(ds.assign(V=("record", V)))
    assert s.sizes["episode"] == 1
    assert s["softening_w_peak"].values[0] == pytest.approx(0.3, abs=0.006)
    drop = 1 - s["softening_V_prototype_trough"] / s["softening_V_prototype_peak"]
    assert float(drop[0]) == pytest.approx(0.2, abs=0.02)
    assert float(s["softening_V_prototype_peak"][0]) == pytest.approx(
        25 * (2000 + 4e5 * 0.006), rel=0.01
    )
