"""Unit tests: ``onbottom.results`` is a package of one module per concern whose public names
stay importable from ``onbottom.results``, with one run identity (one function, one type)."""

from __future__ import annotations

import ast
import importlib
import inspect
import pathlib
import typing

import onbottom.results as results

SRC = pathlib.Path(results.__file__).resolve().parents[1]


def test_every_public_name_is_importable_from_the_package_and_lives_in_one_module():
    owners = {}
    for name in results.__all__:
        obj = getattr(results, name)
        module = getattr(obj, "__module__", None)
        if module is not None:
            owners[name] = module
    assert set(results.__all__) >= {
        "VARIABLES", "annotate", "provenance", "save_dataset", "load_dataset",
        "check_result_file", "write_text_atomic", "write_csv_atomic", "save_figure",
        "atomic_write", "OutputSet", "run_identity", "RunIdentity", "identity_hash",
        "TaskStore", "checksum_json", "verify_json_checksum",
    }  # fmt: skip
    assert owners["save_dataset"] == "onbottom.results.netcdf"
    assert owners["provenance"] == "onbottom.results.provenance"
    assert owners["TaskStore"] == "onbottom.results.tasks"
    assert owners["run_identity"] == owners["RunIdentity"] == "onbottom.results.identity"
    assert owners["write_text_atomic"] == "onbottom.results.files"
    assert owners["annotate"] == "onbottom.results.variables"
    for gone in ("LEGACY_NAMES", "upgrade_names"):  # never-released 0.1 names: dropped
        assert not hasattr(results, gone)


def test_one_run_identity_function_and_one_type():
    """Only ``results.run_identity`` is called run_identity; the DEM's and the pipeline's
    builders return its :class:`RunIdentity`."""
    defined = []
    for path in SRC.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.FunctionDef) and node.name == "run_identity":
                defined.append(path.relative_to(SRC).as_posix())
    assert defined == ["results/identity.py"]
    for module, name in (
        ("onbottom.dem.identity", "dem_identity"),
        ("onbottom.dynamics.pipeline.solver", "pipeline_identity"),
    ):
        fn = getattr(importlib.import_module(module), name)
        hints = typing.get_type_hints(fn, vars(inspect.getmodule(fn)))
        assert hints["return"] is results.RunIdentity, name


def test_dem_identity_is_the_run_identity_of_its_fields():
    from onbottom.dem.config import SD_REDUCED
    from onbottom.dem.identity import dem_identity, fingerprint

    ident = dem_identity(SD_REDUCED, "preparation")
    assert isinstance(ident, results.RunIdentity)
    again = results.run_identity(ident.fields)
    assert again == ident and fingerprint(ident.fields) == ident.fingerprint
    assert ident.fields["kind"] == "preparation" and "onbottom_content" in ident.fields
