"""A study on the ranks: rank 0 plans, every rank computes its chunks, rank 0 merges.

Rank 0 reads and checks the study and its output path (every problem at once, exit status 2,
nothing written), takes the output's lock for the whole run (``runner.lock``: a second run on
the same output is refused), removes what killed runs left, prepares the part files (resuming
from those of a killed run of the same inputs) and deals the chunks; every rank computes and
writes its parts; rank 0 checks every part against the manifest and merges them into the
dataset.  A study with ``refine:`` runs in rounds (``runner.refine``): rank 0 deals each
round's cells the same way, merges the round and decides the next one.  Ctrl-C ends every
rank with one line saying what is saved (exit status 130).  :func:`run_study` does the same in
one process and returns the Dataset (``sweep.run_study`` in a notebook).
"""
import functools
import signal
import sys
import threading
import time
from contextlib import contextmanager

from .. import cf
from ..io.files import output_problem
from ..io.exits import EXIT_BAD_INPUT, EXIT_INTERRUPTED, EXIT_OK
from ..io.problems import FileProblems, Problem
from ..io.study_schema import load_study
from . import fingerprint, grid, mpi, refine, store
from .lock import LockHeld, OutputLock
from .progress import Progress
from .summary import dry_run, refine_summary, refine_text, say, shape_text, summary


def _stop(comm, code):
    """Plans telling every rank to end with ``code``."""
    return [{"exit": code}] * comm.Get_size()


def _problems(args, err):
    """Print a file's problems as the other commands do (nothing was run)."""
    say(f"sweep.run: {args.study}: {len(err.problems)} problem"
        f"{'s' if len(err.problems) != 1 else ''}; nothing was run:", file=sys.stderr)
    for line in str(err).splitlines():
        say(f"  {line}", file=sys.stderr)


def _load(args):
    """The checked study and its writable output, or :class:`FileProblems`."""
    study = load_study(args.study, output=args.output, max_cells=args.max_cells)
    why = output_problem(study.output)
    if why is not None:
        raise FileProblems([Problem("output" if args.output is None else "-o/--output",
                                    str(study.output), why)], args.study)
    return study


def _open(study, args, parts):
    """Take the output's lock and make the output and parts ready (rank 0).

    Returns the lock, or None when the output is already the dataset of these very inputs
    (a run killed after writing it only had its clean-up to finish: done here).

    Raises
    ------
    LockHeld, store.StoreError
    """
    study.output.parent.mkdir(parents=True, exist_ok=True)
    lock = OutputLock(study.output, command=_command(args, None)).acquire()
    try:
        removed = store.clean_leftovers(study.output)
        if removed and not args.quiet:
            say(f"sweep.run: removed what a killed run left: {', '.join(removed)}",
                file=sys.stderr)
        stamp = fingerprint.combined(fingerprint.components(study))
        if not args.force and store.finished_earlier(study.output, stamp):
            ours = parts.manifest_stamp() == stamp  # a run killed before its clean-up ended
            if ours:
                parts.remove()
            say(f"sweep.run: {study.output} is already complete for these inputs"
                + ("; removed the part files its run left" if ours else "")
                + "; nothing to do (--force computes it again)", file=sys.stderr)
            lock.release()
            return None
        store.check_output(study.output, args.force)
        parts.prepare(study, discard=args.force)
    except BaseException:
        lock.release()
        raise
    return lock


def _plan(comm, args):
    """Rank 0: check the study, the output and the parts; the plan of every rank, the study
    and the output's lock."""
    size = comm.Get_size()
    try:
        study = _load(args)
    except FileProblems as err:
        _problems(args, err)
        return _stop(comm, EXIT_BAD_INPUT), None, None
    parts = store.PartStore(store.parts_dir(study.output))
    if args.dry_run:
        done = parts.done_cells() if parts.directory.is_dir() else []
        dry_run(study, size, args.seed, done)
        return _stop(comm, EXIT_OK), None, None
    try:
        lock = _open(study, args, parts)
    except (LockHeld, store.StoreError, OSError) as err:
        say(f"sweep.run: error: {err}", file=sys.stderr)
        return _stop(comm, EXIT_BAD_INPUT), None, None
    if lock is None:
        return _stop(comm, EXIT_OK), None, None
    from .cells import warm_up
    common = {"exit": None, "text": study.text, "source": study.source,
              "output": str(study.output), "parts": str(parts.directory),
              "stamp": parts.stamp}
    if study.refine:  # rounds are dealt one by one (_run_refine)
        if not args.quiet:
            say(f"sweep.run: {study.name}: {refine_text(study)}; on {size} "
                f"rank{'s' if size > 1 else ''}", file=sys.stderr)
        warm_up()
        return [common] * size, study, lock
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
    plans = [{**common, "done": len(done), "chunks": dealt[rank], "dealt": dealt if rank == 0
              else None} for rank in range(size)]
    return plans, study, lock


def _command(args, size):
    """The command line, for the dataset's ``history`` attribute and the lock's holder."""
    ranks = "" if size is None else f" ({size} ranks)"
    return f"{' '.join(['python -m sweep.run', *args.argv])}{ranks}"


def _import_xarray():
    import xarray  # noqa: F401  (for the merge, while rank 0 waits for the others)


def _watch(comm, args, dealt):
    """Rank 0's watch over the other ranks (none with one rank or ``--rank-timeout 0``)."""
    if comm.Get_size() == 1 or not args.rank_timeout:
        return None
    return mpi.Watch(dealt, floor=args.rank_timeout)


def _chunk_runner(args):
    from .cells import run_chunk
    return functools.partial(run_chunk, budget=args.cell_budget)


def _write(ds, study, stamp, parts):
    """The dataset, stamped with its inputs' fingerprint, then the parts removed."""
    ds.attrs[store.FINGERPRINT_ATTR] = stamp
    store.write_netcdf(ds, study.output)
    parts.remove()


def _run_refine(comm, args, study, plan, t_start):
    """The rounds of a refine study: rank 0 plans and merges each one, every rank computes."""
    rank, size = comm.Get_rank(), comm.Get_size()
    run_chunk = _chunk_runner(args)
    if rank != 0:
        while (round_plan := mpi.distribute(comm)) is not None:
            mpi.work(comm, round_plan["study"], round_plan["chunks"], run_chunk=run_chunk,
                     store=store.PartStore(round_plan["parts"], round_plan["stamp"]))
        mpi.barrier(comm)
        return EXIT_OK
    stats = {}

    def evaluate(index, round_study):
        parts = store.PartStore(store.round_dir(plan["parts"], index))
        stamp = parts.prepare(round_study, discard=True)  # the fingerprint guards the folder
        n, done = round_study.n_cells, parts.done_cells()
        chunk_size = args.chunk_size or grid.default_chunk_size(n - len(done), size)
        dealt = grid.plan(n, done, chunk_size, size, args.seed)
        if len(done) and not args.quiet:
            say(f"sweep.run: resuming round {index}: {len(done)} of {n} cells already done "
                f"in {parts.directory}", file=sys.stderr)
        mpi.distribute(comm, [{"study": round_study, "parts": str(parts.directory),
                               "stamp": stamp, "chunks": chunks} for chunks in dealt])
        progress = Progress(n, len(done), quiet=args.quiet, prefix=f"sweep.run: round {index}")
        _, busy = mpi.work(comm, round_study, dealt[0], store=parts, progress=progress,
                           run_chunk=run_chunk, on_idle=_import_xarray,
                           watch=_watch(comm, args, dealt))
        progress.close()
        for r, (cells, seconds) in busy.items():
            before = stats.get(r, (0, 0.0))
            stats[r] = (before[0] + cells, before[1] + seconds)
        return parts.merge(n)["overturned"]

    brackets = refine.bisect(study, evaluate)
    mpi.distribute(comm, [None] * size)
    ds = cf.refine_dataset(study, refine.arrays(brackets), rounds=brackets.rounds,
                           history=_command(args, size))
    _write(ds, study, plan["stamp"], store.PartStore(plan["parts"]))
    refine_summary(study, brackets, time.perf_counter() - t_start, stats, args.quiet, size)
    mpi.barrier(comm)
    return EXIT_OK


class _State:
    """What one rank knows of its run so far: for Ctrl-C's line and the lock's release."""

    study = plan = lock = None


def _interrupted(state, args):
    """Rank 0's one line after Ctrl-C: what is saved and how to resume."""
    plan = state.plan or {}
    if state.study is None or plan.get("exit", 0) is not None:
        say("sweep.run: interrupted before any cell ran; nothing was written", file=sys.stderr)
        return
    parts = store.PartStore(plan["parts"])
    if state.study.refine:
        saved = f"the finished rounds and chunks are saved in {parts.directory}"
    else:
        saved = (f"{len(parts.done_cells())} of {state.study.n_cells} cells are saved in "
                 f"{parts.directory}")
    say(f"sweep.run: interrupted: {saved}; run the same command again to resume "
        f"({_command(args, None)})", file=sys.stderr)


@contextmanager
def _sigint_ignored():
    """Ignore Ctrl-C for a moment (main thread only; the handler is restored after)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


def run(comm, args):
    """Every rank's part of ``python -m sweep.run`` (``args`` of ``runner.command.parse_args``);
    returns the exit status: 0 done, 2 bad input or refused, 130 interrupted."""
    state = _State()
    try:
        return _run(comm, args, state)
    except KeyboardInterrupt:
        if comm.Get_rank() == 0:
            with _sigint_ignored():  # a second Ctrl-C must not cut the line
                _interrupted(state, args)
        return EXIT_INTERRUPTED
    finally:
        if state.lock is not None:
            state.lock.release()


def _run(comm, args, state):
    """The run itself, filling ``state``; returns the exit status."""
    rank, size = comm.Get_rank(), comm.Get_size()
    t_start = time.perf_counter()
    warm = False
    if rank == 0:
        plans, state.study, state.lock = _plan(comm, args)
    else:  # while rank 0 checks the study: load the kernel if it is cached, else numba only
        from .cells import kernel_cached, warm_up
        warm = kernel_cached()
        if warm:
            warm_up()
        else:
            import kernels.driver  # noqa: F401
        plans = None
    plan = state.plan = mpi.distribute(comm, plans)
    if plan["exit"] is not None:
        return plan["exit"]
    if state.study is None:
        state.study = load_study(plan["source"], text=plan["text"], output=plan["output"],
                                 check_cells=False, max_cells=None)
        if not warm:
            warm_up()  # loads what rank 0 compiled into the cache
    study = state.study
    if study.refine:
        return _run_refine(comm, args, study, plan, t_start)
    parts = store.PartStore(plan["parts"], plan["stamp"])
    progress = Progress(study.n_cells, plan["done"], quiet=args.quiet) if rank == 0 else None
    _, stats = mpi.work(comm, study, plan["chunks"], store=parts, progress=progress,
                        run_chunk=_chunk_runner(args), on_idle=_import_xarray,
                        watch=_watch(comm, args, plan["dealt"]) if rank == 0 else None)
    if rank == 0:
        progress.close()
        arrays = parts.merge(study.n_cells)
        _write(cf.to_dataset(study, arrays, history=_command(args, size)), study,
               plan["stamp"], parts)
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
