"""Files written whole or not at all, and the files a pattern of the user's finds.

A file is written under a temporary name in the same folder, then moved with ``os.replace``.

``os.replace`` is atomic on one file system, so a reader (or a run that resumes after being
killed) sees either the old file or the new one, never half of one.  Every file the package
writes goes through :func:`replacing`: part files, manifests, datasets, histories, figures,
tables (:func:`write_csv`, numbers to meaningful digits).  :func:`find_files` expands a glob
of record files (``records/*.AT2``) with the extension matched whatever its case, as the
readers take ``.AT2`` and ``.at2`` alike.
"""
import csv
import glob
import math
import os
import re
from contextlib import contextmanager
from pathlib import Path

TMP_MARK = ".tmp"  # ending of temporary names (a killed run's leftovers are found by it)
NAME_MAX, PATH_MAX = 255, 4096  # bytes of one name and of a whole path (Linux)
NAME_RESERVE = 40  # bytes that names made from an output's add (".<name>.parts.<pid>.trash")


def temporary_name(path):
    """The temporary name next to ``path`` that this process writes before renaming."""
    path = Path(path)
    return path.with_name(f".{path.name}.{os.getpid()}{TMP_MARK}")


@contextmanager
def replacing(path):
    """Yield a temporary path next to ``path``; when the block ends, flush it to disk and rename
    it onto ``path``.  On any exception the temporary file is removed and ``path`` untouched."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = temporary_name(path)
    try:
        yield tmp
        with open(tmp, "rb+") as f:
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def write_atomic(path, write):
    """Call ``write(file)`` on a binary file that becomes ``path`` atomically."""
    with replacing(path) as tmp, open(tmp, "wb") as f:
        write(f)
    return Path(path)


CSV_DIGITS = 6  # significant digits of a float in a table: 0.7, not 0.7000000000000001


def csv_value(value, digits=CSV_DIGITS):
    """A value as a table cell: None empty, a float to ``digits`` significant digits (float
    noise dropped: ``0.7``, ``0.0512346``, ``35.25``), anything else as ``str``."""
    if value is None:
        return ""
    if isinstance(value, float) and math.isfinite(value):
        return f"{value:.{digits}g}"
    return str(value)


def write_csv(path, rows, digits=CSV_DIGITS):
    """Write ``rows`` (dicts; the columns in the order first seen) as a CSV file, atomically,
    each value through :func:`csv_value`."""
    columns = list(dict.fromkeys(key for row in rows for key in row))
    with replacing(path) as tmp, open(tmp, "w", newline="") as f:
        writer = csv.DictWriter(f, columns)
        writer.writeheader()
        writer.writerows({k: csv_value(v, digits) for k, v in row.items()} for row in rows)
    return Path(path)


def output_problem(path):
    """Why a file cannot be written at ``path``, or None when it can (checked before any work,
    creating nothing).

    Refused are names with a NUL byte, a path that is a folder, a path below a regular file,
    and folders that cannot be written or created (``/proc``, ``/sys``, read-only mounts).
    """
    text = str(path)
    if "\x00" in text:
        return "contains a NUL byte"
    if not text.strip():
        return "is empty"
    path = Path(text).absolute()
    longest = max(len(part.encode()) for part in path.parent.parts)
    if max(longest + 1, len(path.name.encode()) + NAME_RESERVE) > NAME_MAX:
        return (f"has a name too long for the file system ({NAME_MAX} bytes a name, "
                f"less {NAME_RESERVE} for the names made from the output's)")
    if len(str(path).encode()) >= PATH_MAX:
        return f"is {len(str(path).encode())} bytes long; the system takes paths below {PATH_MAX}"
    if path.is_dir():
        return "is an existing folder: give a file name such as results/x.nc"
    folder = next(p for p in path.parents if p.exists())  # the root exists
    if not folder.is_dir():
        return f"{folder} is a file, not a folder"
    if not os.access(folder, os.W_OK | os.X_OK) or _pseudo(folder):
        return f"its folder {folder} is not writable"
    if path.exists() and not os.access(path, os.W_OK):
        return "exists and is not writable"
    return None


def _pseudo(folder):
    """True inside the kernel's pseudo file systems, where root may "write" but nothing keeps."""
    resolved = Path(folder).resolve()
    return any(resolved == Path(p) or Path(p) in resolved.parents for p in ("/proc", "/sys"))


def output_problems(paths):
    """Problems of the output files a command was given: ``{option: path or None}`` ->
    :class:`~sweep.io.problems.Problem` s at the option's name (none given, none checked)."""
    from .problems import Problem
    return [Problem(option, str(path), why) for option, path in paths.items()
            if path is not None and (why := output_problem(path)) is not None]


_MAGIC = re.compile(r"[*?[]")
MAX_NAMED = 5  # skipped files named in a message; the others are counted


def _any_case(name):
    """A glob of a file name whose extension (after the last dot) matches in any case:
    ``*.AT2`` -> ``*.[aA][tT]2``.  An extension that holds a glob's own characters is kept."""
    stem, dot, extension = name.rpartition(".")
    if not dot or _MAGIC.search(extension):
        return name
    return stem + dot + "".join(f"[{c.lower()}{c.upper()}]" if c.isalpha() else c
                                for c in extension)


def find_files(pattern, base_dir="."):
    """The files a glob finds below ``base_dir``, its extension matched in any case, and the
    files of the same folders that it leaves out.

    Parameters
    ----------
    pattern : str
        A glob relative to ``base_dir`` (``**`` spans folders): ``records/*.AT2`` finds
        ``records/a.at2`` too.
    base_dir : str or Path

    Returns
    -------
    found : list of str
        The regular files matched, as relative paths in the pattern's form, sorted.
    skipped : list of str
        The other visible regular files of the folders that hold a match (or, with no match,
        of the pattern's folder when it names one), the same form, sorted.
    """
    folder, _, name = pattern.rpartition("/")
    wanted = f"{folder}/{_any_case(name)}" if folder else _any_case(name)
    found = sorted({p for p in glob.glob(wanted, root_dir=base_dir, recursive=True)
                    if (Path(base_dir) / p).is_file()})
    folders = {os.path.dirname(p) for p in found}
    if not found and not _MAGIC.search(folder):
        folders = {folder}
    chosen = set(found)
    skipped = sorted(os.path.join(f, entry.name) for f in folders
                     if (Path(base_dir) / f).is_dir()
                     for entry in os.scandir(Path(base_dir) / f)
                     if entry.is_file() and not entry.name.startswith(".")
                     and os.path.join(f, entry.name) not in chosen)
    return found, skipped


def named(paths, limit=MAX_NAMED):
    """``a.txt, b.VT2 and 3 more``: at most ``limit`` file names, then a count."""
    names = [os.path.basename(p) for p in paths]
    more = len(names) - limit
    return ", ".join(names[:limit]) + (f" and {more} more" if more > 0 else "")
