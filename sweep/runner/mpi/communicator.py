"""The communicator of this process: ``COMM_WORLD`` with its messages counted, or a stand-in.

The stand-in is serial; the tags of the ranks' messages are here too.

mpi4py is loaded here, and only when a launcher started the process (or
``SWEEP_MPI=1``): a plain ``python -m sweep.run`` never loads MPI, and a broken MPI install
cannot break an import of ``sweep`` (the other modules of the package reach mpi4py only
inside functions that run under MPI).
"""
import os
import sys
import threading

from .. import interrupt
from .launcher import first_process, launched, launcher_size

TAG_PLAN, TAG_PROGRESS, TAG_TAKE, TAG_CHUNK = 11, 12, 13, 14


class LauncherMismatch(RuntimeError):
    """A multi-rank launcher started processes that each see an MPI world of size 1."""


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
    reports a status that is neither rank's.  ``ending.leave_interrupted`` uses the counts to
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
