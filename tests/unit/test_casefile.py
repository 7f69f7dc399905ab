"""Strict case files: every problem is a CaseFileError naming the key, its place and range."""

from __future__ import annotations

import pytest
from pydantic import Field, ValidationError

from onbottom._casefile import (
    CaseFileError,
    StrictModel,
    load_case_file,
    parse_case,
    read_json,
    read_toml,
    resolve_path,
)
from onbottom.errors import InputError


class _Solver(StrictModel):
    dt_max: float = Field(0.1, gt=0.0, description="largest step [s]")
    n_cycles: int = Field(3, ge=1, description="cycles [-]")


class _Case(StrictModel):
    name: str
    solver: _Solver = _Solver()


def _load(tmp_path, text: str, suffix: str = ".toml") -> _Case:
    p = tmp_path / f"case{suffix}"
    p.write_text(text, encoding="utf-8")
    return load_case_file(p, _Case)


def test_valid_file_and_defaults(tmp_path):
    case = _load(tmp_path, 'name = "a"\n[solver]\ndt_max = 1\n')
    assert case.solver.dt_max == 1.0 and case.solver.n_cycles == 3
    with pytest.raises(ValidationError):  # frozen
        case.name = "b"


def test_misspelled_table_names_key_line_allowed_and_suggestion(tmp_path):
    with pytest.raises(CaseFileError) as info:
        _load(tmp_path, 'name = "a"\n\n[solvr]\ndt_max = 1\n')
    err = info.value
    assert isinstance(err, InputError)
    assert err.field == "solvr" and err.line == 3
    assert "allowed: name, solver" in str(err) and "did you mean 'solver'" in str(err)


def test_unknown_key_inside_table(tmp_path):
    with pytest.raises(CaseFileError) as info:
        _load(tmp_path, 'name = "a"\n[solver]\ndt_mx = 1\n')
    assert info.value.field == "solver.dt_mx" and info.value.line == 3
    assert "[solver]" in str(info.value) and "did you mean 'dt_max'" in str(info.value)


@pytest.mark.parametrize(
    ("body", "field"),
    [
        ("dt_max = -1", "solver.dt_max"),
        ('dt_max = "1"', "solver.dt_max"),
        ("dt_max = nan", "solver.dt_max"),
        ("dt_max = inf", "solver.dt_max"),
        ("n_cycles = 16.7", "solver.n_cycles"),
        ("n_cycles = 0", "solver.n_cycles"),
        ("n_cycles = true", "solver.n_cycles"),
    ],
)
def test_wrong_values_are_named(tmp_path, body, field):
    with pytest.raises(CaseFileError) as info:
        _load(tmp_path, f'name = "a"\n[solver]\n{body}\n')
    assert info.value.field == field
    assert f"{field} = " in str(info.value) and "line 3" in str(info.value)
    assert "np.float64" not in str(info.value)


def test_missing_key(tmp_path):
    with pytest.raises(CaseFileError, match="name is missing"):
        _load(tmp_path, "[solver]\n")


def test_malformed_toml_names_line(tmp_path):
    with pytest.raises(CaseFileError) as info:
        _load(tmp_path, 'name = "a"\n[solver\n')
    assert info.value.line == 2 and "not valid TOML" in str(info.value)


def test_malformed_json_names_line(tmp_path):
    p = tmp_path / "c.json"
    p.write_text('{"name": "a",\n "solver": }\n', encoding="utf-8")
    with pytest.raises(CaseFileError) as info:
        read_json(p)
    assert info.value.line == 2


def test_json_file_validated(tmp_path):
    case = _load(tmp_path, '{"name": "a", "solver": {"n_cycles": 4}}', suffix=".json")
    assert case.solver.n_cycles == 4


def test_missing_file_folder_and_binary(tmp_path):
    with pytest.raises(CaseFileError, match="file not found"):
        read_toml(tmp_path / "nope.toml")
    with pytest.raises(CaseFileError, match="is a folder"):
        read_toml(tmp_path)
    p = tmp_path / "bin.toml"
    p.write_bytes(b"\xff\xfe\x00")
    with pytest.raises(CaseFileError, match="UTF-8"):
        read_toml(p)


def test_not_a_table():
    with pytest.raises(CaseFileError, match="expected a table"):
        parse_case(_Case, [1, 2])


def test_resolve_path(tmp_path):
    case = tmp_path / "case.toml"
    (tmp_path / "prog.csv").write_text("t,H\n", encoding="utf-8")
    assert resolve_path("prog.csv", relative_to=case, field="programme.file").is_file()
    with pytest.raises(CaseFileError, match=r"programme\.file = 'x\.csv' is invalid"):
        resolve_path("x.csv", relative_to=case, field="programme.file")
