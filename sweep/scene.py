"""``python -m sweep.scene SCENE.yaml [--json | --summary] [--plot out.png] [--animate out.gif]
[--history out.nc]``: run one scene and show what the body did, the verdict first."""
import sys
from pathlib import Path

from .cli import argument_parser, command, print_json
from .io.files import output_problems
from .io.problems import FileProblems, reported
from .io.records import provenance_line
from .runner.simulate import simulate, summary, to_json_dict

DESCRIPTION = ("Run one scene and show what the body did, the verdict first; --plot, "
               "--animate and --history draw and keep its time history.")

@command
def main(argv=None):
    parser = argument_parser("sweep.scene", DESCRIPTION, quantities=True)
    parser.add_argument("scene", help="scene file (YAML)")
    said = parser.add_mutually_exclusive_group()
    said.add_argument("--json", action="store_true",
                      help="print the result as JSON: the verdict's keys first, then the "
                           "per-impact arrays, each on one line")
    said.add_argument("--summary", action="store_true",
                      help="print only what the body did and the end status (two lines)")
    parser.add_argument("--plot", metavar="PNG",
                        help="what the body did as title over its positions, theta/alpha, "
                             "the moving floor components and the motion type")
    parser.add_argument("--animate", metavar="GIF", help="the body on the moving floor")
    parser.add_argument("--history", metavar="NC", help="write the time history (netCDF)")
    args = parser.parse_args(argv)
    files = {key: getattr(args, key) for key in ("plot", "animate", "history")
             if getattr(args, key)}
    with reported(args.scene):
        outputs = output_problems({f"--{key}": path for key, path in files.items()})
        if outputs:  # before any work
            raise FileProblems(outputs, args.scene)
        result = simulate(args.scene, history=bool(files))
    read = [provenance_line(component, said) for component, said in result.provenance.items()]
    if args.history:
        from .runner.store import write_netcdf
        write_netcdf(result.history, args.history)
    if args.plot or args.animate:
        import matplotlib

        matplotlib.use("Agg")  # files only: no window, whatever the user's default backend
        from .plots.scene import animate_scene, draw_scene
        from .plots.style import save_figure
        if args.plot:
            save_figure(draw_scene(result.history, args.scene, read), Path(args.plot), dpi=110)
        if args.animate:
            animate_scene(result.history, args.animate, args.scene)
    if args.json:
        print_json(to_json_dict(result), one_line_per_key=True)
        return 0
    print(summary(result))
    for line in read:
        print(line)
    if not args.summary:
        for path in files.values():
            print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
