"""What a study run says: its size, the dry run's estimate, and the summaries at the end.

Everything here prints (rank 0 only); nothing decides how the run goes.
"""
import sys
import time
from collections import namedtuple

import numpy as np

from kernels import codes

from .. import cf
from . import grid, refine, store
from .grid import shape_text
from .progress import emit, format_seconds

SAMPLE_CELLS = 16  # cells timed by --dry-run for its estimate
MAX_LISTED = 20  # failed cells listed in the summary
SUMMARY_VARIABLES = ("outcome", "status")  # what :func:`summary` reads of every cell


class Timeline(namedtuple("Timeline", "wall startup cells merge")):
    """Where a run's wall time went, in seconds: ``startup`` from the start of the run on
    rank 0 (the study read, nothing yet checked) to the first chunk on any rank, ``cells``
    from there to the last chunk's end on any rank, ``merge`` from there to the dataset
    written (None: no chunk ran, every cell was done by an earlier run)."""

    @classmethod
    def of(cls, start, stats, end):
        """From ``time.time()`` at the start and at the end and the ranks' ``mpi.RankDone``."""
        first = min((s.started for s in stats.values() if s.started is not None), default=None)
        last = max((s.ended for s in stats.values() if s.ended is not None), default=None)
        if first is None:
            return cls(end - start, None, None, None)
        return cls(end - start, first - start, last - first, end - last)

    def text(self):
        if self.startup is None:
            return f"{self.wall:.1f} s"
        return (f"{self.wall:.1f} s (start-up {self.startup:.2f} s, cells {self.cells:.1f} s, "
                f"merge and write {self.merge:.2f} s)")


def say(*text, file=None):
    """Print at once (ranks share the terminal; a buffered line would come late), and go on
    when the reader is gone (``progress.emit``)."""
    emit(" ".join(map(str, text)), sys.stdout if file is None else file)


def _tolerance_text(study):
    _, axis = refine.refined_axis(study)
    return f"{study.refine.tolerance:g} {axis.unit if axis.body_relative else axis.units}"


def refine_text(study):
    """What a refine study will run, at most."""
    _, axis = refine.refined_axis(study)
    lines = study.n_cells // axis.coords.size
    return (f"refine {axis.name} to {_tolerance_text(study)} on {lines} line"
            f"{'s' if lines != 1 else ''}: {study.n_cells} coarse cells ({shape_text(study)}), "
            f"then at most {refine.max_rounds(study)} rounds of one midpoint per line: at most "
            f"{refine.max_simulations(study)} simulations (a grid of the same resolution: "
            f"{refine.dense_simulations(study)} cells)")


def dry_run(study, size, seed, done):
    """Print the cell count and an estimate of the run time from a timed sample of cells."""
    from .cells import run_chunk, warm_up  # the kernel, only when a dry run is asked for

    n, left = study.n_cells, study.n_cells - len(done)
    if study.refine:
        left = refine.max_simulations(study)
        say(f"study {study.name}: {refine_text(study)}")
    else:
        say(f"study {study.name}: {n} cells ({shape_text(study)})")
    say(f"output: {study.output}" + (" (exists: --force to overwrite)"
                                      if study.output.exists() else ""))
    if len(done):
        say(f"resume: {len(done)} cells done in {store.parts_dir(study.output)}")
    t0 = time.perf_counter()
    warm_up()
    compile_s = time.perf_counter() - t0
    sample = grid.sample(n, SAMPLE_CELLS, seed)
    t0 = time.perf_counter()
    run_chunk(study, sample)
    per_cell = (time.perf_counter() - t0) / len(sample)
    estimate = per_cell * left
    say(f"estimated run time: {format_seconds(per_cell)} per cell (timed on {len(sample)}), "
         f"{format_seconds(estimate)} for {'at most ' if study.refine else ''}{left} cells "
         "on 1 rank"
         + (f", about {format_seconds(estimate / size)} on {size} ranks" if size > 1 else "")
         + f"; plus start-up (kernel load {format_seconds(compile_s)})")


def summary(study, arrays, timeline, stats, quiet, size):
    """Counts of outcomes, failed cells with their coordinates, balance of the ranks.

    ``arrays``: the ``SUMMARY_VARIABLES`` of every cell, in cell order.
    """
    outcome, status = arrays["outcome"], arrays["status"]
    failed = np.flatnonzero(outcome == codes.FAILED)
    if not quiet:
        counts = ", ".join(f"{int(np.sum(outcome == code))} {name.replace('_', ' ')}"
                           for code, name in zip(*cf.OUTCOME_FLAGS))
        say(f"sweep.run: wrote {study.output}: {study.n_cells} cells in {timeline.text()} on "
             f"{size} rank{'s' if size > 1 else ''}; {counts}")
        _say_busy(stats, size)
    if failed.size:
        say(f"sweep.run: {failed.size} cell{'s' if failed.size > 1 else ''} failed "
             "(outcome = -1, see `status`):", file=sys.stderr)
        for index in failed[:MAX_LISTED]:
            where = ", ".join(f"{k}={v!r}" for k, v in grid.cell_coords(study, index).items())
            say(f"  cell {index} ({where}): {codes.STATUS_NAMES[status[index]]}",
                 file=sys.stderr)
        _say_more(failed.size)


def _say_busy(stats, size):
    """The cells and busy seconds of every rank (several ranks only)."""
    if size > 1:
        busy = ", ".join(f"rank {r}: {stats[r][0]} cells {stats[r][1]:.1f} s"
                         for r in sorted(stats))
        say(f"sweep.run: busy time per rank: {busy}")


def _say_more(n):
    if n > MAX_LISTED:
        say(f"  ... and {n - MAX_LISTED} more", file=sys.stderr)


def refine_summary(study, brackets, timeline, stats, quiet, size):
    """Counts of the brackets, simulations against a dense grid, lines that failed."""
    k, _ = refine.refined_axis(study)
    first_cells = refine.coarse_cells(study)[:, 0]
    if not quiet:
        counts = ", ".join(f"{int(np.sum(brackets.flag == code))} {name.replace('_', ' ')}"
                           for code, name in enumerate(refine.BRACKET_NAMES))
        say(f"sweep.run: wrote {study.output}: {brackets.flag.size} lines in "
             f"{brackets.rounds} rounds, {int(brackets.simulations.sum())} simulations (at "
             f"most {refine.max_simulations(study)}; a grid of the same resolution: "
             f"{refine.dense_simulations(study)}) in {timeline.text()} on {size} "
             f"rank{'s' if size > 1 else ''}; {counts}")
        _say_busy(stats, size)
    failed = np.flatnonzero(brackets.flag == refine.FAILED)
    if failed.size:
        say(f"sweep.run: a simulation failed on {failed.size} line"
             f"{'s' if failed.size > 1 else ''}; bisection stopped there (bracket = "
             "simulation_failed):", file=sys.stderr)
        for line in failed[:MAX_LISTED]:
            coords = grid.cell_coords(study, first_cells[line])
            coords.pop(study.dims[k].name)
            where = ", ".join(f"{key}={v!r}" for key, v in coords.items())
            say(f"  line {line} ({where}): bracket [{brackets.lower[line]!r}, "
                 f"{brackets.upper[line]!r}]", file=sys.stderr)
        _say_more(failed.size)
