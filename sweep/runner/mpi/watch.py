"""Rank 0's watch over the other ranks: a rank silent for too long ends the job.

A rank silent for longer than ``max(floor, WATCH_FACTOR x the slowest chunk so far)`` is
stopped or stuck, and the job aborts naming it and the cells it held."""
import threading
import time

import numpy as np

from .ending import JobFailure

WATCH_FLOOR = 300.0  # s of silence always allowed to a rank (sweep.run --rank-timeout)
WATCH_FACTOR = 10.0  # a rank silent for this many times the slowest chunk so far is stuck


class RankSilent(JobFailure):
    """A rank sent nothing for longer than the watch allows: stopped, or stuck in a scene."""


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
