"""Started by ``tests/sweep/test_mpi.py`` under ``mpiexec -n 2`` (schwimmbad's CI pattern).

    mpiexec -n 2 python tests/mpi_two_ranks.py run STUDY OUT_DIR   # two runs: chunks of 3, 7
    mpiexec -n 2 python tests/mpi_two_ranks.py abort               # rank 1 raises

``run`` writes OUT_DIR/chunk3.nc and OUT_DIR/chunk7.nc with ``sweep.run.main`` (both runs in
one job, which saves a start-up); ``abort`` raises on rank 1 while rank 0 waits in a barrier
that rank 1 never reaches: only ``abort_on_exception`` ends the job.
"""
import sys
from pathlib import Path

# Python puts this script's folder first on sys.path, where tests/sweep (no __init__.py) would
# shadow the installed package as a namespace package.
_HERE = Path(__file__).resolve().parent
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != _HERE]

from sweep.runner import mpi  # noqa: E402
from sweep.run import main  # noqa: E402


def run(study, out_dir):
    for chunk_size in (3, 7):
        out = Path(out_dir) / f"chunk{chunk_size}.nc"
        code = main([study, "-o", str(out), "--chunk-size", str(chunk_size), "--quiet"])
        if code != 0:
            return code
    return 0


def abort():
    comm = mpi.world()
    assert comm.Get_size() == 2, "run me with mpiexec -n 2"
    with mpi.abort_on_exception(comm):
        if comm.Get_rank() == 1:
            raise RuntimeError("boom on rank 1")
        mpi.barrier(comm)
    return 0


if __name__ == "__main__":
    sys.exit(run(*sys.argv[2:4]) if sys.argv[1] == "run" else abort())
