"""``python -m sweep.scene SCENE.yaml [--json] [--plot out.png] [--animate out.gif]
[--history out.nc]``: run one scene and show what the body did."""
import argparse
import json
import sys

from .io.problems import reported
from .io.scene_schema import load_scene, resolve_scene


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m sweep.scene", description=__doc__)
    parser.add_argument("scene", help="scene file (YAML)")
    parser.add_argument("--json", action="store_true", help="print the result as JSON")
    parser.add_argument("--plot", metavar="PNG", help="positions every 1/50 s, theta, floor, mode")
    parser.add_argument("--animate", metavar="GIF", help="the body on the moving floor")
    parser.add_argument("--history", metavar="NC", help="write the time history (netCDF)")
    args = parser.parse_args(argv)
    with reported(args.scene):
        resolved = resolve_scene(load_scene(args.scene))
    from kernels import run_scene
    from .runner.simulate import to_json_dict
    want_history = bool(args.plot or args.animate or args.history)
    result = run_scene(resolved, history=want_history)
    if want_history:
        from .history import history_dataset, write_netcdf
        ds = history_dataset(result.history, resolved)
        ds.attrs["source"] = args.scene
        if args.history:
            write_netcdf(ds, args.history)
        title = f"{args.scene}: {result.status}"
        if args.plot:
            from .plots.scene import draw_scene
            draw_scene(ds, args.plot, title)
        if args.animate:
            from .plots.scene import animate_scene
            animate_scene(ds, args.animate, args.scene)
    if args.json:
        json.dump(to_json_dict(result), sys.stdout, indent=1)
        print()
    else:
        print(f"{result.status}: {result.message}; {len(result.impact_times)} impacts, "
              f"max |theta| {result.max_abs_theta:.4g} rad, cpu {result.cpu_s * 1e3:.2f} ms")
    return 0


if __name__ == "__main__":
    sys.exit(main())
