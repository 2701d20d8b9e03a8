"""Figures from a study's dataset: ``python -m sweep.plot RESULT.nc --figure NAME -o out.png``.

``FIGURES`` maps a figure name to a function ``(ds, **options) -> matplotlib Figure`` that
reads only the Dataset; a new figure is one more entry.  Figures of ``WITHOUT_DATASET`` are
closed forms and take no RESULT (``python -m sweep.plot --figure fig17 -o fig17.png``).
Figures of ``SEVERAL`` take one or more RESULTs (e.g. one sweep study per kind of sweep) and
receive the list of their Datasets.
"""
import argparse
import os
import sys
from contextlib import ExitStack
from functools import partial
from pathlib import Path

from .io.problems import EXIT_BAD_INPUT
from .plots.histories import figure_history
from .plots.limits import figure_limits
from .plots.map import figure_map
from .plots.records import figure_record_map, figure_summary
from .plots.sweeps import figure_boundaries, figure_plane

FIGURES = {
    "map": figure_map,  # outcome map: amplitude vs frequency, one panel per other axis value
    "fig17": figure_limits,  # lower limits a_o, v_o, d_o and T_c against body size
    "fig18": figure_record_map,  # bodies, H vs H/B, under El Centro NS (+UD)
    "fig19": figure_record_map,  # ... under Taft EW
    "fig20": figure_record_map,  # ... under El Centro EW (+UD), in place of Miyagi-ken-oki
    "fig21": figure_summary,  # every body of every record on (PGA/a_o, PGV/v_o): A, B, C
    # overturning of frequency sweeps in the normalized plane (v/v_H, a/((B/H) g))
    "fig08": partial(figure_plane, label="Fig. 8"),
    "fig09": partial(figure_plane, label="Fig. 9"),
    "fig10": partial(figure_plane, label="Fig. 10"),
    "fig11": partial(figure_boundaries, label="Fig. 11"),  # boundaries a, b, c by rocking kind
    # histories before overturning, by kind of rocking (sweep.classify)
    **{name: partial(figure_history, figure=name)
       for name in ("fig12", "fig13", "fig14", "fig15", "fig16")},
}
WITHOUT_DATASET = {"fig17"}  # drawn from sweep.criteria alone
SEVERAL = {f"fig{k:02d}" for k in range(8, 17)}  # drawn from a list of sweep datasets


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m sweep.plot",
                                     description="Draw a figure from a study's netCDF dataset.")
    parser.add_argument("result", nargs="*", help="dataset written by python -m sweep.run "
                        f"(netCDF); none for {', '.join(sorted(WITHOUT_DATASET))}; one or "
                        f"more for {', '.join(sorted(SEVERAL))}")
    parser.add_argument("--figure", required=True, choices=sorted(FIGURES))
    parser.add_argument("-o", "--output", required=True, help="image file (.png, .pdf, .svg)")
    parser.add_argument("--x", default=None, help="dimension along x (map)")
    parser.add_argument("--y", default=None, help="dimension along y (map)")
    args = parser.parse_args(argv)
    if (not args.result) != (args.figure in WITHOUT_DATASET):
        parser.error(f"--figure {args.figure} " + ("takes no RESULT (it is drawn from closed "
                                                   "forms)" if args.result else "needs a RESULT"))
    if len(args.result) > 1 and args.figure not in SEVERAL:
        parser.error(f"--figure {args.figure} takes one RESULT")
    if not args.result:
        return _save(FIGURES[args.figure](), args.output)

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
        try:
            fig = FIGURES[args.figure](datasets if args.figure in SEVERAL else datasets[0],
                                       **options)
        except (KeyError, ValueError) as err:
            print(f"{' '.join(args.result)}: cannot draw '{args.figure}': {err}",
                  file=sys.stderr)
            return EXIT_BAD_INPUT
    return _save(fig, args.output)


def _save(fig, output):
    """Write the figure atomically: a temporary file renamed onto ``output``."""
    out = Path(output)
    out.parent.mkdir(parents=True, exist_ok=True)
    partial = out.with_name(f".{out.name}.partial")
    fig.savefig(partial, dpi=150, format=out.suffix.lstrip(".") or "png")
    os.replace(partial, out)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
