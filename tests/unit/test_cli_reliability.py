"""``onbottom reliability``: a tiny case end to end (in-process runs), its JSON keys, the
figures, a rerun that reads every storm back, and case-file errors naming the key."""

from __future__ import annotations

import json
import math
import re
import shutil
from pathlib import Path

import pytest

pytest.importorskip("openturns")
pytest.importorskip("zarr")
pytest.importorskip("virocon")

from onbottom.cases.reliability import parse_limit
from onbottom.cli.main import main

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "reliability_case.toml"


def _tiny(tmp_path: Path, **changes: str) -> Path:
    text = EXAMPLE.read_text(encoding="utf-8")
    shutil.copy(EXAMPLE.parent / "hindcast_synthetic.csv", tmp_path)  # inside the case folder
    subs = {
        "max_storms": "40",
        "block_size": "20",
        "contour_points": "8",
        "top_points": "1",
        "top_seeds": "3",
        "peak_hours": "0.2",
    } | changes
    for key, value in subs.items():
        text = re.sub(rf"^{key} = [^#\n]*", f"{key} = {value} ", text, flags=re.M)
    p = tmp_path / "case.toml"
    p.write_text(text, encoding="utf-8")
    return p


def test_tiny_case_json_figures_and_resume(tmp_path, capsys):
    case = _tiny(tmp_path, return_period="1000.0")  # 40 times the 25-year record
    out = tmp_path / "out"
    args = ["reliability", str(case), "--out", str(out), "--workers", "0", "--json"]
    assert main([*args, "--no-progress"]) == 0
    first = json.loads(capsys.readouterr().out)
    for key in (
        "success",
        "diameter",
        "storms_per_year",
        "inputs",
        "climate",
        "estimates",
        "design",
        "campaign",
        "files",
        "notes",
    ):
        assert key in first
    assert first["inputs"][:3] == ["u_hs", "u_tp", "u_current"]
    assert first["inputs"][-1] == "storm_seed"
    assert first["climate"]["current_model"]["scale"] > 0  # current drawn from the hindcast
    from onbottom.cli.json_contract import documented_keys

    assert set(first) == documented_keys("reliability")
    for e in first["estimates"]:
        assert set(e) == documented_keys("reliability", "estimates[]")
    assert set(first["campaign"]) == documented_keys("reliability", "campaign")
    html = (out / "report.html").read_text(encoding="utf-8")
    for text in (
        "Exceedance probabilities",
        "Importance of the inputs",
        "Response-based design",
        'src="exceedance.png"',
        'src="convergence.png"',
        'src="importance.png"',
        "case SHA-256",
        "reliability.json",
    ):
        assert text in html, text
    labels = [e["label"] for e in first["estimates"]]
    assert labels == ["0.5D", "10D"]
    for e in first["estimates"]:
        assert 0.0 < e["probability"] <= 1.0 and e["storms"] <= 40
        assert e["annual"] == pytest.approx(
            -math.expm1(-first["storms_per_year"] * e["probability"])
        )
        assert "storm_seed and interactions" in e["importance"]
    d = first["design"]
    assert d["design_displacement"] >= d["governing"]["median"]
    assert d["return_period"] == 1000.0  # beyond 4 records: metocean's extrapolation note
    assert any(n.startswith("design: return periods up to 1000 years") for n in first["notes"])
    for name in (
        "exceedance.png",
        "convergence.png",
        "importance.png",
        "design.png",
        "reliability.json",
    ):
        assert (out / name).is_file()
    assert main([*args, "--no-progress", "--no-figures"]) == 0
    again = json.loads(capsys.readouterr().out)
    assert again["campaign"]["computed"] == 0  # every storm read back from the stores
    assert [e["probability"] for e in again["estimates"]] == [
        e["probability"] for e in first["estimates"]
    ]


def test_case_errors_name_the_key(tmp_path, capsys):
    case = _tiny(tmp_path, method='"form"')
    assert main(["reliability", str(case), "--workers", "0", "--json"]) == 1
    err = json.loads(capsys.readouterr().out)["error"]
    assert "reliability.method" in json.dumps(err)
    case = _tiny(tmp_path, limits='["2 diameters"]')
    assert main(["reliability", str(case), "--workers", "0", "--json"]) == 1
    assert "reliability.limits" in capsys.readouterr().out


def test_parse_limit():
    assert parse_limit("0.5D", 0.4) == ("0.5D", pytest.approx(0.2))
    assert parse_limit(1.5, 0.4) == ("1.5 m", 1.5)
    with pytest.raises(Exception, match="multiple of"):
        parse_limit("10 d", 0.4)
