"""The project's numba decorator for hot-loop kernels (private).

:func:`njit` is :func:`numba.njit` with ``error_model="numpy"`` unless the caller says
otherwise: a float division by zero gives ±inf or NaN (IEEE 754), as numpy does, instead of
numba's default Python error model, which tests every divisor and raises ZeroDivisionError,
and makes every call between kernels check an exception status. The kernels never rely on
that exception (each solver checks its results for finiteness), and the tests and checks
cost a large part of a small soil kernel call. Results are bit-identical wherever no division
by zero occurs.

It also sets ``no_cfunc_wrapper=True``: numba otherwise builds, optimises and machine-compiles
a C-callable wrapper for every jitted function, used only when a function is passed as a
first-class function value (ctypes/cffi), which the project never does; about a tenth of a
first run's compiling.

:func:`jitted_only` also drops the CPython wrapper, for kernels that only other kernels call
(a Python call goes to their :func:`python_entry` copy).

Kernel modules import it in place of numba's: ``from onbottom._jit import njit``. numba is
imported when this module is, i.e. only with a kernel module.

**Cache folder per package content.** numba's on-disk cache checks only the source file of
the kernel it loads (its time stamp and size): an edited kernel called from another file, or
an upgraded package, would be served stale. :func:`njit` (and :func:`numba_njit`, numba's own
defaults, for the few modules that keep them) therefore put the cache of ``cache=True``
kernels in a folder named by the hash of the package's Python sources
(:func:`onbottom._version.code_hash`, part of the content hash): any edit of a module gives a
new, empty folder (a kernel may call, or freeze as a constant, anything of any module).
The folder is :func:`cache_dir`: ``$NUMBA_CACHE_DIR/onbottom-<hash>`` when the user set
``NUMBA_CACHE_DIR``, else ``<user cache>/onbottom/numba/<hash>`` (``$XDG_CACHE_HOME`` or
``~/.cache``); when that is not writable (a read-only install, a read-only home) the
temporary folder, with a one-line note; when nothing is writable, kernels are compiled in each
process without caching, with a one-line note. Hash folders beyond the most recent few that
have not been used for a week are removed.

:func:`pure_python` builds a kernel's plain-Python twin from the kernel's own source; it lives
here, in a base module, so that the kernels of every package (soil, hydro, dynamics) share it.
"""

from __future__ import annotations

import contextlib
import hashlib
import logging
import operator
import os
import shutil
import tempfile
import types
from collections.abc import Callable, Iterator
from typing import Any

import numba
import numpy as np
from numba import types as nbtypes
from numba.core import cgutils
from numba.core.dispatcher import Dispatcher
from numba.core.registry import CPUDispatcher
from numba.extending import intrinsic, overload
from numba.np.arrayobj import make_array

__all__ = [
    "borrow",
    "cache_dir",
    "call_literal",
    "jitted_only",
    "literal_dispatch",
    "njit",
    "numba_njit",
    "pure_python",
    "python_entry",
    "row_view",
]

logger = logging.getLogger(__name__)

KEEP_CACHE_FOLDERS = 4
"""Hash folders always kept beside the current one (the most recently used)."""
PRUNE_AFTER_S = 7 * 86400.0
"""A hash folder beyond :data:`KEEP_CACHE_FOLDERS` is removed once unused for this long [s]
(a process touches its folder when it starts: a folder in use is never removed under it)."""

_UNSET = object()
_CACHE_DIR: Any = _UNSET


def _writable(folder: str) -> bool:
    try:
        os.makedirs(folder, exist_ok=True)
        fd, probe = tempfile.mkstemp(prefix=".probe-", dir=folder)
        os.close(fd)
        os.unlink(probe)
    except OSError:
        return False
    return True


def _prune(parent: str, keep: str) -> None:
    """Touch ``keep`` (in use); remove the other hash folders of ``parent`` beyond the most
    recent few that have not been used for :data:`PRUNE_AFTER_S`."""
    import time

    try:
        os.utime(keep)
        entries = [
            e for e in os.scandir(parent) if e.is_dir() and e.path != keep and e.name[:1] != "."
        ]
        entries.sort(key=lambda e: e.stat().st_mtime, reverse=True)
        old = time.time() - PRUNE_AFTER_S
        for e in entries[KEEP_CACHE_FOLDERS:]:
            if e.stat().st_mtime < old:
                shutil.rmtree(e.path, ignore_errors=True)
    except OSError:
        pass


def cache_dir() -> str | None:
    """numba's cache folder of the onbottom kernels, one per package content hash (resolved
    once per process; see the module docstring); None when no folder is writable (kernels
    are then not cached)."""
    global _CACHE_DIR
    if _CACHE_DIR is not _UNSET:
        return _CACHE_DIR
    from onbottom._version import code_hash

    key = code_hash()[:16]
    user = os.environ.get("NUMBA_CACHE_DIR", "")
    home = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    if user:
        candidates = [(user, f"onbottom-{key}")]
    else:
        candidates = [(os.path.join(home, "onbottom", "numba"), key)]
    uid = getattr(os, "getuid", lambda: 0)()
    tmp = os.path.join(tempfile.gettempdir(), f"onbottom-numba-{uid}")
    candidates.append((tmp, key))
    chosen = None
    for parent, name in candidates:
        folder = os.path.join(parent, name)
        if _writable(folder):
            chosen = folder
            if name == key:
                _prune(parent, folder)
            break
    first = os.path.join(*candidates[0])
    if chosen is None:
        logger.warning(
            "note: numba's cache folder %s is not writable (nor %s): compiled kernels are not"
            " cached (each run compiles them)",
            first,
            os.path.join(*candidates[-1]),
        )
    elif chosen != first:
        logger.warning(
            "note: numba's cache folder %s is not writable: compiled kernels are cached in %s",
            first,
            chosen,
        )
    _CACHE_DIR = chosen
    return chosen


def _cached(decorate: Callable, kwargs: dict) -> Any:
    """Apply ``decorate`` with numba's cache folder set to :func:`cache_dir` (caching off
    when there is none); numba fixes a kernel's cache folder when it is decorated."""
    if not kwargs.get("cache"):
        return decorate(kwargs)
    folder = cache_dir()
    if folder is None:
        return decorate({**kwargs, "cache": False})
    old = numba.config.CACHE_DIR
    numba.config.CACHE_DIR = folder
    try:
        return decorate(kwargs)
    finally:
        numba.config.CACHE_DIR = old


def numba_njit(*args, **kwargs):
    """:func:`numba.njit` with numba's own defaults, its cache in :func:`cache_dir`."""
    if args and callable(args[0]):
        return _cached(lambda kw: numba.njit(*args, **kw), kwargs)
    return lambda fn: _cached(lambda kw: numba.njit(*args, **kw)(fn), kwargs)


def njit(*args, **kwargs):
    """:func:`numba.njit` with ``error_model="numpy"`` by default (same call forms), its
    cache (``cache=True``) in :func:`cache_dir`."""
    kwargs.setdefault("error_model", "numpy")
    kwargs.setdefault("no_cfunc_wrapper", True)
    return numba_njit(*args, **kwargs)


class _JittedOnlyDispatcher(CPUDispatcher):
    """A dispatcher compiled without numba's CPython wrapper (:func:`jitted_only`); a call
    from Python goes to :func:`python_entry` of it (its entry point would jump to the
    missing wrapper)."""

    def __call__(self, *args, **kwargs):
        return python_entry(self)(*args, **kwargs)


def jitted_only(fn: Callable | None = None, /, *, error_model: str = "numpy") -> Any:
    """:func:`njit` (``cache=True``) for a kernel called from other kernels, not from Python.

    numba otherwise lowers, optimises and machine-compiles a CPython wrapper (the unboxing
    of every argument) for each jitted function, though a callee's compiled code is used
    only through its LLVM module, linked into the caller: for a small helper that is about
    half of its compile. Same source, typing and arithmetic as :func:`njit`. A call from
    Python still works: it compiles and calls :func:`python_entry` of the kernel (a second
    compile, with the wrapper; tests and profiling). Not for an entry point called through
    its compiled overloads (:func:`call_literal`).

    ``@jitted_only`` or ``@jitted_only(error_model="python")`` (the error model of a module
    that keeps numba's defaults, :func:`numba_njit`; its :func:`python_entry` copy too)."""
    if fn is None:
        return lambda f: jitted_only(f, error_model=error_model)
    if numba.config.DISABLE_JIT:
        return fn
    options = {"error_model": error_model, "no_cfunc_wrapper": True, "no_cpython_wrapper": True}
    options["nopython"] = True

    def decorate(kw: dict) -> Any:
        disp = _JittedOnlyDispatcher(py_func=fn, locals={}, targetoptions=options)
        if kw.get("cache"):
            disp.enable_caching()
        return disp

    return _cached(decorate, {"cache": True})


def python_entry(kernel: Any) -> Any:
    """The Python-callable :func:`njit` copy of the :func:`jitted_only` ``kernel``.

    Compiled from the same source under the name ``<name>_entry`` (numba's cache files are
    named by the function's qualified name: the two never share one); one per kernel."""
    if not isinstance(kernel, Dispatcher):  # NUMBA_DISABLE_JIT: the plain function
        return kernel
    got = _ENTRIES.get(kernel)
    if got is None:
        py = kernel.py_func
        copy = types.FunctionType(py.__code__, py.__globals__, py.__name__, py.__defaults__)
        copy.__qualname__ = py.__qualname__ + "_entry"
        copy.__doc__ = py.__doc__
        model = kernel.targetoptions.get("error_model", "numpy")
        got = _ENTRIES[kernel] = njit(cache=True, error_model=model)(copy)
    return got


_ENTRIES: dict = {}


def literal_dispatch(pyfunc, kernels, general):
    """Compile ``pyfunc(model_id, *args)`` in jitted code to a direct call of one kernel.

    With ``model_id`` a numba literal (the caller's entry point calls ``numba.literally``) the
    call is ``kernels[model_id](*args)``, so the caller compiles that model's kernel only;
    otherwise (a non-literal id, or one missing from ``kernels``) it is
    ``general(model_id, *args)``. ``pyfunc`` stays a plain Python function (the twins and
    tests call it), to which numba's typing and lowering registries are attached here.

    Why not ``numba.extending.overload``: an overload compiles its implementation as a
    function of its own, whose machine code holds (links, re-optimises and re-compiles) the
    whole kernel once more; here the call site calls the kernel's compiled function directly,
    as a call of the kernel in the source would (part of a storm run's first compile for the
    soil and force models).
    """
    from numba.core import types
    from numba.core.imputils import lower_builtin
    from numba.core.typing.templates import AbstractTemplate, infer_global, signature

    def target(argtys):
        kernel = kernels.get(getattr(argtys[0], "literal_value", None))
        if kernel is None:
            return general, tuple(argtys)
        return kernel, tuple(argtys[1:])

    def resolve(typingctx, argtys):
        fn, fargs = target(argtys)
        fnty = typingctx.resolve_value_type(fn)
        return fn, fnty, fnty.get_call_type(typingctx, fargs, {})

    class Template(AbstractTemplate):
        key = pyfunc
        prefer_literal = True  # try the literal id first (else the non-literal one is taken)

        def generic(self, args, kws):
            if kws:
                return None
            call_sig = resolve(self.context, args)[2]  # compiles (or loads) the kernel
            if call_sig is None:
                return None
            return signature(call_sig.return_type, *args)

    infer_global(pyfunc)(Template)

    @lower_builtin(pyfunc, types.VarArg(types.Any))
    def lower(context, builder, sig, args):
        fn, fnty, call_sig = resolve(context.typing_context, sig.args)
        skip = 0 if fn is general else 1
        vals = [
            context.cast(builder, v, t, want)
            for v, t, want in zip(args[skip:], sig.args[skip:], call_sig.args, strict=True)
        ]
        return context.get_function(fnty, call_sig)(builder, vals)

    return pyfunc


_SIGNATURES: dict[tuple, tuple] = {}
"""numba signatures of :func:`call_literal`'s calls by :func:`_type_key` of their arguments (the
typing of a dozen arguments costs more than some kernels' calls)."""


def _type_key(a: Any) -> Any:
    """What numba's type of ``a`` depends on, cheaply: an exact ndarray's dtype, dimensions and
    flags (contiguity, alignment, writeability: ``flags.num``), a float's type; anything else
    typed by numba itself (its type is the key)."""
    t = type(a)
    if t is np.ndarray:
        return (a.dtype, a.ndim, a.flags.num)
    if t is float:
        return float
    return numba.typeof(a)


def call_literal(kernel, n_literal, *args):
    """Call ``kernel(*args)`` with its first ``n_literal`` arguments (ints) as numba literals.

    For kernels that call ``numba.literally`` on those arguments (model ids: the kernel then
    compiles only the models used). Called from Python, such a kernel first types
    its arguments as plain ints, raises inside numba and is retyped with literals; numba does
    not remember that, and pays it again on every call (~0.05–0.3 s for a storm kernel). Here
    the literal signature is built directly: the specialisation is compiled (or loaded from
    numba's on-disk cache) once per process and called through its entry point. ``kernel`` a
    plain Python function (a test's ``py_func``) is just called.

    Processes started together (Dask workers of a first run) compile a specialisation one
    at a time (:func:`_compile_lock`): the first compiles and writes numba's cache, the
    others wait and load it, instead of each paying the whole compile.
    """
    overloads = getattr(kernel, "overloads", None)
    if overloads is None:
        return kernel(*args)
    key = (kernel, n_literal, *(_type_key(a) if i >= n_literal else a for i, a in enumerate(args)))
    sig = _SIGNATURES.get(key)
    if sig is None:
        sig = tuple(
            numba.types.literal(operator.index(a)) if i < n_literal else kernel.typeof_pyval(a)
            for i, a in enumerate(args)
        )
        if len(_SIGNATURES) < 4096:
            _SIGNATURES[key] = sig
    cres = overloads.get(sig)
    if cres is None:
        with _compile_lock(kernel, sig):
            kernel.compile(sig)  # numba loads it from its cache when another process wrote it
        cres = overloads[sig]
    return cres.entry_point(*args)


def pure_python(fn: Callable, _memo: dict | None = None) -> Callable:
    """Return ``fn`` with every jitted function it reaches rebound to plain Python.

    A kernel's twin must give the same results with the Python interpreter. Keeping a second,
    hand-written copy of a long algorithm in sync is error-prone, so this builds the twin from
    the jitted function's own source (``py_func``) and rebinds every jitted helper it calls,
    recursively, to its ``py_func``. The twin tests then compare numba's compiled semantics
    (typing, integer/float conversions, branch order) with Python's on the same algorithm.

    ``fn`` is a numba dispatcher (or a Python function). Helpers reached through module
    globals are rebound recursively; the original functions are left untouched.
    """
    memo = {} if _memo is None else _memo
    py = fn.py_func if isinstance(fn, Dispatcher) else fn
    if py in memo:
        return memo[py]
    glb = dict(py.__globals__)
    twin = types.FunctionType(py.__code__, glb, py.__name__ + "_py", py.__defaults__)
    twin.__doc__ = f"Plain-Python twin of :func:`{py.__name__}`."
    memo[py] = twin
    for name in py.__code__.co_names:
        obj = glb.get(name)
        if isinstance(obj, Dispatcher):
            glb[name] = pure_python(obj, memo)
    return twin


def compile_lock_path(kernel, sig) -> str:
    """The lock file of :func:`_compile_lock` for ``kernel`` (a dispatcher) at ``sig``."""
    py = kernel.py_func
    text = "|".join(
        (py.__module__, py.__qualname__, py.__code__.co_filename, repr(sig),
         cache_dir() or "")
    )  # fmt: skip
    key = hashlib.sha256(text.encode()).hexdigest()[:20]
    return os.path.join(tempfile.gettempdir(), f"onbottom-compile-{key}.lock")


@contextlib.contextmanager
def _compile_lock(kernel, sig) -> Iterator[None]:
    """Hold an exclusive lock, across processes, for compiling ``kernel`` at ``sig``.

    A lock file in the temporary folder named by a hash of the kernel, the signature, its
    source file and numba's cache folder; ``fcntl.flock``, released by the system if the
    process dies. Where ``fcntl`` or the file is unavailable (Windows, a read-only
    temporary folder), or the kernel is not cached (the others could not load it, only
    wait), nothing is locked and each process compiles, as numba does.
    """
    from numba.core.caching import NullCache

    try:
        import fcntl
    except ImportError:  # pragma: no cover - Windows
        yield
        return
    if isinstance(getattr(kernel, "_cache", None), NullCache):
        yield
        return
    try:
        f = open(compile_lock_path(kernel, sig), "a")
    except OSError:
        yield
        return
    with f:
        fcntl.flock(f, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(f, fcntl.LOCK_UN)


def row_view(a, i):
    """Row ``a[i]`` of a C-contiguous 2-D array, for the per-node loops of the kernels.

    In a kernel it is the same view as ``a[i]`` but without numba's reference count (the view
    borrows ``a``'s memory: its meminfo is null, so the increments and decrements of the count
    that numba emits when it creates the view and passes it on are no-ops). Those atomic
    operations cost about half of a Verley & Sotberg kernel call in the pipeline FE's node loop.
    The view must not outlive ``a``: a kernel uses it
    within a call during which ``a`` is held and never returns or stores it. In plain Python (the
    twins): ``a[i]``. ``i`` in [0, n): not bounds-checked, as numba's own indexing.
    """
    return a[i]


@intrinsic
def _row_view(typingctx, a, i):
    if not (isinstance(a, nbtypes.Array) and a.ndim == 2 and a.layout == "C"):
        return None
    row = nbtypes.Array(a.dtype, 1, "C", readonly=not a.mutable)

    def codegen(context, builder, sig, args):
        ary = make_array(sig.args[0])(context, builder, args[0])
        k = context.cast(builder, args[1], sig.args[1], nbtypes.intp)
        shape = cgutils.unpack_tuple(builder, ary.shape, 2)
        strides = cgutils.unpack_tuple(builder, ary.strides, 2)
        data = cgutils.pointer_add(builder, ary.data, builder.mul(k, strides[0]))
        out = make_array(row)(context, builder)
        context.populate_array(
            out,
            data=builder.bitcast(data, out.data.type),
            shape=cgutils.pack_array(builder, [shape[1]]),
            strides=cgutils.pack_array(builder, [strides[1]]),
            itemsize=ary.itemsize,
            meminfo=None,
        )
        return out._getvalue()

    return row(a, i), codegen


@overload(row_view, jit_options={"error_model": "numpy"})
def _row_view_overload(a, i):
    if isinstance(a, nbtypes.Array) and a.ndim == 2 and a.layout == "C":
        return lambda a, i: _row_view(a, i)
    return lambda a, i: a[i]


def borrow(a):
    """``a`` itself, passed on without numba's reference count, for calls in hot loops.

    numba increments an array argument's reference count when a called function starts and
    decrements it when it returns (atomic operations, about 4 ns each); for a call per node or
    element with several arrays that is most of a small callee's cost (a large share of the
    pipeline FE's run time). ``callee(borrow(a))`` passes an alias of ``a`` whose meminfo is
    null, so those operations are no-ops. Only for an ``a`` that the calling function does not
    release before the call returns: its own argument (the caller's caller holds it) or an array
    still used after the call; the callee must not return or store the alias. In plain Python
    (the twins): ``a``.
    """
    return a


@intrinsic
def _borrow(typingctx, a):
    if not isinstance(a, nbtypes.Array):
        return None

    def codegen(context, builder, sig, args):
        src = make_array(sig.args[0])(context, builder, args[0])
        out = make_array(sig.return_type)(context, builder)
        context.populate_array(
            out,
            data=src.data,
            shape=src.shape,
            strides=src.strides,
            itemsize=src.itemsize,
            meminfo=None,
        )
        return out._getvalue()

    return a(a), codegen


@overload(borrow, jit_options={"error_model": "numpy"})
def _borrow_overload(a):
    if isinstance(a, nbtypes.Array):
        return lambda a: _borrow(a)
    return lambda a: a


def registered_kernel_id(kernel: Any, first_id: int) -> int:
    """The model id of a registered kernel: ``first_id`` plus a CRC-32 of the kernel's module,
    name and source (mod 2³⁰), so that numba's on-disk cache of a solver specialised on a
    literal id never serves another kernel under it. Shared by the soil and force dispatch."""
    import inspect
    import zlib

    py = getattr(kernel, "py_func", kernel)
    try:
        source = inspect.getsource(py)
    except (OSError, TypeError):
        source = ""
    text = f"{py.__module__}.{py.__qualname__}\n{source}"
    return first_id + zlib.crc32(text.encode()) % (2**30)
