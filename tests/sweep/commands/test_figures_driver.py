"""``python -m sweep.figures``: the studies it runs and how it shares work among the ranks."""
from pathlib import Path

import numpy as np

from sweep import figures, plot

STUDIES = Path(__file__).resolve().parents[3] / "studies"


def test_it_runs_every_sweep_and_record_study_once():
    wanted = {p.stem for pattern in ("fig08_*", "fig09_*", "fig10_*") for p in
              STUDIES.glob(f"{pattern}.yaml")}
    wanted |= {"fig18_elcentro_ns", "fig19_taft_ew", "fig20_elcentro_ew", "fig21_summary",
               "rocking_spectrum_elcentro", "fig05_landing_map", "fig05_landing_speeds",
               "curve_b_points", "rate_study_short_acceleration", "rate_study_short_velocity"}
    wanted |= {p.stem for p in STUDIES.glob("fragility_*.yaml")}
    names = figures.studies()
    assert len(names) == len(set(names)) and set(names) == wanted
    assert all((STUDIES / f"{name}.yaml").exists() for name in names)


def test_every_figure_is_one_of_sweep_plot():
    assert {figure for figure, _ in figures.PLAN.values()} <= set(plot.FIGURES)
    assert set(figures.CLASSIFIED) >= {n for name in ("fig12", "fig13", "fig14", "fig15",
                                                      "fig16") for n in figures.PLAN[name][1]}


def test_share_deals_every_task_once_and_balances_costs():
    rng = np.random.default_rng(1)
    tasks = list(range(40))
    cost = rng.exponential(size=40).tolist()
    for size in (1, 2, 3):
        for dealt in (figures.share(tasks, size), figures.share(tasks, size, cost)):
            assert len(dealt) == size and sorted(sum(dealt, [])) == tasks
    loads = [sum(cost[k] for k in mine) for mine in figures.share(tasks, 2, cost)]
    assert max(loads) - min(loads) <= max(cost)  # greedy: off by one task at most
