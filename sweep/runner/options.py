"""How a study runs: the options of ``python -m sweep.run`` beside its study file.

:class:`RunOptions` is built by the command from its arguments (``runner.command``), by the
site estimate for each of its studies (``probability.site_studies``) and by ``run_study``;
the runner (``runner.launch``) reads it, never an ``argparse`` namespace.
"""
from dataclasses import dataclass

from ..io.study_schema import MAX_CELLS
from . import grid
from .cells import CELL_BUDGET
from .mpi import WATCH_FLOOR

COMMAND = "python -m sweep.run"  # the start of the command line said in history and lock


@dataclass(frozen=True)
class RunOptions:
    """The options of one run of a study (``python -m sweep.run --help`` says each).

    Attributes
    ----------
    output : str or None
        Output file instead of the study's own (``-o``).
    dry_run : bool
        Only check the study and estimate the run time.
    force : bool
        Overwrite an existing result and discard stale part files.
    quiet : bool
        No progress and no summary.
    chunk_size : int or None
        Cells per chunk (part file); None: ``grid.default_chunk_size`` (about
        ``grid.CHUNKS_PER_RANK`` chunks per rank; one per rank on the GPU).
    seed : int
        Seed of the shuffled order of the cells (the results do not depend on it).
    max_cells : int
        Refuse a grid of more cells (0: no limit).
    cell_budget : float
        Wall-time budget of one cell [s] (0: none).
    rank_timeout : float
        Seconds of silence always allowed to a rank before the job aborts (0: no watch).
    backend : str or None
        Where the cells run: ``"cpu"`` or ``"cuda"`` (an NVIDIA GPU per rank,
        ``kernels.cuda_batch``; docs/gpu.md); None: the study's ``run.backend``, else the CPU
        (:meth:`backend_of`).
    argv : tuple of str
        The arguments of the command line, said in the dataset's ``history``, by the output's
        lock and in the line after Ctrl-C (:meth:`command_line`).
    """

    output: str | None = None
    dry_run: bool = False
    force: bool = False
    quiet: bool = False
    chunk_size: int | None = None
    seed: int = grid.DEFAULT_SEED
    max_cells: int = MAX_CELLS
    cell_budget: float = CELL_BUDGET
    rank_timeout: float = WATCH_FLOOR
    backend: str | None = None
    argv: tuple[str, ...] = ()

    def backend_of(self, study):
        """Where the cells of ``study`` are asked to run: this option, else the study's, else
        the CPU."""
        return self.backend or study.backend or "cpu"

    def gpu_declined(self, study):
        """The GPU is asked for, but ``study`` has fewer than ``grid.MIN_GPU_CELLS`` cells."""
        return self.backend_of(study) == "cuda" and study.n_cells < grid.MIN_GPU_CELLS

    def runs_on(self, study):
        """Where the cells of ``study`` run: :meth:`backend_of`, but on the CPU where the GPU
        is declined (:meth:`gpu_declined`)."""
        return "cpu" if self.gpu_declined(study) else self.backend_of(study)

    def command_line(self, size=None):
        """The command line, with ``(<size> ranks)`` after it when ``size`` is given."""
        ranks = "" if size is None else f" ({size} ranks)"
        return f"{' '.join([COMMAND, *self.argv])}{ranks}"
