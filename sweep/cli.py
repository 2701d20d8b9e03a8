"""What every command line of the package shares: bad input is reported, never traced."""
import sys
from contextlib import contextmanager

from .yamlio import FileProblems

EXIT_BAD_INPUT = 2


@contextmanager
def reported_problems(source):
    """Turn ``FileProblems`` and unreadable files into a message per line and exit status 2."""
    try:
        yield
    except FileProblems as problems:
        print(f"{source}: {len(problems.problems)} problem(s):", file=sys.stderr)
        for line in str(problems).splitlines():
            print(f"  {line}", file=sys.stderr)
        raise SystemExit(EXIT_BAD_INPUT) from None
    except (FileNotFoundError, IsADirectoryError, PermissionError) as err:
        print(f"{source}: cannot read: {err.strerror}", file=sys.stderr)
        raise SystemExit(EXIT_BAD_INPUT) from None
