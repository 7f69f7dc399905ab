"""Verification against OpenSees (issue 33 item 5): the same pipeline — corotational elastic
beams, elastic–perfectly plastic lateral and axial springs, a travelling sinusoidal user load —
built in OpenSeesPy (onbottom.peers.opensees) and in onbottom; the envelopes of |y| per node
agree within 1e-4 (Newmark: the same discrete equations) and 0.5 % (HHT α = −0.1: OpenSees
evaluates the springs at the interpolated displacement, onbottom interpolates the forces).
Skipped, with the reason, when openseespy is absent (``pip install onbottom[peers]``)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from onbottom.dynamics.pipeline import PipelineModel
from onbottom.errors import InputError
from onbottom.peers.opensees import check_model, peer_model
from onbottom.soil.coulomb import CoulombFriction

SRC = Path(__file__).resolve().parents[2] / "src"

pytestmark = pytest.mark.verification

# 100 elements of 2 m (the benchmark's 1 km / 500 elements, shortened), 120 s at Δt = 0.1 s
N_EL = 100
DURATION = 120.0


def _isolated(code: str) -> subprocess.CompletedProcess:
    """Run ``code`` in a fresh interpreter: OpenSees' native library (and the BLAS it brings)
    is loaded there, never into the test process — in a process that has loaded numba,
    openturns and others first it crashed the whole test run (segmentation fault, CI)."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(SRC), os.environ.get("PYTHONPATH", "")]))
    return subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=False
    )


@pytest.fixture(scope="module")
def opensees():
    p = _isolated("from onbottom.peers.opensees import import_opensees; import_opensees()")
    if p.returncode != 0:
        tail = (p.stderr.strip().splitlines() or ["no message"])[-1]
        pytest.skip(f"OpenSees peer not available (exit {p.returncode}): {tail}")
    return True


_COMPARE = """
import json, sys
from onbottom.peers.opensees import compare, peer_model
c = compare(peer_model({n}, length={length}), {duration}, dt=0.1, alpha={alpha})
ob, os_ = c["onbottom"], c["opensees"]
print(json.dumps({{
    "ob_steps": ob.n_steps, "os_steps": os_.n_steps, "ob_rejected": ob.info["n_rejected"],
    "ob_y": ob.max_abs_y.tolist(), "os_y": os_.max_abs_y.tolist(),
    "max_rel_diff": c["max_rel_diff"],
}}))
"""


@pytest.mark.parametrize(("alpha", "tol"), [(0.0, 1e-4), (-0.1, 5e-3)])
def test_envelopes_agree_with_opensees(opensees, alpha, tol):
    p = _isolated(_COMPARE.format(n=N_EL, length=2.0 * N_EL, duration=DURATION, alpha=alpha))
    assert p.returncode == 0, p.stderr[-3000:]
    c = json.loads(p.stdout.strip().splitlines()[-1])
    ob_y, os_y = np.array(c["ob_y"]), np.array(c["os_y"])
    # the same fixed steps in both
    assert c["ob_steps"] == c["os_steps"] == round(DURATION / 0.1)
    assert c["ob_rejected"] == 0
    # not a trivial comparison: the pipe slid, far beyond the springs' elastic range (1 mm)
    assert np.max(os_y) > 100 * 1e-3
    assert np.count_nonzero(os_y > 1e-2) > N_EL // 2
    # the fixed ends did not move
    assert os_y[0] == ob_y[0] == 0.0
    assert c["max_rel_diff"] <= tol, c["max_rel_diff"]


def test_the_peer_build_refuses_what_it_does_not_model():
    model = peer_model(10, length=20.0)
    assert check_model(model) is model.user_load
    with pytest.raises(InputError, match="TravellingSineLoad"):
        check_model(PipelineModel(**{**_fields(model), "user_load": None}))
    with pytest.raises(InputError, match="hydrodynamic load must be off"):
        check_model(PipelineModel(**{**_fields(model), "relative_velocity": True}))
    with pytest.raises(InputError, match="effective_axial_force"):
        check_model(PipelineModel(**{**_fields(model), "effective_axial_force": -1e5}))
    with pytest.raises(InputError, match="spring"):
        check_model(PipelineModel(**{**_fields(model), "end_conditions": "spring"}))
    from onbottom.inputs.soil import Sand
    from onbottom.soil.verley_sotberg import VerleySotberg

    vs = VerleySotberg.silica(model.pipe, Sand(submerged_unit_weight=1e4))
    with pytest.raises(InputError, match="CoulombFriction"):
        check_model(PipelineModel(**{**_fields(model), "soil": vs}))
    assert isinstance(model.sections[0].model, CoulombFriction)
    from onbottom.peers.opensees import run_onbottom

    with pytest.raises(InputError, match="whole number of steps"):
        run_onbottom(model, 1.05, dt=0.1)


def _fields(model):
    from dataclasses import fields

    return {f.name: getattr(model, f.name) for f in fields(model)}
