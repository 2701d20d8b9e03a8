"""Ctrl-C during a run: remembered, held back, ignored.

Python raises ``KeyboardInterrupt`` in the main thread wherever it is when SIGINT comes.  A
run needs three things more: it must not lose it where Python cannot raise (a ctypes
callback of numba's compiler prints "Exception ignored" and goes on: :func:`remembered` and
:func:`check`), must not cut a message from its count (:func:`held`), and must not be cut
again while it says what is saved (:func:`ignored`).  Only the main thread handles signals,
so each of these does nothing in another thread.
"""
import signal
import sys
import threading
from contextlib import contextmanager

_came = False  # Ctrl-C came within remembered() and has not been raised by check() since


def _main_thread():
    return threading.current_thread() is threading.main_thread()


def _raise(signum, frame):
    global _came
    _came = True
    raise KeyboardInterrupt


@contextmanager
def remembered():
    """Within the block Ctrl-C raises ``KeyboardInterrupt`` as usual and is remembered, for
    :func:`check` to raise it again where it was swallowed (the swallowing is not printed).
    Does nothing unless Python's own handler is in place."""
    global _came
    if not _main_thread() or signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        yield
        return
    _came = False
    previous, hook = signal.signal(signal.SIGINT, _raise), sys.unraisablehook

    def unraisable(unraisable):
        if not issubclass(unraisable.exc_type, KeyboardInterrupt):
            hook(unraisable)

    sys.unraisablehook = unraisable
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        sys.unraisablehook = hook
        _came = False


def check():
    """Raise ``KeyboardInterrupt`` once if Ctrl-C came within :func:`remembered` and has not
    been raised here since: where it was swallowed, the run stops at its next check."""
    global _came
    if _came and _main_thread():
        _came = False
        raise KeyboardInterrupt


@contextmanager
def held():
    """Hold Ctrl-C back until the block is done (a message and its count go together); one
    that came meanwhile is handed to the handler in place when the block ends."""
    previous = signal.getsignal(signal.SIGINT) if _main_thread() else None
    if not callable(previous):  # another thread, or Ctrl-C ignored or left to the system
        yield
        return
    came = []
    signal.signal(signal.SIGINT, lambda signum, frame: came.append(frame))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
    if came:
        previous(signal.SIGINT, came[0])


@contextmanager
def ignored():
    """Ignore Ctrl-C for a moment (the handler is restored after)."""
    if not _main_thread():
        yield
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
