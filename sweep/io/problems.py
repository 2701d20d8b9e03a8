"""Problems of an input file, all reported at once: the one formatter of every input file.

Every check of a file (YAML syntax, duplicate keys, pydantic models, cross-field rules)
produces :class:`Problem` s: a dotted ``path`` (``grid.amplitude.num``, ``bodies[2].B``), the
``value`` given and a ``message``.  :class:`FileProblems` carries them and formats one per line;
:func:`validation_problems` turns pydantic's errors into problems, :func:`unknown_key` writes the
"unknown key; did you mean" message, and :func:`reported` turns problems into a message on
stderr and exit status 2 in the command-line entry points.  A value that is valid but likely
not what was meant (``sweep.io.plausibility``) is a problem too, issued by :func:`warn` as an
:class:`InputWarning` that never stops the work.
"""
import difflib
import sys
import warnings
from collections import namedtuple
from contextlib import contextmanager

from pydantic import ValidationError

from .exits import EXIT_BAD_INPUT

Problem = namedtuple("Problem", "path value message")
Problem.__doc__ = """One problem in a file: dotted ``path``, the ``value`` given, ``message``."""


class _Missing:
    """The ``value`` of a :class:`Problem` about a key that was not given."""

    def __repr__(self):
        return "MISSING"


MISSING = _Missing()

_MAX_SHOWN = 80  # characters of a value quoted in a message


def _show(value):
    text = repr(value) if isinstance(value, str) else str(value)
    return text if len(text) <= _MAX_SHOWN else text[:_MAX_SHOWN - 3] + "..."


class FileProblems(Exception):
    """Every problem found in a file, formatted one per line as ``path: message (got: value)``.

    Parameters
    ----------
    problems : list of Problem or of (path, value, message) tuples
    source : str, optional
        The file the problems were found in (kept for the caller's message, not in ``str``).
    """

    def __init__(self, problems, source=None):
        self.problems = [Problem(*p) for p in problems]
        self.source = None if source is None else str(source)
        super().__init__(str(self))

    def __str__(self):
        return "\n".join(f"{p.path}: {p.message}" if p.value is MISSING
                         else f"{p.path}: {p.message} (got: {_show(p.value)})"
                         for p in self.problems)

    def with_prefix(self, prefix):
        """The same problems with ``prefix.`` put before each path (a scene inside a study)."""
        return FileProblems([Problem(f"{prefix}.{p.path}" if p.path else prefix, p.value,
                                     p.message) for p in self.problems], self.source)


class InputWarning(UserWarning):
    """A value that is valid but likely not what was meant: ``str`` is ``path: message``, the
    :class:`Problem` is ``problem``.  The commands print it as one line ``warning: <path>:
    <message>``; ``warnings.simplefilter("ignore", InputWarning)`` silences it."""

    def __init__(self, problem):
        super().__init__(f"{problem.path}: {problem.message}")
        self.problem = problem


def warn(problems):
    """Issue each of ``problems`` as an :class:`InputWarning`."""
    for problem in problems:
        warnings.warn(InputWarning(problem), stacklevel=2)


def caution(message, path="caution"):
    """Issue ``message`` (a caution about a result, not a file's value) as an
    :class:`InputWarning` under ``path``."""
    warnings.warn(InputWarning(Problem(path, None, message)), stacklevel=2)


@contextmanager
def cautions(show=True):
    """Collect the :class:`InputWarning` s issued inside (each once) into the list yielded,
    as ``path: message`` strings, and with ``show`` print each as the commands do
    (``warning: ...`` on stderr); other warnings go on as they would."""
    said = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", InputWarning)
        try:
            yield said
        finally:
            for w in caught:
                if issubclass(w.category, InputWarning):
                    text = str(w.message)
                    if text not in said:
                        said.append(text)
                else:
                    warnings.showwarning(w.message, w.category, w.filename, w.lineno)
    for text in said if show else ():
        print(f"warning: {text}", file=sys.stderr, flush=True)


def join_path(path, key):
    """Dotted path of ``key`` below ``path``; list indices as ``[i]``."""
    if isinstance(key, int):
        return f"{path}[{key}]"
    return f"{path}.{key}" if path else str(key)


def dotted_path(loc, tagged):
    """The dotted path of a pydantic location, leaving out the keys at the places ``i`` where
    ``tagged(loc, i)`` holds: the tags pydantic inserts for the member of a union."""
    path = ""
    for i, key in enumerate(loc):
        if not tagged(loc, i):
            path = join_path(path, key)
    return path


def closest(name, names):
    """The entry of ``names`` closest to ``name`` (for "did you mean"), or None."""
    close = difflib.get_close_matches(str(name), list(names), n=1)
    return close[0] if close else None


def unknown_key(path, key, value, names):
    """The problem of ``key`` (at dotted ``path``) that is not one of ``names``:
    "unknown key; did you mean 'x'?"."""
    close = closest(key, names)
    return Problem(path, value, "unknown key" + (f"; did you mean '{close}'?" if close else ""))


class FieldError(ValueError):
    """A check inside a model that blames one ``field`` of it (a cross-field rule).

    ``field`` is a key or a tuple of keys below the model (``("values", 2)``), or the dotted
    path of a problem found by a validator of a whole file (``grid.mu[1]``); ``also`` are more
    ``FieldError`` s found by the same check, reported with it.
    """

    def __init__(self, field, value, message, also=()):
        super().__init__(message)
        self.field, self.value, self.also = field, value, tuple(also)

    @classmethod
    def several(cls, errors):
        """One exception carrying every ``(field, value, message)`` of ``errors``."""
        first, *rest = errors
        return cls(*first, also=[cls(*e) for e in rest])

    @classmethod
    def every(cls, errors):
        """One exception carrying every ``FieldError`` of ``errors`` and those they carry, in
        order (a validator that checks on after a problem, so that all show at once)."""
        return cls.several([(e.field, e.value, str(e)) for error in errors
                            for e in (error, *error.also)])


def _blamed(path, error):
    """The problem of a :class:`FieldError` raised in the model at ``path``."""
    for key in error.field if isinstance(error.field, tuple) else (error.field,):
        path = join_path(path, key)
    return Problem(path, error.value, str(error))


def _from_error(error, path, names, tags=None):
    """The problems (one, or those of a :class:`FieldError`) of one pydantic error dict.

    Parameters
    ----------
    error : dict
        An entry of ``ValidationError.errors()``.
    path : str
        The dotted path of its location (the caller drops union tags from ``error["loc"]``).
    names : sequence of str
        Every field name of the models, for "did you mean".
    tags : tuple of str, optional
        The accepted values of a discriminated union's ``kind``.
    """
    value, kind = error.get("input", MISSING), error["type"]
    cause = (error.get("ctx") or {}).get("error")
    if isinstance(cause, FieldError):
        return [_blamed(path, e) for e in (cause, *cause.also)]
    if kind == "missing":
        return [Problem(path, MISSING, "required")]
    if kind == "extra_forbidden":
        return [unknown_key(path, str(error["loc"][-1]), value, names)]
    if kind in ("union_tag_not_found", "union_tag_invalid"):
        tag = value.get("kind", MISSING) if isinstance(value, dict) else value
        return [Problem(join_path(path, "kind"), tag,
                        "required" if tag is MISSING else
                        f"unknown kind; expected one of: {', '.join(tags or ())}")]
    message = error["msg"].removeprefix("Value error, ").replace("Input should be", "must be")
    return [Problem(path, value, message)]


def validation_problems(error, names, dotted=None, tags=None):
    """Every problem of a pydantic ``ValidationError``, the unknown keys of each mapping first.

    Parameters
    ----------
    error : pydantic.ValidationError
    names : sequence of str
        Every field name of the models, for "did you mean".
    dotted : callable, optional
        ``dotted(loc) -> str``, the path of a pydantic location (default: joined keys).
    tags : tuple of str, optional
        The accepted values of a discriminated union's ``kind``.
    """
    dotted = dotted or _joined
    return [problem for e in _unknown_first(error.errors(include_url=False))
            for problem in _from_error(e, dotted(e["loc"]), names, tags)]


def fields_checked(validate, data, names, dotted=None, tags=None):
    """``(model, errors)``: the model that ``validate`` (``Model.model_validate``, or the
    handler of a ``mode="wrap"`` model validator) makes of ``data``, or None, and a
    :class:`FieldError` for each of its problems, at its dotted path, so that a validator can
    check on and raise them all with its own (:meth:`FieldError.every`); ``dotted``, ``tags``
    as :func:`validation_problems` takes them."""
    try:
        return validate(data), []
    except ValidationError as err:
        return None, [FieldError(*p) for p in validation_problems(err, names, dotted, tags)]


def _joined(loc):
    path = ""
    for key in loc:
        path = join_path(path, key)
    return path


def _unknown_first(errors, depth=0):
    """Errors in pydantic's (field) order, but each mapping's unknown keys before the rest."""
    def extra(e):
        return len(e["loc"]) == depth + 1 and e["type"] == "extra_forbidden"

    first = [e for e in errors if extra(e)]
    groups = {}  # key at this depth -> its errors, in order of first appearance
    for e in errors:
        if not extra(e):
            key = e["loc"][depth] if len(e["loc"]) > depth else None
            groups.setdefault(key, []).append(e)
    rest = [e for key, group in groups.items()
            for e in (group if key is None else _unknown_first(group, depth + 1))]
    return first + rest


@contextmanager
def reported(source):
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
