"""``python -m sweep.scene SCENE.yaml``: run one scene and show what the body did, verdict first.

Usage: ``python -m sweep.scene SCENE.yaml [--json | --summary] [--plot out.png] [--animate
out.gif] [--fps N] [--from S] [--to S] [--history out.nc]``."""
import math
import sys
from pathlib import Path

from .cli import argument_parser, checked_type, command, print_json
from .io.exits import EXIT_OK
from .io.files import output_problems
from .io.problems import FileProblems, reported
from .io.records import provenance_line
from .plots.gif import FPS, MAX_FPS
from .runner.simulate import simulate, summary, to_json_dict

DESCRIPTION = ("Run one scene and show what the body did, the verdict first; --plot, "
               "--animate and --history draw and keep its time history.")
ANIMATION = {"fps": "--fps", "start": "--from", "end": "--to"}  # options of --animate

_fps = checked_type(float, lambda v: 0 < v <= MAX_FPS,
                    f"a number above 0 and at most {MAX_FPS}")
_time = checked_type(float, lambda v: 0 <= v < math.inf, "a finite number of seconds >= 0")


def _parser():
    said = argument_parser("sweep.scene", DESCRIPTION, quantities=True)
    said.add_argument("scene", help="scene file (YAML)")
    shown = said.add_mutually_exclusive_group()
    shown.add_argument("--json", action="store_true",
                       help="print the result as JSON: the verdict's keys first, then how "
                            "each record was read (provenance), then the per-impact arrays, "
                            "each on one line")
    shown.add_argument("--summary", action="store_true",
                       help="print only what the body did and the end status (two lines; a "
                            "third says whether an anchor held or broke, and when), "
                            "and how each record was read (a line each)")
    said.add_argument("--plot", metavar="PNG",
                      help="what the body did as title over its positions, theta/alpha, the "
                           "moving floor components and the motion type, captioned with how "
                           "each record was read")
    said.add_argument("--animate", metavar="GIF",
                      help="the body on the moving floor, in real time, by default from "
                           "shortly before it first moves to shortly after it last moves "
                           "(final rest or overturning); the window, frame count and "
                           "estimated size are said on stderr before writing")
    said.add_argument("--fps", type=_fps, default=None, metavar="N",
                      help=f"frames a second of --animate (default {FPS}; at most {MAX_FPS}, "
                           "the most GIF players show); a frame lasts a whole number of 1/100 "
                           "s, so 30 gives 33.3")
    said.add_argument("--from", dest="start", type=_time, default=None, metavar="S",
                      help="time [s] --animate starts at (default: shortly before the first "
                           "motion)")
    said.add_argument("--to", dest="end", type=_time, default=None, metavar="S",
                      help="time [s] --animate ends at (default: shortly after the last "
                           "motion)")
    said.add_argument("--history", metavar="NC", help="write the time history (netCDF)")
    return said


@command
def main(argv=None):
    said = _parser()
    args = said.parse_args(argv)
    given = [option for key, option in ANIMATION.items() if getattr(args, key) is not None]
    if given and not args.animate:
        said.error(f"{', '.join(given)}: for --animate only")
    if args.start is not None and args.end is not None and not args.end > args.start:
        said.error(f"--to {args.end:g} must be after --from {args.start:g}")
    files = {key: getattr(args, key) for key in ("plot", "animate", "history")
             if getattr(args, key)}
    with reported(args.scene):
        outputs = output_problems({f"--{key}": path for key, path in files.items()})
        if outputs:  # before any work
            raise FileProblems(outputs, args.scene)
        result = simulate(args.scene, history=bool(files))
    read = [provenance_line(component, said) for component, said in result.provenance.items()]
    if args.history:
        from .netcdf import write_netcdf
        write_netcdf(result.history, args.history)
    if args.plot or args.animate:
        import matplotlib

        matplotlib.use("Agg")  # files only: no window, whatever the user's default backend
        from .plots.scene import animate_scene, animation_window, draw_scene
        from .plots.style import save_figure
        if args.animate:
            try:  # before drawing anything
                animation_window(result.history, args.start, args.end)
            except ValueError as err:
                said.error(f"--from/--to: {err}")
        if args.plot:
            save_figure(draw_scene(result.history, args.scene, read), Path(args.plot), dpi=110)
        if args.animate:
            animate_scene(result.history, args.animate, args.scene,
                          fps=FPS if args.fps is None else args.fps, start=args.start,
                          end=args.end)
    if args.json:
        print_json(to_json_dict(result), one_line_per_key=True)
        return EXIT_OK
    print(summary(result))
    for line in read:
        print(line)
    if not args.summary:
        for path in files.values():
            print(f"wrote {path}")
    return EXIT_OK


if __name__ == "__main__":
    sys.exit(main())
