"""``python -m sweep.run STUDY.yaml``: run a study over MPI ranks into one netCDF dataset.

The study file, the run and the labelled dataset are those of docs/design.md sections 5-7.

    python -m sweep.run STUDY.yaml [--dry-run] [--force] [--quiet] [--chunk-size N]
                                   [--seed N] [-o OUTPUT.nc] [--max-cells N]
                                   [--cell-budget S] [--rank-timeout S]
                                   [--backend cpu|cuda]
    mpiexec -n 2 python -m sweep.run STUDY.yaml

The command parses its arguments into ``runner.options.RunOptions``, takes the communicator
(``runner.mpi``) and hands over to ``runner.launch.run_file``, which plans, deals, computes and
merges (the site estimate calls it too); its arguments and entry point are ``runner.command``'s.
"""
import sys

from .runner.command import main, parse_args  # noqa: F401

if __name__ == "__main__":
    sys.exit(main())
