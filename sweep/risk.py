"""``python -m sweep.risk RISK.yaml``: the chance that a body overturns at a site in ``years``.

Hazard (a curve file or a source model) → stripes of synthetic motions drawn from the
hazard's disaggregation → the fragility fitted over the stripes → the annual rate of
overturning λ_O, the probability in ``years`` with its interval, the return period and which
shaking contributes (docs/risk.md).  Also without simulating, from a known lognormal
fragility::

    python -m sweep.risk --hazard CURVE.csv --im pga --median 0.4g --beta 0.3 --years 50

Writes the results as a CF netCDF dataset (``--dataset``, default ``results/<name>/risk.nc``
beside the risk file), the fitted fragility as an OpenQuake NRML fragility model
(``--nrml``, default ``fragility.xml`` beside the dataset; a known fragility where ``--nrml``
says), ``-o`` a figure (the risk map with ``--map`` for a grid of bodies, its options side by
side against the target with ``--options``), ``--csv`` a table per body; ``--json`` prints the
report, and the text lists a grid's options side by side.  With ``--hazard`` the dataset is
written only where ``--dataset`` says.  ``results/<name>`` is one risk file's
(``risk_file.txt`` names it): another of the same name is refused unless ``--force``.  A bad
input gets one line per problem and exit status 2.  Under ``mpiexec -n N`` the ranks share
the stripes' simulations (each stripe study runs on all of them) and rank 0 reports and
writes.
"""
import sys
from pathlib import Path

from .cli import argument_parser, checked_type, command, print_json
from .io.exits import EXIT_BAD_INPUT, EXIT_FAILED, EXIT_OK
from .io.files import output_problems, write_csv
from .io.imt import display_scale
from .io.problems import FileProblems, Problem

_positive = checked_type(float, lambda v: v > 0, "a positive number")
_beta = checked_type(float, lambda v: v >= 0, "a non-negative number")
FORMATS = ("openquake", "usgs", "columns")
CLAIM = "risk_file.txt"  # in results/<name>: the risk file whose results these are
_HEAD_BYTES = 4096  # read to find the format of --hazard


def _parser():
    parser = argument_parser(
        "sweep.risk", quantities=True,
        description="Annual rate and probability of overturning of a body at a site: hazard, "
                    "stripes of synthetic motions, fragility, risk (docs/risk.md).")
    parser.add_argument("risk", nargs="?", help="risk file (YAML)")
    parser.add_argument("--hazard", metavar="CURVE",
                        help="a hazard curve file instead of a risk file (needs --median, "
                             "--beta)")
    parser.add_argument("--format", choices=FORMATS,
                        help="of --hazard (default: usgs for .json, openquake for a file "
                             "whose first line is a comment with investigation_time or whose "
                             "header starts lon,lat, else columns)")
    parser.add_argument("--im", help="intensity measure of --hazard: pga, pgv, sa(T) "
                                      "(default: the file's; must agree with it)")
    parser.add_argument("--units", help="units of the IM column of a two-column --hazard "
                                         "(default: the file's, '# units: g' or a header "
                                         "such as pga_g; must agree with it)")
    parser.add_argument("--poe", type=_positive, metavar="T",
                        help="the second column of --hazard is a probability of exceedance "
                             "in T years (default: what its header says, poe_50yr or "
                             "annual_rate, else annual rates; must agree with it)")
    parser.add_argument("--median", help="median of a known lognormal fragility, with units "
                                          "(0.4g, 3.9 m/s^2, 30 cm/s)")
    parser.add_argument("--beta", type=_beta, help="its dispersion")
    parser.add_argument("--fragility-model", metavar="XML",
                        help="a known fragility from an OpenQuake fragility model (NRML 0.5, "
                             "continuous logncdf, limit state 'overturned')")
    parser.add_argument("--function", metavar="ID",
                        help="the fragilityFunction of --fragility-model (default: its only "
                             "one)")
    parser.add_argument("--years", type=_positive, help="period of the probability (default: "
                                                        "the risk file's, else 50)")
    parser.add_argument("--json", action="store_true", help="print the report as JSON (SI)")
    parser.add_argument("-o", "--output", help="figure file (.png, .pdf, .svg)")
    parser.add_argument("--map", help="risk map figure over the grid of bodies")
    parser.add_argument("--options", metavar="FIG",
                        help="options figure of a grid or of named options: P with its "
                             "interval per body, against the target")
    parser.add_argument("--csv", help="table: one row per body")
    parser.add_argument("--dataset", help="netCDF dataset of the results")
    parser.add_argument("--nrml", help="OpenQuake fragility model (NRML 0.5) of the fit, or "
                                       "of the known fragility")
    parser.add_argument("--force", action="store_true",
                        help="replace the results of another risk file of the same name")
    return parser


def _median(text, im):
    """The median [SI] of ``--median`` in the IM's dimension, or a Problem."""
    from .io.imt import im_dimension
    from .io.units import parse_quantity

    try:
        q = parse_quantity(text, (im_dimension(im),))
        if q.body_relative or not q.value > 0:
            raise ValueError("must be positive, in fixed units")
        return q.to_si()
    except ValueError as err:
        return Problem("--median", text, str(err))


def _given_fragility(args, im, source=None):
    """(median [SI], beta) of ``--median``/``--beta`` or ``--fragility-model``, or None when
    none is given; FileProblems when they are incomplete or do not fit the IM ``im``."""
    if args.fragility_model is not None:
        from .probability.nrml import read_fragility_model

        if args.median is not None or args.beta is not None:
            raise FileProblems([Problem("--fragility-model", args.fragility_model,
                                        "give it or --median and --beta, not both")], source)
        try:
            functions = read_fragility_model(args.fragility_model)
        except OSError as err:
            raise FileProblems([Problem("--fragility-model", args.fragility_model,
                                        f"cannot read: {err.strerror}")], source) from None
        except (ValueError, SyntaxError, AttributeError) as err:
            raise FileProblems([Problem("--fragility-model", args.fragility_model,
                                        f"not a fragility model: {err}")], source) from None
        if args.function is None and len(functions) > 1:
            raise FileProblems([Problem("--function", None, "required: the model has "
                                        f"{', '.join(functions)}")], source)
        key = args.function if args.function is not None else next(iter(functions))
        if key not in functions:
            raise FileProblems([Problem("--function", key, "not in the model; it has "
                                        f"{', '.join(functions)}")], source)
        chosen = functions[key]
        if chosen.im != im:
            raise FileProblems([Problem("--fragility-model", args.fragility_model,
                                        f"a fragility of {chosen.im}, the hazard is of "
                                        f"{im}")], source)
        return chosen.median, chosen.beta
    if args.median is None and args.beta is None:
        return None
    if (args.median is None) != (args.beta is None):
        raise FileProblems([Problem("--median" if args.median is None else "--beta", None,
                                    "give --median and --beta together")], source)
    median = _median(args.median, im)
    if isinstance(median, Problem):
        raise FileProblems([median], source)
    return median, args.beta


def _hazard_format(path, given):
    """``--format``, or the format found from the file: usgs for a .json, openquake for a
    file whose first line is OpenQuake's comment (``investigation_time``) or whose header
    starts ``lon,lat``, else columns; FileProblems for a file that cannot be opened."""
    try:
        with open(path, "rb") as stream:
            head = stream.read(_HEAD_BYTES)
    except OSError as err:
        raise FileProblems([Problem("--hazard", str(path), f"cannot read: {err.strerror}")]) \
            from None
    if given:
        return given
    if path.suffix.lower() == ".json":
        return "usgs"
    lines = head.decode("utf-8", "replace").splitlines()[:2]
    if lines and lines[0].startswith("#") and "investigation_time" in lines[0]:
        return "openquake"
    return "openquake" if any(line.replace(" ", "").lower().startswith("lon,lat")
                              for line in lines) else "columns"


def _curve_only(args):
    """The :class:`RiskOutcome` of ``--hazard`` with a known fragility, or problems."""
    from .io.imt import normalize_im
    from .probability import hazard_curve as hc
    from .probability import hazard_files as hf
    from .probability import risk_report

    problems = [] if args.fragility_model is not None else [
        Problem(opt, None, "required with --hazard (or --fragility-model)")
        for opt, value in (("--median", args.median), ("--beta", args.beta)) if value is None]
    path = Path(args.hazard)
    im = None
    if args.im is not None:
        try:
            im = normalize_im(args.im)
        except ValueError as err:
            problems.append(Problem("--im", args.im, str(err)))
    if problems:
        raise FileProblems(problems)
    fmt = _hazard_format(path, args.format)
    if fmt != "columns" and args.poe is not None:
        raise FileProblems([Problem("--poe", args.poe, f"read from the {fmt} file itself")])
    try:
        if fmt == "columns":
            curve = hf.read_columns(path, im, args.units, investigation_time=args.poe)
        else:
            curve = hf.read_openquake_csv(path, im=im) if fmt == "openquake" else \
                hf.read_usgs_json(path, im)
            hf.check_given_units(curve, args.units, path)
    except hc.HazardFileError as err:
        raise FileProblems([_hazard_problem(err, path, args)]) from None
    except OSError as err:
        raise FileProblems([Problem("--hazard", str(path), f"cannot read: {err.strerror}")]) \
            from None
    if im is not None and curve.im != im:
        raise FileProblems([Problem("--im", args.im, f"the curve is of {curve.im}")])
    median, beta = _given_fragility(args, curve.im)
    return risk_report.known(curve, median, beta, args.years or 50.0, name=path.stem)


def _hazard_problem(err, path, args):
    """The :class:`Problem` of a ``HazardFileError``: at the option it is about (``--im``,
    ``--units``, ``--poe``), else at ``--hazard``."""
    from .io.problems import MISSING

    option, value = {"im": ("--im", args.im), "units": ("--units", args.units),
                     "kind": ("--poe", args.poe),
                     "investigation_time": ("--poe", args.poe)}.get(err.key,
                                                                    ("--hazard", str(path)))
    return Problem(option, MISSING if value is None else value,
                   str(err).removeprefix(f"{path}: "))


def _from_file(args):
    """The outcome of a risk file, its default dataset path, and the file's spec."""
    from .io.risk_schema import load_risk
    from .probability import risk_report
    from .probability.risk_inputs import checked_hazard

    spec = load_risk(args.risk, hazard=checked_hazard)
    folder = spec.folder / "results" / spec.name
    _claim(folder, args.risk, args.force)
    given = _given_fragility(args, spec.curve.im, args.risk)
    median, beta = (None, None) if given is None else given
    outcome = risk_report.compute(spec, folder, say=_say, median=median, beta=beta)
    if args.years is not None:
        outcome = _with_years(outcome, args.years)
    dataset = Path(spec.checked.output) if spec.checked.output else folder / "risk.nc"
    if spec.checked.output and not dataset.is_absolute():
        dataset = spec.folder / dataset
    return outcome, dataset


def _claim(folder, source, force):
    """Make ``folder`` (``results/<name>``) hold the results of the risk file ``source``,
    as its file ``CLAIM`` says; FileProblems when another risk file's results are there (the
    same ``name``), unless ``force``."""
    from .io.files import replacing
    from .runner.mpi import first_process

    marker, mine = folder / CLAIM, str(Path(source).resolve())
    try:
        holder = marker.read_text().strip()
    except OSError:  # none yet
        holder = None
    if holder not in (None, mine) and not force:
        raise FileProblems([Problem("name", folder.name, f"results/{folder.name} holds the "
                                    f"results of {holder}: rename this file's name, or use "
                                    "--force to replace them")], source)
    if holder != mine and first_process():
        with replacing(marker) as tmp:
            Path(tmp).write_text(mine + "\n")


def _with_years(outcome, years):
    """The outcome with its probabilities for another period."""
    import dataclasses

    import numpy as np

    from .probability.hazard_curve import poe_from_rate

    risks = np.empty(outcome.shape, dtype=object)
    for index in np.ndindex(*outcome.shape):
        r = outcome.risks[index]
        if r is not None:
            risks[index] = dataclasses.replace(
                r, years=years, probability=float(poe_from_rate(r.annual_rate, years)),
                probability_interval=tuple(float(p) for p in poe_from_rate(
                    r.rate_interval, years)))
    return dataclasses.replace(outcome, risks=risks, years=years)


def _say(text):
    from .runner.mpi import first_process

    if first_process():
        print(f"sweep.risk: {text}", file=sys.stderr, flush=True)


def _pct(p):
    return "n/a" if p is None or p != p else f"{100 * p:.3g} %"


def print_report(outcome):
    """One block per body: λ_O, P in years with its interval, return period, fragility, and
    the disaggregation of λ_O by IM segment (segments with ≥ 1 % of it)."""
    import numpy as np

    from .probability.risk_report import asymmetric

    from .probability.isolator_demand import said

    curve, demands = outcome.curve, outcome.demands()
    factor, unit = display_scale(curve.units)
    print(f"hazard: {curve.source}")
    if outcome.placement and outcome.placement != "the ground under the body":
        print(f"the stripes' motions: {outcome.placement}")
    for index in np.ndindex(*outcome.shape):
        r, f = outcome.risks[index], outcome.fits[index]
        print(f"{outcome.names()[index]}:")
        if f is not None and not f.identifiable and r is not None and r.bound is None:
            print(f"  fragility: a step at {r.median / factor:.3g} {unit}, where the stripes "
                  f"separate ({f.reason}); the interval: a step anywhere between the highest "
                  "stripe where none overturned and the lowest where all did (the curve's "
                  "ends where there is no such stripe)")
        elif f is not None and not f.identifiable:
            print(f"  fragility: not identifiable ({f.reason})")
        elif f is not None:
            lo, hi = f.theta_interval
            print(f"  fragility: median {f.theta / factor:.3g} {unit} [{lo / factor:.3g}, "
                  f"{hi / factor:.3g}], beta {f.beta:.3g} [{f.beta_interval[0]:.3g}, "
                  f"{f.beta_interval[1]:.3g}] ({f.reason})")
        elif r is not None:
            print(f"  fragility (given): median {r.median / factor:.3g} {unit}, "
                  f"beta {r.beta:.3g}")
        if asymmetric(outcome, index):
            print(_side_line(outcome, index, factor, unit))
        if r is None:
            print("  risk: not computed (the fragility is not identifiable)")
            continue
        for line in _risk_lines(r, outcome.target):
            print(f"  {line}")
        if demands is not None and demands[index] is not None:
            print(f"  isolator displacement: {said(demands[index])}")
        print(f"  {curve.im} segment [{unit}]     share of the {'bound' if r.bound else 'rate'}")
        for lower, upper, share in zip(r.lower, r.upper, r.shares):
            if share >= 0.01:
                top = "..." if not np.isfinite(upper) else f"{upper / factor:.3g}"
                print(f"  {lower / factor:8.3g} - {top:<8} {100 * share:6.1f} %  "
                      + "#" * int(round(40 * share)))
    if outcome.body_dims:
        print("\n".join(_options_lines(outcome)))
    if outcome.target is not None and outcome.shape:
        meeting = [outcome.names()[i] for i in np.ndindex(*outcome.shape)
                   if outcome.risks[i] is not None
                   and outcome.risks[i].probability <= outcome.target]
        sure = {outcome.names()[i] for i in np.ndindex(*outcome.shape)
                if outcome.risks[i] is not None
                and outcome.risks[i].probability_interval[1] <= outcome.target}
        print(f"bodies meeting the target ({_pct(outcome.target)} in {outcome.years:g} years): "
              f"{len(meeting)} of {outcome.risks.size} ({len(sure)} also with the upper "
              f"bound of the interval or the bound of a body never overturned, marked *)")
        for label in meeting:
            print(f"  {label}{' *' if label in sure else ''}")
    for text in outcome.warnings:
        print(f"caution: {text}")


def _verdicts(r, target):
    """Whether ``r`` meets ``target``: by its estimate and by its interval's upper bound (a
    body never overturned: by its bound, both); ``n/a`` where not known."""
    if r is None:
        return "n/a", "n/a"
    upper = r.probability if r.bound is not None else r.probability_interval[1]
    said = {True: "yes", False: "no"}
    return said[bool(r.probability <= target)], \
        said[bool(upper <= target)] if upper == upper else "n/a"


def _options_lines(outcome):
    """The options of a grid side by side, a row per body: its axes' values (SI), P in
    years with its interval (≤ its bound for a body never overturned) and, with a target,
    whether it meets it by the estimate and by the upper bound."""
    import numpy as np

    heads = [a + (f" [{u}]" if u != "1" else "") for a, u in zip(outcome.axes(),
                                                                 outcome.units())]
    heads += [f"P in {outcome.years:g} yr", f"{100 * outcome.confidence:g} % interval"]
    if outcome.target is not None:
        heads += ["meets (estimate)", "meets (upper bound)"]
    demands = outcome.demands()
    if demands is not None:
        heads += [f"isolator d* [m] at {_pct(outcome.target)}"]
    rows = []
    for index in np.ndindex(*outcome.shape):
        r = outcome.risks[index]
        row = [v if isinstance(v, str) else f"{v:.4g}" for v in outcome.option(index).values()]
        if r is None:
            row += ["n/a", ""]
        elif r.bound is not None:
            row += [f"≤ {_pct(r.probability)}", "(never overturned: bound)"]
        else:
            lo, hi = r.probability_interval
            row += [_pct(r.probability), f"[{_pct(lo)}, {_pct(hi)}]" if lo == lo else ""]
        if outcome.target is not None:
            row += list(_verdicts(r, outcome.target))
        if demands is not None:
            d = demands[index]
            row.append("" if d is None else "n/a" if d.displacement is None
                       else f"{d.displacement:.3g}")
        rows.append(row)
    widths = [max(len(c) for c in column) for column in zip(heads, *rows)]
    target = "" if outcome.target is None else f"; target {_pct(outcome.target)}"
    return [f"options ({outcome.risks.size}{target}):"] + [
        "  " + "  ".join(c.ljust(w) for c, w in zip(row, widths)).rstrip()
        for row in (heads, *rows)]


def _side_line(outcome, index, factor, unit):
    """The overturnings of a body with G off the middle to the left (−x, about corner 1)
    and to the right at each stripe (docs/bodies.md)."""
    import math

    sides = outcome.sides
    along = (slice(None),) + index
    counts = ", ".join(f"{s.level / factor:.3g}: {left}/{right}" for s, left, right in zip(
        outcome.stripes, sides.left[along].tolist(), sides.right[along].tolist()))
    return (f"  G off the middle (alpha_1 {math.degrees(sides.alpha_1[index]):.3g} deg, "
            f"alpha_2 {math.degrees(sides.alpha_2[index]):.3g} deg): overturned to the left "
            f"(-x) / right (+x) at each stripe [{unit}]: {counts}")


def _risk_lines(r, target):
    """The lines of a body's risk: λ_O and P with their intervals (or, for a body never
    overturned, their bounds), the target, the shares beyond the curve's ends."""
    import numpy as np

    from .probability.hazard_curve import poe_from_rate

    verdict = "" if target is None else \
        f"; target {_pct(target)}: " + ("met" if r.probability <= target else "NOT met")
    if r.bound is not None:
        return [f"annual rate of overturning ≤ {r.annual_rate:.3g}/yr; return period ≥ "
                f"{r.return_period:.3g} yr ({r.bound})",
                f"probability in {r.years:g} years ≤ {_pct(r.probability)}{verdict}"
                + (" on the bound" if verdict else ""),
                f"share of the bound from above the curve's last level "
                f"{_pct(r.share_above)}"]
    lo, hi = r.rate_interval
    interval = f" [{lo:.3g}, {hi:.3g}]" if np.isfinite(lo) else ""
    plo, phi = r.probability_interval
    pint = f" [{_pct(plo)}, {_pct(phi)}]" if np.isfinite(plo) else ""
    rate_most, p_most = "", ""
    if r.open_above:  # the part above the curve: between F(x_n) λ(x_n) and λ(x_n)
        rate_most = (f" (at least: up to {r.rate_at_most:.3g}/yr if all shaking above the "
                     "curve overturned it; see the caution)")
        p_most = f" (at least: up to {_pct(poe_from_rate(r.rate_at_most, r.years))})"
    return [f"annual rate of overturning {r.annual_rate:.3g}/yr{interval}{rate_most}; return "
            f"period {r.return_period:.3g} yr",
            f"probability in {r.years:g} years: {_pct(r.probability)}{pint}{p_most}{verdict}",
            f"share from above the curve's last level {_pct(r.share_above)} (included, with "
            f"the fragility there), below its first level {_pct(r.share_below)} (estimate, "
            "not included)"]


def _csv_rows(outcome):
    from .probability.risk_report import body_record
    import numpy as np

    rows = []
    for index in np.ndindex(*outcome.shape):
        record = body_record(outcome, index)
        interval = record.get("interval") or {}
        rows.append({"body": record["body"], **outcome.option(index),
                     "median": record["fragility"]["median"],
                     "beta": record["fragility"]["beta"],
                     "annual_rate": record["annual_rate"],
                     "annual_rate_lower": (interval.get("annual_rate") or [None])[0],
                     "annual_rate_upper": (interval.get("annual_rate") or [None, None])[1],
                     "years": record["years"], "probability": record["probability"],
                     "probability_lower": (interval.get("probability") or [None])[0],
                     "probability_upper": (interval.get("probability") or [None, None])[1],
                     "return_period": record["return_period"],
                     "bound": record.get("bound") or "",
                     **({"isolator_demand": (record.get("isolator_demand") or {}).get(
                         "displacement")} if outcome.displacements is not None else {})})
    return rows


def _write_nrml(outcome, path):
    import numpy as np

    from .probability.nrml import write_fragility_model

    functions = []
    for index in np.ndindex(*outcome.shape):
        f, r = outcome.fits[index], outcome.risks[index]
        label = outcome.labels()[index].replace(" = ", "=").replace(", ", "_").replace(" ", "")
        if f is not None and f.identifiable:
            functions.append((label, f.theta, f.beta))
        elif f is None and r is not None:  # a known fragility
            functions.append((label, r.median, r.beta))
    if not functions:
        return None
    return write_fragility_model(path, functions, outcome.curve.im,
                                 description=f"overturning: {outcome.name}")


def _draw(outcome, figure, risk_map, options=None):
    import matplotlib
    import numpy as np

    matplotlib.use("Agg")
    from .plots import risk as risk_plots

    if figure:
        shown = next((i for i in np.ndindex(*outcome.shape) if outcome.risks[i] is not None),
                     next(np.ndindex(*outcome.shape)))
        risk_plots.save(risk_plots.figure_body(outcome, shown), Path(figure))
    if risk_map:
        risk_plots.save(risk_plots.figure_map(outcome), Path(risk_map))
    if options:
        risk_plots.save(risk_plots.figure_options(outcome), Path(options))


@command
def main(argv=None):
    args = _parser().parse_args(argv)
    source = args.risk or args.hazard
    if (args.risk is None) == (args.hazard is None):
        print("sweep.risk: give a risk file or --hazard CURVE (not both)", file=sys.stderr)
        return EXIT_BAD_INPUT
    unusable = output_problems({"-o/--output": args.output, "--map": args.map,
                                "--options": args.options,
                                "--csv": args.csv, "--dataset": args.dataset,
                                "--nrml": args.nrml})
    if unusable:
        print(FileProblems(unusable), file=sys.stderr)
        return EXIT_BAD_INPUT
    from .io.problems import cautions, reported
    from .probability.risk_dataset import to_dataset, write_dataset
    from .probability.risk_report import report
    from .probability.site_studies import RunFailed
    from .runner.mpi import first_process

    try:
        with cautions(show=first_process()) as said, reported(source):
            if args.hazard:
                outcome = _curve_only(args)
                dataset = Path(args.dataset) if args.dataset else None
            else:
                outcome, default = _from_file(args)
                dataset = Path(args.dataset) if args.dataset else default
    except RunFailed as err:
        print(f"sweep.risk: {err}", file=sys.stderr)
        return EXIT_FAILED
    if not first_process():  # under mpiexec: the ranks shared the stripes; rank 0 reports
        return EXIT_OK
    outcome.warnings = said
    for flag, given in (("--map", args.map), ("--options", args.options)):
        if given and not outcome.body_dims:
            print(f"sweep.risk: {flag} needs a grid of bodies in the risk file",
                  file=sys.stderr)
            return EXIT_BAD_INPUT
    history = "python -m sweep.risk " + " ".join(sys.argv[1:] if argv is None else argv)
    written = []
    if dataset is not None:
        write_dataset(to_dataset(outcome, history), dataset)
        written.append(str(dataset))
    nrml = Path(args.nrml) if args.nrml else None
    if nrml is None and dataset is not None and outcome.stripes is not None:
        nrml = dataset.with_name(dataset.stem.replace("risk", "fragility") + ".xml")
    if nrml is not None and _write_nrml(outcome, nrml):
        written.append(str(nrml))
    elif args.nrml:
        print("sweep.risk: --nrml not written: no body has a lognormal fragility",
              file=sys.stderr)
    if args.csv:
        write_csv(args.csv, _csv_rows(outcome))
        written.append(args.csv)
    if args.output or args.map or args.options:
        _draw(outcome, args.output, args.map, args.options)
        written += [p for p in (args.output, args.map, args.options) if p]
    if args.json:
        document = report(outcome)
        document["written"] = written
        print_json(document)
    else:
        print_report(outcome)
        if written:
            print(f"wrote {', '.join(written)}")
    return EXIT_OK


if __name__ == "__main__":
    sys.exit(main())
