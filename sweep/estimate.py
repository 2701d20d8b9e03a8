"""``python -m sweep.estimate BODIES.yaml``: what bodies seen at sites tell of the shaking there.

Bodies seen overturned and standing at sites bound the peak ground motion there.

    python -m sweep.estimate BODIES.yaml [--json] [--csv FILE] [-o FIG.png]
    python -m sweep.estimate BODIES.yaml --write-study DIR

For every site of the bodies file (``sweep.io.bodies_schema``): the paper's deterministic
lower limits of PGA, PGV and PGD from the overturned bodies (Ishiyama 1982, Eqs. 14, 16, 18;
``sweep.paper.estimate``); with an ``ensemble:`` section, also the bounds at stated
probabilities from simulating every body under the ensemble's motions, overturned bodies
bounding the shaking from below and standing ones from above (``sweep.probability.site``),
side by side.  Bodies that slide (mu < B/H) are kept out of both and said so.

Output: tables in the paper's units, or JSON in SI (``--json``: the site's object for a
one-site file, else ``{"sites": [...]}``); ``--csv`` one row per site and body; ``-o`` one
figure per site (``FIG_<site>.png`` with several sites).  The simulations are kept in
``results/<file stem>/`` beside the bodies file and reused while their inputs are unchanged;
``--write-study DIR`` only writes the studies, for ``python -m sweep.run`` on a cluster.
"""
import re
import sys
from pathlib import Path

from .cli import argument_parser, command, print_json
from .io.bodies_schema import load_bodies, load_survey  # noqa: F401  (load_bodies: one site)
from .io.exits import EXIT_FAILED, EXIT_OK
from .io.files import output_problems, write_csv
from .io.problems import MISSING, FileProblems, Problem, reported
from .paper.estimate import estimate, format_text


def _parse(argv):
    parser = argument_parser(
        "sweep.estimate", quantities=True,
        description="What bodies seen overturned and standing at sites tell of the peak ground "
                    "motion: the lower limits of PGA, PGV and PGD of Ishiyama (1982, Eqs. 14, "
                    "16, 18) and, with an ensemble of motions in the file, bounds at stated "
                    "probabilities from simulating every body.")
    parser.add_argument("bodies", help="bodies file (YAML): sites: [{name, latitude, longitude, "
                                       "bodies: [{name, B, H, overturned, mu, i_g, "
                                       "direction}]}], ensemble: {...}")
    parser.add_argument("--json", action="store_true", help="print the result as JSON (SI)")
    parser.add_argument("--csv", metavar="FILE", help="write one row per site and body (SI)")
    parser.add_argument("-o", "--output", metavar="FIG.png",
                        help="draw the ensemble's figure of each site (suffixed _<site> with "
                             "several sites)")
    parser.add_argument("--write-study", metavar="DIR",
                        help="only write the study of every body (YAML) to DIR, for "
                             "python -m sweep.run on a cluster")
    return parser.parse_args(argv)


def slug(name):
    """A file-name part of a site's name: ``graveyard A`` -> ``graveyard_a``."""
    return re.sub(r"[^0-9a-z]+", "_", name.lower()).strip("_") or "site"


def figure_paths(output, sites):
    """The figure of each site: ``output`` for one, ``<stem>_<site><suffix>`` for several."""
    output = Path(output)
    if len(sites) == 1:
        return [output]
    return [output.with_name(f"{output.stem}_{slug(site.name)}{output.suffix}")
            for site in sites]


def _check(args, survey):
    """Problems of the options against the file, before any work."""
    found = output_problems({"--csv": args.csv})
    for path in figure_paths(args.output, survey.sites) if args.output else ():
        found += output_problems({"-o/--output": path})
    wants = [option for option, given in (("-o/--output", args.output),
                                          ("--write-study", args.write_study)) if given]
    if wants and survey.ensemble is None:
        found.append(Problem("ensemble", MISSING, f"required by {' and '.join(wants)}: the "
                                                  "motions the bodies are simulated under"))
    if found:
        raise FileProblems(found, args.bodies)


def _say(text):
    print(f"sweep.estimate: {text}", file=sys.stderr, flush=True)


def _write_studies(survey, folder):
    from .probability import site_studies

    results = site_studies.results_folder(survey.source)
    written = site_studies.write_studies(survey, folder, results)
    print(f"wrote {len(written)} studies (one per body that rocks) to {folder}; their "
          f"datasets go to {results.resolve()}, where python -m sweep.estimate "
          f"{survey.source} reads them:")
    for path in written:
        print(f"  mpiexec -n <ranks> python -m sweep.run {path}")
    return EXIT_OK


def _site_json(site, deterministic, probabilistic):
    """One site's result, SI: its name and coordinates, the deterministic estimate's keys,
    ``ensemble`` and ``side_by_side`` (None without an ensemble)."""
    from .probability.site_report import summary

    out = {"site": site.name, "latitude": site.latitude, "longitude": site.longitude,
           **deterministic, "ensemble": None, "side_by_side": None}
    if probabilistic is None:
        return out
    out["ensemble"] = summary(probabilistic)
    quantiles, limits = probabilistic.quantiles, deterministic["lower_limits"]
    out["side_by_side"] = {
        key: {"deterministic_lower_limit": None if limits is None else limits[key]["value"],
              "probabilities": list(probabilistic.ensemble.probabilities),
              "posterior_quantiles": None if quantiles is None else quantiles[k]}
        for k, key in enumerate(("pga", "pgv"))}
    return out


def _csv_rows(site, deterministic, probabilistic):
    """One row per body of a site: SI values, the site's name and coordinates."""
    probabilities = () if probabilistic is None else probabilistic.ensemble.probabilities
    by_name = {} if probabilistic is None else {b.name: b for b in probabilistic.bodies}
    kept_out = {} if probabilistic is None else dict(probabilistic.excluded)
    quantiles = None if probabilistic is None else probabilistic.quantiles
    limits = deterministic["lower_limits"]
    rows = []
    for row in deterministic["bodies"]:
        body = by_name.get(row["name"])
        out = {"site": site.name, "latitude": site.latitude, "longitude": site.longitude,
               "body": row["name"], "B_m": row["B"], "H_m": row["H"], "i_g_m": row["i_g"],
               "mu": row["mu"], "mu_simulated": None if body is None else body.mu,
               "overturned": row["overturned"], "direction": row["direction"],
               "a_o_m_s2": row["a_o"], "v_o_m_s": row["v_o"], "d_o_m": row["d_o"],
               "slides": row["slides"],
               "excluded": kept_out.get(row["name"], "; ".join(
                   n for n in row["notes"] if "slides" in n)),
               "site_a_o_m_s2": None if limits is None else limits["pga"]["value"],
               "site_v_o_m_s": None if limits is None else limits["pgv"]["value"],
               "bound": "" if body is None else ("lower" if body.overturned else "upper")}
        for i, q in enumerate(probabilities):
            bound = None if body is None else body.bounds[i]
            out[f"bound_q{q:g}_m_s2"] = None if bound is None else bound.value
            out[f"bound_q{q:g}_beyond"] = None if bound is None else bound.beyond
        if probabilities:
            out["slid_near_bound"] = None if body is None else body.slid
        if probabilities:
            sup = probabilistic.support
            out["site_simulations_reproducing"] = None if sup is None else sup.matches
            out["site_levels_with_likelihood"] = None if sup is None else sup.levels
        for i, q in enumerate(probabilities):
            out[f"site_pga_q{q:g}_m_s2"] = None if quantiles is None else quantiles[0][i]
            out[f"site_pgv_q{q:g}_m_s"] = None if quantiles is None else quantiles[1][i]
        rows.append(out)
    return rows


def _figures(paths, results):
    import matplotlib

    matplotlib.use("Agg")  # files only: no window, whatever the user's default backend
    import matplotlib.pyplot as plt

    from .plots.site import figure_site
    from .plots.style import save_figure

    for path, (deterministic, probabilistic) in zip(paths, results):
        fig = figure_site(probabilistic, deterministic["lower_limits"])
        save_figure(fig, Path(path), dpi=110)
        plt.close(fig)


def _site_text(site, deterministic, probabilistic):
    where = "" if site.latitude is None or site.longitude is None else \
        f" ({site.latitude:g} N, {site.longitude:g} E)"
    text = format_text(deterministic, None if site.name is None else site.name + where)
    if probabilistic is None:
        return text
    from .probability.site_report import format_text as probability_text
    return text + "\n\n" + probability_text(probabilistic, deterministic["lower_limits"])


@command
def main(argv=None):
    args = _parse(argv)
    with reported(args.bodies):
        survey = load_survey(args.bodies)
        _check(args, survey)
    if args.write_study:
        return _write_studies(survey, Path(args.write_study))
    probabilistic = [None] * len(survey.sites)
    if survey.ensemble is not None:
        from .probability import site, site_studies

        try:
            datasets = site_studies.ensemble_datasets(
                survey, site_studies.results_folder(args.bodies), _say)
        except site_studies.RunFailed as err:
            _say(f"error: {err}")
            return EXIT_FAILED
        probabilistic = [site.estimate_site(s, survey.ensemble, datasets)
                         for s in survey.sites]
    results = [(estimate(s.bodies), p) for s, p in zip(survey.sites, probabilistic)]
    if args.json:
        sites = [_site_json(s, d, p) for s, (d, p) in zip(survey.sites, results)]
        print_json(sites[0] if survey.one_site_format else {"sites": sites})
    else:
        print("\n\n".join(_site_text(s, d, p) for s, (d, p) in zip(survey.sites, results)))
    if args.csv:
        write_csv(args.csv, [row for s, (d, p) in zip(survey.sites, results)
                             for row in _csv_rows(s, d, p)])
    if args.output:
        _figures(figure_paths(args.output, survey.sites), results)
    return EXIT_OK


if __name__ == "__main__":
    sys.exit(main())
