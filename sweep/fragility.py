"""``python -m sweep.fragility RESULT.nc``: fragility of overturning over a study's ensemble.

``--over seed --im pga``: probabilities of overturning over the ensemble, lognormal fragility
fits, curves and (PGA, PGV) maps.

For every body (each combination of the dimensions that are neither ensemble nor levels) the
probabilities of overturning, rocking and sliding at each level with their intervals, and
the lognormal fragility of overturning with the intervals of its median θ and dispersion β
(``sweep.probability.fragility``; docs/fragility.md).  The fragility dataset is written
beside RESULT as ``<stem>_fragility_<im>.nc`` (``--dataset`` elsewhere); ``-o`` draws curves
or, with ``--kind map``, the two-parameter fragility over (PGA, PGV); ``--json`` prints every
group, otherwise one line per group, and for a body with G off the middle one more: how many
members fell to each side (docs/bodies.md).
"""
import math
import sys
from pathlib import Path

from .cli import argument_parser, checked_type, command, positive_int, print_json
from .io.exits import EXIT_BAD_INPUT, EXIT_OK
from .io.files import output_problems
from .io.problems import FileProblems
from .probability.fit import DEFAULT_REPLICATES, FIT_REASONS, FIT_STATUS_NAMES, INTERVALS
from .probability.fragility import (DEFAULT_BINS, EVENTS, INTENSITY_MEASURES, SIDE_ANGLES,
                                    FragilityError, asymmetric, counted, default_levels,
                                    describe_group, group_coords, group_indices, output_path)
from .probability.intervals import METHODS

NO_LEVELS = "none"  # --levels none: a cloud of cells, binned in ln IM
KINDS = ("curves", "map")


_confidence = checked_type(float, lambda v: 0.0 < v < 1.0, "strictly between 0 and 1")


def _parser():
    parser = argument_parser(
        "sweep.fragility",
        description="Probabilities of overturning over a study's ensemble with confidence "
                    "intervals, lognormal fragility fits (median, beta and their intervals), "
                    "curves and (PGA, PGV) maps.")
    parser.add_argument("result", help="study dataset written by python -m sweep.run (netCDF)")
    parser.add_argument("--over", action="append", required=True, metavar="DIM",
                        help="ensemble dimension whose cells are the members (seed, record); "
                             "repeat for several")
    parser.add_argument("--im", required=True, choices=sorted(INTENSITY_MEASURES),
                        help="intensity measure of the fragility: of the motion applied to "
                             "the body (pga, pgv; on a building's floor, the floor's), or "
                             "ground_pga, ground_pgv: of the ground under a floor (the axis "
                             "that scales it, the IM of a site's hazard)")
    parser.add_argument("--levels", metavar="DIM",
                        help="dimension along which the members are scaled (default: pga, "
                             "pgv, scale or amplitude if present, else the axis that scales "
                             f"a floor's ground); '{NO_LEVELS}': each cell at its own IM, "
                             "probabilities in bins of ln IM")
    parser.add_argument("--bins", type=positive_int, default=DEFAULT_BINS,
                        help=f"bins in ln IM without levels (default {DEFAULT_BINS})")
    parser.add_argument("--confidence", type=_confidence, default=0.95,
                        help="coverage of every interval (default 0.95)")
    parser.add_argument("--interval", choices=METHODS, default="wilson",
                        help="interval of the probabilities (default wilson)")
    parser.add_argument("--fit-interval", choices=INTERVALS, default="bootstrap",
                        help="intervals of theta and beta: bootstrap over the members (BCa, "
                             "default) or the delta method")
    parser.add_argument("--replicates", type=positive_int, default=DEFAULT_REPLICATES,
                        help=f"bootstrap replicates (default {DEFAULT_REPLICATES})")
    parser.add_argument("--seed", type=int, default=0, help="seed of the bootstrap (default 0)")
    parser.add_argument("--json", action="store_true", help="print every group as JSON (SI)")
    parser.add_argument("-o", "--output", help="figure file (.png, .pdf, .svg)")
    parser.add_argument("--kind", choices=KINDS, default="curves",
                        help="figure: fragility curves, or the two-parameter map over "
                             "(PGA, PGV) (needs pga and pgv)")
    parser.add_argument("--dataset", help="fragility dataset to write (default: "
                                          "<RESULT stem>_fragility_<im>.nc beside RESULT)")
    return parser


@command
def main(argv=None):
    args = _parser().parse_args(argv)
    source = Path(args.result)
    if not source.is_file():
        why = "is a folder" if source.is_dir() else "No such file or directory"
        print(f"{source}: cannot read: {why}", file=sys.stderr)
        return EXIT_BAD_INPUT
    dataset_path = Path(args.dataset) if args.dataset else output_path(source, args.im)
    unusable = output_problems({"--dataset": dataset_path, "-o/--output": args.output})
    if unusable:  # before any work
        print(FileProblems(unusable), file=sys.stderr)
        return EXIT_BAD_INPUT

    import xarray as xr

    from .probability.fragility import fragility, validate_request
    from .netcdf import write_netcdf

    try:
        with xr.open_dataset(source) as opened:
            ds = opened.load()
    except (OSError, ValueError) as err:  # xarray finds no engine for it: ValueError
        why = "not a netCDF file" if isinstance(err, ValueError) else str(err).splitlines()[0]
        print(f"{source}: cannot open as a netCDF dataset: {why}", file=sys.stderr)
        return EXIT_BAD_INPUT
    levels = None if args.levels == NO_LEVELS else args.levels or default_levels(ds, args.over)
    try:
        validate_request(ds, args.over, args.im, levels)
        if args.output and args.kind == "map":
            missing = [name for name in ("pga", "pgv") if name not in ds.variables]
            if missing:
                raise FragilityError(f"--kind map needs pga and pgv; the dataset has no "
                                     f"{' and no '.join(missing)}")
        frag = fragility(ds, args.over, args.im, levels, bins=args.bins,
                         confidence=args.confidence, interval=args.interval,
                         fit_interval=args.fit_interval, replicates=args.replicates,
                         seed=args.seed, source=str(source),
                         history=_history(argv))
    except FragilityError as err:
        print(f"{source}: {err}", file=sys.stderr)
        return EXIT_BAD_INPUT
    write_netcdf(frag, dataset_path)
    if args.output:
        _draw(frag, ds, args, levels)
    if args.json:
        print_json(summary(frag, dataset_path, args.output))
    else:
        print(format_table(frag))
        print(f"wrote {dataset_path}" + (f" and {args.output}" if args.output else ""))
    return EXIT_OK


def _history(argv):
    words = sys.argv[1:] if argv is None else list(argv)
    return "python -m sweep.fragility " + " ".join(words)


def _draw(frag, ds, args, levels):
    """Draw the figure of ``--kind`` and write it whole."""
    import matplotlib

    matplotlib.use("Agg")  # files only: no window, whatever the user's default backend
    from .plots.fragility import figure
    from .plots.style import save_figure

    save_figure(figure(args.kind, frag, ds, args.over, args.im, levels), Path(args.output))


def summary(frag, dataset_path=None, figure=None):
    """The fragility dataset as a JSON-ready dict: settings, then one entry per group."""
    level_dim = next(d for d in frag["p_overturned"].dims if d not in frag["theta"].dims)
    events = [e for e in EVENTS if f"p_{e}" in frag]
    groups = []
    for index in group_indices(frag):
        group = frag.isel(index)
        entry = {"coords": {name: value for name, (value, _) in
                            group_coords(frag, index).items()},
                 "label": describe_group(group_coords(frag, index))}
        if level_dim == "im_bin":
            entry["bins"] = [[lo, hi] for lo, hi in zip(frag["im_lower"].values,
                                                        frag["im_upper"].values)]
        else:
            entry["levels"] = frag[level_dim].values
        entry.update(im_median=group["im_median"].values, n=group["n_members"].values,
                     n_failed=group["n_failed"].values)
        entry.update({name: float(group[name]) for name in SIDE_ANGLES if name in frag})
        for event in events:
            entry[event] = {"k": group[f"k_{event}"].values, "p": group[f"p_{event}"].values,
                            "lower": group[f"p_{event}_lower"].values,
                            "upper": group[f"p_{event}_upper"].values}
        status = int(group["fit_status"])
        entry["fit"] = {
            "theta": float(group["theta"]),
            "theta_interval": [float(group["theta_lower"]), float(group["theta_upper"])],
            "beta": float(group["beta"]),
            "beta_interval": [float(group["beta_lower"]), float(group["beta_upper"])],
            "status": FIT_STATUS_NAMES[status], "reason": FIT_REASONS[status],
            "points": int(group["fit_points"]), "levels": int(group["fit_levels"]),
            "bootstrap_unfitted": int(group["bootstrap_unfitted"])}
        if "surface_coefficient" in frag:
            surface = int(group["surface_status"])
            entry["surface"] = {"coefficients": dict(zip(frag["term"].values.tolist(),
                                                         group["surface_coefficient"].values)),
                                "status": FIT_STATUS_NAMES[surface],
                                "reason": FIT_REASONS[surface]}
        groups.append(entry)
    attrs = frag.attrs
    return {"input": attrs["input_file"], "dataset": None if dataset_path is None
            else str(dataset_path), "figure": figure,
            "intensity_measure": attrs["intensity_measure"],
            "units": frag["theta"].attrs["units"], "over": attrs["ensemble_dimensions"].split(),
            "levels": None if level_dim == "im_bin" else level_dim,
            "confidence": attrs["confidence"], "interval": attrs["interval_method"],
            "fit_interval": attrs["fit_interval_method"], "failed_cells": attrs["failed_cells"],
            "cells": attrs["cells"], "groups": groups}


def format_table(frag):
    """One line per group: its name, θ and β with their intervals, the fit's status."""
    attrs = frag.attrs
    units = frag["theta"].attrs["units"]
    units = "" if units == "1" else f" [{units}]"
    level = attrs["level_dimension"]
    members = int(frag["n_members"].max())
    confidence = f"{float(attrs['confidence']):.0%}"
    lines = [f"{attrs['input_file']}: fragility of overturning against "
             f"{attrs['intensity_measure']}{units}, members over {attrs['ensemble_dimensions']}"
             f" (up to {members} per {'bin' if level == 'none' else 'level'}), "
             + (f"levels {level}" if level != "none" else attrs["im_bins"]),
             f"{attrs['failed_cells']} of {counted(int(attrs['cells']), 'cell')} failed and "
             "left out; "
             f"{confidence} intervals of theta and beta: {attrs['fit_interval_method']}"]
    rows = [("group", f"theta{units}", f"{confidence} interval", "beta",
             f"{confidence} interval", "fit")]
    for index in group_indices(frag):
        group = frag.isel(index)
        status = int(group["fit_status"])
        rows.append((describe_group(group_coords(frag, index)),
                     _number(group["theta"]), _pair(group["theta_lower"], group["theta_upper"]),
                     _number(group["beta"]), _pair(group["beta_lower"], group["beta_upper"]),
                     FIT_STATUS_NAMES[status]))
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    lines += ["  ".join(cell.ljust(w) for cell, w in zip(row, widths)).rstrip()
              for row in rows]
    return "\n".join(lines + _side_lines(frag, units))


def _side_lines(frag, units):
    """For each body with G off the middle, a line: how many of the members that overturned
    fell to the left (−x, about corner 1) and to the right, at each IM where any did."""
    lines = []
    for index in group_indices(frag):
        group = frag.isel(index)
        if not asymmetric(group) or "k_overturned_left" not in frag:
            continue
        k = group["k_overturned"].values
        pairs = [f"{_number(x)}: {int(left)}/{int(right)}" for x, left, right, total in zip(
            group["im_median"], group["k_overturned_left"].values,
            group["k_overturned_right"].values, k) if total > 0]
        angles = [math.degrees(float(group[name])) for name in SIDE_ANGLES]
        lines.append(f"{describe_group(group_coords(frag, index))}: G off the middle "
                     f"(alpha_1 {angles[0]:.3g} deg, alpha_2 {angles[1]:.3g} deg); overturned "
                     f"to the left (-x) / right (+x) at {frag.attrs['intensity_measure']}"
                     f"{units}: " + (", ".join(pairs) or "none overturned"))
    return lines


def _number(da):
    value = float(da)
    return f"{value:.4g}" if value == value else "-"


def _pair(lower, upper):
    return f"[{_number(lower)}, {_number(upper)}]" if float(lower) == float(lower) else "-"


if __name__ == "__main__":
    sys.exit(main())
