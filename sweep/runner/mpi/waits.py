"""Waiting without spinning: test-and-sleep waits, and the ranks' meetings built on them.

Every wait of a rank is a test-and-sleep loop, which first raises a Ctrl-C that was swallowed;
the meetings are the barrier, the gather and the plans rank 0 hands out."""
import time

from .. import interrupt
from .communicator import TAG_PLAN, is_mpi

POLL = 0.02  # s between tests of a pending message or request
DEAL_POLL = 0.001  # s between the dealer's tests for requests, and a rank's for its answer


def pause(seconds):
    """A waiting rank's sleep, first raising a Ctrl-C that was swallowed
    (``interrupt.check``): a rank waiting for an answer must not wait for ever."""
    interrupt.check()
    time.sleep(seconds)


def wait(request):
    """Wait for a non-blocking request by testing and sleeping (an idle rank does not spin)."""
    while not request.Test():
        pause(POLL)


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
        pause(POLL)
    return comm.recv(source=0, tag=TAG_PLAN)
