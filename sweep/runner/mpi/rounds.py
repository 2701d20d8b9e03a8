"""A round's chunks computed on every rank until none is left, rank 0 following the others.

The other ranks send rank 0 one small message per finished chunk (:class:`ChunkDone`) and
one when they are done (:class:`RankDone`) with non-blocking sends, which it drains between
its own chunks with ``Iprobe`` (no busy ``recv``).
"""
import time
from collections import namedtuple

import numpy as np

from kernels import codes

from .. import interrupt
from .communicator import TAG_PROGRESS
from .dealing import Dealer, Taker
from .waits import DEAL_POLL, POLL, pause, wait

ChunkDone = namedtuple("ChunkDone", "cells failed seconds first")
ChunkDone.__doc__ = """A rank's message to rank 0 (``TAG_PROGRESS``): a chunk of ``cells`` cells, of
which ``failed`` failed, took ``seconds``; ``first`` is its first cell id (the ``watch.Watch``
finds the chunk by it)."""

RankDone = namedtuple("RankDone", "cells seconds started ended")
RankDone.__doc__ = """A rank's last message to rank 0 (``TAG_PROGRESS``): it computed ``cells``
cells in ``seconds`` busy, from ``started`` to ``ended`` (``time.time()``, None without a
chunk); also the value of :func:`work`'s ``stats`` for each rank."""


def _failed(result):
    return int(np.isin(result["status"], codes.FAILED_STATUSES).sum())


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
        from ..cells import run_chunk
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
                pause(DEAL_POLL if not source.threaded() else POLL)
    else:
        requests.append(comm.isend(stats[rank], dest=0, tag=TAG_PROGRESS))
        for request in requests:
            wait(request)
    return kept, stats
