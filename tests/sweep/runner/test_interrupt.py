"""Ctrl-C within a run (``runner.interrupt``): held back, remembered where it was swallowed,
and raised again in a rank that waits for an answer."""
import ctypes
import os
import signal

import pytest

from sweep.runner import interrupt, mpi


def _ctrl_c():
    """SIGINT to this process; Python raises it at the next instruction of the main thread."""
    os.kill(os.getpid(), signal.SIGINT)
    for _ in range(100):
        pass


def test_ctrl_c_within_a_held_block_comes_at_its_end():
    done = []
    with pytest.raises(KeyboardInterrupt):
        with interrupt.held():
            _ctrl_c()
            done.append("rest of the block")
    assert done == ["rest of the block"]
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def _swallowed_ctrl_c():
    """Ctrl-C within a callback called from C, as numba's compiler calls one: ctypes cannot
    pass the exception back through C and swallows it.  True if the callback was cut."""
    went_on = []

    def callback():
        _ctrl_c()
        went_on.append(True)

    ctypes.CFUNCTYPE(None)(callback)()
    return not went_on


def test_ctrl_c_swallowed_by_a_callback_is_raised_at_the_next_check():
    with interrupt.remembered():
        assert _swallowed_ctrl_c()  # the callback was cut, the caller was not
        with pytest.raises(KeyboardInterrupt):
            interrupt.check()
        interrupt.check()  # once only
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


class _Silent:
    """A rank 0 that never answers (it has stopped: Ctrl-C came to it too); after 200 looks
    the test fails rather than wait for ever."""

    looks = 0

    def send(self, obj, dest, tag):
        pass

    def Iprobe(self, source, tag):
        return self.Test()

    def Test(self):
        self.looks += 1
        assert self.looks < 200, "still waiting after the swallowed Ctrl-C"
        return False


def test_a_rank_waiting_for_an_answer_stops_on_a_swallowed_ctrl_c():
    with interrupt.remembered():
        assert _swallowed_ctrl_c()
        with pytest.raises(KeyboardInterrupt):
            mpi.Taker(_Silent(), chunks=[]).take()  # asked for a chunk: no answer comes
        assert _swallowed_ctrl_c()
        with pytest.raises(KeyboardInterrupt):
            mpi.wait(_Silent())  # a request that never completes


def test_ctrl_c_raised_where_it_comes_is_not_raised_again_after_the_run():
    with pytest.raises(KeyboardInterrupt):
        with interrupt.remembered():
            _ctrl_c()
    interrupt.check()  # the run is over: nothing left to raise


def test_a_held_block_without_ctrl_c_leaves_no_trace():
    with interrupt.remembered():
        with interrupt.held():
            pass
        interrupt.check()
