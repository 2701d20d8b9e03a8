"""Progress of a study on rank 0: one tqdm bar on a terminal, plain log lines otherwise.

Log lines (one per ~10 % or ``LOG_EVERY`` seconds) are used when the stream is not a terminal
or the ``CI`` variable is set, so that logs of batch jobs and CI stay readable; ``quiet``
shows nothing.  Lines go out through :func:`emit`: a study goes on when the reader of its
output goes away (``sweep.run s.yaml 2>&1 | head``), since its results are in the files.
"""
import os
import sys
import time

LOG_EVERY = 30.0  # s between log lines at most
LOG_STEP = 0.1  # fraction of the cells between log lines


def emit(text, stream):
    """Print a line at once; when the reader is gone, the stream goes to ``os.devnull`` and
    the run carries on."""
    try:
        print(text, file=stream, flush=True)
    except BrokenPipeError:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, stream.fileno())
        os.close(devnull)


def format_seconds(s):
    """A duration for people: ``0.4 ms``, ``3.2 s``, ``4.5 min``, ``2.0 h``."""
    if s < 0.1:
        return f"{s * 1e3:.2g} ms"
    if s < 90:
        return f"{s:.1f} s"
    return f"{s / 60:.1f} min" if s < 5400 else f"{s / 3600:.1f} h"


class Progress:
    """Cells (or other ``unit``s) done out of ``total``; ``initial`` were done by an earlier
    run (resume).

    Parameters
    ----------
    total, initial : int
    quiet : bool
        Show nothing.
    stream : file, default sys.stderr
    prefix : str
        Start of log lines.
    unit : str
        What is counted.
    """

    def __init__(self, total, initial=0, quiet=False, stream=None, prefix="sweep.run",
                 unit="cell"):
        self.total, self.done, self.failed = total, initial, 0
        self.initial = initial
        self.stream = sys.stderr if stream is None else stream
        self.prefix, self.unit = prefix, unit
        self.start = time.perf_counter()
        self._bar = None
        self._last_time, self._last_done = self.start, initial
        if quiet:
            self.mode = "off"
        elif self.stream.isatty() and not os.environ.get("CI"):
            from tqdm import tqdm
            self.mode = "bar"
            self._bar = tqdm(total=total, initial=initial, unit=unit, file=self.stream,
                             dynamic_ncols=True, smoothing=0.1)
        else:
            self.mode = "log"

    def update(self, n, failed=0):
        """``n`` more cells done, ``failed`` of them failed."""
        self.done += n
        self.failed += failed
        if self.mode == "bar":
            self._bar.update(n)
            if self.failed:
                self._bar.set_postfix(failed=self.failed, refresh=False)
        elif self.mode == "log":
            now = time.perf_counter()
            if (self.done - self._last_done >= LOG_STEP * self.total
                    or now - self._last_time >= LOG_EVERY) and self.done < self.total:
                self._log(now)

    def eta(self, now=None):
        """Seconds left at the rate of this run so far, or None before any cell finished."""
        now = time.perf_counter() if now is None else now
        rate = (self.done - self.initial) / max(now - self.start, 1e-9)
        return (self.total - self.done) / rate if rate > 0 else None

    def _log(self, now):
        eta = self.eta(now)
        text = (f"{self.prefix}: {self.done}/{self.total} {self.unit}s "
                f"({100 * self.done / max(self.total, 1):.0f}%), "
                + (f"{self.failed} failed, " if self.unit == "cell" or self.failed else "")
                + f"{format_seconds(now - self.start)} elapsed"
                + (f", ETA {format_seconds(eta)}" if eta is not None and self.done < self.total
                   else ""))
        emit(text, self.stream)
        self._last_time, self._last_done = now, self.done

    def close(self):
        """End the bar (or write the last log line)."""
        if self.mode == "bar":
            self._bar.close()
        elif self.mode == "log":
            self._log(time.perf_counter())
