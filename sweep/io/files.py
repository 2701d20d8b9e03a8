"""Files written whole or not at all: a temporary name in the same folder, then ``os.replace``.

``os.replace`` is atomic on one file system, so a reader (or a run that resumes after being
killed) sees either the old file or the new one, never half of one.  Every file the package
writes goes through :func:`replacing`: part files, manifests, datasets, histories, figures.
"""
import os
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
