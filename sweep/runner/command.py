"""The arguments and the entry point of ``python -m sweep.run`` (``sweep/run.py`` calls them).

:func:`main` parses the arguments into a :class:`RunOptions` (:func:`run_options`), takes the
communicator (``runner.mpi``) and hands over to ``runner.launch.run_file``, which plans, deals,
computes and merges; how that ends becomes the exit status (``launch.run_status``).
"""
import math
import sys

from ..cli import argument_parser, checked_type, command, positive_int
from ..io.exits import EXIT_BAD_INPUT
from ..io.study_schema import BACKENDS, MAX_CELLS
from . import grid, mpi
from .cells import CELL_BUDGET
from .options import RunOptions

# seconds of a budget or a time-out: 0 for no limit
_seconds = checked_type(float, lambda v: 0 <= v < math.inf, "a finite number of seconds >= 0")
_cells = checked_type(int, lambda v: v >= 0, "a whole number >= 0 (0: no limit)")


def parse_args(argv=None):
    parser = argument_parser(
        "sweep.run", "Run a study (a base scene and axes to vary) into one netCDF dataset. "
                     "Under mpiexec the cells are shared by the ranks; a killed run resumes "
                     "from its part files when started again.", quantities=True)
    parser.add_argument("study", help="study file (YAML)")
    parser.add_argument("--dry-run", action="store_true",
                        help="check the study, print the cell count and an estimated run time")
    parser.add_argument("--force", action="store_true",
                        help="overwrite an existing result (and discard stale part files)")
    parser.add_argument("--quiet", action="store_true", help="no progress and no summary")
    parser.add_argument("--chunk-size", type=positive_int, default=None, metavar="N",
                        help="cells per chunk (part file); default: about 16 chunks per rank, "
                             f"at most {grid.MAX_CHUNK} cells (on the GPU: a rank's share, "
                             f"at most {grid.CUDA_CHUNK:,} cells)")
    parser.add_argument("--seed", type=int, default=grid.DEFAULT_SEED, metavar="N",
                        help="seed of the shuffled order of the cells (default %(default)s)")
    parser.add_argument("-o", "--output", default=None, metavar="PATH",
                        help="output file (default: the study's output)")
    parser.add_argument("--max-cells", type=_cells, default=MAX_CELLS, metavar="N",
                        help="refuse a grid of more cells than this (default %(default)s; "
                             "0: no limit)")
    parser.add_argument("--cell-budget", type=_seconds, default=CELL_BUDGET, metavar="S",
                        help="wall-time budget of one cell in seconds: a cell still running "
                             "then is stopped and flagged (status time_budget) and the study "
                             "goes on (default %(default)s; 0: none)")
    parser.add_argument("--rank-timeout", type=_seconds, default=mpi.WATCH_FLOOR,
                        metavar="S",
                        help="under MPI, a rank silent for longer than max(S, "
                             f"{mpi.WATCH_FACTOR:g} x the slowest chunk so far) is taken for "
                             "stopped or stuck and the job aborts, naming it and its cells "
                             "(default %(default)s; 0: no watch)")
    parser.add_argument("--backend", choices=BACKENDS, default=None,
                        help="where the cells run: cpu or cuda, an NVIDIA GPU per rank (needs "
                             "numba-cuda: pip install '.[cuda]'; docs/gpu.md); default: the "
                             "study's run.backend, else cpu")
    args = parser.parse_args(argv)
    args.argv = list(sys.argv[1:] if argv is None else argv)
    return args


def run_options(args):
    """The :class:`RunOptions` of the arguments ``args`` of :func:`parse_args`."""
    return RunOptions(output=args.output, dry_run=args.dry_run, force=args.force,
                      quiet=args.quiet, chunk_size=args.chunk_size, seed=args.seed,
                      max_cells=args.max_cells, cell_budget=args.cell_budget,
                      rank_timeout=args.rank_timeout, backend=args.backend,
                      argv=tuple(args.argv))


@command
def main(argv=None):
    """Entry point; returns the exit status (0 ok, 1 error, 2 bad input or refused, 130
    interrupted)."""
    args = parse_args(argv)
    comm = mpi.world_or_say("sweep.run")
    if comm is None:
        return EXIT_BAD_INPUT
    from . import launch  # the study machinery once the communicator stands
    return launch.run_status(comm, args.study, run_options(args))
