"""V–H load envelope: FFT synthesis twin, per-cycle peaks by hand, angles, plot."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.errors import InputError
from onbottom.hydro.flow_synthesis import bed_velocity_record, near_bed_velocity_series
from onbottom.hydro.load_envelope import cycle_peak_loads, envelopes_dataset, load_envelope


def test_fft_record_equals_direct_synthesis():
    t, u, du = bed_velocity_record(3.0, 9.0, 20.0, 2.0, 7, 600, 1000.0, 30)
    assert t[-1] <= 1000.0 and np.allclose(np.diff(t), t[1] - t[0])
    u2, du2 = near_bed_velocity_series(t[::13], 3.0, 9.0, 20.0, gamma=2.0, seed=7, n_components=600)
    assert np.max(np.abs(u[::13] - u2)) < 1e-10 * np.max(np.abs(u2))
    assert np.max(np.abs(du[::13] - du2)) < 1e-10 * np.max(np.abs(du2))


def test_cycle_peaks_of_a_regular_wave_by_hand():
    # U = sin(t) over 3 full cycles; F_Y = U|U| peaks at U = ±1 (|F_Y| = 1), F_Z = U²
    t = np.linspace(-0.5, 6 * math.pi + 0.5, 20001)
    u = np.sin(t)
    tc, h, fz = cycle_peak_loads(t, u, u * np.abs(u), u**2)
    assert tc.size == 3  # complete cycles only
    assert np.allclose(h, 1.0, atol=1e-6) and np.allclose(fz, 1.0, atol=1e-6)


def test_angles_and_fraction():
    e = load_envelope(
        hs=3.0, tp=9.0, depth=15.0, diameter=0.4, submerged_weight=1500.0, current=0.3,
        duration=1800.0, seed=1,
    )  # fmt: skip
    assert e.n_cycles > 150
    assert np.allclose(e.vertical, 1500.0 - e.lift)
    assert np.allclose(np.tan(np.radians(e.angle_deg)), e.horizontal / e.vertical)
    frac = e.fraction_between(20.0, 45.0)
    assert frac == pytest.approx(np.mean((e.angle_deg >= 20) & (e.angle_deg <= 45)))
    assert e.fraction_between(0.0, 90.0) == 1.0
    # heavier pipe: smaller angles
    e2 = load_envelope(
        hs=3.0, tp=9.0, depth=15.0, diameter=0.4, submerged_weight=3000.0, current=0.3,
        duration=1800.0, seed=1,
    )  # fmt: skip
    assert np.all(e2.angle_deg < e.angle_deg)
    ds = envelopes_dataset([e, e2], ["light", "heavy"])
    assert ds["load_angle"].attrs["units"] == "degree" and ds.sizes["combination"] == 2


def test_same_seed_same_record_and_bad_inputs():
    kw = {"hs": 2.0, "tp": 8.0, "depth": 20.0, "diameter": 0.3, "submerged_weight": 800.0}
    a = load_envelope(**kw, duration=600.0, seed=4)
    b = load_envelope(**kw, duration=600.0, seed=4)
    assert np.array_equal(a.horizontal, b.horizontal)
    with pytest.raises(InputError, match="n_components = 64"):
        load_envelope(**kw, duration=3600.0, n_components=64)
    with pytest.raises(InputError, match="r_z"):
        load_envelope(**kw, r_z=1.5)
    with pytest.raises(InputError, match="submerged_weight"):
        load_envelope(**{**kw, "submerged_weight": -1.0})


def test_plot(tmp_path):
    from onbottom.plotting.load_envelope import plot_load_envelope

    kw = {"hs": 2.0, "tp": 8.0, "depth": 20.0, "diameter": 0.3, "submerged_weight": 800.0}
    fig = plot_load_envelope([load_envelope(**kw, duration=600.0)], ["a"], title="t")
    p = tmp_path / "vh.png"
    fig.savefig(p)
    assert p.stat().st_size > 1000
    with pytest.raises(InputError):
        plot_load_envelope([])
