"""The one place where numba options live, and where the compiled kernel is kept.

Every compiled function of the package is decorated with :func:`jit`: cached on disk,
numpy's error model (division by zero gives inf/nan, which explicit finite checks catch),
and no fastmath (it would silently break ``isnan``/``isfinite``).  With
``NUMBA_DISABLE_JIT=1`` the decorator returns plain Python functions (``DISABLED``).

Inlining.  The small functions called inside every step (floor motion, corner geometry,
mode dynamics, right-hand side, dense output) are marked ``jit(inline="always")``: a call
between compiled functions that pass arrays costs more than their arithmetic.  Each is
compiled once and handed to LLVM as ``alwaysinline`` (numba's ``forceinline``), which puts
its machine code into every caller.  numba's own ``inline="always"`` re-types the function
at every call site instead: the first compile of a scene and a study took 38 s of CPU with
it and 15 s this way, and steady rocking runs no slower (2-12% faster).  The functions of
``IR_INLINED`` keep numba's inlining: they return records, for which numba cannot build the
Python wrapper it gives every function compiled on its own.  A function called from
compiled code is compiled once per argument types, not once more for each constant it is
passed.

Reference counts: numba counts a reference each time compiled code receives an array or
takes one out of a tuple (a call of ``NRT_incref`` and ``NRT_decref``, atomic where the array
owns memory); a step passes a dozen arrays to its right-hand sides, so the calls took 12 %
of a sweep-map cell even with every buffer a field of one record (``state.WORK_DTYPE``),
which owns nothing.  The kernel therefore compiles without numba's runtime (``_nrt=False``):
no function counts references, and none may allocate or hand an array to Python.  The few
that do (``state.new_work``, ``driver.run_cells``, ``tableaus.tableau``, helpers outside
the step loop) say so with ``jit(runtime=True)``, as must every compiled caller that keeps
an array they allocate (it would never be freed otherwise).  numba refuses to compile an
allocation without the runtime; an array returned to Python without it crashes.

The cache.  numba's cache notices edits of a function's own file only, not of the files it
calls, so the compiled code is kept in a folder named after the digest of every kernel
source, ``CACHE_DIR`` = ``$XDG_CACHE_HOME`` (or ``~/.cache``)
``/rigid-block-sweeps/numba-<digest>``, for every command of this user; ``NUMBA_CACHE_DIR``,
when set, is used as it is.  The first compile says so on stderr, once (rank 0 only under
MPI).

Start-up.  numba's CPU target loads its registries at the first function it compiles or
loads from the cache (``refresh``); one of them, ``numba.np.arraymath``, imports
``scipy.linalg`` at once (0.13 s of a warm scene's 0.7) to see whether a BLAS is there for
``np.dot``.  :func:`_quicker` skips that look while the registries load: scipy is a dependency
of the package, which is what the look would find, and numba still imports scipy's BLAS (and
checks it) before it compiles a BLAS call; no kernel function makes one.  It also holds the
garbage collector off meanwhile: the registries' tables are some 54,000 objects that live as
long as the process, and collections among them took 0.05 s.

Contraction.  ``KERNEL_CONTRACT=1`` compiles the kernel with LLVM's ``contract`` flag alone,
which fuses a*b + c into one rounding (an FMA) as GPU compilers do by default, into a cache
folder of its own (``-contract``).  It is not for results: ``benchmarks/gpu.py`` measures with
it how far results move when only the rounding of the arithmetic changes, the yardstick for
the GPU's results (docs/gpu.md).
"""
import gc
import hashlib
import os
import sys
from pathlib import Path

_SOURCES = Path(__file__).resolve().parent


def source_digest():
    """SHA-256 over the names and bytes of ``kernels/*.py`` (as
    ``sweep.runner.fingerprint.source_digest(("kernels/*.py",))``)."""
    digest = hashlib.sha256()
    for path in sorted(_SOURCES.glob("*.py")):
        digest.update(f"{_SOURCES.name}/{path.name}".encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()


def _default_cache_dir(digest):
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return str(Path(base) / "rigid-block-sweeps" / f"numba-{digest[:16]}")


SOURCE_DIGEST = source_digest()
CONTRACT = os.environ.get("KERNEL_CONTRACT") == "1"
CACHE_DIR = os.environ.get("NUMBA_CACHE_DIR") or _default_cache_dir(SOURCE_DIGEST)
if CONTRACT and not CACHE_DIR.endswith("-contract"):
    CACHE_DIR += "-contract"
os.environ["NUMBA_CACHE_DIR"] = CACHE_DIR  # read by numba at import, inherited by children

import numba  # noqa: E402  (after NUMBA_CACHE_DIR is set)
from numba.core import cpu, event, types  # noqa: E402

numba.config.reload_config()  # in case numba was imported before this module

DISABLED = numba.config.DISABLE_JIT
_OPTIONS = dict(cache=True, error_model="numpy", fastmath={"contract"} if CONTRACT else False,
                nogil=True,
                forceinline=False,      # set, so that a callee never inherits its caller's
                no_cfunc_wrapper=True)  # no compiled function is passed as a value
IR_INLINED = ("scene_of",)
COMPILE_SECONDS = 15  # about the CPU time of the first compile of a scene and a study
_RANK_VARIABLES = ("PMI_RANK", "OMPI_COMM_WORLD_RANK", "PMIX_RANK", "SLURM_PROCID")


def jit(func=None, runtime=False, **overrides):
    """``numba.njit`` with the project's options (usable bare or with overrides); a function
    that allocates arrays, keeps one that another allocated or returns one to Python takes
    ``runtime=True``: numba's runtime and its reference counts, off for the rest."""
    if func is None:
        return lambda f: jit(f, runtime=runtime, **overrides)
    options = {**_OPTIONS, "_nrt": runtime, **overrides}
    if options.get("inline") == "always" and func.__name__ not in IR_INLINED:
        del options["inline"]
        options["forceinline"] = True
    dispatcher = numba.njit(**options)(func)
    if not DISABLED:
        _one_version_per_types(dispatcher)
    return dispatcher


def _one_version_per_types(dispatcher):
    """Compile ``dispatcher`` for the types of the arguments a compiled caller passes, never
    for their constant values (numba's literal types), which would compile it again."""
    call_template = dispatcher.get_call_template

    def get_call_template(args, kws):
        return call_template(tuple(types.unliteral(a) for a in args),
                             {key: types.unliteral(a) for key, a in kws.items()})
    dispatcher.get_call_template = get_call_template


def jit_for(solver, algorithm, f):
    """Compile ``solver``, a closure of ``algorithm`` over the compiled function f that it
    calls, under the name ``<algorithm>_<f>``.  (A compiled function passed as an argument
    would make every caller uncacheable; bound in a closure, each solver is cached under its
    own name.)"""
    solver.__name__ = solver.__qualname__ = f"{algorithm}_{f.__name__.lstrip('_')}"
    return jit(solver)


class _Announcer(event.Listener):
    """Says on stderr, before the first compile of a kernel function, what is going on."""

    said = False

    def on_start(self, ev):
        module = ev.data["dispatcher"].py_func.__module__
        if not self.said and (module == __package__ or module.startswith(__package__ + ".")):
            self.said = True
            print(f"compiling the kernel once (about {COMPILE_SECONDS} s); later runs load "
                  f"it from {CACHE_DIR}", file=sys.stderr, flush=True)

    def on_end(self, ev):
        pass


def _blas_of_scipy():
    """Stands for ``numba.np.linalg.ensure_blas`` while numba's registries load (scipy, a
    dependency of the package, provides BLAS)."""


def _quicker(refresh):
    """``refresh`` (``CPUContext.refresh``, which loads numba's registries) without numba's
    look for a BLAS, and without garbage collections while it makes its tables."""
    def refresh_registries(self):
        from numba.np import linalg
        probe = getattr(linalg, "ensure_blas", None)
        if probe is None:                 # another numba: its registries load as they do
            return refresh(self)
        linalg.ensure_blas = _blas_of_scipy
        collecting = gc.isenabled()
        gc.disable()
        try:
            refresh(self)
        finally:
            linalg.ensure_blas = probe
            if collecting:
                gc.enable()
    return refresh_registries


if hasattr(cpu.CPUContext, "refresh"):
    cpu.CPUContext.refresh = _quicker(cpu.CPUContext.refresh)


def launcher_rank():
    """This process's MPI rank as the launcher tells it (0 when not under MPI)."""
    for name in _RANK_VARIABLES:
        if os.environ.get(name, "").isdigit():
            return int(os.environ[name])
    return 0


if not DISABLED and launcher_rank() == 0:
    event.register("numba:compile", _Announcer())
