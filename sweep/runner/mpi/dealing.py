"""Chunks dealt one at a time to whichever rank asks: :class:`Dealer` and :class:`Taker`.

Dynamic self-scheduling, as OpenMP's ``schedule(dynamic)``: rank 0's :class:`Dealer` answers
the other ranks' :class:`Taker` from a thread of its own while rank 0 computes its chunks too,
so a rank that drew slow cells takes fewer chunks and every rank ends within about one chunk of
the others."""
import threading
import time

from .communicator import TAG_CHUNK, TAG_TAKE, is_mpi
from .waits import DEAL_POLL, pause


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
            pause(DEAL_POLL)
        k = self.comm.recv(source=0, tag=TAG_CHUNK)
        return None if k < 0 else self.chunks[k]
