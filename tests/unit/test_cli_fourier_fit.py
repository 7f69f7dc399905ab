"""``onbottom fourier-fit``: run CSVs in, a table out; schema errors named with exit 1."""

from __future__ import annotations

import json

import numpy as np
import pytest

from onbottom.cli.main import main
from onbottom.errors import InputError
from onbottom.hydro.fourier_fit import morison_regular_run, read_run_csv
from onbottom.hydro.fourier_table import FourierTable


def _write(path, run, *, current=None, k=None, m=None, units="s,m/s,N/m,N/m"):
    lines = ["# a synthetic flume run"]
    if current is not None:
        lines.append(f"# current_m_s: {current!r}")
    if k is not None:
        lines += [f"# K: {k!r}", f"# M: {m!r}"]
    lines += ["t,U,F_Y,F_Z", units]
    data = np.column_stack((run.time, run.velocity, run.force_y, run.force_z))
    lines += [",".join(f"{x:.17g}" for x in row) for row in data]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_fourier_fit_writes_a_table(tmp_path, capsys):
    paths = []
    for k in (5.0, 10.0):
        for m in (0.0, 0.4):
            run = morison_regular_run(k, m, cd=0.7, cm=3.29, cl=0.9, samples_per_cycle=400)
            paths.append(_write(tmp_path / f"k{k:g}_m{m:g}.csv", run, current=m, k=k, m=m))
    out = tmp_path / "table.nc"
    rc = main(
        [
            "fourier-fit",
            *map(str, paths),
            "--diameter",
            "1",
            "--harmonics",
            "3",
            "--out",
            str(out),
            "--json",
        ]
    )
    assert rc == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["K"] == [5.0, 10.0] and payload["M"] == [-0.4, 0.0, 0.4]
    tab = FourierTable.load(out)
    # M = 0 Morison: A1 of F_Y = π² C_M / K (hand value, docs/theory/fourier_model.md)
    assert tab.coefficients_at(10.0, 0.0)[0, 1] == pytest.approx(np.pi**2 * 3.29 / 10.0, 1e-9)


def test_run_csv_errors_named(tmp_path, capsys):
    run = morison_regular_run(5.0, 0.0, cd=0.7, cm=3.29, cl=0.9, samples_per_cycle=100)
    bad = _write(tmp_path / "bad.csv", run, units="s,m/s,kN/m,N/m")
    with pytest.raises(InputError, match="column F_Y has unit 'kN/m'"):
        read_run_csv(bad)
    rc = main(["fourier-fit", str(bad), "--diameter", "1", "--out", str(tmp_path / "t.csv")])
    assert rc == 1
    assert "F_Y has unit" in capsys.readouterr().err
    rc = main(["fourier-fit", str(bad), "--diameter", "1", "--out", str(tmp_path / "t.txt")])
    assert rc == 1
    good = _write(tmp_path / "good.csv", run)
    text = good.read_text().replace("t,U,F_Y,F_Z", "time,U,F_Y,F_Z")
    (tmp_path / "hdr.csv").write_text(text)
    with pytest.raises(InputError, match="header 'time,U,F_Y,F_Z' is invalid"):
        read_run_csv(tmp_path / "hdr.csv")
