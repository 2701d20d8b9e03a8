"""The one place where numba options live.

Every compiled function of the package is decorated with :func:`jit`: cached on disk,
numpy's error model (division by zero gives inf/nan, which explicit finite checks catch),
and no fastmath (it would silently break ``isnan``/``isfinite``).  The small functions
called inside every step (floor motion, corner geometry, mode dynamics, right-hand side) are
compiled with ``jit(inline="always")``: a call between compiled functions that pass arrays
costs more than their arithmetic (the steady-rocking scene runs ~1.4x faster inlined).  With
``NUMBA_DISABLE_JIT=1`` the decorator returns plain Python functions (``DISABLED``).

Reference counts: numba counts a reference each time compiled code receives an array that
owns its memory or takes one out of a tuple, with an atomic operation.  Arrays that are
fields of one record allocation (``state.WORK_DTYPE``) or module constants own nothing and
are passed for free; the kernel keeps its buffers there (the steady-rocking scene counts
85,000 references with its buffers as separate arrays, 8,800 with them in one record).
"""
import numba

DISABLED = numba.config.DISABLE_JIT
_OPTIONS = dict(cache=True, error_model="numpy", fastmath=False, nogil=True)


def jit(func=None, **overrides):
    """``numba.njit`` with the project's options (usable bare or with overrides)."""
    options = {**_OPTIONS, **overrides}
    if func is None:
        return lambda f: numba.njit(**options)(f)
    return numba.njit(**options)(func)


def jit_for(solver, algorithm, f):
    """Compile ``solver``, a closure of ``algorithm`` over the compiled function f that it
    calls, under the name ``<algorithm>_<f>``.  (A compiled function passed as an argument
    would make every caller uncacheable; bound in a closure, each solver is cached under its
    own name.)"""
    solver.__name__ = solver.__qualname__ = f"{algorithm}_{f.__name__.lstrip('_')}"
    return jit(solver)
