"""Faults a new user meets end in one named error, never a traceback (issue 41 item 6).

* ``metocean`` on a hindcast with its header and units rows and no data rows;
* ``metocean`` on a full disk: the file is named, and no output file of the run appears under
  its final name (they are written under temporary names and renamed together);
* ``reliability`` with γ' typed in kN/m³ (a named plausibility error, before any storm);
* ``reliability`` on a full disk: the campaign store is named.

Ctrl-C during ``warmup`` is in ``test_warmup.py``, a read-only numba cache in
``test_jit_cache.py``. A full disk is simulated by a writer raising ``OSError(ENOSPC)``.
"""

from __future__ import annotations

import errno
import re
import shutil
from pathlib import Path

import pytest

from onbottom.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
HINDCAST = ROOT / "examples" / "hindcast_synthetic.csv"
RELIABILITY = ROOT / "examples" / "reliability_case.toml"


def _no_traceback(err: str) -> None:
    assert "Traceback" not in err and "Exception ignored" not in err


def _enospc(*args, **kwargs):
    raise OSError(errno.ENOSPC, "No space left on device")


def test_metocean_hindcast_with_headers_and_no_rows(tmp_path, capsys):
    pytest.importorskip("pyextremes")
    empty = tmp_path / "empty.csv"
    lines = [x for x in HINDCAST.read_text(encoding="utf-8").splitlines() if x[:1] != "#"]
    empty.write_text("\n".join(lines[:2]) + "\n", encoding="utf-8")  # header + units rows
    code = main(["metocean", str(empty), "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 1
    _no_traceback(err)
    assert "empty.csv" in err and "no data rows" in err


def test_metocean_full_disk_names_the_file_and_leaves_no_complete_looking_file(
    tmp_path, capsys, monkeypatch
):
    pytest.importorskip("pyextremes")
    pytest.importorskip("virocon")
    from xarray.backends import H5NetCDFStore

    monkeypatch.setattr(H5NetCDFStore, "open", _enospc)  # metocean.nc: the disk fills up
    out = tmp_path / "out"
    code = main(["metocean", str(HINDCAST), "--out", str(out), "--sectors", "1", "--no-report"])
    err = capsys.readouterr().err
    assert code == 1
    _no_traceback(err)
    assert "metocean.nc" in err and "No space left on device" in err
    # the table and the case fragments were written before, under temporary names: gone
    assert sorted(p.name for p in out.iterdir()) == []


def _reliability_case(tmp_path: Path, **subs: str) -> Path:
    text = RELIABILITY.read_text(encoding="utf-8")
    shutil.copyfile(HINDCAST, tmp_path / HINDCAST.name)
    for key, value in subs.items():
        text = re.sub(rf"^{key} = [^#\n]*", f"{key} = {value} ", text, flags=re.M)
    p = tmp_path / "case.toml"
    p.write_text(text, encoding="utf-8")
    return p


def test_reliability_unit_weight_in_kn_is_a_named_error(tmp_path, capsys):
    case = _reliability_case(tmp_path)
    text = case.read_text(encoding="utf-8")
    drawn = 'submerged_unit_weight = {distribution = "normal", mean = 10.0e3, std = 1.0e3}'
    assert drawn in text
    kn = 'submerged_unit_weight = {distribution = "normal", mean = 10.0, std = 1.0}'
    case.write_text(text.replace(drawn, kn), encoding="utf-8")
    code = main(["reliability", str(case), "--out", str(tmp_path / "out"), "--workers", "0"])
    err = capsys.readouterr().err
    assert code == 1
    _no_traceback(err)
    assert "submerged_unit_weight" in err and "N/m³" in err and "plausible range" in err
    assert not (tmp_path / "out").exists()  # refused before any storm


def test_reliability_full_disk_names_the_store(tmp_path, capsys, monkeypatch):
    pytest.importorskip("openturns")
    pytest.importorskip("zarr")
    pytest.importorskip("virocon")
    from onbottom.reliability.campaign import ResultStore

    monkeypatch.setattr(ResultStore, "_append", _enospc)  # the first rows written fill the disk
    case = _reliability_case(
        tmp_path, max_storms="20", block_size="10", peak_hours="0.05", limits='["0.5D"]'
    )
    out = tmp_path / "out"
    args = ["reliability", str(case), "--out", str(out), "--workers", "0", "--no-progress"]
    code = main(args)
    err = capsys.readouterr().err
    assert code == 1
    _no_traceback(err)
    assert "campaign.zarr" in err and "No space left on device" in err
    assert not (out / "reliability.json").exists()
