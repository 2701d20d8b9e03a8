"""The cells' checks of a study shared by the ranks, before any cell runs.

Checking every cell's scene (``cell_checks``, about 0.3-0.5 ms a cell, up to 10,000 cells)
is the part of a run's start that grows with the study; rank 0 alone would keep every other
rank waiting for it.  Under MPI rank 0 sends the study's text to the others (a
:class:`Check`), each rank checks every ``size``-th of the checked cells, and rank 0 puts
their findings together in the cells' order (``cell_checks.combined``): the same problems and
doubts, in the same order, as one process finds.  A rank that cannot load the study (the
file has problems of its own) sends None and rank 0 checks its share.
"""
from collections import namedtuple

from ..io.problems import FileProblems
from . import cell_checks, mpi

Check = namedtuple("Check", "text source output limit doubts")
Check.__doc__ = """Rank 0's request to the others (``mpi.distribute``): load the study from its
file's ``text`` (``source`` names the file, ``output`` as given) and check a share of its
cells (``cell_checks.findings``: up to ``limit`` problems, the ``doubts`` too if true)."""


def shared(comm):
    """``cells(study, limit, doubts)`` for ``io.study_schema.load_study`` on rank 0: the
    checks of ``cell_checks.cell_problems`` shared by the ranks of ``comm``."""
    def cells(study, limit=50, doubts=None):
        size, with_doubts = comm.Get_size(), doubts is not None
        mpi.distribute(comm, [None] + [Check(study.text, study.source, str(study.output),
                                             limit, with_doubts)] * (size - 1))
        picks = list(enumerate(cell_checks.checked_cells(study)))
        parts = mpi.gather(comm, cell_checks.findings(study, picks[0::size], limit,
                                                      with_doubts))
        for rank, part in enumerate(parts):
            if part is None:
                parts[rank] = cell_checks.findings(study, picks[rank::size], limit, with_doubts)
        found = sorted((f for part in parts for f in part), key=lambda f: f[0])
        return cell_checks.combined(found, limit, doubts)
    return cells


def check_share(comm, check, load):
    """A rank other than 0: load the study of ``check`` with ``load(source, text, output)``
    (the run's loader, as rank 0 loads it), send rank 0 the findings of its share of the
    cells, and return the study (None when it cannot be loaded)."""
    try:
        study = load(check.source, check.text, check.output)
    except FileProblems:  # the file's own problems: rank 0 reports them and checks this share
        mpi.gather(comm, None)
        return None
    rank, size = comm.Get_rank(), comm.Get_size()
    picks = list(enumerate(cell_checks.checked_cells(study)))[rank::size]
    mpi.gather(comm, cell_checks.findings(study, picks, check.limit, check.doubts))
    return study
