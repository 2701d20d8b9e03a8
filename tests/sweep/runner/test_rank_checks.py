"""The cells' checks shared by ranks (``runner.rank_checks``): however the checked cells are
split into shares, put together they give the problems and doubts of one process, in its
order, also when a share stops at the limit of problems."""
import pytest
from study_helpers import make_study

from sweep.runner import cell_checks

# 60 bad frequencies (each its own problem) x a bad B, and a phase in rad that reads as deg
GRID = {"frequency": [float(f) for f in range(-30, 31) if f],
        "excitation.horizontal.phase": [0.0, 90.0], "B": [0.1, -0.2, 0.3]}


@pytest.fixture(scope="module")
def study():
    return cell_checks.load_study(make_study(GRID), check_cells=False)


def _shared(study, size, limit):
    """What ``rank_checks.shared`` computes on ``size`` ranks, in one process."""
    picks = list(enumerate(cell_checks.checked_cells(study)))
    found = sorted((f for rank in range(size)
                    for f in cell_checks.findings(study, picks[rank::size], limit)),
                   key=lambda f: f[0])
    doubts = []
    return cell_checks.combined(found, limit, doubts), doubts


@pytest.mark.parametrize("limit", [50, 7])
def test_any_split_gives_the_problems_of_one_process(study, limit):
    doubts = []
    one = cell_checks.cell_problems(study, limit=limit, doubts=doubts)
    assert len(one) == min(limit, 31)  # 30 negative frequencies and B[1], each once
    assert one[:2] == [("grid.frequency[0]", -30.0, "must be greater than 0"),
                       ("grid.B[1]", -0.2, "must be greater than 0")]
    # the checks stop at the limit: with 7, before the first right cell with phase 90
    assert [d.path for d in doubts] == (["grid.excitation.horizontal.phase[1]"]
                                        if limit > 31 else [])
    for size in (2, 3, 4, 7):
        assert _shared(study, size, limit) == (one, doubts), size
