"""Unit tests: calibration figures draw the data they are given."""

from __future__ import annotations

import numpy as np
import xarray as xr

from onbottom.calibration.records import TestRecord
from onbottom.plotting.calibration import plot_fit, plot_misfit_map, plot_misfit_slices


def _record():
    t = np.linspace(0.0, 10.0, 11)
    ds = xr.Dataset({"y": ("time", 0.1 * t), "z": ("time", 0.05 + 0.001 * t)}, coords={"time": t})
    return TestRecord(name="rec", data=ds, diameter=1.0, displacement_limit=1.0)


def test_plot_fit_has_measured_and_simulated(tmp_path):
    rec = _record()
    sim = rec.data.assign(y=rec.data["y"] * 1.1)
    fig = plot_fit(rec, sim)
    ax_wu, ax_ut = fig.axes
    assert ax_wu.yaxis_inverted()
    np.testing.assert_allclose(ax_ut.lines[1].get_ydata(), sim["y"].values)
    assert [t.get_text() for t in ax_ut.get_legend().get_texts()][:2] == ["measured", "simulated"]
    fig.savefig(tmp_path / "fit.png")


def test_misfit_map_marks_minimum(tmp_path):
    a = np.array([0.1, 0.2, 0.3])
    b = np.array([1.0, 2.0])
    ds = xr.Dataset(
        {"misfit": (("a", "b"), (a[:, None] - 0.2) ** 2 + (b[None, :] - 2.0) ** 2 + 0.1)},
        coords={"a": a, "b": b},
    )
    ax = plot_misfit_map(ds, "a", "b", truth={"a": 0.2, "b": 2.0})
    star = ax.lines[0]
    assert (star.get_xdata()[0], star.get_ydata()[0]) == (0.2, 2.0)
    fig = plot_misfit_slices({"a": ds.sel(b=2.0)}, fitted={"a": 0.2})
    assert fig.axes[0].get_xlabel() == "a"
    ax.figure.savefig(tmp_path / "map.png")
