"""One writer per output: a lock that a run holds on its output for its whole life.

The lock is an exclusive ``flock`` on ``<output>.lock`` beside the output, which names its holder
(host, pid, start time, command).  The operating system releases it when the holder ends in any
way (exit, kill -9, crash), so the lock of a run that is gone is taken over by the next one; a
second run while the holder lives is refused at once with the holder's name.  ``flock`` works
across the hosts of a cluster on NFS (Linux emulates it with POSIX locks there).
"""
import datetime
import fcntl
import json
import os
import socket
from pathlib import Path

LOCK_SUFFIX = ".lock"


class LockHeld(Exception):
    """Another live run holds the output; the message names it."""


def lock_path(output):
    """The lock file of an output: ``results/x.nc`` -> ``results/x.nc.lock``."""
    output = Path(output)
    return output.with_name(output.name + LOCK_SUFFIX)


def _holder_text(info, path):
    if not info:
        return f"another run holds {path}"
    return (f"pid {info.get('pid')} on host {info.get('host')}, started "
            f"{info.get('started')} ({info.get('command', 'sweep.run')})")


class OutputLock:
    """The lock of one output, held from :meth:`acquire` to :meth:`release` (or process end).

    Parameters
    ----------
    output : str or Path
        The output the lock guards (its parts folder is guarded with it).
    command : str
        What the holder runs, shown to a run that is refused.
    """

    def __init__(self, output, command="sweep.run"):
        self.output = Path(output)
        self.path = lock_path(output)
        self.command = command
        self._fd = None

    def acquire(self):
        """Take the lock or raise :class:`LockHeld` naming the live holder."""
        while True:
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                info = _read_info(fd)
                os.close(fd)
                raise LockHeld(f"{self.output} is being written by another run: "
                               f"{_holder_text(info, self.path)}. Wait for it to end, or give "
                               "this run another output (-o)") from None
            if _same_file(fd, self.path):
                break
            os.close(fd)  # its holder removed the file as it ended: lock the new one
        info = {"host": socket.gethostname(), "pid": os.getpid(),
                "started": datetime.datetime.now(datetime.timezone.utc).strftime(
                    "%Y-%m-%d %H:%M:%S UTC"), "command": self.command}
        os.ftruncate(fd, 0)
        os.pwrite(fd, json.dumps(info).encode(), 0)
        self._fd = fd
        return self

    def release(self):
        """Remove the lock file and let go of the lock (nothing when not held)."""
        if self._fd is None:
            return
        try:
            if _same_file(self._fd, self.path):
                self.path.unlink()
        except OSError:
            pass
        os.close(self._fd)  # closing the last descriptor releases the flock
        self._fd = None

    def __enter__(self):
        return self.acquire()

    def __exit__(self, *exc):
        self.release()


def _same_file(fd, path):
    """True while ``path`` still names the file open as ``fd``."""
    try:
        return os.fstat(fd).st_ino == os.stat(path).st_ino
    except FileNotFoundError:
        return False


def _read_info(fd):
    try:
        return json.loads(os.pread(fd, 4096, 0).decode() or "{}")
    except (OSError, ValueError):
        return {}
