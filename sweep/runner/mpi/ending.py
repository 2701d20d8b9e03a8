"""How a job ends early: an exception aborts every rank; after Ctrl-C the ranks settle, then end.

An exception on any rank aborts the whole job with its traceback; after Ctrl-C the ranks settle
what they left unmatched and end MPI before they end."""
import ctypes
import os
import signal
import sys
import threading
import time
import traceback
from contextlib import contextmanager

import numpy as np

from ...io.exits import EXIT_INTERRUPTED
from .communicator import is_mpi
from .waits import DEAL_POLL

FORWARD = 0.5  # s left to the launcher to pass a failed rank's traceback on before Abort
LEAVE_WAIT = 10.0  # s an interrupted rank waits to settle with the others (leave_interrupted)


class JobFailure(RuntimeError):
    """A failure that ends the whole job and is said in words, without a traceback."""


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
    and how many barriers each entered (on ``communicator.World.quit``).  Each then takes the
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
