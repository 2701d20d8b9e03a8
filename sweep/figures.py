"""``python -m sweep.figures``: the paper's figures from our own simulations, in one job.

    mpiexec -n 2 python -m sweep.figures [-o FIGURES]

The ranks stay together from the first figure to the last, so start-up, imports and the
kernel load are paid once: they draw the scenes of Figs 3-5 (``studies/fig0[345][a-g]_*.yaml``,
into ``FIGURES/scenes``), run every study of ``PLAN`` one after the other
(``runner.launch.run_file``, so each dataset is the one ``python -m sweep.run STUDY --force``
writes into ``results/``), classify the overturnings of the sweeps of Fig. 11 once for Figs
11-16 (``sweep.paper.classify``), draw the figures (``sweep.plot``) and fit and draw the
fragilities of ``FRAGILITY`` (``sweep.probability.fragility``, as ``python -m
sweep.fragility`` does).  Scenes, classifications and figures are shared out among the ranks.
A line per stage on stderr says how long it took.
"""
import sys
import time
from collections import namedtuple
from pathlib import Path

from .cli import argument_parser, command
from .io.exits import EXIT_BAD_INPUT, EXIT_OK
from .runner import mpi
from .runner.progress import emit, format_seconds

STUDIES = Path("studies")
SCENES = "fig0[345][a-g]_*.yaml"  # the scenes of Figs 3-5
KINDS = ("acceleration", "velocity", "displacement")  # the sweeps of Figs 8-10
# output name -> (figure of sweep.plot, the studies whose datasets it draws), in drawing order
PLAN = {
    **{f"fig{n}": (f"fig{n}", tuple(f"fig{n}_{kind}" for kind in KINDS))
       for n in ("08", "09", "10")},
    **{f"fig09_{s}": ("fig09", (f"fig09_{s}",))
       for s in ("variants_acceleration", "variants_velocity", "bodies_acceleration",
                 "bodies_velocity", "rate_acceleration", "rate_velocity")},
    "fig11": ("fig11", (*(f"fig{n}_{kind}" for n in ("08", "09") for kind in KINDS),
                        "fig10_acceleration", "curve_b_points")),
    "fig12": ("fig12", ("fig08_acceleration", *(f"fig09_{kind}" for kind in KINDS))),
    "fig13": ("fig13", ("fig09_acceleration",)),
    "fig14": ("fig14", ("fig08_acceleration", "fig09_acceleration", "curve_b_points")),
    "fig15": ("fig15", ("fig09_velocity",)),
    "fig16": ("fig16", ("fig09_displacement",)),
    "fig17": ("fig17", ()),
    "fig18": ("fig18", ("fig18_elcentro_ns",)),
    "fig19": ("fig19", ("fig19_taft_ew",)),
    "fig20": ("fig20", ("fig20_elcentro_ew",)),
    "fig21": ("fig21", ("fig21_summary",)),
    "rocking_spectrum": ("spectrum", ("rocking_spectrum_elcentro",)),
    "rate_study_short": ("rates", ("rate_study_short_acceleration",
                                   "rate_study_short_velocity")),
    "fig05_landing_map": ("landing", ("fig05_landing_map",)),
    "fig05_landing_speeds": ("landing", ("fig05_landing_speeds",)),
}
Fragility = namedtuple("Fragility", "study over im kind")
Fragility.__doc__ = """A fragility figure: of the dataset of ``study``, members over the
dimensions ``over``, intensity measure ``im``, figure ``kind`` (``plots.fragility.figure``)."""
# Fragility figures and their datasets (results/<output name>.nc): output name -> Fragility
FRAGILITY = {
    "fragility_records_pga": Fragility("fragility_records", ("record",), "pga", "curves"),
    "fragility_synthetic_pga": Fragility("fragility_synthetic", ("seed",), "pga", "curves"),
    "fragility_synthetic_map": Fragility("fragility_synthetic", ("seed", "magnitude"), "pga",
                                         "map"),
    "fragility_synthetic_pgv": Fragility("fragility_synthetic", ("seed",), "pgv", "curves"),
}
CLASSIFIED = PLAN["fig11"][1]  # the sweeps whose overturnings Figs 11-16 classify


def studies():
    """The studies of ``PLAN`` and ``FRAGILITY``, each once, in order of first use."""
    return list(dict.fromkeys([*(name for _, names in PLAN.values() for name in names),
                               *(f.study for f in FRAGILITY.values())]))


def share(tasks, size, cost=None):
    """Tasks dealt to ``size`` ranks: the costliest first, each to the least loaded rank
    (round-robin without ``cost``); a list of ``size`` lists, in the tasks' order."""
    if cost is None:
        return [tasks[rank::size] for rank in range(size)]
    load, dealt = [0.0] * size, [[] for _ in range(size)]
    for k in sorted(range(len(tasks)), key=lambda k: -cost[k]):
        rank = load.index(min(load))
        load[rank] += cost[k]
        dealt[rank].append(k)
    return [[tasks[k] for k in sorted(ks)] for ks in dealt]


class _Stages:
    """Rank 0's line per stage: its name, what it did and the seconds it took."""

    def __init__(self, comm):
        self.comm, self.start = comm, time.perf_counter()
        self.last = self.start

    def done(self, what):
        now = time.perf_counter()
        if self.comm.Get_rank() == 0:
            emit(f"sweep.figures: {what} in {format_seconds(now - self.last)}", sys.stderr)
        self.last = now

    def total(self, output):
        if self.comm.Get_rank() == 0:
            emit(f"sweep.figures: wrote {len(PLAN) + len(FRAGILITY)} figures into {output} in "
                 f"{format_seconds(time.perf_counter() - self.start)}", sys.stderr)


def draw_scenes(comm, output):
    """This rank's share of the scenes of Figs 3-5, drawn as ``python -m sweep.scene SCENE
    --plot`` draws them; returns how many scenes there are."""
    import matplotlib.pyplot as plt

    from .plots.scene import draw_scene
    from .plots.style import save_figure
    from .runner.simulate import simulate

    paths = sorted(STUDIES.glob(SCENES))
    (output / "scenes").mkdir(parents=True, exist_ok=True)
    for path in share(paths, comm.Get_size())[comm.Get_rank()]:
        result = simulate(path, history=True)
        fig = draw_scene(result.history, path.name)
        save_figure(fig, output / "scenes" / f"{path.stem}.png", dpi=110)
        plt.close(fig)
    return len(paths)


def run_studies(comm, names):
    """Every study on every rank, one after the other, as ``python -m sweep.run STUDY --force
    --quiet`` runs it; the first nonzero exit status, or 0."""
    from .runner.launch import run_status
    from .runner.options import RunOptions

    for name in names:
        path = str(STUDIES / f"{name}.yaml")
        status = run_status(comm, path, RunOptions(force=True, quiet=True,
                                                   argv=(path, "--force", "--quiet")))
        if status:
            return status
    return EXIT_OK


def classify(comm, datasets):
    """{``classify.dataset_key``: its classification} of the sweeps ``CLASSIFIED``, every
    overturned cell simulated again once, the cells shared out by the time they ran."""
    from .paper import classify

    tasks = [(name, int(cell)) for name in CLASSIFIED
             for cell in classify.overturned_cells(datasets[name])]
    cost = [float(datasets[name]["t_overturn"].values.ravel()[cell]) for name, cell in tasks]
    mine = share(tasks, comm.Get_size(), cost)[comm.Get_rank()]
    found = {}
    for name in CLASSIFIED:
        cells = [cell for of, cell in mine if of == name]
        found[name] = classify.classify_dataset(datasets[name], cells)
    known = {}
    for name in CLASSIFIED:
        key = classify.dataset_key(datasets[name])
        known[key] = {cell: rocking for part in mpi.allgather(comm, found[name])
                      for cell, rocking in part.items()}
    return known, len(tasks)


def draw_figures(comm, datasets, known, output):
    """This rank's share of the figures of ``PLAN``."""
    import matplotlib.pyplot as plt

    from . import plot
    from .plots.style import save_figure

    for name in share(list(PLAN), comm.Get_size())[comm.Get_rank()]:
        figure, names = PLAN[name]
        options = {"known": known} if figure in plot.CLASSIFIED else {}
        fig = plot.draw(figure, [datasets[n] for n in names], **options)
        save_figure(fig, output / f"{name}.png")
        plt.close(fig)


def draw_fragility(comm, output):
    """This rank's share of the fragility figures of ``FRAGILITY`` and their datasets,
    ``results/<figure name>.nc``, as ``python -m sweep.fragility`` writes them."""
    import matplotlib.pyplot as plt
    import xarray as xr

    from .io.study_schema import load_study
    from .plots.fragility import figure as fragility_figure
    from .plots.style import save_figure
    from .probability.fragility import default_levels, fragility
    from .netcdf import write_netcdf

    for name in share(list(FRAGILITY), comm.Get_size())[comm.Get_rank()]:
        wanted = FRAGILITY[name]
        result = load_study(STUDIES / f"{wanted.study}.yaml").output
        dataset, figure = result.with_name(f"{name}.nc"), output / f"{name}.png"
        with xr.open_dataset(result) as opened:
            ds = opened.load()
        levels = default_levels(ds, wanted.over)
        frag = fragility(ds, wanted.over, wanted.im, levels, source=str(result),
                         history=_fragility_command(wanted, result, figure, dataset))
        write_netcdf(frag, dataset)
        fig = fragility_figure(wanted.kind, frag, ds, wanted.over, wanted.im, levels)
        save_figure(fig, figure)
        plt.close(fig)


def _fragility_command(wanted, result, figure, dataset):
    """The ``python -m sweep.fragility`` command line that writes the same dataset and figure:
    the history of the dataset."""
    over = [word for dim in wanted.over for word in ("--over", dim)]
    kind = ["--kind", wanted.kind] if wanted.kind != "curves" else []
    return " ".join(["python -m sweep.fragility", str(result), *over, "--im", wanted.im, *kind,
                     "-o", str(figure), "--dataset", str(dataset)])


def open_datasets(names):
    """{study: its dataset}, opened from the study's output."""
    import xarray as xr

    from .io.study_schema import load_study

    return {name: xr.open_dataset(load_study(STUDIES / f"{name}.yaml")
                                  .output) for name in names}


@command
def main(argv=None):
    import matplotlib

    matplotlib.use("Agg")  # files only: no window, whatever the user's default backend
    parser = argument_parser("sweep.figures", __doc__, lines=True)
    parser.add_argument("-o", "--output", default="figures", help="folder of the figures")
    args = parser.parse_args(argv)
    output = Path(args.output)
    comm = mpi.world_or_say("sweep.figures")
    if comm is None:
        return EXIT_BAD_INPUT
    with mpi.abort_on_exception(comm):
        stages = _Stages(comm)
        n = draw_scenes(comm, output)
        mpi.barrier(comm)
        stages.done(f"{n} scenes of Figs 3-5 drawn")
        names = studies()
        status = run_studies(comm, names)
        if status:
            return status
        stages.done(f"{len(names)} studies run")
        datasets = open_datasets(names)
        known, n = classify(comm, datasets)
        stages.done(f"{n} overturnings classified")
        draw_figures(comm, datasets, known, output)
        for ds in datasets.values():
            ds.close()
        mpi.barrier(comm)
        stages.done(f"{len(PLAN)} figures drawn")
        draw_fragility(comm, output)
        mpi.barrier(comm)
        stages.done(f"{len(FRAGILITY)} fragility figures drawn")
        stages.total(output)
    return EXIT_OK


if __name__ == "__main__":
    sys.exit(main())
