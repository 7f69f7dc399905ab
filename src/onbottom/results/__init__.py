"""Result conventions: variable names and units, provenance, kill-safe result files, run identity.

One module per concern; the public names are re-exported here (``from onbottom.results import
save_dataset``):

- :mod:`~onbottom.results.variables`: every variable's ``long_name`` and ``units``
  (:data:`VARIABLES`, :func:`annotate`);
- :mod:`~onbottom.results.provenance`: the attributes recording what produced a result
  (:func:`provenance`);
- :mod:`~onbottom.results.files`: files written under a temporary name and renamed when
  complete (:func:`atomic_write`, :func:`write_text_atomic`, :func:`write_csv_atomic`,
  :func:`save_figure`, :class:`OutputSet`), so a file under its final name is always whole;
- :mod:`~onbottom.results.netcdf`: NetCDF results with ``run_status`` (:func:`save_dataset`,
  :func:`load_dataset`, :func:`check_result_file`), written by a direct NetCDF-4 writer
  (:mod:`~onbottom.results._nc4write`) when the dataset allows it;
- :mod:`~onbottom.results.identity`: the run identity of every resumable run
  (:func:`run_identity`, :class:`RunIdentity`) and sealed JSON documents
  (:func:`checksum_json`);
- :mod:`~onbottom.results.tasks`: the per-task store of runs of many independent tasks
  (:class:`TaskStore`: one small JSON file per finished task, so an interrupted run resumes
  without repeating them).
"""

from __future__ import annotations

from onbottom.results.files import (
    OutputSet,
    atomic_write,
    clean_stale_temporaries,
    glob_escape,
    save_figure,
    write_csv_atomic,
    write_text_atomic,
)
from onbottom.results.identity import (
    CHECKSUM_KEY,
    RunIdentity,
    checksum_json,
    identity_hash,
    run_identity,
    verify_json_checksum,
)
from onbottom.results.netcdf import (
    IN_MEMORY_MAX_BYTES,
    RESTART_ADVICE,
    RUN_STATUS_COMPLETE,
    RUN_STATUS_PARTIAL,
    check_result_file,
    load_dataset,
    netcdf_encoding,
    save_dataset,
)
from onbottom.results.provenance import provenance
from onbottom.results.tasks import TaskStore
from onbottom.results.variables import VARIABLES, annotate

__all__ = [
    "CHECKSUM_KEY",
    "IN_MEMORY_MAX_BYTES",
    "RESTART_ADVICE",
    "RUN_STATUS_COMPLETE",
    "RUN_STATUS_PARTIAL",
    "VARIABLES",
    "OutputSet",
    "RunIdentity",
    "TaskStore",
    "annotate",
    "atomic_write",
    "check_result_file",
    "checksum_json",
    "clean_stale_temporaries",
    "glob_escape",
    "identity_hash",
    "load_dataset",
    "netcdf_encoding",
    "provenance",
    "run_identity",
    "save_dataset",
    "save_figure",
    "verify_json_checksum",
    "write_csv_atomic",
    "write_text_atomic",
]
