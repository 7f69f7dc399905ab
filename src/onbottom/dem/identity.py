"""Run identity of DEM checkpoints and results: resume only what was started.

Every checkpoint and result of :func:`~onbottom.dem.preparation.prepare_sample` and
:func:`~onbottom.dem.experiment.penetrate` carries a *run identity*: the whole configuration
(preset name, geometry, PSD, target, contacts, preparation, loading — pipe velocity included —,
numerics and seed), the engine version, the checkpoint file-format version and, for a
penetration, the fingerprint of the specimen. A checkpoint is resumed only when its identity
equals the one of the run asked for; otherwise :class:`CheckpointMismatchError` lists the
fields that differ and says how to start afresh. A checkpoint that cannot be read (truncated,
corrupt, not a checkpoint) is a :class:`CheckpointError` with the same advice.
"""

from __future__ import annotations

import hashlib
import json
import os
from collections.abc import Mapping
from typing import Any

import numpy as np

from onbottom import results
from onbottom.errors import InputError

__all__ = [
    "ENGINE_VERSION",
    "FILE_FORMAT_VERSION",
    "CheckpointError",
    "CheckpointMismatchError",
    "check_identity",
    "check_sample_config",
    "dem_identity",
    "differences",
    "fingerprint",
    "guard_output",
    "recorded_identity",
    "sample_fingerprint",
]

ENGINE_VERSION = 1
"""Version of the DEM engine's equations and state layout (bump when results change)."""

FILE_FORMAT_VERSION = 2
"""Version of the checkpoint layout (2: run identity stored in every checkpoint)."""

RESTART_ADVICE = (
    "rerun with --restart to discard it and start afresh (Python: delete the file, or pass"
    " restart=True)"
)

# configuration fields that do not change a prepared specimen
_NOT_PREPARATION = ("name", "loading.pipe_velocity", "loading.final_embedment_ratio")


class CheckpointError(InputError):
    """A checkpoint cannot be used (unreadable, truncated, or written by another run)."""

    def __init__(self, message: str, *, field: str = "checkpoint") -> None:
        super().__init__(message)
        self.field = field


class CheckpointMismatchError(CheckpointError):
    """A checkpoint belongs to another run; ``differing`` lists the fields that differ."""

    def __init__(self, message: str, differing: list[str], *, field: str = "checkpoint"):
        super().__init__(message, field=field)
        self.differing = differing


def _config_dict(config: Any) -> dict[str, Any]:
    return json.loads(config.to_json())


def sample_fingerprint(sample: Any) -> str:
    """SHA-256 (16 hex digits) of a specimen's positions, radii and box."""
    h = hashlib.sha256()
    h.update(np.ascontiguousarray(sample.positions, dtype=np.float64).tobytes())
    h.update(np.ascontiguousarray(sample.radii, dtype=np.float64).tobytes())
    h.update(json.dumps([float(x) for x in sample.box]).encode())
    return h.hexdigest()[:16]


def dem_identity(config: Any, kind: str, *, sample: Any = None) -> results.RunIdentity:
    """The run identity (:func:`onbottom.results.run_identity`) of a checkpoint or result of
    stage ``kind``: its ``fields`` hold everything that determines it.

    ``kind`` is ``"preparation"`` or ``"penetration"``; ``sample`` (penetration) adds the
    specimen's fingerprint. The files store and compare the ``fields`` (field by field).
    """
    from onbottom.dem._kernels import N_PRM

    ident: dict[str, Any] = {
        "kind": kind,
        "config": _config_dict(config),
        "engine_version": ENGINE_VERSION,
        "engine_parameters": int(N_PRM),
        "file_format": FILE_FORMAT_VERSION,
    }
    if sample is not None:
        ident["sample"] = sample_fingerprint(sample)
    return results.run_identity(ident)


def fingerprint(identity: Mapping[str, Any]) -> str:
    """SHA-256 (16 hex digits) of the fields of a run identity (:func:`dem_identity`)."""
    return results.run_identity(identity).fingerprint


def _flatten(d: Any, prefix: str = "") -> dict[str, Any]:
    if isinstance(d, Mapping):
        out: dict[str, Any] = {}
        for k, v in d.items():
            out.update(_flatten(v, f"{prefix}.{k}" if prefix else str(k)))
        return out
    return {prefix: d}


# fields added after files were written, with the default that reproduces the older behaviour:
# a file without one matches a configuration holding that default
_ADDED_WITH_DEFAULT: dict[str, Any] = {
    "config.numerics.subcycle_preparation": True,
    "config.numerics.subcycle_dt_safety": None,
    "config.numerics.penetration_mass_floor": 0.0,
    "config.numerics.equilibrium_mass_floor": 0.0,
    "config.numerics.compaction_dt_safety": None,
    "config.preparation.lid_pause": "fixed",
}


def differences(saved: Mapping[str, Any], expected: Mapping[str, Any]) -> list[str]:
    """``"config.seed: 2 in the file, 7 now"`` for every field that differs.

    A field added to the configuration after the file was written, absent from the file, is
    not a difference while it holds the default that reproduces the older behaviour.
    """
    a, b = _flatten(saved), _flatten(expected)
    out = []
    for key in sorted(set(a) | set(b)):
        va, vb = a.get(key, "(absent)"), b.get(key, "(absent)")
        if key not in a and key in _ADDED_WITH_DEFAULT and vb == _ADDED_WITH_DEFAULT[key]:
            continue
        if va != vb:
            out.append(f"{key}: {va!r} in the file, {vb!r} now")
    return out


def check_identity(saved: Any, expected: Mapping[str, Any], path: Any, *, what: str) -> None:
    """Raise unless the identity ``saved`` (read from the file ``path``) equals ``expected``."""
    if not isinstance(saved, Mapping):
        raise CheckpointMismatchError(
            f"{what} {path} has no run identity (written by an older onbottom or another"
            f" program), so it cannot be checked to belong to this run; {RESTART_ADVICE}",
            ["identity: (absent) in the file"],
        )
    diff = differences(saved, expected)
    if diff:
        shown = "; ".join(diff[:8]) + (f"; and {len(diff) - 8} more" if len(diff) > 8 else "")
        raise CheckpointMismatchError(
            f"{what} {path} belongs to another run ({len(diff)} differing field"
            f"{'s' if len(diff) > 1 else ''}: {shown}); {RESTART_ADVICE}, or give another"
            " --checkpoint / --out file",
            diff,
        )


def check_sample_config(sample: Any, config: Any, path: Any) -> None:
    """Raise if the specimen in ``path`` was prepared with a configuration other than ``config``.

    Only the fields that determine a specimen are compared (not the name, the pipe velocity
    or the final embedment). A specimen without a recorded configuration is not checked.
    """
    text = sample.attrs.get("config")
    if not isinstance(text, str):
        return
    try:
        saved = json.loads(text)
    except ValueError:
        return
    now = _config_dict(config)
    diff = [
        d
        for d in differences({"config": saved}, {"config": now})
        if not any(d.startswith(f"config.{k}:") for k in _NOT_PREPARATION)
    ]
    if diff:
        raise CheckpointMismatchError(
            f"specimen {path} was prepared with another configuration ({'; '.join(diff[:8])});"
            " give a --sample file prepared for this run (a new path prepares one), or"
            " prepare it again with 'onbottom dem prepare --restart --out' that path",
            diff,
            field="sample",
        )


def recorded_identity(path: str | os.PathLike) -> dict[str, Any] | None:
    """The run identity recorded in a result or specimen file, its ``config`` included (None if
    the file has none or cannot be read)."""
    import xarray as xr

    try:
        with xr.open_dataset(path, engine="h5netcdf") as ds:
            attrs = dict(ds.attrs)
        if "sample_attrs" in attrs and "run_identity" not in attrs:
            attrs = json.loads(attrs["sample_attrs"])
        return {**json.loads(attrs["run_identity"]), "config": json.loads(attrs["config"])}
    except Exception:  # unreadable or without identity: not a result of this run either
        return None


def guard_output(
    path: str | os.PathLike, identity: Mapping[str, Any], *, restart: bool, field: str = "out"
) -> None:
    """Refuse to overwrite a file that holds the result of another run (unless ``restart``).

    ``identity`` is the :func:`dem_identity` fields of the run about to write ``path``; a file whose
    recorded identity (:func:`recorded_identity`) differs, or that has none, is an
    :class:`~onbottom.errors.InputError` naming ``field`` and the differing fields.
    """
    if restart or not os.path.exists(path):
        return
    found = recorded_identity(path)
    if found == identity:
        return
    what = (
        "a file without a run identity"
        if found is None
        else "the result of another run (" + "; ".join(differences(found, identity)[:8]) + ")"
    )
    err = InputError(
        f"{field} = {str(path)!r} is invalid: it already holds {what}; give another {field},"
        " or --restart to replace it"
    )
    err.field = field  # type: ignore[attr-defined]
    raise err
