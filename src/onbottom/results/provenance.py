"""Provenance attributes of every result: what produced it (:func:`provenance`)."""

from __future__ import annotations

import datetime as _dt
import json
from collections.abc import Mapping
from typing import Any

import numpy as np

from onbottom._version import __version__, content_hash, git_commit

__all__ = ["provenance"]


def provenance(model: str, parameters: Mapping[str, Any] | None = None, **extra: Any) -> dict:
    """Attributes recording what produced a result.

    Parameters
    ----------
    model
        Name of the model or solver.
    parameters
        Model parameters (SI); stored as a JSON string under ``parameters``.
    **extra
        Any further attributes (``seed``, ``standard_edition``, ...). Values that are not
        str/int/float are JSON-encoded so that the attributes survive NetCDF.

    Besides the version, the attributes hold ``onbottom_content_hash`` (the SHA-256 of the
    package's source and data files, :func:`onbottom._version.content_hash`: the version
    string alone does not change between commits) and, from a git checkout,
    ``onbottom_git_commit``.
    """
    attrs: dict[str, Any] = {
        "onbottom_version": __version__,
        "onbottom_content_hash": content_hash(),
        "model": model,
        "created": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
    }
    commit = git_commit()
    if commit:
        attrs["onbottom_git_commit"] = commit
    if parameters is not None:
        attrs["parameters"] = json.dumps(dict(parameters), sort_keys=True, default=float)
    for k, v in extra.items():
        attrs[k] = (
            v
            if isinstance(v, (str, int, float, np.integer, np.floating))
            else json.dumps(v, default=str)
        )
    return attrs
