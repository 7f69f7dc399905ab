"""One-time warm-up: compile the numba kernels of the everyday commands into numba's cache.

numba compiles a kernel on its first call and keeps the machine code in its on-disk cache
(``cache=True``), so the first ``onbottom storm``, ``assess`` or pipeline run after an install
or an update pays 5–11 CPU-s of compiling before any physics (the per-kernel
cost is numba's typing, lowering and LLVM work, which fewer specialisations cut only by a
few per cent). :func:`warm_kernels` pays it once, ahead of time: it runs tiny real problems
(a few seconds of storm, a 24-m line, one load cycle) through the same public functions the
commands call, so numba compiles — and caches — the very specialisations (same kernels, same
literal model ids, same argument types) the commands use; a command run afterwards loads them
from the cache.

Targets (:data:`TARGETS`, one kernel group each):

``storm-sand``
    the storm-section kernel with Verley & Sotberg (``[seabed] model = "sand"`` and
    ``"calcareous"``) × the Morison and the wake force models (``storm``'s default Morison,
    ``assess``'s default wake: :data:`onbottom.cases.assess.DEFAULT_FORCE_MODEL`);
``storm-clay``
    the same with Verley & Lund (``"clay"``);
``storm-rock``
    the same with Coulomb friction (``"rock"``);
``pipeline``, ``pipeline-clay``
    the pipeline FE (``storm`` on a case with ``[pipeline]``, ``assess``'s pipeline FE
    level) with Verley & Sotberg (``examples/pipeline_case.toml``), and with Verley & Lund
    (the clay section of the embedded ``assess`` route), × Morison and wake;
``section``
    the centrifuge-section kernel (``reproduce``, ``simulate``, ``calibrate``) with Verley &
    Sotberg;
``fixed-pipe``
    the fixed-pipe load kernel of ``assess``'s design report (its V–H figure:
    :func:`onbottom.hydro.fixed_pipe.fixed_pipe_envelope`) × Morison and wake.

Targets run in worker processes, as many as there are cores (at most one per target); the
compile of each specialisation holds a cross-process lock (:func:`onbottom._jit.call_literal`)
so two processes never compile the same one. A model or force model not listed (Fourier, the
parabolic V–H model, mixed soils along a line) compiles on its first use, as before.
"""

from __future__ import annotations

import contextlib
import os
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from functools import partial

__all__ = [
    "PIPELINE_SEABEDS",
    "STORM_FORCE_MODELS",
    "STORM_SEABEDS",
    "TARGETS",
    "TargetTime",
    "WarmupReport",
    "WarmupTarget",
    "estimate",
    "warm_kernels",
]

_DEPTH = 15.0  # m, water depth of the tiny storms
_STORM_S = 6.0  # s of storm: a few dozen steps reach every branch that compiles


@dataclass(frozen=True)
class WarmupTarget:
    """One kernel group of the warm-up: its name (``--only``), what it compiles, and the CPU
    time its compile took from an empty cache [s] (measured; :func:`estimate`)."""

    name: str
    title: str
    cpu_s: float = 0.0


TARGETS: tuple[WarmupTarget, ...] = (
    WarmupTarget("pipeline", "pipeline FE kernel: sand/calcareous (Verley & Sotberg)", 19.0),
    WarmupTarget("pipeline-clay", "pipeline FE kernel: clay (Verley & Lund)", 18.7),
    WarmupTarget("storm-sand", "storm-section kernel: sand/calcareous (Verley & Sotberg)", 4.6),
    WarmupTarget("storm-clay", "storm-section kernel: clay (Verley & Lund)", 4.2),
    WarmupTarget("storm-rock", "storm-section kernel: rock (Coulomb)", 3.2),
    WarmupTarget("section", "centrifuge-section kernel: Verley & Sotberg", 2.0),
    WarmupTarget("fixed-pipe", "fixed-pipe load kernel of the assess report's V–H figure", 1.5),
)
"""The warm-up's kernel groups, the longest compile first (worker processes take them in
this order). Each storm-section group compiles the Morison and the wake force model."""

_BY_NAME = {t.name: t for t in TARGETS}

WORKER_START_S = 1.5
"""CPU time of a worker process's start (a fresh interpreter importing numba and onbottom) [s]."""


def estimate(
    targets: Sequence[str] | None = None, *, processes: int | None = None
) -> tuple[float, float, int]:
    """(CPU s, wall s on free cores, processes) the warm-up of ``targets`` should take.

    From each target's measured :attr:`WarmupTarget.cpu_s` (an empty cache): the CPU time is
    their sum (plus each worker's start); the wall time deals the targets in order to the
    processes, each taking the next when it finishes, as :func:`warm_kernels` does. A busy
    machine takes longer; targets already cached take seconds. ``targets`` and
    ``processes`` as :func:`warm_kernels` (unknown names are its to refuse).
    """
    import heapq

    names = [t.name for t in TARGETS] if targets is None else list(dict.fromkeys(targets))
    cpu = [_BY_NAME[n].cpu_s for n in names if n in _BY_NAME]
    workers = max(1, min(processes or available_cores(), max(len(cpu), 1)))
    start = WORKER_START_S if workers > 1 else 0.0
    free = [start] * workers
    for c in cpu:
        heapq.heappush(free, heapq.heappop(free) + c)
    return sum(cpu) + start * workers, max(free), workers


STORM_FORCE_MODELS: tuple[str, ...] = ("morison", "wake")
"""Force models (:mod:`onbottom.hydro.registry` names) each storm-section group compiles:
``storm``'s default and ``assess``'s default."""

STORM_SEABEDS: dict[str, str] = {
    "storm-sand": "sand",
    "storm-clay": "clay",
    "storm-rock": "rock",
}
"""Storm-section target → the seabed kind (``[seabed] model``) whose default soil model it
compiles (``"calcareous"`` is Verley & Sotberg too, ``"coulomb"`` Coulomb as ``"rock"``)."""

PIPELINE_SEABEDS: dict[str, str] = {"pipeline": "sand", "pipeline-clay": "clay"}
"""Pipeline target → the seabed kind whose soil model it compiles (with each of
:data:`STORM_FORCE_MODELS`): the example's sand and the embedded ``assess`` route's sand and
clay sections (its pipeline FE run takes the governing section's soil)."""


@dataclass(frozen=True)
class TargetTime:
    """What one target cost: wall and CPU seconds of its process, and the number of numba
    compiles (specialisations, the helpers they call included; 0: all loaded from the cache)."""

    target: WarmupTarget
    wall_s: float
    cpu_s: float
    compiled: int


@dataclass(frozen=True)
class WarmupReport:
    """Result of :func:`warm_kernels`: each target's cost (in the order finished), the wall
    time of the whole warm-up [s] and the number of processes used."""

    targets: tuple[TargetTime, ...]
    wall_s: float
    processes: int

    @property
    def cpu_s(self) -> float:
        """CPU seconds of all targets together [s]."""
        return sum(t.cpu_s for t in self.targets)

    @property
    def compiled(self) -> int:
        """numba compiles of all targets together."""
        return sum(t.compiled for t in self.targets)


def _pipe():
    from onbottom.inputs.pipe import Pipe

    # D [m], w_s [N/m], EI [N m²], EA [N]: any valid pipe compiles the same specialisations
    return Pipe(
        outer_diameter=0.3, submerged_weight=800.0, bending_stiffness=2e7, axial_stiffness=2e9
    )


def _storm():
    from onbottom.inputs.storm import SeaState, Storm

    # H_s [m], T_p [s], duration [s]
    sea = SeaState(hs=3.0, tp=9.0, duration_s=_STORM_S, direction_deg=90.0, spreading_s=8.0)
    return Storm(stages=(sea,), build_up_s=0.0, transition_s=0.0, seed=0)


def _seabed(kind: str):
    from onbottom.inputs.soil import Clay, Rock, Sand

    # unit weights [N/m³], s_u [Pa]
    if kind == "sand":
        return Sand(submerged_unit_weight=10.0e3)
    if kind == "clay":
        return Clay(undrained_shear_strength=5.0e3, submerged_unit_weight=6.0e3, unit_weight=16e3)
    return Rock()


def _force_models():
    from onbottom.hydro.registry import build_force_model

    return tuple(build_force_model(name, {}) for name in STORM_FORCE_MODELS)


def _storm_section(kind: str) -> None:
    """The storm-section kernel for seabed ``kind`` × Morison, wake (``storm``, ``assess``)."""
    from onbottom.dynamics.storm_section import StormSolverSettings, simulate_storm_section
    from onbottom.inputs.storm import Current
    from onbottom.soil.registry import soil_model_for_seabed

    pipe = _pipe()
    soil = soil_model_for_seabed(kind, pipe, _seabed(kind))
    for fm in _force_models():
        simulate_storm_section(
            pipe,
            soil,
            _storm(),
            depth=_DEPTH,
            current=Current(velocity=0.3, reference_height=1.0, direction_deg=90.0),
            z0=1e-5,
            force_model=fm,
            settings=StormSolverSettings(record_interval=0.5),
        )


def _pipeline(kind: str) -> None:
    """The pipeline FE kernel for seabed ``kind`` × Morison, wake (a ``storm`` case with
    ``[pipeline]``; the pipeline FE level of ``assess``, whose default force model is wake)."""
    from onbottom.dynamics.pipeline import PipelineModel, PipelineSettings, simulate_pipeline
    from onbottom.hydro.short_crested import pipeline_kinematics
    from onbottom.soil.registry import soil_model_for_seabed

    pipe = _pipe()
    soil = soil_model_for_seabed(kind, pipe, _seabed(kind))
    for fm in _force_models():
        model = PipelineModel(
            pipe=pipe, length=24.0, element_length=4.0, soil=soil, force_model=fm,
            effective_axial_force=-1.0e5, current=0.3,
        )  # fmt: skip
        kin = pipeline_kinematics(_storm(), _DEPTH, model.x)
        simulate_pipeline(model, kin, settings=PipelineSettings(record_interval=1.0))


def _fixed_pipe() -> None:
    """The fixed-pipe load kernel × Morison, wake (the V–H figure of ``assess``'s report)."""
    from onbottom.hydro.fixed_pipe import fixed_pipe_envelope
    from onbottom.hydro.storm_kinematics import storm_kinematics

    pipe = _pipe()
    kin = storm_kinematics(_storm(), _DEPTH, diameter=pipe.outer_diameter)
    for fm in _force_models():
        fixed_pipe_envelope(
            fm, kin, diameter=pipe.outer_diameter, submerged_weight=pipe.submerged_weight,
            density=pipe.seawater_density,
        )  # fmt: skip


def _section() -> None:
    """The centrifuge-section kernel, Verley & Sotberg (``reproduce``, ``simulate``)."""
    from onbottom.dynamics.centrifuge import run_centrifuge_test

    run_centrifuge_test("Inclined 1", n_cycles=1)


_RUNS: dict[str, Callable[[], None]] = {
    **{name: partial(_pipeline, kind) for name, kind in PIPELINE_SEABEDS.items()},
    **{name: partial(_storm_section, kind) for name, kind in STORM_SEABEDS.items()},
    "section": _section,
    "fixed-pipe": _fixed_pipe,
}


def _run_target(name: str) -> tuple[str, float, float, int]:
    """Run target ``name`` here: (name, wall s, CPU s, numba compiles)."""
    import warnings

    from numba.core import event
    from numba.core.errors import NumbaWarning

    count = [0]

    with _interruptible() as check:

        class Counter(event.Listener):
            def on_start(self, ev) -> None:
                check()
                count[0] += 1

            def on_end(self, ev) -> None:
                check()

        t0, c0 = time.perf_counter(), time.process_time()
        with event.install_listener("numba:compile", Counter()), warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the tiny problems' out-of-range notes mean nothing
            warnings.simplefilter("default", NumbaWarning)  # e.g. a cache that cannot be written
            _RUNS[name]()
        check()
    return name, time.perf_counter() - t0, time.process_time() - c0, count[0]


@contextlib.contextmanager
def _interruptible() -> Iterator[Callable[[], None]]:
    """Ctrl-C during numba's compile in this process stops the run (KeyboardInterrupt).

    LLVM calls back into Python through ctypes while it compiles; a KeyboardInterrupt raised
    there is printed with a traceback ("Exception ignored …") and swallowed, and the compile
    goes on. Here Ctrl-C is remembered, that print is suppressed, and the interrupt is raised
    again by the yielded ``check()`` (called at every compile event and after the target).
    Only in the main thread with Python's default SIGINT handler (a pool worker ignores
    Ctrl-C: the parent handles it).
    """
    import signal
    import sys
    import threading

    if (
        threading.current_thread() is not threading.main_thread()
        or signal.getsignal(signal.SIGINT) is not signal.default_int_handler
    ):
        yield lambda: None
        return
    hit = [False]

    def handler(signum, frame) -> None:
        hit[0] = True
        raise KeyboardInterrupt

    def check() -> None:
        if hit[0]:
            raise KeyboardInterrupt

    old_hook = sys.unraisablehook

    def hook(unraisable) -> None:
        if not isinstance(unraisable.exc_value, KeyboardInterrupt):
            old_hook(unraisable)

    signal.signal(signal.SIGINT, handler)
    sys.unraisablehook = hook
    try:
        yield check
    finally:
        signal.signal(signal.SIGINT, signal.default_int_handler)
        sys.unraisablehook = old_hook


def available_cores() -> int:
    """Cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - macOS, Windows
        return os.cpu_count() or 1


def warm_kernels(
    targets: Sequence[str] | None = None,
    *,
    processes: int | None = None,
    progress: Callable[[int, int, WarmupTarget], None] | None = None,
) -> WarmupReport:
    """Compile the kernels of ``targets`` into numba's on-disk cache.

    Parameters
    ----------
    targets : sequence of str or None
        Names of :data:`TARGETS` (None: all of them).
    processes : int or None
        Worker processes (None: one per core, at most one per target); 1 runs the targets in
        this process, one after the other.
    progress : callable or None
        ``progress(k, n, target)`` when the ``k``-th of ``n`` targets starts (k from 1).

    Returns
    -------
    WarmupReport
        Each target's wall and CPU seconds and numba compile count, the total wall time.
        A second warm-up compiles nothing (every specialisation loads from the cache).
    """
    from onbottom.errors import InputError

    names = [t.name for t in TARGETS] if targets is None else list(dict.fromkeys(targets))
    for name in names:
        if name not in _BY_NAME:
            raise InputError(f"targets = {name!r} is invalid: choose from {', '.join(_BY_NAME)}")
    if processes is not None and processes < 1:
        raise InputError(f"processes = {processes!r} is invalid: must be >= 1")
    n = len(names)
    workers = min(processes or available_cores(), max(n, 1))
    done: list[TargetTime] = []
    t0 = time.perf_counter()

    def record(row: tuple[str, float, float, int]) -> None:
        name, wall, cpu, compiled = row
        done.append(TargetTime(_BY_NAME[name], wall, cpu, compiled))

    if workers <= 1:
        for k, name in enumerate(names, 1):
            if progress is not None:
                progress(k, n, _BY_NAME[name])
            record(_run_target(name))
        return WarmupReport(tuple(done), time.perf_counter() - t0, 1)

    import multiprocessing
    import queue

    # spawn: a clean interpreter per worker (the parent may have imported numba or threads);
    # the workers ignore Ctrl-C, and leaving the pool terminates them (an interrupted
    # compile leaves no partial cache file: numba writes a temporary file and renames it)
    ctx = multiprocessing.get_context("spawn")
    pending = list(enumerate(names, 1))
    finished: queue.SimpleQueue = queue.SimpleQueue()
    running = 0
    with ctx.Pool(workers, initializer=_ignore_interrupts) as pool:
        while pending or running:
            while pending and running < workers:
                k, name = pending.pop(0)
                if progress is not None:
                    progress(k, n, _BY_NAME[name])
                pool.apply_async(
                    _run_target, (name,), callback=finished.put, error_callback=finished.put
                )
                running += 1
            row = finished.get()
            running -= 1
            if isinstance(row, BaseException):
                raise row
            record(row)
    return WarmupReport(tuple(done), time.perf_counter() - t0, workers)


def _ignore_interrupts() -> None:
    """Worker initializer: Ctrl-C is the parent's to handle (it terminates the workers)."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
