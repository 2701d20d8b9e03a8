"""Ranks: the communicator or a serial stand-in, dealing work, progress messages, aborting.

The only module that imports mpi4py, and only when a launcher started the process (or
``SWEEP_MPI=1``): a plain ``python -m sweep.run`` never loads MPI, and a broken MPI install
cannot break an import of ``sweep``.  Rank 0 computes too; the other ranks send it one small
message per finished chunk (:class:`ChunkDone`) and one when they are done (:class:`RankDone`)
with non-blocking sends, which it drains between its own chunks with ``Iprobe`` (no busy
``recv``).  Every wait is a test-and-sleep loop, so an idle rank
does not spin.  An exception on any rank prints its traceback and calls
``COMM_WORLD.Abort``: the whole job ends within seconds instead of hanging.  Rank 0 watches the
others (:class:`Watch`): a rank silent for longer than ``max(floor, WATCH_FACTOR x the slowest
chunk so far)`` is stopped or stuck, and the job aborts naming it and the cells it held.
"""
import os
import sys
import time
import traceback
from collections import namedtuple
from contextlib import contextmanager

import numpy as np

from kernels import codes

POLL = 0.02  # s between tests of a pending message or request
FORWARD = 0.5  # s left to the launcher to pass a failed rank's traceback on before Abort
TAG_PLAN, TAG_PROGRESS = 11, 12
WATCH_FLOOR = 300.0  # s of silence always allowed to a rank (sweep.run --rank-timeout)
WATCH_FACTOR = 10.0  # a rank silent for this many times the slowest chunk so far is stuck

# Variables by which launchers announce the number of ranks (Hydra/MPICH, Intel MPI, Open MPI,
# PMIx, MVAPICH) and the rank (their presence alone means "started by a launcher").
SIZE_VARS = ("PMI_SIZE", "OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS",
             "MV2_COMM_WORLD_SIZE")
RANK_VARS = ("PMI_RANK", "OMPI_COMM_WORLD_RANK", "PMIX_RANK", "MV2_COMM_WORLD_RANK")


ChunkDone = namedtuple("ChunkDone", "cells failed seconds first")
ChunkDone.__doc__ = """A rank's message to rank 0 (``TAG_PROGRESS``): a chunk of ``cells`` cells, of
which ``failed`` failed, took ``seconds``; ``first`` is its first cell id (the :class:`Watch`
finds the chunk by it)."""

RankDone = namedtuple("RankDone", "cells seconds")
RankDone.__doc__ = """A rank's last message to rank 0 (``TAG_PROGRESS``): it computed ``cells``
cells in ``seconds`` busy; also the value of :func:`work`'s ``stats`` for each rank."""


class LauncherMismatch(RuntimeError):
    """A multi-rank launcher started processes that each see an MPI world of size 1."""


class JobFailure(RuntimeError):
    """A failure that ends the whole job and is said in words, without a traceback."""


class RankSilent(JobFailure):
    """A rank sent nothing for longer than the watch allows: stopped, or stuck in a scene."""


class _DoneRequest:
    def Test(self):
        return True


class SerialComm:
    """Stand-in for ``COMM_WORLD`` in one process without MPI: rank 0 of 1."""

    rank, size = 0, 1

    def Get_rank(self):
        return 0

    def Get_size(self):
        return 1

    def Iprobe(self, *args, **kwargs):
        return False

    def Ibarrier(self):
        return _DoneRequest()

    def Abort(self, errorcode=1):
        os._exit(errorcode)


def is_mpi(comm):
    """True for a real MPI communicator."""
    return not isinstance(comm, SerialComm)


def launcher_size(environ=None):
    """Largest rank count announced by a launcher's variables: (size, variable) or (0, None)."""
    environ = os.environ if environ is None else environ
    best = (0, None)
    for var in SIZE_VARS:
        try:
            size = int(environ.get(var, ""))
        except ValueError:
            continue
        best = max(best, (size, var), key=lambda s: s[0])
    return best


def launched(environ=None):
    """True when a launcher's variables are set (the process is a rank of an MPI job)."""
    environ = os.environ if environ is None else environ
    return any(var in environ for var in SIZE_VARS + RANK_VARS)


def first_process(environ=None):
    """True unless a launcher's variables name a rank other than 0 (one message per job)."""
    environ = os.environ if environ is None else environ
    return all(environ.get(v, "0") == "0" for v in RANK_VARS)


def _threads_off():
    """One thread per rank: MPI is the only parallelism (numba, OpenMP, BLAS)."""
    for var in ("NUMBA_NUM_THREADS", "OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS",
                "MKL_NUM_THREADS"):
        os.environ[var] = "1"
    if "numba" in sys.modules:  # already configured: lower the threads actually used
        try:
            sys.modules["numba"].set_num_threads(1)
        except (AttributeError, ValueError):
            pass


def world(environ=None):
    """The communicator of this process.

    ``COMM_WORLD`` of mpi4py when a launcher started the process (or ``SWEEP_MPI=1``;
    ``SWEEP_MPI=0`` forces serial), else a :class:`SerialComm`.  Under MPI the numba, OpenMP
    and BLAS threads are set to one.

    Raises
    ------
    LauncherMismatch
        A launcher announced several ranks but this MPI library sees a world of size 1, or
        mpi4py cannot be imported under a launcher.
    """
    environ = os.environ if environ is None else environ
    choice = environ.get("SWEEP_MPI")
    use = launched(environ) if choice is None else choice not in ("", "0")
    if not use:
        return SerialComm()
    _threads_off()
    size, var = launcher_size(environ)
    try:
        from mpi4py import MPI
    except ImportError as err:
        raise LauncherMismatch(
            f"this process was started by an MPI launcher ({var or 'PMI/PMIx'} is set) but "
            f"mpi4py cannot be imported: {err}. Install mpi4py (pip install -e '.[mpi]' for "
            "the bundled MPICH, or without the extra to build against the site MPI).") from None
    comm = MPI.COMM_WORLD
    if comm.Get_size() == 1 and size > 1:
        raise LauncherMismatch(
            f"launcher/library mismatch: the launcher announced {size} ranks ({var}={size}) but "
            f"mpi4py's MPI ({MPI.Get_library_version().splitlines()[0].strip()}) sees a world "
            "of size 1 in every process, so each would run the whole study alone. Start the "
            "job with the mpiexec of the MPI that mpi4py was built with (for the bundled "
            "MPICH: .venv/bin/mpiexec), or reinstall mpi4py against the site MPI "
            "(pip install --no-binary mpi4py --force-reinstall mpi4py).")
    return comm


def world_or_say(prog):
    """The communicator (:func:`world`), or None after ``prog`` says why not (once per job)."""
    try:
        return world()
    except LauncherMismatch as err:
        if first_process():
            print(f"{prog}: error: {err}", file=sys.stderr, flush=True)
        return None


def wait(request):
    """Wait for a non-blocking request by testing and sleeping (an idle rank does not spin)."""
    while not request.Test():
        time.sleep(POLL)


def barrier(comm):
    """A barrier that sleeps while it waits."""
    wait(comm.Ibarrier())


def allgather(comm, value):
    """Every rank's ``value``, in rank order, on every rank (one process: ``[value]``); the
    ranks meet in a sleeping :func:`barrier` first, so the exchange itself does not wait."""
    if not is_mpi(comm):
        return [value]
    barrier(comm)
    return comm.allgather(value)


@contextmanager
def abort_on_exception(comm):
    """Turn an exception on any rank into the end of the whole job, with its traceback.

    Serially the exception propagates as usual.  Under MPI the traceback is printed with the
    rank and ``Abort`` ends every rank within seconds (a rank that died alone would leave the
    others waiting forever).  ``SystemExit`` aborts too: ranks leave together only through
    the normal return path.
    """
    try:
        yield
    except BaseException as err:
        if not is_mpi(comm):
            raise
        sys.stdout.flush()
        why = f"{err}\n" if isinstance(err, JobFailure) else traceback.format_exc()
        sys.stderr.write(f"sweep.run: rank {comm.Get_rank()} of {comm.Get_size()} failed, "
                         f"aborting the job:\n{why}")
        sys.stderr.flush()
        time.sleep(FORWARD)  # the launcher forwards the traceback before Abort kills the job
        comm.Abort(1)


def distribute(comm, plans=None):
    """Rank 0 hands ``plans[r]`` to each rank r and keeps ``plans[0]``; the others wait for it.

    A plan is any picklable object (what to run, or that the job ends: the named tuples of
    ``runner.launch``).  Rank 0 must always
    call this once it has decided, even to say "stop", or the other ranks wait forever.
    """
    if comm.Get_rank() == 0:
        for rank in range(1, comm.Get_size()):
            comm.send(plans[rank], dest=rank, tag=TAG_PLAN)
        return plans[0]
    while not comm.Iprobe(source=0, tag=TAG_PLAN):
        time.sleep(POLL)
    return comm.recv(source=0, tag=TAG_PLAN)


def _failed(result):
    return int(np.isin(result["status"], codes.FAILED_STATUSES).sum())


class Watch:
    """Rank 0's view of the other ranks: when each was last heard, the chunks it still holds.

    Parameters
    ----------
    held : list of lists of ndarray
        The chunks dealt to every rank (``grid.plan``).
    floor : float
        Seconds of silence always allowed; 0 or None: no watch.
    """

    def __init__(self, held, floor=WATCH_FLOOR, clock=time.monotonic):
        self.clock = clock
        now = clock()
        self.floor = floor or 0.0
        self.held = {r: {int(c[0]): c for c in chunks} for r, chunks in enumerate(held) if r}
        self.last = {r: now for r in self.held}
        self.slowest = 0.0

    def chunk_done(self, rank, seconds, first=None):
        """A chunk (starting at cell ``first``) took ``seconds`` on ``rank``."""
        self.slowest = max(self.slowest, seconds)
        self.last[rank] = self.clock()
        self.held.get(rank, {}).pop(first, None)

    def rank_done(self, rank):
        """``rank`` finished all its chunks."""
        self.held.pop(rank, None)
        self.last.pop(rank, None)

    def limit(self):
        """Seconds of silence after which a rank is taken for stopped or stuck."""
        return max(self.floor, WATCH_FACTOR * self.slowest)

    def check(self):
        """Raise :class:`RankSilent` for the first rank silent for longer than :meth:`limit`."""
        if not self.floor:
            return
        now, limit = self.clock(), self.limit()
        for rank, last in self.last.items():
            if now - last > limit:
                cells = np.concatenate(list(self.held[rank].values()) or [np.zeros(0, int)])
                raise RankSilent(
                    f"rank {rank} sent nothing for {now - last:.0f} s (the limit is "
                    f"max({self.floor:g} s, {WATCH_FACTOR:g} x the slowest chunk so far, "
                    f"{self.slowest:.2g} s)): it is stopped or stuck. It held {cells.size} "
                    f"cells not yet saved (first: {np.sort(cells)[:10].tolist()}); the "
                    "others' parts are kept: run the same command again to resume, or raise "
                    "--rank-timeout")


def _drain(comm, progress, stats, watch):
    """Take every waiting progress message on rank 0; returns how many ranks said done."""
    from mpi4py import MPI

    status, finished = MPI.Status(), 0
    while comm.Iprobe(source=MPI.ANY_SOURCE, tag=TAG_PROGRESS, status=status):
        source = status.Get_source()
        message = comm.recv(source=source, tag=TAG_PROGRESS)
        if isinstance(message, ChunkDone):
            if progress is not None:
                progress.update(message.cells, message.failed)
            if watch is not None:
                watch.chunk_done(source, message.seconds, message.first)
        else:  # RankDone
            stats[source] = message
            finished += 1
            if watch is not None:
                watch.rank_done(source)
    return finished


def work(comm, study, chunks, *, store=None, progress=None, run_chunk=None, on_idle=None,
         watch=None):
    """Run this rank's chunks; on rank 0, also follow every rank until all are done.

    Parameters
    ----------
    comm : communicator or SerialComm
    study : Study
    chunks : list of ndarray
        This rank's chunks of cell ids.
    store : PartStore, optional
        Where each finished chunk is written; without it (one process only) the results are
        kept in memory and returned.
    progress : Progress, optional
        Rank 0's progress display.
    run_chunk : callable, optional
        ``run_chunk(study, cells) -> dict``; default ``cells.run_chunk``.
    on_idle : callable, optional
        Called once on rank 0 when its own chunks are done and other ranks are still working
        (to prepare the merge in time that would be spent waiting).
    watch : Watch, optional
        Rank 0: the other ranks' chunks, to detect a rank that stopped answering.

    Returns
    -------
    results : list of dict
        The chunk results kept in memory (empty with a store).
    stats : dict
        On rank 0: rank -> :class:`RankDone` (cells computed, seconds busy) for every rank;
        else this rank's.

    Raises
    ------
    RankSilent
        On rank 0, when a rank stays silent for longer than the watch allows.
    """
    if run_chunk is None:
        from .cells import run_chunk
    if store is None and comm.Get_size() > 1:
        raise ValueError("several ranks need a `store` for their results")
    rank, size = comm.Get_rank(), comm.Get_size()
    kept, requests, stats = [], [], {}
    busy, n_done, pending = 0.0, 0, size - 1
    for chunk in chunks:
        t0 = time.perf_counter()
        result = run_chunk(study, chunk)
        if store is not None:
            store.write_part(result)
        else:
            kept.append(result)
        seconds = time.perf_counter() - t0
        busy += seconds
        n_done += len(chunk)
        if rank == 0:
            if progress is not None:
                progress.update(len(chunk), _failed(result))
            if size > 1:
                if watch is not None:
                    watch.chunk_done(0, seconds)
                pending -= _drain(comm, progress, stats, watch)
                if watch is not None:
                    watch.check()
        else:
            requests.append(comm.isend(ChunkDone(len(chunk), _failed(result), seconds,
                                                 int(chunk[0])), dest=0, tag=TAG_PROGRESS))
            requests = [r for r in requests if not r.Test()]
    stats[rank] = RankDone(n_done, busy)
    if rank == 0:
        pending -= _drain(comm, progress, stats, watch) if size > 1 else 0
        if pending > 0 and on_idle is not None:
            on_idle()
        while pending > 0:
            pending -= _drain(comm, progress, stats, watch)
            if pending > 0:
                if watch is not None:
                    watch.check()
                time.sleep(POLL)
    else:
        requests.append(comm.isend(stats[rank], dest=0, tag=TAG_PROGRESS))
        for request in requests:
            wait(request)
    return kept, stats
