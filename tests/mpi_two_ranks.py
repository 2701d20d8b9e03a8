"""Started by ``tests/sweep/runner/test_mpi.py`` under ``mpiexec -n 2`` (schwimmbad's CI pattern).

    mpiexec -n 2 python tests/mpi_two_ranks.py run STUDY OUT_DIR   # two runs: chunks of 3, 7
    mpiexec -n 2 python tests/mpi_two_ranks.py abort               # rank 1 raises
    mpiexec -n 2 python tests/mpi_two_ranks.py deal OUT_DIR        # rank 1 three times slower
    mpiexec -n 2 python tests/mpi_two_ranks.py leave               # leave as Ctrl-C does

``run`` writes OUT_DIR/chunk3.nc and OUT_DIR/chunk7.nc with ``sweep.run.main`` (both runs in
one job, which saves a start-up); ``abort`` raises on rank 1 while rank 0 waits in a barrier
that rank 1 never reaches: only ``abort_on_exception`` ends the job.  ``deal`` runs
``mpi.work`` over 120 one-cell chunks whose cells take 10 ms on rank 0 and 30 ms on rank 1
(a sleep, which releases the GIL as the kernel does) into part files in OUT_DIR, and prints
each rank's cells and the end of its last chunk as JSON.  ``leave`` leaves the exchange as
Ctrl-C may: rank 1 sent rank 0 messages it never took (one too large to go before it is
taken), rank 0 sent rank 1 one it never took, and waits in a barrier that rank 1 never
reached; then both call ``mpi.leave_interrupted``, which ends them.
"""
import json
import sys
import time
from pathlib import Path

# Python puts this script's folder first on sys.path, where tests/sweep (no __init__.py) would
# shadow the installed package as a namespace package.
_HERE = Path(__file__).resolve().parent
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != _HERE]

import numpy as np  # noqa: E402

from sweep.runner import grid, mpi, store  # noqa: E402
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


def deal(out_dir):
    comm = mpi.world()
    rank = comm.Get_rank()

    def run_chunk(study, cells):
        time.sleep((0.010, 0.030)[rank] * len(cells))
        return {"cell": np.asarray(cells), "status": np.zeros(len(cells), np.int8)}

    with mpi.abort_on_exception(comm):
        parts = store.PartStore(out_dir, stamp="deal")
        _, stats = mpi.work(comm, None, grid.Chunks(np.arange(120)[::-1], 1), store=parts,
                            run_chunk=run_chunk)
        if rank == 0:
            print(json.dumps({r: [s.cells, s.ended] for r, s in stats.items()}))
    return 0


def leave():
    comm = mpi.world()
    if comm.Get_rank() == 1:
        comm.send(None, dest=0, tag=mpi.TAG_TAKE)
        comm.isend(np.arange(300_000.0), dest=0, tag=mpi.TAG_PROGRESS)
    else:
        comm.send("plan", dest=1, tag=mpi.TAG_PLAN)
        comm.Ibarrier()
    mpi.leave_interrupted(comm)
    return 1  # not reached: leave_interrupted ends the process


if __name__ == "__main__":
    sys.exit({"run": lambda: run(*sys.argv[2:4]), "abort": abort, "leave": leave,
              "deal": lambda: deal(sys.argv[2])}[sys.argv[1]]())
