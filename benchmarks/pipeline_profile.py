"""Where the pipeline FE's time goes: the parts of a Newton step timed one by one.

The benchmark storm of ``pipeline_storm.py`` (1 km pipe, Verley & Sotberg sand, Morison + lift)
is run to ``--at`` seconds; from that state (the predictor d₁ = d_n + Δt v_n of the next step)
each part of :func:`onbottom.dynamics.pipeline._pipeline_kernel.integrate` is called on its own
many times and timed in CPU seconds: the residual evaluation with and without the tangent
(``evaluate``), in it the corotational beam (``assemble_internal``), the lateral soil kernel and
the force model of every node, the band LDLᵀ factor and solve. With the counters of a run of
``--span`` seconds from there (Newton iterations and factorisations per step) they give the
estimated cost of a step by part, set beside the measured cost of a step; the rest (commit,
envelopes, residual and predictor loops, kinematics, lift once per step) is the difference.

    NUMBA_NUM_THREADS=1 python benchmarks/pipeline_profile.py --elements 500 --at 3600

Figures are CPU time of this process (``time.process_time``): on a loaded machine take the best
of ``--repeat`` (default 5).
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np
from numba import literally, njit

from onbottom._jit import borrow, call_literal, row_view
from onbottom.dynamics.pipeline import PipelineSettings
from onbottom.dynamics.pipeline import _pipeline_kernel as K
from onbottom.dynamics.pipeline import solver as S
from onbottom.dynamics.pipeline._banded import ldl_factor, ldl_solve
from onbottom.dynamics.pipeline._beam_kernel import HALF_BAND, NDOF_NODE, assemble_internal
from onbottom.hydro.force_model import N_FORCE_STATE
from onbottom.hydro.kernel_contract import FO_SIZE
from onbottom.hydro.kernel_contract import force_step_of as force_step
from onbottom.hydro.short_crested import pipeline_kinematics
from onbottom.inputs.storm import SeaState, Storm
from onbottom.soil.base import OUT_SIZE
from onbottom.soil.kernel_contract import lateral_step_node as lateral_step

sys.path.insert(0, str(Path(__file__).resolve().parent))
from pipeline_storm import model_of


@njit
def _evaluate(soil_id, force_id, reps, want_k, a):
    literally(soil_id)
    literally(force_id)
    (st, props, nodes, fixed, spring, mids, sp, ss, ax, fp, fs, t1, d1, v1, uk, ak, vc, ry,
     c_v, p, fh, fsoil, ab, trial, ftrial, nr, nf, nfa, fe, ke, out, fout, mom, nax, ktu,
     ktv) = a  # fmt: skip
    ok = True
    for _ in range(reps):
        ok = K.evaluate(
            soil_id, force_id, st, props, nodes, fixed, spring, mids, sp, ss, ax, fp, fs, t1,
            d1, v1, uk, ak, vc, ry, c_v, want_k, p, fh, fsoil, ab, trial, ftrial, nr, nf, nfa,
            fe, ke, out, fout, mom, nax, ktu, ktv,
        )  # fmt: skip
    return ok


@njit
def _soil(soil_id, reps, mids, sp, ss, d1, vc, trial, out):
    literally(soil_id)
    acc = 0.0
    for _ in range(reps):
        for i in range(ss.shape[0]):
            u = d1[NDOF_NODE * i + 1]
            # row views and borrowed arrays as in the kernel (no reference counting per call)
            lateral_step(
                soil_id, mids[i], row_view(sp, i), row_view(ss, i), u, vc[i],
                row_view(trial, i), borrow(out),
            )  # fmt: skip
            acc += out[0]
    return acc


@njit
def _force(force_id, reps, prow, fs, t1, uk, ak, nodes, v1, dd, rho, ftrial, fout):
    literally(force_id)
    acc = 0.0
    for _ in range(reps):
        for i in range(uk.shape[0]):
            force_step(
                force_id, borrow(prow), row_view(fs, i), t1, uk[i], ak[i], nodes[i, K.ND_CURRENT],
                v1[NDOF_NODE * i + 1], dd, rho, row_view(ftrial, i), borrow(fout),
            )  # fmt: skip
            acc += fout[0]
    return acc


@njit
def _beam(reps, want_k, d1, props, p, ab, fe, ke, mom, nax):
    for _ in range(reps):
        for j in range(p.shape[0]):
            p[j] = 0.0
        assemble_internal(d1, props, p, ab, want_k, fe, ke, mom, nax)


@njit
def _factor(reps, ab0, ab):
    neg = 0
    for _ in range(reps):
        ab[:, :] = ab0
        neg = ldl_factor(ab)
    return neg


@njit
def _copy(reps, ab0, ab):
    for _ in range(reps):
        ab[:, :] = ab0


@njit
def _solve(reps, ab, b0, b):
    for _ in range(reps):
        b[:] = b0
        ldl_solve(ab, b)


def _best(fn, reps: int, repeat: int) -> float:
    """CPU seconds per repetition of fn(reps): the least time of fn(reps) over ``repeat``
    tries less the least of fn(0) (the call's own overhead), over reps."""
    fn(1)

    def least(m: int) -> float:
        best = np.inf
        for _ in range(repeat):
            c0 = time.process_time()
            fn(m)
            best = min(best, time.process_time() - c0)
        return best

    return max(least(reps) - least(0), 0.0) / reps


def _run_to(model, kin, t: float):
    """The solver's stages run from the start to t: the run's state."""
    s, t_end = S._checked_settings(model, kin, PipelineSettings(record_interval=None), t, "auto")
    run = S._setup(model, kin, s, t_end, None, None, None, None)
    S._start(run, "auto")
    S._time_loop(run, False)
    return run


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--elements", type=int, default=500)
    ap.add_argument("--at", type=float, default=3600.0, help="storm time of the state [s]")
    ap.add_argument("--span", type=float, default=300.0, help="run for the counters [s]")
    ap.add_argument("--reps", type=int, default=200, help="calls per timing")
    ap.add_argument("--repeat", type=int, default=5, help="timings (least kept)")
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    a = ap.parse_args()
    if a.smoke:
        a.elements, a.at, a.span, a.reps, a.repeat = 20, 20.0, 10.0, 5, 1
    print(f"load average: {os.getloadavg()}")
    model = model_of(a.elements)
    sea = SeaState(hs=4.5, tp=10.0, direction_deg=80.0, spreading_s=8.0)
    hours = (a.at + a.span) / 3600.0
    build_up = min(0.5, hours / 2.0)
    storm = Storm.standard(sea, build_up_hours=build_up, peak_hours=hours - build_up, seed=0)
    kin = pipeline_kinematics(storm, 13.0, model.x)
    run = _run_to(model, kin, a.at)
    # counters and cost of a run of a.span seconds from there
    sc0 = run.scal.copy()
    c0 = time.process_time()
    _s, t_end = S._checked_settings(
        model, kin, PipelineSettings(record_interval=None), a.at + a.span, "auto"
    )
    run.t_end = t_end
    S._time_loop(run, False)
    cpu = time.process_time() - c0
    dsc = run.scal - sc0
    steps = dsc[K.SC_NSTEP]
    tried = steps + dsc[K.SC_NREJ]
    its = dsc[K.SC_NITER] / tried
    facs = dsc[K.SC_N_FACTOR] / tried
    step_us = 1e6 * cpu / tried
    # the parts, from the state at the end of that run (predictor of the next step)
    arr, n = run.arr, model.x.size
    ndof = NDOF_NODE * n
    dt = run.s.dt_max
    vec = run.vec
    d1 = vec[K.V_D] + dt * vec[K.V_V]
    v1 = vec[K.V_V].copy()
    t1 = float(run.scal[K.SC_T]) + dt
    ku, ka = run.kin.cover(t1, t1)
    uk, ak, vc, ry = (np.empty(n) for _ in range(4))
    K.kinematics_at(t1, ku, ka, run.st[K.ST_T_KIN0], run.st[K.ST_DT_KIN],
                    int(run.st[K.ST_KIN_K0]), int(run.st[K.ST_KIN_NT]), uk, ak)  # fmt: skip
    fscr, fout = np.zeros(N_FORCE_STATE), np.empty(FO_SIZE)
    K.node_loads(run.force_id, run.st, arr["nodes"], run.sstate, run.fparams, run.fstate, t1,
                 uk, ak, vec[K.V_V], vc, ry, fscr, fout)  # fmt: skip
    ab = np.zeros((ndof, HALF_BAND + 1))
    trial, ftrial = np.empty_like(run.sstate), np.zeros_like(run.fstate)
    out = np.empty(OUT_SIZE)
    fe, ke = np.empty(6), np.empty((6, 6))
    vecs = [np.empty(ndof) for _ in range(3)]
    nodal = [np.empty(n) for _ in range(7)]
    beta = 0.25 * (1.0 - run.s.alpha) ** 2
    c_v = (0.5 - run.s.alpha) / (beta * dt)
    args = (
        run.st, arr["props"], arr["nodes"], arr["fixed"], arr["spring"], arr["model_ids"],
        arr["sparams"], run.sstate, run.axst, run.fparams, run.fstate, t1, d1, v1, uk, ak,
        vc, ry, c_v, *vecs, ab, trial, ftrial, *nodal[:3], fe, ke, out, fout, *nodal[3:],
    )  # fmt: skip
    sid, fid = run.soil_id, run.force_id
    r, k = a.reps, a.repeat
    parts = {
        "evaluate, no tangent": _best(
            lambda m: call_literal(_evaluate, 2, sid, fid, m, np.bool_(False), args), r, k
        ),
        "evaluate with tangent": _best(
            lambda m: call_literal(_evaluate, 2, sid, fid, m, np.bool_(True), args), r, k
        ),
    }
    ab0 = ab.copy()  # the tangent of the last evaluation (no mass: the factor's cost only)
    ab0[:, 0] += 1e3 * np.abs(ab0).sum(axis=1).max()  # diagonally dominant: no zero pivot
    beam = {}
    for want in (np.bool_(False), np.bool_(True)):
        beam[bool(want)] = _best(
            lambda m, w=want: _beam(
                m, w, d1, arr["props"], vecs[0], ab, fe, ke, nodal[3], nodal[4]
            ),
            r,
            k,
        )
    parts["  of which beam, no tangent"] = beam[False]
    parts["  of which beam with tangent"] = beam[True]
    prow = np.ascontiguousarray(K.parameter_row(run.st, run.fparams, t1))
    soil_args = (arr["model_ids"], arr["sparams"], run.sstate, d1, vc, trial, out)
    parts["  of which soil kernel, all nodes"] = _best(
        lambda m: call_literal(_soil, 1, sid, m, *soil_args), r, k
    )
    dd, rho = run.st[K.ST_D], run.st[K.ST_RHO]
    force_args = (prow, run.fstate, t1, uk, ak, arr["nodes"], v1, dd, rho, ftrial, fout)
    parts["  of which force model, all nodes"] = _best(
        lambda m: call_literal(_force, 1, fid, m, *force_args), r, k
    )
    ab2 = np.empty_like(ab0)
    parts["band LDL factor"] = _best(lambda m: _factor(m, ab0, ab2), r, k) - _best(
        lambda m: _copy(m, ab0, ab2), r, k
    )
    b0 = np.random.default_rng(0).standard_normal(ndof)
    parts["band LDL solve"] = _best(lambda m: _solve(m, ab2, b0, vecs[1]), r, k)
    us = {name: 1e6 * v for name, v in parts.items()}
    per_step = {
        "evaluate with tangent": 1.0,
        "evaluate, no tangent": its - 1.0,
        "band LDL factor": facs,
        "band LDL solve": its - 1.0,
    }
    est = sum(us[p] * w for p, w in per_step.items())
    print(
        f"{a.elements} elements, state at t = {a.at:g} s; counters over {a.span:g} s:"
        f" {steps:.0f} steps, {tried - steps:.0f} rejected, {its:.2f} iterations and"
        f" {facs:.2f} factorisations per step tried"
    )
    print(f"{'part':36s} {'us/call':>9s} {'calls/step':>10s} {'us/step':>9s} {'share':>7s}")
    for name, v in us.items():
        w = per_step.get(name)
        if w is None:
            print(f"{name:36s} {v:9.2f}")
            continue
        print(f"{name:36s} {v:9.2f} {w:10.2f} {v * w:9.2f} {100 * v * w / step_us:6.1f}%")
    rest = step_us - est
    name = "rest (commit, loops, envelopes, ...)"
    print(f"{name:36s} {'':9s} {'':10s} {rest:9.2f} {100 * rest / step_us:6.1f}%")
    soil = us["  of which soil kernel, all nodes"] * its
    beam_us = us["  of which beam, no tangent"] * (its - 1.0) + us["  of which beam with tangent"]
    print(
        f"in the step: soil kernel {soil:.2f} us ({100 * soil / step_us:.1f}%),"
        f" beam {beam_us:.2f} us ({100 * beam_us / step_us:.1f}%)"
    )
    print(f"measured step: {step_us:.2f} us CPU ({1e3 * step_us / n:.1f} ns per node-step)")
    print(f"load average: {os.getloadavg()}")


if __name__ == "__main__":
    main()
