"""Figures from a study's dataset: ``python -m sweep.plot RESULT.nc --figure NAME -o out.png``.

``FIGURES`` maps a figure name to a function ``(ds, **options) -> matplotlib Figure`` that
reads only the Dataset; a new figure is one more entry.
"""
import argparse
import sys
from pathlib import Path

from .cli import EXIT_BAD_INPUT
from .plot_map import figure_map

FIGURES = {
    "map": figure_map,  # outcome map: amplitude vs frequency, one panel per other axis value
}


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m sweep.plot",
                                     description="Draw a figure from a study's netCDF dataset.")
    parser.add_argument("result", help="dataset written by python -m sweep.run (netCDF)")
    parser.add_argument("--figure", required=True, choices=sorted(FIGURES))
    parser.add_argument("-o", "--output", required=True, help="image file (.png, .pdf, .svg)")
    parser.add_argument("--x", default=None, help="dimension along x (map)")
    parser.add_argument("--y", default=None, help="dimension along y (map)")
    args = parser.parse_args(argv)

    import xarray as xr

    try:
        ds = xr.open_dataset(args.result)
    except (OSError, ValueError) as err:
        print(f"{args.result}: cannot open as a netCDF dataset: {err}", file=sys.stderr)
        return EXIT_BAD_INPUT
    options = {k: v for k, v in (("x", args.x), ("y", args.y)) if v is not None}
    with ds:
        try:
            fig = FIGURES[args.figure](ds, **options)
        except (KeyError, ValueError) as err:
            print(f"{args.result}: cannot draw '{args.figure}': {err}", file=sys.stderr)
            return EXIT_BAD_INPUT
    out = Path(args.output)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=150)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
