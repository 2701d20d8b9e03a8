"""``python -m sweep.run STUDY.yaml``: run a study over MPI ranks into one labelled netCDF
dataset (DESIGN.md sections 5-7).

    python -m sweep.run STUDY.yaml [--dry-run] [--force] [--quiet] [--chunk-size N]
                                   [--seed N] [-o OUTPUT.nc] [--max-cells N]
                                   [--cell-budget S] [--rank-timeout S]
    mpiexec -n 2 python -m sweep.run STUDY.yaml

The command parses its arguments, takes the communicator (``runner.mpi``) and hands over to
``runner.launch``, which plans, deals, computes and merges; its arguments and entry point are
``runner.command``'s, which the site estimate also calls.
"""
import sys

from .runner.command import main, parse_args  # noqa: F401

if __name__ == "__main__":
    sys.exit(main())
