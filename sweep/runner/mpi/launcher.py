"""Which launcher started this process, and the ranks it announced, with no MPI loaded.

Whether an MPI launcher started this process, how many ranks it announced, and whether this is
its first process; read from the launchers' variables alone."""
import os

# Variables by which launchers announce the number of ranks (Hydra/MPICH, Intel MPI, Open MPI,
# PMIx, MVAPICH) and the rank (their presence alone means "started by a launcher").
SIZE_VARS = ("PMI_SIZE", "OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS",
             "MV2_COMM_WORLD_SIZE")
RANK_VARS = ("PMI_RANK", "OMPI_COMM_WORLD_RANK", "PMIX_RANK", "MV2_COMM_WORLD_RANK")


def launcher_size(environ=None):
    """Largest rank count announced by a launcher's variables: (size, variable) or (0, None)."""
    environ = os.environ if environ is None else environ
    best = (0, None)
    for var in SIZE_VARS:
        try:
            size = int(environ.get(var, ""))
        except ValueError:
            continue
        best = max(best, (size, var), key=lambda s: s[0])
    return best


def launched(environ=None):
    """True when a launcher's variables are set (the process is a rank of an MPI job)."""
    environ = os.environ if environ is None else environ
    return any(var in environ for var in SIZE_VARS + RANK_VARS)


def first_process(environ=None):
    """True unless a launcher's variables name a rank other than 0 (one message per job)."""
    environ = os.environ if environ is None else environ
    return all(environ.get(v, "0") == "0" for v in RANK_VARS)
