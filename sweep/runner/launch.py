"""A study on the ranks: rank 0 plans, every rank computes its chunks, rank 0 merges.

Rank 0 reads and checks the study (every problem at once, exit status 2, nothing written),
prepares the part files (resuming from those of a killed run) and deals the chunks; every rank
computes and writes its parts; rank 0 merges them into the dataset.  A study with ``refine:``
runs in rounds (``runner.refine``): rank 0 deals each round's cells the same way, merges the
round and decides the next one.  :func:`run_study` does the same in one process and returns
the Dataset (``sweep.run_study`` in a notebook).
"""
import sys
import time

from .. import cf
from ..io.problems import EXIT_BAD_INPUT, FileProblems
from ..io.study_schema import load_study
from . import grid, mpi, refine, store
from .progress import Progress
from .summary import dry_run, refine_summary, refine_text, say, shape_text, summary

EXIT_OK = 0


def _stop(comm, code):
    """Plans telling every rank to end with ``code``."""
    return [{"exit": code}] * comm.Get_size()


def _plan(comm, args):
    """Rank 0: check the study, the output and the parts; the plan of every rank."""
    size = comm.Get_size()
    try:
        study = load_study(args.study, output=args.output)
    except FileProblems as err:
        say(f"sweep.run: {args.study}: {len(err.problems)} problem"
             f"{'s' if len(err.problems) != 1 else ''}; nothing was run:", file=sys.stderr)
        for line in str(err).splitlines():
            say(f"  {line}", file=sys.stderr)
        return _stop(comm, EXIT_BAD_INPUT), None
    parts = store.PartStore(store.parts_dir(study.output))
    if args.dry_run:
        done = parts.done_cells() if parts.directory.exists() else []
        dry_run(study, size, args.seed, done)
        return _stop(comm, EXIT_OK), None
    try:
        store.check_output(study.output, args.force)
        parts.prepare(study, discard=args.force)
    except store.StoreError as err:
        say(f"sweep.run: error: {err}", file=sys.stderr)
        return _stop(comm, EXIT_BAD_INPUT), None
    from .cells import warm_up
    common = {"exit": None, "text": study.text, "source": study.source,
              "output": str(study.output), "parts": str(parts.directory)}
    if study.refine:  # rounds are dealt one by one (_run_refine)
        if not args.quiet:
            say(f"sweep.run: {study.name}: {refine_text(study)}; on {size} "
                 f"rank{'s' if size > 1 else ''}", file=sys.stderr)
        warm_up()
        return [common] * size, study
    n = study.n_cells
    done = parts.done_cells()
    chunk_size = args.chunk_size or grid.default_chunk_size(n - len(done), size)
    dealt = grid.plan(n, done, chunk_size, size, args.seed)
    if not args.quiet:
        say(f"sweep.run: {study.name}: {n} cells ({shape_text(study)}) on {size} "
             f"rank{'s' if size > 1 else ''}, chunks of {chunk_size}", file=sys.stderr)
        if len(done):
            say(f"sweep.run: resuming: {len(done)} cells already done in {parts.directory}",
                 file=sys.stderr)
    warm_up()  # rank 0 compiles (or loads the cache) before the others start
    return [{**common, "done": len(done), "chunks": dealt[rank]} for rank in range(size)], study


def _command(args, size):
    """The command line, for the dataset's ``history`` attribute."""
    return f"{' '.join(['python -m sweep.run', *args.argv])} ({size} ranks)"


def _import_xarray():
    import xarray  # noqa: F401  (for the merge, while rank 0 waits for the others)


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
            say(f"sweep.run: resuming round {index}: {len(done)} of {n} cells already done "
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
    ds = cf.refine_dataset(study, refine.arrays(brackets), rounds=brackets.rounds,
                           history=_command(args, size))
    store.write_netcdf(ds, study.output)
    store.PartStore(parts_dir).remove()
    refine_summary(study, brackets, time.perf_counter() - t_start, stats, args.quiet, size)
    mpi.barrier(comm)
    return EXIT_OK


def run(comm, args):
    """Every rank's part of ``python -m sweep.run`` (``args`` of ``sweep.run.parse_args``);
    returns the exit status: 0 done, 2 bad input or refused."""
    rank, size = comm.Get_rank(), comm.Get_size()
    t_start = time.perf_counter()
    warm = False
    if rank == 0:
        plans, study = _plan(comm, args)
    else:  # while rank 0 checks the study: load the kernel if it is cached, else numba only
        from .cells import kernel_cached, warm_up
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
        ds = cf.to_dataset(study, arrays, history=_command(args, size))
        store.write_netcdf(ds, study.output)
        parts.remove()
        summary(study, arrays, time.perf_counter() - t_start, stats, args.quiet, size)
    mpi.barrier(comm)
    return EXIT_OK


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
