"""Ranks: the communicator or a serial stand-in, dealing chunks, progress messages, aborting.

One module per job: :mod:`.launcher` (which launcher started the process), :mod:`.communicator`
(``COMM_WORLD`` with its messages counted, or a serial stand-in; the only import of mpi4py
that decides whether MPI is loaded), :mod:`.waits` (test-and-sleep waits and the ranks'
meetings), :mod:`.dealing` (chunks dealt to whichever rank asks), :mod:`.rounds` (a round's
chunks computed, rank 0 following the others), :mod:`.watch` (a rank silent for too long)
and :mod:`.ending` (an exception aborts the job; Ctrl-C settles the ranks).  The names below
are the package's; its users call them as ``mpi.<name>``.

mpi4py is loaded only when a launcher started the process (or ``SWEEP_MPI=1``): a plain
``python -m sweep.run`` never loads MPI, and a broken MPI install cannot break an import of
``sweep``.  Chunks are dealt one at a time to whichever rank asks (dynamic self-scheduling,
as OpenMP's ``schedule(dynamic)``): rank 0's :class:`Dealer` answers the other ranks'
requests from a thread of its own while rank 0 computes its chunks too, so a rank that drew
slow cells takes fewer chunks and every rank ends within about one chunk of the others.  The
other ranks send rank 0 one small message per finished chunk (:class:`ChunkDone`) and one
when they are done (:class:`RankDone`) with non-blocking sends, which it drains between its
own chunks with ``Iprobe`` (no busy ``recv``).  Every wait is a test-and-sleep loop, so an
idle rank does not spin.  An exception on any rank prints its traceback and calls
``COMM_WORLD.Abort``: the whole job ends within seconds instead of hanging.  After Ctrl-C,
which ``mpiexec`` passes on to every rank, the ranks settle what they left unmatched and end
MPI before they end (:func:`leave_interrupted`).  Rank 0 watches the others
(:class:`Watch`): a rank silent for longer than ``max(floor, WATCH_FACTOR x the slowest chunk
so far)`` is stopped or stuck, and the job aborts naming it and the cells it held.
"""
from .communicator import (TAG_CHUNK, TAG_PLAN, TAG_PROGRESS, TAG_TAKE, LauncherMismatch,
                           SerialComm, World, is_mpi, world, world_or_say)
from .dealing import Dealer, Taker
from .ending import FORWARD, LEAVE_WAIT, JobFailure, abort_on_exception, leave_interrupted
from .launcher import RANK_VARS, SIZE_VARS, first_process, launched, launcher_size
from .waits import DEAL_POLL, POLL, allgather, barrier, distribute, gather, wait
from .watch import WATCH_FACTOR, WATCH_FLOOR, RankSilent, Watch
from .rounds import ChunkDone, RankDone, work

__all__ = ["TAG_CHUNK", "TAG_PLAN", "TAG_PROGRESS", "TAG_TAKE", "LauncherMismatch",
           "SerialComm", "World", "is_mpi", "world", "world_or_say", "Dealer", "Taker",
           "FORWARD", "LEAVE_WAIT", "JobFailure", "abort_on_exception", "leave_interrupted",
           "RANK_VARS", "SIZE_VARS", "first_process", "launched", "launcher_size", "DEAL_POLL",
           "POLL", "allgather", "barrier", "distribute", "gather", "wait",
           "WATCH_FACTOR", "WATCH_FLOOR", "RankSilent", "Watch", "ChunkDone", "RankDone", "work"]
