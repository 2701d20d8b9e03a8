"""What every command does around its work: how it ends, and the JSON it prints.

``command`` decorates a command's entry point ``main(argv=None) -> int``, the function that
both ``python -m sweep.<name>`` and the console script call::

    @command
    def main(argv=None):
        ...
        return 0

    if __name__ == "__main__":
        sys.exit(main())

The decorated ``main`` returns the exit status instead of a traceback when

* the reader of its output goes away (``python -m sweep.scene s.yaml --json | head -1``):
  stdout is pointed at ``os.devnull``, so that the interpreter's last flush cannot fail
  either (the recipe of the Python docs, "Note on SIGPIPE"), and the status is 141 = 128 +
  SIGPIPE, what a shell reports for a program ended by a broken pipe (``yes | head -1``);
  under ``set -o pipefail`` the command thus counts as those do;
* the user presses Ctrl-C: one line ``interrupted`` on stderr, status 130 = 128 + SIGINT.

It prints an input file's values that are likely not meant (``InputWarning``) as one line
each, ``warning: <path>: <message>``.  A command run to its end leaves the objects alive at
the interpreter's exit out of its last garbage collections (``gc.freeze`` at exit): walking
numba's compiler state took 0.2 s of a warm ``sweep.scene``; what their counts free still
goes, and every file is written and closed before.

``argument_parser`` makes a command's ``argparse`` parser: named as it was called
(``rigid-scene`` as the console script, ``python -m sweep.scene`` otherwise; :func:`program`),
its description without reStructuredText markup (:func:`plain`), and ``EPILOG`` (the units of
quantities and where every key of the input files is described) for the commands that read
quantities.

``print_json`` prints standard JSON (RFC 8259): NaN and infinities become ``null``; a long
list can be kept on one line, so that a reader sees the keys before the arrays.
"""
import atexit
import functools
import gc
import json
import math
import os
import re
import sys
import warnings
from pathlib import Path

import numpy as np

from .io.exits import EXIT_BROKEN_PIPE, EXIT_INTERRUPTED
from .io.problems import InputWarning
from .io.units import listing

EPILOG = (f"A quantity is a number in SI units (m, s, rad, Hz) or a string '<number> <unit>'; "
          f"units: {listing()} (west, v_H and alpha: times the body's (B/H) g, single-shock "
          "overturning velocity and slenderness angle).  Every key of scene, study and bodies "
          "files, with its units and default: docs/schema.md.")
SCRIPTS = {"sweep.run": "rigid-run", "sweep.scene": "rigid-scene", "sweep.plot": "rigid-plot",
           "sweep.estimate": "rigid-estimate", "sweep.fragility": "rigid-fragility",
           "sweep.risk": "rigid-risk"}
"""The console scripts of pyproject.toml's [project.scripts], by the module they run."""
_ROLE = re.compile(r":[a-z]+(?::[a-z]+)?:`(~?)([^`]*)`")  # :func:`~a.b` (the ~: b alone)
_LITERAL = re.compile(r"``(.*?)``", re.DOTALL)
_INTERPRETED = re.compile(r"(?<![`\w])`([^`]+)`_{0,2}(?!`)")  # `text`, `link`_


def _show_input_warning(show):
    """``warnings.showwarning`` that prints an :class:`InputWarning` as one line and hands
    the others to ``show``."""
    def shown(message, category, filename, lineno, file=None, line=None):
        if issubclass(category, InputWarning):
            print(f"warning: {message}", file=sys.stderr, flush=True)
        else:
            show(message, category, filename, lineno, file, line)
    return shown


def command(main):
    """``main(argv=None) -> int`` that ends quietly on a closed pipe or Ctrl-C (see above)."""
    @functools.wraps(main)
    def guarded(argv=None):
        try:
            with warnings.catch_warnings():
                warnings.showwarning = _show_input_warning(warnings.showwarning)
                status = main(argv)
            sys.stdout.flush()  # a closed pipe shows here, not at the interpreter's exit
            _no_collection_at_exit()
            return status
        except BrokenPipeError:
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, sys.stdout.fileno())
            return EXIT_BROKEN_PIPE
        except KeyboardInterrupt:
            print("interrupted", file=sys.stderr)
            return EXIT_INTERRUPTED
    return guarded


@functools.cache
def _no_collection_at_exit():
    """Keep the interpreter's last garbage collections off the objects alive at its exit."""
    atexit.register(gc.freeze)


def program(module):
    """The name a command shows (usage, errors): its console script's name (:data:`SCRIPTS`)
    when ``sys.argv[0]`` is that script, else ``python -m <module>``."""
    called = Path(sys.argv[0]).name if sys.argv and sys.argv[0] else ""
    script = SCRIPTS.get(module)
    if script and re.sub(r"(-script\.pyw?|\.exe)$", "", called) == script:
        return script
    return f"python -m {module}"


def plain(text):
    """``text`` (a docstring) as plain text for ``--help``: the reStructuredText roles
    (``:func:`x```), double backticks, interpreted text and ``::`` of a literal block
    reduced to what they quote."""
    if not text:
        return text
    text = _ROLE.sub(lambda m: m[2].rsplit(".", 1)[-1] if m[1] else m[2], text)
    text = _LITERAL.sub(r"\1", text)
    text = _INTERPRETED.sub(r"\1", text)
    return re.sub(r"(\S)::(\s*\n)", r"\1:\2", text)


def argument_parser(module, description, quantities=False, lines=False):
    """The ``argparse.ArgumentParser`` of the command run as ``python -m <module>``: named by
    :func:`program`, its ``description`` made :func:`plain` (its lines kept as written with
    ``lines``, else filled), and ended by :data:`EPILOG` where the command reads
    ``quantities`` (a scene, study or bodies file, or options in units)."""
    import argparse

    return argparse.ArgumentParser(
        prog=program(module), description=plain(description),
        epilog=EPILOG if quantities else None,
        formatter_class=argparse.RawDescriptionHelpFormatter if lines else
        argparse.HelpFormatter)


def jsonable(value):
    """``value`` with non-finite floats as None, numpy scalars and arrays as Python values."""
    if isinstance(value, dict):
        return {key: jsonable(v) for key, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [jsonable(v) for v in value]
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    if isinstance(value, (np.integer, np.bool_)):
        return value.item()
    return value


def print_json(value, one_line_per_key=False):
    """Print ``value`` as one standard JSON document (``jsonable``) on stdout; with
    ``one_line_per_key``, a dict is written one key a line, its value (lists and dicts
    included) on that line."""
    value = jsonable(value)
    if not one_line_per_key:
        json.dump(value, sys.stdout, indent=1, allow_nan=False)
        print()
        return
    print("{")
    last = len(value) - 1
    for k, (key, item) in enumerate(value.items()):
        comma = "," if k < last else ""
        print(f" {json.dumps(key)}: {json.dumps(item, allow_nan=False)}{comma}")
    print("}")


def report_command(module, description, report):
    """A command ``main(argv=None)`` that prints ``report(ds)`` for each dataset it is given
    (``python -m sweep.paper.rates RESULT.nc ...``: ``module`` is ``sweep.paper.rates``)."""
    @command
    def main(argv=None):
        said = argument_parser(module, description)
        said.add_argument("result", nargs="+", help="dataset of a study (netCDF)")
        args = said.parse_args(argv)

        import xarray as xr

        for path in args.result:
            with xr.open_dataset(path) as ds:
                print(report(ds))
        return 0
    return main


def checked_type(convert, ok, what):
    """An ``argparse`` type: ``convert(text)``, refused with "must be <what>" when it fails or
    the value is not ``ok``."""
    import argparse

    def parse(text):
        try:
            value = convert(text)
        except ValueError:
            value = None
        if value is None or not ok(value):
            raise argparse.ArgumentTypeError(f"must be {what}, got {text!r}")
        return value
    return parse


positive_int = checked_type(int, lambda v: v >= 1, "a whole number >= 1")

