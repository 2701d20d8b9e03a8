"""Ctrl-C within a run (``runner.interrupt``): held back, remembered where it was swallowed."""
import ctypes
import os
import signal

import pytest

from sweep.runner import interrupt


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


def test_ctrl_c_swallowed_by_a_callback_is_raised_at_the_next_check():
    went_on = []

    def callback():  # ctypes cannot pass an exception back through C: it is swallowed
        _ctrl_c()
        went_on.append(True)

    callback_from_c = ctypes.CFUNCTYPE(None)(callback)
    with interrupt.remembered():
        callback_from_c()
        assert went_on == []  # the callback was cut, the caller was not
        with pytest.raises(KeyboardInterrupt):
            interrupt.check()
        interrupt.check()  # once only
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


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
