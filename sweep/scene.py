"""``python -m sweep.scene SCENE.yaml [--json] [--plot out.png] [--animate out.gif]
[--history out.nc]``: run one scene and show what the body did."""
import argparse
import sys
from pathlib import Path

from .cli import command, print_json
from .io.files import output_problems
from .io.problems import FileProblems, reported
from .runner.simulate import simulate, summary_line, to_json_dict


@command
def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m sweep.scene", description=__doc__)
    parser.add_argument("scene", help="scene file (YAML)")
    parser.add_argument("--json", action="store_true", help="print the result as JSON")
    parser.add_argument("--plot", metavar="PNG", help="positions every 1/50 s, theta, floor, mode")
    parser.add_argument("--animate", metavar="GIF", help="the body on the moving floor")
    parser.add_argument("--history", metavar="NC", help="write the time history (netCDF)")
    args = parser.parse_args(argv)
    with reported(args.scene):
        outputs = output_problems({f"--{key}": getattr(args, key)
                                   for key in ("plot", "animate", "history")})
        if outputs:  # before any work
            raise FileProblems(outputs, args.scene)
        result = simulate(args.scene, history=bool(args.plot or args.animate or args.history))
    if args.history:
        from .runner.store import write_netcdf
        write_netcdf(result.history, args.history)
    if args.plot or args.animate:
        import matplotlib

        matplotlib.use("Agg")  # files only: no window, whatever the user's default backend
        from .plots.scene import animate_scene, draw_scene
        from .plots.style import save_figure
        if args.plot:
            save_figure(draw_scene(result.history, f"{args.scene}: {result.status}"),
                        Path(args.plot), dpi=110)
        if args.animate:
            animate_scene(result.history, args.animate, args.scene)
    if args.json:
        print_json(to_json_dict(result))
    else:
        print(summary_line(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
