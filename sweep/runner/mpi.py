"""Ranks: the communicator or a serial stand-in, dealing chunks, progress messages, aborting.

The only module that imports mpi4py, and only when a launcher started the process (or
``SWEEP_MPI=1``): a plain ``python -m sweep.run`` never loads MPI, and a broken MPI install
cannot break an import of ``sweep``.  Chunks are dealt one at a time to whichever rank asks
(dynamic self-scheduling, as OpenMP's ``schedule(dynamic)``): rank 0's :class:`Dealer`
answers the other ranks' requests from a thread of its own while rank 0 computes its chunks
too, so a rank that drew slow cells takes fewer chunks and every rank ends within about one
chunk of the others.  The other ranks send rank 0 one small message per finished chunk
(:class:`ChunkDone`) and one when they are done (:class:`RankDone`) with non-blocking sends,
which it drains between its own chunks with ``Iprobe`` (no busy ``recv``).  Every wait is a
test-and-sleep loop, so an idle rank does not spin.  An exception on any rank prints its
traceback and calls ``COMM_WORLD.Abort``: the whole job ends within seconds instead of
hanging.  After Ctrl-C, which ``mpiexec`` passes on to every rank, the ranks settle what they
left unmatched and end MPI before they end (:func:`leave_interrupted`).  Rank 0 watches the
others (:class:`Watch`): a rank silent for longer than ``max(floor, WATCH_FACTOR x the
slowest chunk so far)`` is stopped or stuck, and the job aborts naming it and the cells it
held.
"""
import ctypes
import os
import signal
import sys
import threading
import time
import traceback
from collections import namedtuple
from contextlib import contextmanager

import numpy as np

from kernels import codes

from ..io.exits import EXIT_INTERRUPTED
from . import interrupt

POLL = 0.02  # s between tests of a pending message or request
DEAL_POLL = 0.001  # s between the dealer's tests for requests, and a rank's for its answer
FORWARD = 0.5  # s left to the launcher to pass a failed rank's traceback on before Abort
LEAVE_WAIT = 10.0  # s an interrupted rank waits to settle with the others (leave_interrupted)
TAG_PLAN, TAG_PROGRESS, TAG_TAKE, TAG_CHUNK = 11, 12, 13, 14
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

RankDone = namedtuple("RankDone", "cells seconds started ended")
RankDone.__doc__ = """A rank's last message to rank 0 (``TAG_PROGRESS``): it computed ``cells``
cells in ``seconds`` busy, from ``started`` to ``ended`` (``time.time()``, None without a
chunk); also the value of :func:`work`'s ``stats`` for each rank."""


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


class World:
    """``COMM_WORLD`` with its point-to-point messages and its barriers counted.

    Ranks stopped by Ctrl-C leave messages to each other unmatched (a request for a chunk,
    the chunk dealt in reply, progress) and may leave one rank waiting in a barrier that the
    others never reached.  ``MPI_Finalize`` refuses that: MPICH ends such a rank abnormally
    ("being freed has N unmatched messages"), and its launcher then kills the other ranks and
    reports a status that is neither rank's.  :func:`leave_interrupted` uses the counts to
    take every message sent to this rank and to join the barrier another rank waits in.
    Sends, receives and barriers made here count them, Ctrl-C being held back between a
    message and its count (``interrupt.held``); everything else is ``COMM_WORLD``'s.

    Parameters
    ----------
    comm : mpi4py.MPI.Intracomm
        ``COMM_WORLD``; a duplicate of it (:attr:`quit`) is made at once (every rank calls
        this at start-up) for the ranks' exchange when they leave early.
    """

    def __init__(self, comm):
        self._comm = comm
        self.quit = comm.Dup()
        self.sent = [0] * comm.Get_size()  # messages sent to each rank
        self.received = [0] * comm.Get_size()  # messages taken from each rank
        self.barriers = 0  # barriers entered
        self.open = []  # requests not yet seen complete (sends, barriers)
        self._lock = threading.Lock()  # rank 0's dealer thread counts too

    def __getattr__(self, name):
        return getattr(self._comm, name)

    def _count(self, counts, rank, request=None):
        with self._lock:
            counts[rank] += 1
            if request is not None:
                self._keep(request)

    def _keep(self, request):
        """Add ``request`` to :attr:`open`, leaving out those seen complete (under the lock)."""
        self.open = [r for r in self.open if not r.Test()] + [request]

    def send(self, obj, dest, tag):
        with interrupt.held():
            self._comm.send(obj, dest=dest, tag=tag)
            self._count(self.sent, dest)

    def isend(self, obj, dest, tag):
        with interrupt.held():
            request = self._comm.isend(obj, dest=dest, tag=tag)
            self._count(self.sent, dest, request)
        return request

    def recv(self, source, tag):
        with interrupt.held():
            obj = self._comm.recv(source=source, tag=tag)
            self._count(self.received, source)
        return obj

    def Ibarrier(self):
        with interrupt.held():
            request = self._comm.Ibarrier()
            with self._lock:
                self.barriers += 1
                self._keep(request)
        return request


_WORLD = None  # this process's World, once made


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
    """One thread per rank: MPI is the only parallelism (numba, OpenMP, BLAS).

    Where numba is imported already, its thread count is lowered in place and its variable
    left alone: numba rereads the environment at every compilation and refuses a
    ``NUMBA_NUM_THREADS`` that differs from the pool it launched."""
    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ[var] = "1"
    if "numba" not in sys.modules:
        os.environ["NUMBA_NUM_THREADS"] = "1"
        return
    try:
        sys.modules["numba"].set_num_threads(1)
    except (AttributeError, ValueError):
        pass


def world(environ=None):
    """The communicator of this process.

    ``COMM_WORLD`` of mpi4py, as one :class:`World` per process, when a launcher started the
    process (or ``SWEEP_MPI=1``; ``SWEEP_MPI=0`` forces serial), else a :class:`SerialComm`.
    Under MPI the numba, OpenMP and BLAS threads are set to one.

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
    global _WORLD
    if _WORLD is None:
        _WORLD = World(comm)
    return _WORLD


def world_or_say(prog):
    """The communicator (:func:`world`), or None after ``prog`` says why not (once per job)."""
    try:
        return world()
    except LauncherMismatch as err:
        if first_process():
            print(f"{prog}: error: {err}", file=sys.stderr, flush=True)
        return None


def _pause(seconds):
    """A waiting rank's sleep, first raising a Ctrl-C that was swallowed
    (``interrupt.check``): a rank waiting for an answer must not wait for ever."""
    interrupt.check()
    time.sleep(seconds)


def wait(request):
    """Wait for a non-blocking request by testing and sleeping (an idle rank does not spin)."""
    while not request.Test():
        _pause(POLL)


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


def leave_interrupted(comm):
    """After Ctrl-C, when this is one of several ranks: settle with the other ranks, end MPI
    and end the process with status 130 (``io.exits.EXIT_INTERRUPTED``); serially, return.

    Ctrl-C is ignored from here on.  The ranks exchange how many messages each sent to each
    and how many barriers each entered (on :attr:`World.quit`).  Each then takes the
    messages still due to it, joins a barrier another rank waits in, and meets the others
    once more, so that ``MPI_Finalize`` finds nothing unmatched.  The process then ends with
    the C library's ``exit``, not Python's: MPICH tells its launcher that the rank ended
    well only in a C exit hook (``MPIR_pmi_finalize_on_exit``; without it the launcher kills
    the other ranks and may report their SIGKILL), and CPython would end the process by
    SIGINT instead of its status when a ``KeyboardInterrupt``, caught since, once passed
    through code it ran from a string (``_Py_UnhandledKeyboardInterrupt``: set on rank 0 in
    5 of 10 runs of the Ctrl-C test).  Nothing else is left to do by then: the part files are
    written, the output's lock is released and stdout and stderr are flushed.  A rank that
    cannot settle within ``LEAVE_WAIT`` (another rank still in a long chunk, or cut between a
    barrier and the exchange after it) ends at once with ``os._exit``, and the launcher ends
    the others.
    """
    if not is_mpi(comm):
        return
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C: no traceback now
    from mpi4py import MPI

    end = os._exit
    try:
        if _settle(comm, time.monotonic() + LEAVE_WAIT):
            MPI.Finalize()
            end = ctypes.PyDLL(None).exit  # the GIL held: no Python thread runs meanwhile
    except MPI.Exception:
        pass
    sys.stdout.flush()
    sys.stderr.flush()
    end(EXIT_INTERRUPTED)


def _settle(world, end):
    """Take every message due to this rank and complete every barrier and send it began, by
    ``end`` (``time.monotonic()``); True when done and every rank is done too."""
    size, rank = world.Get_size(), world.Get_rank()
    table = np.zeros((size, size + 1), np.int64)
    mine = np.array(world.sent + [world.barriers], np.int64)
    if not _until(world, world.quit.Iallgather(mine, table).Test, end):
        return False
    for _ in range(table[:, -1].max() - world.barriers):  # the barrier a rank waits in
        world.Ibarrier()
    due = table[:, rank]
    if not _until(world, lambda: (np.all(np.array(world.received) >= due)
                                  and all(r.Test() for r in world.open)), end):
        return False
    if not _until(world, world.quit.Ibarrier().Test, end):
        return False
    world.quit.Free()
    return True


def _until(world, done, end):
    """Take every message that arrives at ``world`` until ``done()`` or ``end``; True if
    done."""
    from mpi4py import MPI

    status = MPI.Status()
    while True:
        while world.Iprobe(source=MPI.ANY_SOURCE, tag=MPI.ANY_TAG, status=status):
            world.recv(source=status.Get_source(), tag=status.Get_tag())
        if done():
            return True
        if time.monotonic() > end:
            return False
        time.sleep(DEAL_POLL)


def gather(comm, value):
    """Every rank's ``value``, in rank order, on rank 0 (None on the others; one process:
    ``[value]``); the ranks meet in a sleeping :func:`barrier` first."""
    if not is_mpi(comm):
        return [value]
    barrier(comm)
    return comm.gather(value, root=0)


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
        _pause(POLL)
    return comm.recv(source=0, tag=TAG_PLAN)


def _failed(result):
    return int(np.isin(result["status"], codes.FAILED_STATUSES).sum())


class Watch:
    """Rank 0's view of the other ranks: when each was last heard, the chunks it holds.

    Parameters
    ----------
    size : int
        Number of ranks (rank 0 is not watched).
    floor : float
        Seconds of silence always allowed; 0 or None: no watch.
    """

    def __init__(self, size, floor=WATCH_FLOOR, clock=time.monotonic):
        self.clock = clock
        now = clock()
        self.floor = floor or 0.0
        self.held = {r: {} for r in range(1, size)}
        self.last = {r: now for r in self.held}
        self.slowest = 0.0
        self._lock = threading.Lock()  # the dealer's thread hands out chunks (took)

    def took(self, rank, chunk):
        """``rank`` was handed ``chunk`` (it is alive)."""
        with self._lock:
            if rank in self.held:
                self.held[rank][int(chunk[0])] = chunk
                self.last[rank] = self.clock()

    def chunk_done(self, rank, seconds, first=None):
        """A chunk (starting at cell ``first``) took ``seconds`` on ``rank``."""
        with self._lock:
            self.slowest = max(self.slowest, seconds)
            if rank in self.last:
                self.last[rank] = self.clock()
                self.held[rank].pop(first, None)

    def rank_done(self, rank):
        """``rank`` finished all its chunks."""
        with self._lock:
            self.held.pop(rank, None)
            self.last.pop(rank, None)

    def limit(self):
        """Seconds of silence after which a rank is taken for stopped or stuck."""
        return max(self.floor, WATCH_FACTOR * self.slowest)

    def check(self):
        """Raise :class:`RankSilent` for the first rank silent for longer than :meth:`limit`."""
        if not self.floor:
            return
        with self._lock:
            now, limit = self.clock(), self.limit()
            silent = [(rank, now - last) for rank, last in self.last.items()
                      if now - last > limit]
            if not silent:
                return
            rank, quiet = silent[0]
            cells = np.concatenate(list(self.held[rank].values()) or [np.zeros(0, int)])
        raise RankSilent(
            f"rank {rank} sent nothing for {quiet:.0f} s (the limit is "
            f"max({self.floor:g} s, {WATCH_FACTOR:g} x the slowest chunk so far, "
            f"{self.slowest:.2g} s)): it is stopped or stuck. It held {cells.size} "
            f"cells not yet saved (first: {np.sort(cells)[:10].tolist()}); the "
            "others' parts are kept: run the same command again to resume, or raise "
            "--rank-timeout")


class Dealer:
    """Rank 0's dealing of a round's chunks (``grid.Chunks``), one at a time, to whichever
    rank asks first.

    Rank 0 takes its own with :meth:`take`; the other ranks ask with a message
    (``TAG_TAKE``, :class:`Taker`) and are answered with the chunk's index (``TAG_CHUNK``; -1
    when none is left) by :meth:`serve`, which a thread of rank 0 runs every ``DEAL_POLL``
    seconds while rank 0 computes (the kernel releases the GIL).  An MPI library that allows
    no calls from a second thread (below ``MPI_THREAD_SERIALIZED``) gets no thread: rank 0
    then serves between its chunks.  MPI calls of the thread and of rank 0's own loop are
    made under one lock.

    Parameters
    ----------
    comm : communicator or SerialComm
    chunks : grid.Chunks
    watch : Watch, optional
        Told which rank took which chunk.
    """

    def __init__(self, comm, chunks, watch=None):
        self.comm, self.chunks, self.watch = comm, chunks, watch
        self.next = 0
        self.told = 0  # ranks told that no chunk is left
        self.mpi_lock = threading.Lock()
        self._stop = threading.Event()
        self._thread = None

    def _index(self, rank):
        """The index of the next chunk, now ``rank``'s, or -1 when none is left."""
        with self.mpi_lock:
            if self.next >= len(self.chunks):
                return -1
            k, self.next = self.next, self.next + 1
        if self.watch is not None and rank:
            self.watch.took(rank, self.chunks[k])
        return k

    def take(self):
        """Rank 0's next chunk, or None when none is left."""
        k = self._index(0)
        return None if k < 0 else self.chunks[k]

    def serve(self):
        """Answer every request waiting; True if there was one."""
        from mpi4py import MPI

        status, served = MPI.Status(), False
        while True:
            with self.mpi_lock:
                if not self.comm.Iprobe(source=MPI.ANY_SOURCE, tag=TAG_TAKE, status=status):
                    return served
                source = status.Get_source()
                self.comm.recv(source=source, tag=TAG_TAKE)
            k = self._index(source)
            with self.mpi_lock:
                self.comm.send(k, dest=source, tag=TAG_CHUNK)
            self.told += k < 0
            served = True

    def _serve_all(self):
        while self.told < self.comm.Get_size() - 1 and not self._stop.is_set():
            if not self.serve():
                time.sleep(DEAL_POLL)

    def threaded(self):
        """True when :meth:`start` runs the dealing in a thread."""
        return self._thread is not None

    def start(self):
        """Serve the other ranks from a thread (several ranks and a library that allows it)."""
        if not is_mpi(self.comm) or self.comm.Get_size() == 1:
            return self
        from mpi4py import MPI

        if MPI.Query_thread() >= MPI.THREAD_SERIALIZED:
            self._thread = threading.Thread(target=self._serve_all, name="sweep-dealer",
                                            daemon=True)
            self._thread.start()
        return self

    def close(self):
        """Stop serving (every rank has been told; or the job is ending early)."""
        self._stop.set()
        if self._thread is not None:
            self._thread.join()


class Taker:
    """A rank other than 0: asks rank 0's :class:`Dealer` for its next chunk."""

    def __init__(self, comm, chunks):
        self.comm, self.chunks = comm, chunks

    def take(self):
        """The next chunk, or None when none is left."""
        self.comm.send(None, dest=0, tag=TAG_TAKE)
        while not self.comm.Iprobe(source=0, tag=TAG_CHUNK):
            _pause(DEAL_POLL)
        k = self.comm.recv(source=0, tag=TAG_CHUNK)
        return None if k < 0 else self.chunks[k]


def _drain(comm, progress, stats, watch, lock):
    """Take every waiting progress message on rank 0; returns how many ranks said done."""
    from mpi4py import MPI

    status, finished = MPI.Status(), 0
    while True:
        with lock:
            if not comm.Iprobe(source=MPI.ANY_SOURCE, tag=TAG_PROGRESS, status=status):
                return finished
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


def work(comm, study, chunks, *, store=None, progress=None, run_chunk=None, before=None,
         watch=None):
    """Compute chunks of a round until none is left; on rank 0, also deal them and follow
    every rank until all are done.

    Parameters
    ----------
    comm : communicator or SerialComm
    study : Study
    chunks : grid.Chunks
        The round's chunks, the same on every rank; each rank computes those it is dealt.
    store : PartStore, optional
        Where each finished chunk is written; without it (one process only) the results are
        kept in memory and returned.
    progress : Progress, optional
        Rank 0's progress display.
    run_chunk : callable, optional
        ``run_chunk(study, cells) -> dict``; default ``cells.run_chunk``.
    before : callable, optional
        Called once on rank 0 after the dealing started, before its own first chunk (what rank
        0 still has to load while the others compute).
    watch : Watch, optional
        Rank 0: to detect a rank that stopped answering.

    Returns
    -------
    results : list of dict
        The chunk results kept in memory (empty with a store).
    stats : dict
        On rank 0: rank -> :class:`RankDone` for every rank; else this rank's.

    Raises
    ------
    RankSilent
        On rank 0, when a rank stays silent for longer than the watch allows.
    """
    if run_chunk is None:
        from .cells import run_chunk
    if store is None and comm.Get_size() > 1:
        raise ValueError("several ranks need a `store` for their results")
    rank = comm.Get_rank()
    source = Dealer(comm, chunks, watch).start() if rank == 0 else Taker(comm, chunks)
    try:
        if before is not None:
            before()
            interrupt.check()
        return _work(comm, study, source, store, progress, run_chunk, watch)
    finally:
        if rank == 0:
            source.close()


def _work(comm, study, source, store, progress, run_chunk, watch):
    """:func:`work` once the dealing stands."""
    rank, size = comm.Get_rank(), comm.Get_size()
    kept, requests, stats = [], [], {}
    busy, n_done, pending = 0.0, 0, size - 1
    started = ended = None
    lock = getattr(source, "mpi_lock", None)
    while (chunk := source.take()) is not None:
        interrupt.check()
        t0 = time.perf_counter()
        started = started or time.time()
        result = run_chunk(study, chunk)
        if store is not None:
            store.write_part(result)
        else:
            kept.append(result)
        seconds = time.perf_counter() - t0
        ended = time.time()
        busy += seconds
        n_done += len(chunk)
        if rank == 0:
            if progress is not None:
                progress.update(len(chunk), _failed(result))
            if size > 1:
                if not source.threaded():
                    source.serve()
                if watch is not None:
                    watch.chunk_done(0, seconds)
                pending -= _drain(comm, progress, stats, watch, lock)
                if watch is not None:
                    watch.check()
        else:
            requests.append(comm.isend(ChunkDone(len(chunk), _failed(result), seconds,
                                                 int(chunk[0])), dest=0, tag=TAG_PROGRESS))
            requests = [r for r in requests if not r.Test()]
    stats[rank] = RankDone(n_done, busy, started, ended)
    if rank == 0:
        while pending > 0:
            served = False if source.threaded() else source.serve()
            pending -= _drain(comm, progress, stats, watch, lock)
            if pending > 0 and not served:
                if watch is not None:
                    watch.check()
                _pause(DEAL_POLL if not source.threaded() else POLL)
    else:
        requests.append(comm.isend(stats[rank], dest=0, tag=TAG_PROGRESS))
        for request in requests:
            wait(request)
    return kept, stats
