"""Unit tests: the public kernel contracts re-export the private kernels' own objects.

The dynamics kernels and peers/ import the soil and force-model kernel contracts and the
pipeline's node layout from public modules (docs/architecture.md, "Kernels"). numba resolves a
called kernel, and its ``@overload`` specialisations, by the function object, and caches it by
its defining file: the public names must be the very objects of the private modules, and every
model id and node column must be there.
"""

from __future__ import annotations

import importlib

import pytest

from onbottom.dynamics.pipeline import _pipeline_kernel, node_layout
from onbottom.hydro import _force_contract, _force_dispatch, _load_kernels, kernel_contract
from onbottom.soil import _coulomb_kernel, _dispatch
from onbottom.soil import kernel_contract as soil_contract

CONTRACTS = [
    (soil_contract, [_dispatch, _coulomb_kernel]),
    (kernel_contract, [_force_dispatch, _force_contract, _load_kernels]),
    (node_layout, [_pipeline_kernel]),
]


@pytest.mark.parametrize(("public", "sources"), CONTRACTS, ids=lambda m: getattr(m, "__name__", ""))
def test_public_names_are_the_private_objects(public, sources):
    assert public.__all__, public.__name__
    for name in public.__all__:
        assert not name.startswith("_")
        owners = [m for m in sources if hasattr(m, name)]
        assert owners, f"{public.__name__}.{name} is in none of its private modules"
        assert all(getattr(public, name) is getattr(m, name) for m in owners), name


@pytest.mark.parametrize(
    ("public", "source", "prefix"),
    [
        ("onbottom.soil.kernel_contract", _dispatch, "MODEL_"),
        ("onbottom.hydro.kernel_contract", _force_dispatch, "FORCE_"),
        ("onbottom.hydro.kernel_contract", _force_contract, "FO_"),
        ("onbottom.dynamics.pipeline.node_layout", _pipeline_kernel, "ND_"),
    ],
)
def test_every_id_and_slot_is_public(public, source, prefix):
    exported = set(importlib.import_module(public).__all__)
    defined = {n for n in vars(source) if n.startswith(prefix)}
    assert defined, prefix
    assert defined <= exported, f"add {sorted(defined - exported)} to {public}"


def test_contract_modules_name_their_parts():
    assert soil_contract.lateral_step_of.__name__ == "lateral_step_of"
    assert node_layout.N_NODE_COLS == len([n for n in node_layout.__all__ if n.startswith("ND_")])


# ---- a registered model must name a kernel of the dispatch ---------------------------------------
def test_registration_without_a_dispatch_kernel_is_a_named_error():
    from dataclasses import dataclass

    from onbottom.errors import InputError
    from onbottom.hydro.registry import register_force_model
    from onbottom.soil.coulomb import CoulombFriction
    from onbottom.soil.registry import SOIL_MODELS, register_soil_model

    class Orphan(CoulombFriction):
        model_id = 987654321

    with pytest.raises(InputError, match=r"soil model 'orphan': Orphan.model_id = 987654321"):
        register_soil_model("orphan", Orphan)
    assert "orphan" not in SOIL_MODELS

    @dataclass(frozen=True)
    class OrphanForce:
        model_id: int = 987654321

    with pytest.raises(InputError, match="names no kernel of the solvers' dispatch"):
        register_force_model("orphan_force", OrphanForce)


@pytest.mark.parametrize(("suite", "name"), [("soil", "coulomb"), ("force", "morison")])
def test_a_missing_dispatch_entry_fails_the_named_conformance_test(monkeypatch, suite, name):
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "conformance"))
    module = importlib.import_module(f"test_{suite}_models")
    kernels = module._KERNELS
    model_id = next(k for k in kernels if k == module._model(name).model_id)
    module.test_dispatch_entry_exists(name)  # passes with the entry
    monkeypatch.delitem(kernels, model_id)
    with pytest.raises(AssertionError, match="not in the dispatch"):
        module.test_dispatch_entry_exists(name)
