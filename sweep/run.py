"""Run a study over MPI ranks into one labelled netCDF dataset (DESIGN.md sections 5-7).

    python -m sweep.run STUDY.yaml [--dry-run] [--force] [--quiet] [--chunk-size N]
                                   [--seed N] [-o OUTPUT.nc]
    mpiexec -n 2 python -m sweep.run STUDY.yaml

Rank 0 reads and checks the study (every problem at once, exit status 2, nothing written),
prepares the part files (resuming from those of a killed run) and deals the chunks; every rank
computes and writes its parts; rank 0 merges them into the dataset.  A study with ``refine:``
runs in rounds (``sweep.refine``): rank 0 deals each round's cells the same way, merges the
round and decides the next one.  ``run_study`` does the same in one process and returns the
Dataset (``sweep.run_study`` in a notebook).
"""
import argparse
import os
import sys
import time

import numpy as np

from kernels import codes

from . import cf
from .io.problems import EXIT_BAD_INPUT
from .io.study_schema import load_study
from .io.problems import FileProblems
from .runner import grid, mpi, refine, store
from .runner.progress import Progress, format_seconds

EXIT_OK, EXIT_ERROR, EXIT_INPUT = 0, 1, EXIT_BAD_INPUT
SAMPLE_CELLS = 16  # cells timed by --dry-run for its estimate
MAX_LISTED = 20  # failed cells listed in the summary


def _say(*text, file=sys.stdout):
    print(*text, file=file, flush=True)


def _stop(comm, code):
    """Plans telling every rank to end with ``code``."""
    return [{"exit": code}] * comm.Get_size()


def _shape_text(study):
    return " x ".join(f"{dim.name} {dim.size}" for dim in study.dims)


def _tolerance_text(study):
    _, axis = refine.refined_axis(study)
    return f"{study.refine.tolerance:g} {axis.unit if axis.body_relative else axis.units}"


def _refine_text(study):
    """What a refine study will run, at most."""
    _, axis = refine.refined_axis(study)
    lines = study.n_cells // axis.coords.size
    return (f"refine {axis.name} to {_tolerance_text(study)} on {lines} line"
            f"{'s' if lines != 1 else ''}: {study.n_cells} coarse cells ({_shape_text(study)}), "
            f"then at most {refine.max_rounds(study)} rounds of one midpoint per line: at most "
            f"{refine.max_simulations(study)} simulations (a grid of the same resolution: "
            f"{refine.dense_simulations(study)} cells)")


def _dry_run(study, size, seed, done):
    """Print the cell count and an estimate of the run time from a timed sample of cells."""
    from .runner.cells import run_chunk, warm_up

    n, left = study.n_cells, study.n_cells - len(done)
    if study.refine:
        left = refine.max_simulations(study)
        _say(f"study {study.name}: {_refine_text(study)}")
    else:
        _say(f"study {study.name}: {n} cells ({_shape_text(study)})")
    _say(f"output: {study.output}" + (" (exists: --force to overwrite)"
                                      if study.output.exists() else ""))
    if len(done):
        _say(f"resume: {len(done)} cells done in {store.parts_dir(study.output)}")
    t0 = time.perf_counter()
    warm_up()
    compile_s = time.perf_counter() - t0
    sample = grid.shuffled(n, seed)[:min(n, SAMPLE_CELLS)]
    t0 = time.perf_counter()
    run_chunk(study, sample)
    per_cell = (time.perf_counter() - t0) / len(sample)
    estimate = per_cell * left
    _say(f"estimated run time: {format_seconds(per_cell)} per cell (timed on {len(sample)}), "
         f"{format_seconds(estimate)} for {'at most ' if study.refine else ''}{left} cells "
         "on 1 rank"
         + (f", about {format_seconds(estimate / size)} on {size} ranks" if size > 1 else "")
         + f"; plus start-up (kernel load {format_seconds(compile_s)})")


def _plan(comm, args):
    """Rank 0: check the study, the output and the parts; the plan of every rank."""
    size = comm.Get_size()
    try:
        study = load_study(args.study, output=args.output)
    except FileProblems as err:
        _say(f"sweep.run: {args.study}: {len(err.problems)} problem"
             f"{'s' if len(err.problems) != 1 else ''}; nothing was run:", file=sys.stderr)
        for line in str(err).splitlines():
            _say(f"  {line}", file=sys.stderr)
        return _stop(comm, EXIT_INPUT), None
    parts = store.PartStore(store.parts_dir(study.output))
    if args.dry_run:
        done = parts.done_cells() if parts.directory.exists() else []
        _dry_run(study, size, args.seed, done)
        return _stop(comm, EXIT_OK), None
    try:
        store.check_output(study.output, args.force)
        parts.prepare(study, discard=args.force)
    except store.StoreError as err:
        _say(f"sweep.run: error: {err}", file=sys.stderr)
        return _stop(comm, EXIT_INPUT), None
    from .runner.cells import warm_up
    common = {"exit": None, "text": study.text, "source": study.source,
              "output": str(study.output), "parts": str(parts.directory)}
    if study.refine:  # rounds are dealt one by one (_run_refine)
        if not args.quiet:
            _say(f"sweep.run: {study.name}: {_refine_text(study)}; on {size} "
                 f"rank{'s' if size > 1 else ''}", file=sys.stderr)
        warm_up()
        return [common] * size, study
    n = study.n_cells
    done = parts.done_cells()
    chunk_size = args.chunk_size or grid.default_chunk_size(n - len(done), size)
    dealt = grid.plan(n, done, chunk_size, size, args.seed)
    if not args.quiet:
        _say(f"sweep.run: {study.name}: {n} cells ({_shape_text(study)}) on {size} "
             f"rank{'s' if size > 1 else ''}, chunks of {chunk_size}", file=sys.stderr)
        if len(done):
            _say(f"sweep.run: resuming: {len(done)} cells already done in {parts.directory}",
                 file=sys.stderr)
    warm_up()  # rank 0 compiles (or loads the cache) before the others start
    return [{**common, "done": len(done), "chunks": dealt[rank]} for rank in range(size)], study


def _summary(study, arrays, wall, stats, quiet, size):
    """Counts of outcomes, failed cells with their coordinates, balance of the ranks."""
    outcome, status = arrays["outcome"], arrays["status"]
    failed = np.flatnonzero(outcome == codes.FAILED)
    if not quiet:
        counts = ", ".join(f"{int(np.sum(outcome == code))} {name.replace('_', ' ')}"
                           for code, name in zip(*cf.OUTCOME_FLAGS))
        _say(f"sweep.run: wrote {study.output}: {study.n_cells} cells in {wall:.1f} s on "
             f"{size} rank{'s' if size > 1 else ''}; {counts}")
        if size > 1:
            busy = ", ".join(f"rank {r}: {stats[r][0]} cells {stats[r][1]:.1f} s"
                             for r in sorted(stats))
            _say(f"sweep.run: busy time per rank: {busy}")
    if failed.size:
        _say(f"sweep.run: {failed.size} cell{'s' if failed.size > 1 else ''} failed "
             "(outcome = -1, see `status`):", file=sys.stderr)
        for index in failed[:MAX_LISTED]:
            where = ", ".join(f"{k}={v!r}" for k, v in grid.cell_coords(study, index).items())
            _say(f"  cell {index} ({where}): {codes.STATUS_NAMES[status[index]]}",
                 file=sys.stderr)
        if failed.size > MAX_LISTED:
            _say(f"  ... and {failed.size - MAX_LISTED} more", file=sys.stderr)


def _import_xarray():
    import xarray  # noqa: F401  (for the merge, while rank 0 waits for the others)


def _refine_summary(study, brackets, wall, stats, quiet, size):
    """Counts of the brackets, simulations against a dense grid, lines that failed."""
    k, _ = refine.refined_axis(study)
    first_cells = refine.coarse_cells(study)[:, 0]
    if not quiet:
        counts = ", ".join(f"{int(np.sum(brackets.flag == code))} {name.replace('_', ' ')}"
                           for code, name in enumerate(refine.BRACKET_NAMES))
        _say(f"sweep.run: wrote {study.output}: {brackets.flag.size} lines in "
             f"{brackets.rounds} rounds, {int(brackets.simulations.sum())} simulations (at "
             f"most {refine.max_simulations(study)}; a grid of the same resolution: "
             f"{refine.dense_simulations(study)}) in {wall:.1f} s on {size} "
             f"rank{'s' if size > 1 else ''}; {counts}")
        if size > 1:
            busy = ", ".join(f"rank {r}: {stats[r][0]} cells {stats[r][1]:.1f} s"
                             for r in sorted(stats))
            _say(f"sweep.run: busy time per rank: {busy}")
    failed = np.flatnonzero(brackets.flag == refine.FAILED)
    if failed.size:
        _say(f"sweep.run: a simulation failed on {failed.size} line"
             f"{'s' if failed.size > 1 else ''}; bisection stopped there (bracket = "
             "simulation_failed):", file=sys.stderr)
        for line in failed[:MAX_LISTED]:
            coords = grid.cell_coords(study, first_cells[line])
            coords.pop(study.dims[k].name)
            where = ", ".join(f"{key}={v!r}" for key, v in coords.items())
            _say(f"  line {line} ({where}): bracket [{brackets.lower[line]!r}, "
                 f"{brackets.upper[line]!r}]", file=sys.stderr)
        if failed.size > MAX_LISTED:
            _say(f"  ... and {failed.size - MAX_LISTED} more", file=sys.stderr)


def _run_refine(comm, args, study, parts_dir, t_start):
    """The rounds of a refine study: rank 0 plans and merges each one, every rank computes."""
    rank, size = comm.Get_rank(), comm.Get_size()
    if rank != 0:
        while (plan := mpi.distribute(comm)) is not None:
            mpi.work(comm, plan["study"], plan["chunks"], store=store.PartStore(plan["parts"]))
        mpi.barrier(comm)
        return EXIT_OK
    stats = {}

    def evaluate(index, round_study):
        parts = store.PartStore(store.round_dir(parts_dir, index))
        parts.prepare(round_study, discard=True)  # the study's fingerprint guards the folder
        n, done = round_study.n_cells, parts.done_cells()
        chunk_size = args.chunk_size or grid.default_chunk_size(n - len(done), size)
        dealt = grid.plan(n, done, chunk_size, size, args.seed)
        if len(done) and not args.quiet:
            _say(f"sweep.run: resuming round {index}: {len(done)} of {n} cells already done "
                 f"in {parts.directory}", file=sys.stderr)
        mpi.distribute(comm, [{"study": round_study, "parts": str(parts.directory),
                               "chunks": chunks} for chunks in dealt])
        progress = Progress(n, len(done), quiet=args.quiet, prefix=f"sweep.run: round {index}")
        _, busy = mpi.work(comm, round_study, dealt[0], store=parts, progress=progress,
                           on_idle=_import_xarray)
        progress.close()
        for r, (cells, seconds) in busy.items():
            before = stats.get(r, (0, 0.0))
            stats[r] = (before[0] + cells, before[1] + seconds)
        return parts.merge(n)["overturned"]

    brackets = refine.bisect(study, evaluate)
    mpi.distribute(comm, [None] * size)
    command = " ".join(["python -m sweep.run", *args.argv])
    ds = cf.refine_dataset(study, refine.arrays(brackets), rounds=brackets.rounds,
                           history=f"{command} ({size} ranks)")
    store.write_netcdf(ds, study.output)
    store.PartStore(parts_dir).remove()
    _refine_summary(study, brackets, time.perf_counter() - t_start, stats, args.quiet, size)
    mpi.barrier(comm)
    return EXIT_OK


def _run(comm, args):
    rank, size = comm.Get_rank(), comm.Get_size()
    t_start = time.perf_counter()
    warm = False
    if rank == 0:
        plans, study = _plan(comm, args)
    else:  # while rank 0 checks the study: load the kernel if it is cached, else numba only
        from .runner.cells import kernel_cached, warm_up
        warm = kernel_cached()
        if warm:
            warm_up()
        else:
            import kernels.driver  # noqa: F401
        plans, study = None, None
    plan = mpi.distribute(comm, plans)
    if plan["exit"] is not None:
        return plan["exit"]
    if study is None:
        study = load_study(plan["source"], text=plan["text"], output=plan["output"],
                           check_cells=False)
        if not warm:
            warm_up()  # loads what rank 0 compiled into the cache
    if study.refine:
        return _run_refine(comm, args, study, plan["parts"], t_start)
    parts = store.PartStore(plan["parts"])
    progress = Progress(study.n_cells, plan["done"], quiet=args.quiet) if rank == 0 else None
    _, stats = mpi.work(comm, study, plan["chunks"], store=parts, progress=progress,
                        on_idle=_import_xarray)
    if rank == 0:
        progress.close()
        arrays = parts.merge(study.n_cells)
        command = " ".join(["python -m sweep.run", *args.argv])
        ds = cf.to_dataset(study, arrays, history=f"{command} ({size} ranks)")
        store.write_netcdf(ds, study.output)
        parts.remove()
        _summary(study, arrays, time.perf_counter() - t_start, stats, args.quiet, size)
    mpi.barrier(comm)
    return EXIT_OK


def _positive(text):
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be >= 1, got {value}")
    return value


def parse_args(argv=None):
    parser = argparse.ArgumentParser(
        prog="python -m sweep.run",
        description="Run a study (a base scene and axes to vary) into one netCDF dataset. "
                    "Under mpiexec the cells are shared by the ranks; a killed run resumes "
                    "from its part files when started again.")
    parser.add_argument("study", help="study file (YAML)")
    parser.add_argument("--dry-run", action="store_true",
                        help="check the study, print the cell count and an estimated run time")
    parser.add_argument("--force", action="store_true",
                        help="overwrite an existing result (and discard stale part files)")
    parser.add_argument("--quiet", action="store_true", help="no progress and no summary")
    parser.add_argument("--chunk-size", type=_positive, default=None, metavar="N",
                        help="cells per chunk (part file); default: about 16 chunks per rank, "
                             f"at most {grid.MAX_CHUNK} cells")
    parser.add_argument("--seed", type=int, default=grid.DEFAULT_SEED, metavar="N",
                        help="seed of the shuffled order of the cells (default %(default)s)")
    parser.add_argument("-o", "--output", default=None, metavar="PATH",
                        help="output file (default: the study's output)")
    args = parser.parse_args(argv)
    args.argv = list(sys.argv[1:] if argv is None else argv)
    return args


def _first_process(environ=None):
    environ = os.environ if environ is None else environ
    return all(environ.get(v, "0") == "0" for v in mpi.RANK_VARS)


def main(argv=None):
    """Entry point; returns the exit status (0 ok, 1 error, 2 bad input or refused)."""
    args = parse_args(argv)
    try:
        comm = mpi.world()
    except mpi.LauncherMismatch as err:
        if _first_process():
            _say(f"sweep.run: error: {err}", file=sys.stderr)
        return EXIT_INPUT
    with mpi.abort_on_exception(comm):
        return _run(comm, args)


def run_study(study, *, chunk_size=None, seed=grid.DEFAULT_SEED, progress=False):
    """Run a study in this process and return its Dataset (nothing is written).

    Parameters
    ----------
    study : str, Path, dict or Study
        A study file or a dict of the same schema (``output`` is not used).
    chunk_size : int, optional
        Cells per compiled call; default as ``sweep.run``.
    seed : int
        Seed of the order of the cells (the results do not depend on it).
    progress : bool
        Show a progress bar (or log lines).

    Returns
    -------
    xarray.Dataset
        The dataset of DESIGN.md section 6, as ``python -m sweep.run`` writes it; for a
        study with ``refine``, its boundaries (``cf.refine_dataset``).

    Raises
    ------
    FileProblems
        Every problem of the study, with dotted paths.
    """
    study = load_study(study)
    history = f"sweep.run_study({study.source or study.name!r})"

    def run(cells_study, prefix="sweep.run_study"):
        n = cells_study.n_cells
        chunks = grid.plan(n, [], chunk_size or grid.default_chunk_size(n, 1), 1, seed)[0]
        shown = Progress(n, quiet=not progress, prefix=prefix)
        kept, _ = mpi.work(mpi.SerialComm(), cells_study, chunks, progress=shown)
        shown.close()
        return store.merge(kept, n)

    if study.refine:
        brackets = refine.bisect(study, lambda index, round_study: run(
            round_study, f"sweep.run_study: round {index}")["overturned"])
        return cf.refine_dataset(study, refine.arrays(brackets), rounds=brackets.rounds,
                                 history=history)
    return cf.to_dataset(study, run(study), history=history)


if __name__ == "__main__":
    sys.exit(main())
