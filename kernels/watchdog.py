"""A per-cell wall-time budget for a chunk of scenes run in one compiled call.

Compiled code cannot be interrupted by a signal, and ``driver.run_cells`` runs without the
GIL (``_jit``: ``nogil``).  So the kernel and a watchdog thread share a small int64 control
array (``codes.CTL_*``): the kernel writes the index of the cell it runs, the watchdog writes
the index of a cell to stop once that cell has run longer than the budget, and the kernel's
event loop reads that request and ends the cell with status ``TIME_BUDGET``.
"""
import threading
import time

import numpy as np

from .codes import CTL_CELL, CTL_STOP, N_CTL

NO_CELL = -1          # in CTL_CELL: no cell started yet; in CTL_STOP: no stop request
POLL_FRACTION = 0.05  # the watchdog looks at the running cell every 5 % of the budget ...
MAX_POLL = 0.1        # ... and at least every 0.1 s


def control(cell=NO_CELL):
    """A control array: ``cell`` running (``NO_CELL``: none yet), no stop request."""
    ctl = np.full(N_CTL, NO_CELL, dtype=np.int64)
    ctl[CTL_CELL] = cell
    return ctl


class Watchdog:
    """While open, a thread stops the running cell of ``ctl`` once it has run for more than
    ``budget`` seconds of wall time (None or 0: no budget, no thread).

    A cell's time counts from the first look at it, so compiling the kernel before the first
    cell starts costs none of it; the budget holds to within one poll interval.
    """

    def __init__(self, ctl, budget):
        self.ctl = ctl
        self.budget = float(budget) if budget else 0.0
        self._done = threading.Event()
        self._thread = None

    def __enter__(self):
        if self.budget > 0.0:
            self._thread = threading.Thread(target=self._watch, name="cell-watchdog",
                                            daemon=True)
            self._thread.start()
        return self

    def __exit__(self, *exc):
        self._done.set()
        if self._thread is not None:
            self._thread.join()
        return False

    def _watch(self):
        ctl, poll = self.ctl, min(POLL_FRACTION * self.budget, MAX_POLL)
        cell, since = NO_CELL, time.monotonic()
        while not self._done.wait(poll):
            running = int(ctl[CTL_CELL])
            if running != cell:
                cell, since = running, time.monotonic()
            elif cell != NO_CELL and time.monotonic() - since > self.budget:
                ctl[CTL_STOP] = cell
