"""``python -m sweep.estimate BODIES.yaml [--json]``: lower limits of the peak ground motion
at a site from the sizes of bodies that overturned there (``sweep.paper.estimate``).

A bodies file lists ``site`` and ``bodies: [{name, B, H, overturned, mu, i_g, direction}]``
(``sweep.io.bodies_schema``).  Output in SI with ``--json``, else a table in the paper's units.
"""
import argparse
import sys

from .cli import command, print_json
from .io.bodies_schema import load_bodies
from .io.problems import reported
from .paper.estimate import estimate, format_text


@command
def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python -m sweep.estimate",
        description="Lower limits of the peak ground acceleration, velocity and displacement "
                    "at a site from the sizes of bodies that overturned there (Ishiyama 1982, "
                    "Eqs. 14, 16, 18).")
    parser.add_argument("bodies", help="bodies file (YAML): site, bodies: [{name, B, H, "
                                       "overturned, mu, i_g, direction}]")
    parser.add_argument("--json", action="store_true", help="print the result as JSON (SI)")
    args = parser.parse_args(argv)
    with reported(args.bodies):
        site, bodies = load_bodies(args.bodies)
    result = estimate(bodies)
    if args.json:
        print_json({"site": site, **result})
    else:
        print(format_text(result, site))
    return 0


if __name__ == "__main__":
    sys.exit(main())
