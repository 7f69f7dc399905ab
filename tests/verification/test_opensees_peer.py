"""Verification against OpenSees (issue 33 item 5): the same pipeline — corotational elastic
beams, elastic–perfectly plastic lateral and axial springs, a travelling sinusoidal user load —
built in OpenSeesPy (onbottom.peers.opensees) and in onbottom; the envelopes of |y| per node
agree within 1e-4 (Newmark: the same discrete equations) and 0.5 % (HHT α = −0.1: OpenSees
evaluates the springs at the interpolated displacement, onbottom interpolates the forces).
Skipped, with the reason, when openseespy is absent (``pip install onbottom[peers]``)."""

from __future__ import annotations

import numpy as np
import pytest

from onbottom.dynamics.pipeline import PipelineModel
from onbottom.errors import InputError
from onbottom.peers.opensees import check_model, compare, import_opensees, peer_model
from onbottom.soil.coulomb import CoulombFriction

pytestmark = pytest.mark.verification

# 100 elements of 2 m (the benchmark's 1 km / 500 elements, shortened), 120 s at Δt = 0.1 s
N_EL = 100
DURATION = 120.0


@pytest.fixture(scope="module")
def opensees():
    try:
        return import_opensees()
    except ImportError as exc:
        pytest.skip(f"OpenSees peer not available: {exc}")


@pytest.mark.parametrize(("alpha", "tol"), [(0.0, 1e-4), (-0.1, 5e-3)])
def test_envelopes_agree_with_opensees(opensees, alpha, tol):
    model = peer_model(N_EL, length=2.0 * N_EL)
    c = compare(model, DURATION, dt=0.1, alpha=alpha)
    ob, os_ = c["onbottom"], c["opensees"]
    # the same fixed steps in both
    assert ob.n_steps == os_.n_steps == round(DURATION / 0.1)
    assert ob.info["n_rejected"] == 0
    # not a trivial comparison: the pipe slid, far beyond the springs' elastic range (1 mm)
    assert np.max(os_.max_abs_y) > 100 * 1e-3
    assert np.count_nonzero(os_.max_abs_y > 1e-2) > N_EL // 2
    # the fixed ends did not move
    assert os_.max_abs_y[0] == ob.max_abs_y[0] == 0.0
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
