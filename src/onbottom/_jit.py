"""The project's numba decorator for hot-loop kernels (private).

:func:`njit` is :func:`numba.njit` with ``error_model="numpy"`` unless the caller says
otherwise: a float division by zero gives ±inf or NaN (IEEE 754), as numpy does, instead of
numba's default Python error model, which tests every divisor and raises ZeroDivisionError,
and makes every call between kernels check an exception status. The kernels never rely on
that exception (each solver checks its results for finiteness), and the tests and checks
cost 30–45 % of a soil kernel call (issue 33: Coulomb kernel 70 → 38 ns, V&S 0.17 →
0.12 µs per node call). Results are bit-identical wherever no division by zero occurs.

Kernel modules import it in place of numba's: ``from onbottom._jit import njit``. numba is
imported when this module is, i.e. only with a kernel module.
"""

from __future__ import annotations

import operator

import numba
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic, overload
from numba.np.arrayobj import make_array

__all__ = ["borrow", "call_literal", "njit", "row_view"]


def njit(*args, **kwargs):
    """:func:`numba.njit` with ``error_model="numpy"`` by default (same call forms)."""
    kwargs.setdefault("error_model", "numpy")
    return numba.njit(*args, **kwargs)


def call_literal(kernel, n_literal, *args):
    """Call ``kernel(*args)`` with its first ``n_literal`` arguments (ints) as numba literals.

    For kernels that call ``numba.literally`` on those arguments (model ids: the kernel then
    compiles only the models used, issue 33). Called from Python, such a kernel first types
    its arguments as plain ints, raises inside numba and is retyped with literals; numba does
    not remember that, and pays it again on every call (~0.05–0.3 s for a storm kernel). Here
    the literal signature is built directly: the specialisation is compiled (or loaded from
    numba's on-disk cache) once per process and called through its entry point. ``kernel`` a
    plain Python function (a test's ``py_func``) is just called.
    """
    overloads = getattr(kernel, "overloads", None)
    if overloads is None:
        return kernel(*args)
    sig = tuple(
        numba.types.literal(operator.index(a)) if i < n_literal else kernel.typeof_pyval(a)
        for i, a in enumerate(args)
    )
    cres = overloads.get(sig)
    if cres is None:
        kernel.compile(sig)
        cres = overloads[sig]
    return cres.entry_point(*args)


def row_view(a, i):
    """Row ``a[i]`` of a C-contiguous 2-D array, for the per-node loops of the kernels.

    In a kernel it is the same view as ``a[i]`` but without numba's reference count (the view
    borrows ``a``'s memory: its meminfo is null, so the increments and decrements of the count
    that numba emits when it creates the view and passes it on are no-ops). Those atomic
    operations cost about half of a Verley & Sotberg kernel call in the pipeline FE's node loop
    (issue 33: 105 → 52 ns per node call). The view must not outlive ``a``: a kernel uses it
    within a call during which ``a`` is held and never returns or stores it. In plain Python (the
    twins): ``a[i]``. ``i`` in [0, n): not bounds-checked, as numba's own indexing.
    """
    return a[i]


@intrinsic
def _row_view(typingctx, a, i):
    if not (isinstance(a, types.Array) and a.ndim == 2 and a.layout == "C"):
        return None
    row = types.Array(a.dtype, 1, "C", readonly=not a.mutable)

    def codegen(context, builder, sig, args):
        ary = make_array(sig.args[0])(context, builder, args[0])
        k = context.cast(builder, args[1], sig.args[1], types.intp)
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
    if isinstance(a, types.Array) and a.ndim == 2 and a.layout == "C":
        return lambda a, i: _row_view(a, i)
    return lambda a, i: a[i]


def borrow(a):
    """``a`` itself, passed on without numba's reference count, for calls in hot loops.

    numba increments an array argument's reference count when a called function starts and
    decrements it when it returns (atomic operations, about 4 ns each); for a call per node or
    element with several arrays that is most of a small callee's cost (issue 33: a fifth of the
    pipeline FE's run time). ``callee(borrow(a))`` passes an alias of ``a`` whose meminfo is
    null, so those operations are no-ops. Only for an ``a`` that the calling function does not
    release before the call returns: its own argument (the caller's caller holds it) or an array
    still used after the call; the callee must not return or store the alias. In plain Python
    (the twins): ``a``.
    """
    return a


@intrinsic
def _borrow(typingctx, a):
    if not isinstance(a, types.Array):
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
    if isinstance(a, types.Array):
        return lambda a: _borrow(a)
    return lambda a: a
