"""Saved section results of ``assess --out`` are tied to what made them (issue 41 item 1).

A section's saved result is reused only when its inputs, the package's content hash and the
content hash of every data file it read (the curve sweeps of the generalized level) match;
otherwise it is recomputed and the reason is given. A section file edited by hand is refused
by name (its checksum no longer matches).
"""

from __future__ import annotations

import json
import shutil
import sys
from pathlib import Path

import pytest
import xarray as xr

from onbottom.assess import assess
from onbottom.assess import core as assess_core
from onbottom.assess.generalized import default_curve_files
from onbottom.cases.assess import build_route, parse_route_case
from onbottom.errors import ResultFileError

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from assess_cases import route_document

pytestmark = pytest.mark.verification


def _route(generalized: bool = False):
    doc = route_document(seeds=1, peak_hours=0.05)
    doc["levels"] = {"generalized": generalized, "dynamic": False}
    return build_route(parse_route_case(doc))


def test_package_hash_change_recomputes_with_the_reason(tmp_path, monkeypatch):
    route = _route()
    first = assess(route, out=tmp_path, n_workers=0)
    (f,) = (tmp_path / "sections").glob("*.json")
    saved = json.loads(f.read_text(encoding="utf-8"))
    assert saved["checksum"].startswith("sha256:")
    assert saved["identity_parts"]["package"] == assess_core.content_hash()
    again = assess(route, out=tmp_path, n_workers=0)
    assert again.reused == ["section 0"] and again.recomputed == []
    monkeypatch.setattr(assess_core, "content_hash", lambda: "f" * 64)
    other = assess(route, out=tmp_path, n_workers=0)
    assert other.reused == []
    ((name, why),) = other.recomputed
    assert name == "section 0" and "onbottom package changed" in why
    assert other.summary.equals(first.summary)  # same code really: same numbers
    # the file now carries the new package hash: a third run reuses it
    assert assess(route, out=tmp_path, n_workers=0).reused == ["section 0"]


def test_hand_edited_section_file_is_refused_by_name(tmp_path):
    route = _route()
    assess(route, out=tmp_path, n_workers=0)
    (f,) = (tmp_path / "sections").glob("*.json")
    doc = json.loads(f.read_text(encoding="utf-8"))
    doc["design_value"] = 0.0 if doc["design_value"] else 0.1  # a result changed by hand
    f.write_text(json.dumps(doc, indent=1), encoding="utf-8")
    with pytest.raises(ResultFileError, match=r"sections.*changed after onbottom wrote it"):
        assess(route, out=tmp_path, n_workers=0)


def test_changed_curve_sweep_recomputes_naming_the_file(tmp_path):
    committed = default_curve_files()
    if not committed:
        pytest.skip("no committed curve sweep in this installation")
    sweep = tmp_path / "sweep.nc"
    shutil.copyfile(committed[0], sweep)
    route = _route(generalized=True)
    out = tmp_path / "out"
    assess(route, out=out, n_workers=0, curve_files=[str(sweep)])
    assert assess(route, out=out, n_workers=0, curve_files=[str(sweep)]).reused == ["section 0"]
    with xr.open_dataset(sweep, engine="h5netcdf") as ds:
        changed = ds.load()
    changed.attrs["note"] = "regenerated"
    sweep.unlink()
    changed.to_netcdf(sweep, engine="h5netcdf")
    again = assess(route, out=out, n_workers=0, curve_files=[str(sweep)])
    assert again.reused == []
    ((_, why),) = again.recomputed
    assert f"data file {sweep} changed" in why


def test_stale_reason_names_every_part():
    new = {"inputs": "a", "package": "p" * 64, "data": {"x.nc": "1", "y.nc": "2"}}
    old = {"inputs": "b", "package": "q" * 64, "data": {"x.nc": "0", "z.nc": "3"}}
    why = assess_core.stale_reason(old, new)
    assert "inputs changed" in why and "package changed" in why
    assert "x.nc changed" in why and "y.nc added" in why and "z.nc no longer read" in why
    assert "earlier onbottom" in assess_core.stale_reason(None, new)
    assert assess_core.stale_reason(dict(new), new) == ""


def test_provenance_identities_and_task_files_carry_the_package_hash(tmp_path):
    from onbottom._version import content_hash, package_files
    from onbottom.results import TaskStore, provenance, run_identity

    assert provenance("x")["onbottom_content_hash"] == content_hash()
    assert run_identity({"a": 1}).fields["onbottom_content"] == content_hash()
    assert "_version.py" in package_files() and not any(
        "__pycache__" in f or f.endswith(".pyc") for f in package_files()
    )
    store = TaskStore(tmp_path / "tasks", {"case": 1}, what="seed")
    store.put({"seed": 1}, {"y": 0.25})
    assert store.load([{"seed": 1}]) == {0: {"y": 0.25}}
    (f,) = (tmp_path / "tasks").glob("*.json")
    f.write_text(f.read_text(encoding="utf-8").replace("0.25", "0.5"), encoding="utf-8")
    with pytest.raises(ResultFileError, match=r"seed file .* changed after onbottom wrote it"):
        store.load([{"seed": 1}])
