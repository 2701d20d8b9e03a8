"""Figures from a study's dataset: ``python -m sweep.plot RESULT.nc --figure NAME -o out.png``.

``FIGURES`` maps a figure name to a function ``(ds, **options) -> matplotlib Figure``; a new
figure is one more entry.  The drawing functions (``sweep.plots``) read only what they are
given; Figs 11-16 need the rocking before each overturning, which this command first computes
from the datasets (``sweep.paper.classify``: the overturned cells simulated again) and hands
to the drawing.  Figures of ``WITHOUT_DATASET`` are closed forms and take no RESULT
(``python -m sweep.plot --figure fig17 -o fig17.png``).  Figures of ``SEVERAL`` take one or
more RESULTs (e.g. one sweep study per kind of sweep) and receive the list of their Datasets.
A refine study's dataset is drawn by ``map`` or ``boundary``; a figure that does not fit its
datasets (:func:`misfit`, or a ``KeyError``/``ValueError`` of the drawing) is one line on
stderr and exit status 2.  The backend is ``Agg``, chosen by :func:`main`, never on import of
``sweep.plots``.
"""
import sys
from contextlib import ExitStack
from functools import partial
from pathlib import Path

import yaml

from .cli import argument_parser, command
from .io.exits import EXIT_BAD_INPUT, EXIT_OK
from .io.files import output_problems
from .io.problems import FileProblems
from .paper import classify
from .plots.histories import figure_history
from .plots.landing import figure_landing
from .plots.limits import figure_limits
from .plots.map import figure_boundary, figure_map
from .plots.rates import figure_rates
from .plots.records import figure_record_map, figure_summary
from .plots.spectra import figure_spectrum
from .plots.style import save_figure
from .plots.sweeps import figure_boundaries, figure_plane


def boundaries(datasets, label=None, known=None):
    """Fig. 11: the overturnings of sweep datasets classified, then drawn by kind
    (``known``: classifications already made, see ``classify.classifications``)."""
    return figure_boundaries(datasets, classify.classifications(datasets, known), label=label)


def histories(datasets, figure, known=None):
    """Figs 12-16: the overturning of each panel's kind found with its history, then drawn."""
    return figure_history(classify.figure_overturnings(datasets, figure, known), figure)


FIGURES = {
    "map": figure_map,  # outcome map: amplitude vs frequency, one panel per other axis value
    "boundary": figure_boundary,  # a refine study's boundary against another axis ("map" too)
    "fig17": figure_limits,  # lower limits a_o, v_o, d_o and T_c against body size
    "fig18": figure_record_map,  # bodies, H vs H/B, under El Centro NS (+UD)
    "fig19": figure_record_map,  # ... under Taft EW
    "fig20": figure_record_map,  # ... under El Centro EW (+UD), in place of Miyagi-ken-oki
    "fig21": figure_summary,  # every body of every record on (PGA/a_o, PGV/v_o): A, B, C
    "spectrum": figure_spectrum,  # rocking spectrum: peak |theta|/alpha against p, per alpha
    "landing": figure_landing,  # after a translation jump: slides, tilts, overturns (Fig. 5)
    # overturning of frequency sweeps in the normalized plane (v/v_H, a/((B/H) g))
    "fig08": partial(figure_plane, label="Fig. 8"),
    "fig09": partial(figure_plane, label="Fig. 9"),
    "fig10": partial(figure_plane, label="Fig. 10"),
    "fig11": partial(boundaries, label="Fig. 11"),  # boundaries a, b, c by rocking kind
    # histories before overturning, by kind of rocking (sweep.paper.classify)
    **{name: partial(histories, figure=name)
       for name in ("fig12", "fig13", "fig14", "fig15", "fig16")},
    "rates": figure_rates,  # overturning against the sweep rate, fitted to its slow limit
}
WITHOUT_DATASET = {"fig17"}  # drawn from sweep.paper.criteria alone
SEVERAL = {*(f"fig{k:02d}" for k in range(8, 17)), "rates"}  # from a list of sweep datasets
CLASSIFIED = {f"fig{k}" for k in range(11, 17)}  # take ``known=`` classifications (Figs 11-16)
REFINE_FIGURES = {"map", "boundary"}  # the figures that draw a refine study's boundaries


def _horizontal_kind(ds):
    """Kind of the horizontal excitation of the study's base scene (``study`` attribute)."""
    study = yaml.safe_load(ds.attrs.get("study", "")) or {}
    scene = study.get("scene") or {}
    return ((scene.get("excitation") or {}).get("horizontal") or {}).get("kind", "none")


def misfit(figure, path, ds):
    """Why ``figure`` cannot be drawn from the dataset ``ds`` read from ``path`` (one line),
    or None: a refine study's boundaries are drawn by ``REFINE_FIGURES`` only, ``boundary``
    needs them, Figs 8-16 need frequency sweeps."""
    refined = "boundary" in ds
    if refined and figure not in REFINE_FIGURES:
        return (f"{path} holds a refine study's boundaries, not the cells --figure {figure} "
                f"draws: --figure map or boundary draws it")
    if not refined and figure == "boundary":
        return (f"{path} holds no boundaries (it is not the result of a refine study): "
                "--figure map draws its outcomes")
    kind = _horizontal_kind(ds)
    if figure in SEVERAL and kind != "sweep":
        return (f"{path}: --figure {figure} draws studies of frequency sweeps; this study's "
                f"horizontal excitation is of kind {kind}")
    return None


def draw(figure, datasets, **options):
    """The matplotlib Figure ``figure`` from its datasets: none (``WITHOUT_DATASET``), the
    list (``SEVERAL``) or the first."""
    if figure in WITHOUT_DATASET:
        return FIGURES[figure](**options)
    return FIGURES[figure](datasets if figure in SEVERAL else datasets[0], **options)


@command
def main(argv=None):
    import matplotlib

    matplotlib.use("Agg")  # files only: no window, whatever the user's default backend
    parser = argument_parser("sweep.plot", "Draw a figure from a study's netCDF dataset.")
    parser.add_argument("result", nargs="*", help="dataset written by python -m sweep.run "
                        f"(netCDF); none for {', '.join(sorted(WITHOUT_DATASET))}; one or "
                        f"more for {', '.join(sorted(SEVERAL))}")
    parser.add_argument("--figure", required=True, choices=sorted(FIGURES))
    parser.add_argument("-o", "--output", required=True, help="image file (.png, .pdf, .svg)")
    parser.add_argument("--x", default=None, help="dimension along x (map; default frequency, "
                        "else the second dimension, a numeric one beside names)")
    parser.add_argument("--y", default=None, help="dimension along y (map; default amplitude, "
                        "else the first dimension; an axis of names such as record: one row "
                        "per name)")
    args = parser.parse_args(argv)
    if (not args.result) != (args.figure in WITHOUT_DATASET):
        parser.error(f"--figure {args.figure} " + ("takes no RESULT (it is drawn from closed "
                                                   "forms)" if args.result else "needs a RESULT"))
    if len(args.result) > 1 and args.figure not in SEVERAL:
        parser.error(f"--figure {args.figure} takes one RESULT")
    unusable = output_problems({"-o/--output": args.output})
    if unusable:  # before any work
        print(FileProblems(unusable), file=sys.stderr)
        return EXIT_BAD_INPUT
    if not args.result:
        return _save(draw(args.figure, []), args.output)

    import xarray as xr

    options = {k: v for k, v in (("x", args.x), ("y", args.y)) if v is not None}
    with ExitStack() as stack:
        datasets = []
        for path in args.result:
            try:
                datasets.append(stack.enter_context(xr.open_dataset(path)))
            except (OSError, ValueError) as err:
                print(f"{path}: cannot open as a netCDF dataset: {err}", file=sys.stderr)
                return EXIT_BAD_INPUT
        for path, ds in zip(args.result, datasets):
            why = misfit(args.figure, path, ds)
            if why:
                print(why, file=sys.stderr)
                return EXIT_BAD_INPUT
        try:
            fig = draw(args.figure, datasets, **options)
        except (KeyError, ValueError) as err:
            said = err.args[0] if isinstance(err, KeyError) and err.args else err
            print(f"{' '.join(args.result)}: cannot draw '{args.figure}': "
                  f"{' '.join(str(said).split())}", file=sys.stderr)
            return EXIT_BAD_INPUT
    return _save(fig, args.output)


def _save(fig, output):
    """Write the figure whole (``sweep.plots.style.save_figure``) and say so."""
    save_figure(fig, Path(output))
    print(f"wrote {output}")
    return EXIT_OK


if __name__ == "__main__":
    sys.exit(main())
