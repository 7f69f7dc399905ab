"""Run identity: the one hash of a resumable run's inputs, and sealed JSON documents.

:func:`run_identity` is the run identity of every resumable solver (the pipeline FE, the DEM,
the task stores): a :class:`RunIdentity` holding the inputs (``fields``) and their SHA-256
(``digest``, :func:`identity_hash`). :func:`checksum_json` seals a JSON result file.
"""

from __future__ import annotations

import hashlib
import json
import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from onbottom._version import content_hash

__all__ = [
    "CHECKSUM_KEY",
    "RunIdentity",
    "checksum_json",
    "identity_hash",
    "run_identity",
    "verify_json_checksum",
]

_ADDRESS = re.compile(r" at 0x[0-9a-fA-F]+")


def identity_hash(meta: Any, *arrays: Any) -> str:
    """SHA-256 (hex) of ``meta`` as canonical JSON, then of the bytes of ``arrays``.

    The run identity of every resumable result: ``meta`` holds the inputs (JSON-able; other
    objects count by ``str``, memory addresses removed), ``arrays`` large numeric inputs
    (hashed by their bytes in C order). Equal inputs give equal hashes in any process.
    """
    h = hashlib.sha256()
    text = json.dumps(meta, sort_keys=True, default=str)
    h.update(_ADDRESS.sub("", text).encode())
    for a in arrays:
        h.update(np.ascontiguousarray(a).tobytes())
    return h.hexdigest()


@dataclass(frozen=True)
class RunIdentity:
    """The identity of a resumable run (checkpoint, chunk files, result file).

    ``fields``: the inputs that determine the run (JSON-able; written to files where they are
    compared field by field, as the DEM does); ``digest``: :func:`identity_hash` of the fields
    and the large arrays (written as ``run_id``, as the pipeline does).
    """

    fields: dict[str, Any]
    digest: str

    @property
    def fingerprint(self) -> str:
        """The first 16 hex digits of :attr:`digest` (a short name for a file's attributes)."""
        return self.digest[:16]


def run_identity(fields: Mapping[str, Any], *arrays: Any) -> RunIdentity:
    """The run identity of every resumable solver: the pipeline FE and the DEM.

    ``fields``: the inputs (model, settings, versions, …) as a JSON-able mapping; ``arrays``:
    large numeric inputs hashed by their bytes (kinematics). One function, one format:
    :class:`RunIdentity` (fields + sha256 digest). The fields get ``onbottom_content``, the
    package's content hash (:func:`onbottom._version.content_hash`), unless they hold it:
    a checkpoint or result of other code is another run.
    """
    meta = dict(fields)
    meta.setdefault("onbottom_content", content_hash())
    return RunIdentity(fields=meta, digest=identity_hash(meta, *arrays))


CHECKSUM_KEY = "checksum"
"""Key of the SHA-256 that seals a JSON result file (:func:`checksum_json`)."""


def _canonical_digest(doc: Mapping[str, Any]) -> str:
    body = {k: v for k, v in doc.items() if k != CHECKSUM_KEY}
    text = json.dumps(body, sort_keys=True, allow_nan=True)
    return "sha256:" + hashlib.sha256(text.encode()).hexdigest()


def checksum_json(doc: Mapping[str, Any], *, default: Any = None, indent: int | None = 1) -> str:
    """The JSON text of ``doc`` sealed with a checksum (key ``"checksum"``).

    The checksum is the SHA-256 of the document's canonical JSON (sorted keys) as it reads
    back; :func:`verify_json_checksum` recomputes it, so a file edited by hand (a result
    changed, a key removed) is told apart from one onbottom wrote. ``default``: as
    :func:`json.dumps` (objects JSON cannot encode).
    """
    obj = json.loads(json.dumps(dict(doc), default=default, allow_nan=True))
    obj.pop(CHECKSUM_KEY, None)
    obj[CHECKSUM_KEY] = _canonical_digest(obj)
    return json.dumps(obj, indent=indent, allow_nan=True)


def verify_json_checksum(doc: Mapping[str, Any]) -> bool | None:
    """True when the checksum of a JSON document read back (``json.loads`` of
    :func:`checksum_json`'s text) matches its content, False when it does not (the file was
    edited), None when the document carries none (written before checksums existed)."""
    got = doc.get(CHECKSUM_KEY)
    if got is None:
        return None
    return got == _canonical_digest(doc)
