"""A study on the ranks: rank 0 plans, every rank computes its chunks, rank 0 merges.

Rank 0 reads and checks the study and its output path (every problem at once, nothing
written), takes the output's lock for the whole run (``runner.lock``: a second run on the same
output is refused), removes what killed runs left, prepares the part files (resuming from
those of a killed run of the same inputs) and tells every rank what to run (a :class:`Start`
plan, or :class:`Stop`).  The cells then run in rounds (:class:`Round`): one for a grid study,
one per bisection step for a study with ``refine:`` (``runner.refine``); rank 0 deals each
round's chunks, every rank computes and writes its parts, rank 0 checks every part against the
manifest and merges them.  :func:`run_file` is what ``python -m sweep.run`` and the site
estimate run; it ends by raising: :class:`Refused`, ``KeyboardInterrupt`` after Ctrl-C (with
one line saying what is saved) or ``mpi.JobFailure``; :func:`run_status` turns that into an
exit status.  :func:`run_study` runs the same rounds in one process with the serial
communicator, keeps the results in memory and returns the Dataset (``sweep.run_study`` in a
notebook).
"""
import sys
import time
import warnings
from collections import namedtuple

from .. import cf, netcdf
from ..io.exits import EXIT_BAD_INPUT, EXIT_FAILED, EXIT_INTERRUPTED, EXIT_OK
from ..io.files import output_problem
from ..io.problems import FileProblems, Problem
from . import fingerprint, grid, interrupt, mpi, rank_checks, refine, store
from .cell_checks import cell_problems, load_study
from .lock import LockHeld, OutputLock
from .options import RunOptions
from .progress import Progress
from .summary import (SUMMARY_VARIABLES, Timeline, dry_run, refine_summary, refine_text, say,
                      shape_text, summary)

# What rank 0 hands every rank (mpi.distribute)
Stop = namedtuple("Stop", "refused")
Stop.__doc__ = """The job ends before any cell runs: ``refused`` (a bad study or output, a held
lock: rank 0 said why), or done (a dry run, a result already complete for these inputs)."""

Start = namedtuple("Start", "text source output parts stamp")
Start.__doc__ = """A run: the study (its file's ``text`` and ``source``, its ``output``), the
folder of its ``parts`` and the fingerprint ``stamp`` of its inputs."""

Round = namedtuple("Round", "study parts stamp chunks")
Round.__doc__ = """The cells of one round, sent to every rank: ``study`` (None: the run's own
study; else a refine round's point study), the ``parts`` folder and ``stamp`` its part files
are written with, and the round's ``chunks`` (``grid.Chunks``), which rank 0 deals one at a
time (``mpi.Dealer``).  None instead of a Round ends the rounds."""

Deal = namedtuple("Deal", "done chunks")
Deal.__doc__ = """Rank 0's plan of a round: the cells ``done`` by an earlier run and the
``chunks`` of the others (``grid.plan``)."""


class Refused(Exception):
    """The study, its output or the output's lock refused the run; rank 0 said why and nothing
    was run.  Raised on every rank."""


def _problems(path, err):
    """Print a file's problems as the other commands do (nothing was run)."""
    say(f"sweep.run: {path}: {len(err.problems)} problem"
        f"{'s' if len(err.problems) != 1 else ''}; nothing was run:", file=sys.stderr)
    for line in str(err).splitlines():
        say(f"  {line}", file=sys.stderr)


def _study(source, options, *, text=None, output=None, cells=None):
    """The study as every rank loads it (``cell_checks.load_study``: the run's output and
    limit on cells); its cells' scenes checked with ``cells`` (rank 0), else not."""
    return load_study(source, text=text, output=output or options.output,
                      max_cells=options.max_cells, check_cells=cells is not None, cells=cells)


def _load(comm, path, options):
    """The checked study and its writable output, or :class:`FileProblems`; the cells'
    checks shared by the ranks (``rank_checks``)."""
    study = _study(path, options, cells=rank_checks.shared(comm) if comm.Get_size() > 1
                   else cell_problems)
    why = output_problem(study.output)
    if why is not None:
        raise FileProblems([Problem("output" if options.output is None else "-o/--output",
                                    str(study.output), why)], path)
    return study


def _backend_problem(study, options):
    """Why the study's cells cannot run where they are asked to (on CUDA), or None."""
    if options.backend_of(study) != "cuda":
        return None
    from kernels import gpu
    return gpu.unavailable()


def _backend_refused(path, study, options):
    """Say why the study's cells cannot run on the CUDA backend asked for (True), or False."""
    why = _backend_problem(study, options)
    if why is None:
        return False
    said = f"--backend cuda: {why}" if options.backend else \
        f"{path}: run.backend: {why} (got: 'cuda')"
    say(f"sweep.run: {said}; nothing was run", file=sys.stderr)
    return True


def _say_gpu_declined(study, options, name="sweep.run"):
    """Say in one line that the GPU asked for is left alone: the study is too small."""
    if options.gpu_declined(study):
        say(f"{name}: {study.n_cells:,} cells run on the CPU: fewer than "
            f"{grid.MIN_GPU_CELLS:,} are too few for the GPU to win (docs/gpu.md)",
            file=sys.stderr)


def _open(study, options, parts):
    """Take the output's lock and make the output and parts ready (rank 0).

    Returns the lock, or None when the output is already the dataset of these very inputs
    (a run killed after writing it only had its clean-up to finish: done here).

    Raises
    ------
    LockHeld, store.StoreError
    """
    study.output.parent.mkdir(parents=True, exist_ok=True)
    lock = OutputLock(study.output, command=options.command_line()).acquire()
    try:
        removed = store.clean_leftovers(study.output)
        if removed and not options.quiet:
            say(f"sweep.run: removed what a killed run left: {', '.join(removed)}",
                file=sys.stderr)
        stamp = fingerprint.combined(fingerprint.components(study))
        if not options.force and store.finished_earlier(study.output, stamp):
            ours = parts.manifest_stamp() == stamp  # a run killed before its clean-up ended
            if ours:
                parts.remove()
            say(f"sweep.run: {study.output} is already complete for these inputs"
                + ("; removed the part files its run left" if ours else "")
                + "; nothing to do (--force computes it again)", file=sys.stderr)
            lock.release()
            return None
        store.check_output(study.output, options.force)
        parts.prepare(study, discard=options.force)
    except BaseException:
        lock.release()
        raise
    return lock


def _deal(n, done, options, size, backend):
    """The :class:`Deal` of ``n`` cells less those ``done`` to ``size`` ranks running on
    ``backend``."""
    chunk_size = options.chunk_size or grid.default_chunk_size(n - len(done), size, backend)
    return Deal(done, grid.plan(n, done, chunk_size, options.seed))


def _plan(comm, path, options):
    """Rank 0: check the study, the output and the parts.

    Returns the plan of every rank (:class:`Start` or :class:`Stop`), the study, the output's
    lock and, for a grid study, the :class:`Deal` of its cells (said before the kernel is
    loaded).
    """
    size = comm.Get_size()
    try:
        study = _load(comm, path, options)
    except FileProblems as err:
        _problems(path, err)
        return [Stop(refused=True)] * size, None, None, None
    if _backend_refused(path, study, options):
        return [Stop(refused=True)] * size, None, None, None
    _say_gpu_declined(study, options)
    parts = store.PartStore(store.parts_dir(study.output))
    if options.dry_run:
        done = parts.done_cells() if parts.directory.is_dir() else []
        dry_run(study, size, options.seed, done)
        return [Stop(refused=False)] * size, None, None, None
    try:
        lock = _open(study, options, parts)
    except (LockHeld, store.StoreError, OSError) as err:
        say(f"sweep.run: error: {err}", file=sys.stderr)
        return [Stop(refused=True)] * size, None, None, None
    if lock is None:
        return [Stop(refused=False)] * size, None, None, None
    start = Start(study.text, study.source, str(study.output), str(parts.directory), parts.stamp)
    ranks = f"{size} rank{'s' if size > 1 else ''}"
    first = None
    if study.refine:  # rounds are dealt one by one (_Rounds)
        if not options.quiet:
            say(f"sweep.run: {study.name}: {refine_text(study)}; on {ranks}", file=sys.stderr)
    else:
        n = study.n_cells
        first = _deal(n, parts.done_cells(), options, size, options.runs_on(study))
        if not options.quiet:
            say(f"sweep.run: {study.name}: {n} cells ({shape_text(study)}) on {ranks}, chunks "
                f"of {first.chunks.chunk_size}", file=sys.stderr)
            if len(first.done):
                say(f"sweep.run: resuming: {len(first.done)} cells already done in "
                    f"{parts.directory}", file=sys.stderr)
    return [start] * size, study, lock, first


def _load_rest(others):
    """What rank 0 loads while the ``others`` ranks compute their first chunks: the kernel
    (when it was compiled before the run) and, with other ranks, xarray for the merge (alone,
    rank 0 imports it when it merges, after its chunks)."""
    from .cells import warm_up

    warm_up()
    if others:
        import xarray  # noqa: F401


def _watch(comm, options):
    """Rank 0's watch over the other ranks (none with one rank or ``--rank-timeout 0``)."""
    if comm.Get_size() == 1 or not options.rank_timeout:
        return None
    return mpi.Watch(comm.Get_size(), floor=options.rank_timeout)


def _chunk_runner(study, options):
    """This rank's ``run_chunk`` for every round of ``study`` (its records kept between)."""
    from .cells import ChunkRunner
    return ChunkRunner(budget=options.cell_budget, backend=options.runs_on(study))


class _Rounds:
    """Rank 0's part of each round: deal its cells to the ranks, compute rank 0's chunks,
    follow the others, merge; ``stats`` adds up every rank's :class:`mpi.RankDone`.

    Parameters
    ----------
    comm : communicator or SerialComm
    study : Study
        The run's study.
    options : RunOptions
    name : str
        Start of the progress lines (``sweep.run``, ``sweep.run_study``).
    parts : PartStore, optional
        The run's part files, prepared (a refine study's rounds each get a folder in it);
        None: the results are kept in memory (one rank, nothing written).
    first : Deal, optional
        The dealing of a grid study's cells, made while planning.
    """

    def __init__(self, comm, study, options, name, parts=None, first=None):
        self.comm, self.study, self.options, self.name = comm, study, options, name
        self.parts, self.first = parts, first
        self.before = lambda: _load_rest(comm.Get_size() - 1)  # before rank 0's first chunk
        self.stats = {}
        self.run_chunk = _chunk_runner(study, options)

    def _round_parts(self, index, study):
        """The part files of round ``index`` (None: a grid study's) and their fingerprint."""
        if self.parts is None:
            return None, None
        if index is None:
            return self.parts, self.parts.stamp
        parts = store.PartStore(store.round_dir(self.parts.directory, index))
        return parts, parts.prepare(study, discard=True)  # the fingerprint guards the folder

    def __call__(self, index, study):
        """The arrays of every cell of ``study``, in cell order: the run's grid (``index``
        None) or refine round ``index`` (``refine.bisect``'s ``evaluate``)."""
        comm, options = self.comm, self.options
        n, size = study.n_cells, comm.Get_size()
        parts, stamp = self._round_parts(index, study)
        if index is None and self.first is not None:
            deal = self.first
        else:
            deal = _deal(n, () if parts is None else parts.done_cells(), options, size,
                         options.runs_on(self.study))
            if len(deal.done) and not options.quiet:
                say(f"sweep.run: resuming round {index}: {len(deal.done)} of {n} cells "
                    f"already done in {parts.directory}", file=sys.stderr)
        mpi.distribute(comm, [Round(None if study is self.study else study,
                                    None if parts is None else str(parts.directory), stamp,
                                    deal.chunks)] * size)
        progress = Progress(n, len(deal.done), quiet=options.quiet,
                            prefix=self.name if index is None else f"{self.name}: round {index}")
        before, self.before = self.before, None
        kept, stats = mpi.work(comm, study, deal.chunks, store=parts, progress=progress,
                               run_chunk=self.run_chunk, before=before,
                               watch=_watch(comm, options))
        progress.close()
        for rank, done in stats.items():
            self.stats[rank] = _added(self.stats.get(rank), done)
        return store.merge(kept, n) if parts is None else parts.merge(n)


def _added(total, done):
    """Two :class:`mpi.RankDone` of one rank added up (``total`` may be None)."""
    if total is None:
        return done
    times = [t for t in (total.started, done.started) if t is not None]
    ends = [t for t in (total.ended, done.ended) if t is not None]
    return mpi.RankDone(total.cells + done.cells, total.seconds + done.seconds,
                        min(times, default=None), max(ends, default=None))


def _follow(comm, study, options):
    """A rank other than 0: compute the chunks of every round rank 0 deals, until it ends."""
    run_chunk = _chunk_runner(study, options)
    while (plan := mpi.distribute(comm)) is not None:
        mpi.work(comm, study if plan.study is None else plan.study, plan.chunks,
                 run_chunk=run_chunk, store=store.PartStore(plan.parts, plan.stamp))


def _compute(comm, study, options, rounds=None):
    """Every cell of ``study`` on the ranks: one round, or a refine study's rounds.

    ``rounds`` is rank 0's :class:`_Rounds`.  Returns, on rank 0, the arrays of every cell
    (``cf.to_dataset``: a dict in memory, or ``merged.MergedParts`` reading the part files a
    group of variables at a time) or a refine study's ``refine.Brackets``; None on the other
    ranks.
    """
    if comm.Get_rank() != 0:
        _follow(comm, study, options)
        return None
    if study.refine:
        result = refine.bisect(study, lambda index, cells: rounds(index, cells)["overturned"])
    else:
        result = rounds(None, study)
    mpi.distribute(comm, [None] * comm.Get_size())  # the rounds are over
    return result


def _dataset(study, result, history):
    """The dataset of :func:`_compute`'s result."""
    if study.refine:
        return cf.refine_dataset(study, refine.arrays(result), rounds=result.rounds,
                                 history=history)
    return cf.to_dataset(study, result, history=history)


def _write(study, result, history, stamp, parts):
    """The dataset of :func:`_compute`'s result, stamped with its inputs' fingerprint, then
    the parts removed.  A grid study's is written from its part files a group of variables at
    a time (``store.write_merged``); a refine study's boundaries are few, in memory."""
    stamped = {store.FINGERPRINT_ATTR: stamp}
    if study.refine:
        ds = _dataset(study, result, history)
        ds.attrs.update(stamped)
        netcdf.write_netcdf(ds, study.output)
    else:
        store.write_merged(study, result, study.output, history=history, attrs=stamped)
    parts.remove()


class _State:
    """What one rank knows of its run so far: for Ctrl-C's line and the lock's release."""

    study = plan = lock = None


def _interrupted(state, options):
    """Rank 0's one line after Ctrl-C: what is saved and how to resume."""
    if state.study is None or not isinstance(state.plan, Start):
        say("sweep.run: interrupted before any cell ran; nothing was written", file=sys.stderr)
        return
    parts = store.PartStore(state.plan.parts)
    if state.study.refine:
        saved = f"the finished rounds and chunks are saved in {parts.directory}"
    else:
        saved = (f"{len(parts.done_cells())} of {state.study.n_cells} cells are saved in "
                 f"{parts.directory}")
    say(f"sweep.run: interrupted: {saved}; run the same command again to resume "
        f"({options.command_line()})", file=sys.stderr)


def _one_line(message, category, filename, lineno, file=None, line=None):
    """A warning as one line of the run's log, without the source line."""
    say(f"sweep.run: warning: {message}", file=sys.stderr)


def run_file(comm, path, options):
    """Every rank's part of running the study file at ``path`` into its output, as
    ``python -m sweep.run`` does (docs/design.md section 7).

    Parameters
    ----------
    comm : communicator or SerialComm
        ``mpi.world()``.
    path : str
        The study file.
    options : RunOptions

    Raises
    ------
    Refused
        The study, its output or the output's lock refused the run (said on stderr).
    KeyboardInterrupt
        Ctrl-C; rank 0 said what is saved and how to resume.
    mpi.JobFailure
        The run failed (said on stderr: in one process here; under MPI the job was aborted).
    """
    ended = None
    try:
        with mpi.abort_on_exception(comm), warnings.catch_warnings():
            warnings.showwarning = _one_line  # cells flagged as they fail: one line each
            try:
                _run_file(comm, path, options)
            except (Refused, KeyboardInterrupt) as err:  # every rank leaves, none aborts
                ended = err
    except mpi.JobFailure as err:  # one process (several ranks were aborted above)
        say(f"sweep.run: error: {err}", file=sys.stderr)
        raise
    if ended is not None:
        raise ended


def run_status(comm, path, options):
    """:func:`run_file`, and the exit status (``io.exits``) of how it ended: what
    ``python -m sweep.run`` and ``python -m sweep.figures`` return."""
    try:
        run_file(comm, path, options)
    except Refused:  # said by rank 0
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:  # rank 0 said what is saved
        mpi.leave_interrupted(comm)
        return EXIT_INTERRUPTED
    except mpi.JobFailure:  # one process: said in words (several ranks abort instead)
        return EXIT_FAILED
    return EXIT_OK


def _run_file(comm, path, options):
    """:func:`run_file` within its guards: the line after Ctrl-C, the lock released."""
    state = _State()
    try:
        with interrupt.remembered():
            _run(comm, path, options, state)
    except KeyboardInterrupt:
        if comm.Get_rank() == 0:
            with interrupt.ignored():  # a second Ctrl-C must not cut the line
                _interrupted(state, options)
        raise
    finally:
        if state.lock is not None:
            state.lock.release()


def _run(comm, path, options, state):
    """The run itself, filling ``state``."""
    from .cells import kernel_cached, warm_up

    rank, size = comm.Get_rank(), comm.Get_size()
    t_start = time.time()
    warm, first = kernel_cached(), None
    if rank == 0:
        plans, state.study, state.lock, first = _plan(comm, path, options)
        if not warm and isinstance(plans[0], Start):
            warm_up()  # rank 0 compiles before the others load the cache; else _load_rest
    else:  # while rank 0 checks the study: load the kernel if it is cached, else numba only
        plans = None
        if warm:
            warm_up()
        else:
            import kernels.driver  # noqa: F401
    plan = state.plan = mpi.distribute(comm, plans)
    while isinstance(plan, rank_checks.Check):  # ranks other than 0: check cells first
        state.study = rank_checks.check_share(comm, plan, lambda source, text, output: _study(
            source, options, text=text, output=output))
        plan = state.plan = mpi.distribute(comm)
    if isinstance(plan, Stop):
        if plan.refused:
            raise Refused(path)
        return
    if state.study is None:
        state.study = _study(plan.source, options, text=plan.text, output=plan.output)
    if rank and not warm:
        warm_up()  # loads what rank 0 compiled into the cache
    study = state.study
    parts = store.PartStore(plan.parts, plan.stamp)
    rounds = _Rounds(comm, study, options, "sweep.run", parts, first) if rank == 0 else None
    result = _compute(comm, study, options, rounds)
    if rank == 0:
        # the summary's variables from the group the write reads first (the parts go in _write)
        said = result if study.refine else {name: result[name] for name in SUMMARY_VARIABLES}
        _write(study, result, options.command_line(size), plan.stamp, parts)
        timeline = Timeline.of(t_start, rounds.stats, time.time())
        if study.refine:
            refine_summary(study, said, timeline, rounds.stats, options.quiet, size)
        else:
            summary(study, said, timeline, rounds.stats, options.quiet, size)
    mpi.barrier(comm)


def run_study(study, *, chunk_size=None, seed=grid.DEFAULT_SEED, progress=False):
    """Run a study in this process and return its Dataset (nothing is written).

    The rounds of ``python -m sweep.run`` on the serial communicator, the results kept in
    memory.

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
        The dataset of docs/design.md section 6, as ``python -m sweep.run`` writes it; for a
        study with ``refine``, its boundaries (``cf.refine_dataset``).

    Raises
    ------
    FileProblems
        Every problem of the study, with dotted paths (``run.backend`` when it asks for CUDA
        and none is usable).
    """
    study = load_study(study)
    options = RunOptions(quiet=not progress, chunk_size=chunk_size, seed=seed)
    why = _backend_problem(study, options)
    if why is not None:
        raise FileProblems([Problem("run.backend", "cuda", why)], study.source)
    _say_gpu_declined(study, options, "sweep.run_study")
    comm = mpi.SerialComm()
    result = _compute(comm, study, options, _Rounds(comm, study, options, "sweep.run_study"))
    return _dataset(study, result, f"sweep.run_study({study.source or study.name!r})")
