"""The chunk kernel on an NVIDIA GPU: resident threads taking scene rows in turn (numba-cuda).

``driver.run_scene`` is the device function as it is: numba-cuda compiles a CPU-compiled
function called from a CUDA kernel for the device from its Python source, with every function
it calls, so the CPU and the GPU run one source.  What device code cannot do, the source
leaves to its callers: the scene's buffers (``state.WORK_DTYPE``) are a record in each
thread's local memory, zeroed by the thread before each of its rows, as ``driver.run_cells``
zeroes them on the CPU (local memory interleaves the threads' words, so a warp's lanes read
neighbouring addresses).  A launch has as many threads as the device holds resident
(:func:`launch_grid`); each takes the next row from an atomic counter, in grid order, and
runs its scene to the end (DiffEqGPU's per-thread ensemble kernels, MPGOS: one trajectory a
thread) before it takes another: there is no wall-time budget on the device, only the
scene's step and event budgets.  A study's records stay in device memory from chunk to chunk
(:class:`DeviceRecords`).  The compiled kernel is cached on disk beside the CPU's, in
``_jit.CACHE_DIR`` (named after the digest of the kernel's sources; numba-cuda's cache keys
hold the compute capability).

Imported only for ``--backend cuda``: it needs numba-cuda (``pip install .[cuda]``) and, to
run, a GPU or the CUDA simulator (``NUMBA_ENABLE_CUDASIM=1``).
"""
import contextlib
import functools

import numpy as np

if not hasattr(np, "row_stack"):   # numpy 2.5 removed it; numba-cuda 0.30 still overloads it
    np.row_stack = np.vstack
from numba import cuda, float64, from_dtype, int64  # noqa: E402  (after the shim)
from numba.cuda import config  # noqa: E402

from . import api, codes
from ._jit import launcher_rank
from .driver import run_scene
from .state import WORK_DTYPE
from .watchdog import control

THREADS_PER_BLOCK = 128  # threads per block; a thread's registers, not shared memory, bound it
BATCH = 1 << 20          # scenes per launch, in grid order: rows and results take 0.6 kB each
SIMULATED_GRID = (1, 3)  # blocks and threads on the simulator: fewer threads than rows
WARP = 32
REGISTER_UNIT = 256      # registers go to a warp in units of 256 (sm_50 to sm_90)
_WORK = np.dtype((np.record, WORK_DTYPE))   # read by field name, also on the simulator


@cuda.jit(cache=True)
def _run_rows(rows, rec, results, log, hist, ctl, taken):
    """Scene rows of ``rows`` into their records of ``results``: each thread takes the next
    row from the counter ``taken[0]`` (rows in increasing order) until none is left."""
    work = cuda.local.array(1, _WORK)
    words = work.view(np.float64)
    i = cuda.atomic.add(taken, 0, 1)
    while i < rows.shape[0]:
        for k in range(words.size):
            words[k] = 0.0
        run_scene(rows[i], rec, results[i], log, hist, ctl, work[0])
        i = cuda.atomic.add(taken, 0, 1)


def resident_blocks(regs, device, threads=THREADS_PER_BLOCK):
    """Blocks of ``threads`` that one multiprocessor of ``device`` (its attributes) holds at
    once for a kernel of ``regs`` registers per thread and no shared memory: NVIDIA's
    occupancy calculation (CUDA C++ Best Practices Guide, "Calculating Occupancy")."""
    per_warp = -(-regs * WARP // REGISTER_UNIT) * REGISTER_UNIT
    warps = -(-threads // WARP)
    return max(1, min(device.MAX_REGISTERS_PER_MULTIPROCESSOR // per_warp // warps,
                      device.MAX_THREADS_PER_MULTIPROCESSOR // threads,
                      device.MAX_BLOCKS_PER_MULTIPROCESSOR))


def launch_grid(n, regs, device):
    """(blocks, threads per block) of a launch over ``n`` rows: the threads ``device`` holds
    resident at ``regs`` registers per thread, and no more blocks than the rows fill."""
    blocks = resident_blocks(regs, device) * device.MULTIPROCESSOR_COUNT
    return min(blocks, -(-n // THREADS_PER_BLOCK)), THREADS_PER_BLOCK


def _grid(args):
    """The grid of ``_run_rows`` on ``args``: :func:`launch_grid` for its registers on the
    current device (compiled or loaded first), :data:`SIMULATED_GRID` on the simulator."""
    if config.ENABLE_CUDASIM:
        return SIMULATED_GRID
    kernel = _run_rows.compile(tuple(_run_rows.typeof_pyval(a) for a in args))
    return launch_grid(args[0].shape[0], kernel.regs_per_thread, cuda.get_current_device())


def _argument_types():
    """The types of ``_run_rows``'s arguments as :func:`run_cells` passes them."""
    row, result = (from_dtype(d) for d in (codes.SCENE_DTYPE, codes.RESULT_DTYPE))
    return (row[::1], float64[::1], result[::1], float64[:, ::1], float64[:, ::1], int64[::1],
            int64[::1])


@contextlib.contextmanager
def _compute_capability(cc):
    """Compile for ``cc`` without a GPU: numba-cuda asks the current device for its compute
    capability when it compiles a device function, even for PTX alone."""
    from numba.cuda import dispatcher

    class Target:
        compute_capability = cc
    asked = dispatcher.get_current_device
    dispatcher.get_current_device = Target
    try:
        yield
    finally:
        dispatcher.get_current_device = asked


def ptx(cc=(9, 0)):
    """The kernel's PTX for compute capability ``cc`` (NVVM; no GPU needed)."""
    with _compute_capability(cc):
        return cuda.compile_ptx(_run_rows.py_func, _argument_types(), cc=cc)[0]


def available():
    """None when a GPU (or the CUDA simulator) can run the kernel, else why not."""
    try:
        if cuda.is_available():
            return None
    except Exception as err:      # a broken driver or toolkit says so here
        return f"CUDA is not usable: {err}"
    return "no CUDA GPU is visible (numba.cuda.is_available() is False)"


@functools.cache
def _select_device():
    """One GPU per MPI rank where a node has several (rank modulo their number)."""
    cuda.select_device(launcher_rank() % len(cuda.gpus))


class DeviceRecords:
    """A study's ``record_cache.RecordCache`` in device memory, kept from chunk to chunk.

    :meth:`update` sends only the samples the cache gained since the last call (all of them
    after the cache started over); a larger device buffer takes the old one's samples by a
    device-to-device copy.  ``sent`` counts the samples sent from the host.
    """

    def __init__(self):
        self._array = None
        self._generation = None
        self.size = 0
        self.sent = 0

    def update(self, cache):
        """The device copy of ``cache.buffer()``, brought up to date."""
        _select_device()
        host = cache.buffer()
        if cache.generation != self._generation:
            self._generation, self.size = cache.generation, 0
        if self._array is None or host.size > self._array.size:
            grown = cuda.device_array(max(host.size, 2 * self.size))
            if self.size:
                grown[:self.size].copy_to_device(self._array[:self.size])
            self._array = grown
        if host.size > self.size:
            self._array[self.size:host.size].copy_to_device(host[self.size:])
            self.sent += host.size - self.size
            self.size = host.size
        return self._array[:self.size]


def run_cells(rows, rec, batch=BATCH):
    """``kernels.api.run_cells`` on the GPU: n scene rows to n result records.

    The record buffer ``rec`` is a device array (:class:`DeviceRecords`) or goes to device
    memory once; rows go in launches of ``batch``.
    """
    _select_device()
    rows = np.ascontiguousarray(api.as_records(rows).view(np.ndarray))
    results = np.zeros(rows.shape[0], codes.RESULT_DTYPE)
    d_rec = cuda.to_device(np.ascontiguousarray(rec, dtype=np.float64)) \
        if isinstance(rec, np.ndarray) else rec
    log = cuda.to_device(np.zeros((0, codes.N_LOG)))
    hist = cuda.to_device(np.zeros((0, codes.N_HIST)))
    ctl = cuda.to_device(control(cell=0))       # no stop request names cell 0
    for start in range(0, rows.shape[0], batch):
        d_results = cuda.to_device(results[start:start + batch])
        args = (cuda.to_device(rows[start:start + batch]), d_rec, d_results, log, hist, ctl,
                cuda.to_device(np.zeros(1, np.int64)))
        _run_rows[_grid(args)](*args)
        results[start:start + batch] = d_results.copy_to_host()
    return results
