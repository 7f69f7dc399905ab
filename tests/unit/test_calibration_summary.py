"""Unit tests: Table-2/Table-3 summaries (the paper's own numbers as input)."""

from __future__ import annotations

import pytest

from onbottom import InputError
from onbottom.calibration.summary import recommend, to_csv, to_markdown

# Youssef & Cassidy (2014) Table 2
TABLE2 = [
    {"case": "Inclined 1", "A": 0.25, "B": 0.35, "C": 0.79, "mu": 0.48},
    {"case": "Inclined 2", "A": 0.25, "B": 0.45, "C": 1.05, "mu": 0.60},
    {"case": "Inclined 3", "A": 0.25, "B": 0.45, "C": 1.18, "mu": 0.65},
    {"case": "Inclined 4", "A": 0.45, "B": 0.35, "C": 0.96, "mu": 0.75},
    {"case": "Inclined 5", "A": 0.25, "B": 0.35, "C": 0.84, "mu": 0.85},
    {"case": "Regular", "A": 0.25, "B": 0.28, "C": 0.97, "mu": 0.85},
    {"case": "Irregular", "A": 0.25, "B": 0.24, "C": 1.12, "mu": 0.85},
]


def test_paper_rules_reproduce_table3():
    rec = {r["parameter"]: r for r in recommend(TABLE2)}
    # the paper: A mean 0.28, conservative 0.25 (lowest); B mean 0.35; C mean 0.98
    assert rec["A"]["mean"] == pytest.approx(0.2786, abs=1e-4)
    assert rec["A"]["recommended"] == 0.25
    assert rec["B"]["recommended"] == pytest.approx(0.3529, abs=1e-4)
    assert rec["C"]["recommended"] == pytest.approx(0.9871, abs=1e-4)
    assert rec["mu"]["rule"] == "range"
    assert (rec["mu"]["min"], rec["mu"]["max"]) == (0.48, 0.85)


def test_custom_rules_and_bad_rule():
    rec = recommend(TABLE2, names=("B",), rules={"B": "max"})
    assert rec[0]["recommended"] == 0.45
    with pytest.raises(InputError, match="rules"):
        recommend(TABLE2, names=("B",), rules={"B": "mode"})


def test_markdown_and_csv(tmp_path):
    md = to_markdown(TABLE2[:2], floatfmt=".2f")
    assert md.splitlines()[0] == "| case | A | B | C | mu |"
    assert "| Inclined 1 | 0.25 | 0.35 | 0.79 | 0.48 |" in md
    text = to_csv(TABLE2, tmp_path / "t.csv")
    assert text.splitlines()[1] == "Inclined 1,0.25,0.35,0.79,0.48"
    assert (tmp_path / "t.csv").read_text().count("\n") == 8
