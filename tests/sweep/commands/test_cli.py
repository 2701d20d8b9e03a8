"""``sweep.cli``: commands end quietly when their reader goes away or the user presses Ctrl-C,
and print standard JSON.  Real subprocesses, real pipes closed early, a real SIGINT."""
import errno
import json
import os
import signal
import subprocess
import time

import pytest
import yaml
from study_helpers import PY, cli_env, sigint_default

from sweep.cli import command, jsonable, print_json
from sweep.io.exits import EXIT_BROKEN_PIPE, EXIT_INTERRUPTED

# a block bouncing on its corners: ~3800 impacts in 10 s, a JSON of some hundred kB
BOUNCING = {"body": {"B": 0.1, "H": 0.3}, "contact": {"mu": 10, "e_x": -0.8, "e_y": 0.2},
            "excitation": {"horizontal": {"kind": "sine", "amplitude": "1.5 west",
                                          "frequency": 4.0}},
            "solver": {"t_end": 10.0}}
MANY_BODIES = {"bodies": [{"name": f"body {k}", "B": 0.1, "H": 0.3 + 0.001 * k,
                           "overturned": True} for k in range(1000)]}


def _write(path, data):
    path.write_text(yaml.safe_dump(data))
    return path


def _reader_leaves(module, args, cwd, lines):
    """Run ``python -m module args`` into a pipe whose reader reads ``lines`` lines and
    closes it; the exit status and stderr."""
    child = subprocess.Popen([PY, "-m", module, *map(str, args)], cwd=cwd, env=cli_env(),
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    for _ in range(lines):
        child.stdout.readline()
    child.stdout.close()
    err = child.stderr.read()
    child.wait(timeout=120)
    return child.returncode, err


def test_scene_json_into_head(tmp_path):
    """The user's own command line: ``... --json | head -1`` in bash with pipefail."""
    scene = _write(tmp_path / "bouncing.yaml", BOUNCING)
    done = subprocess.run(["bash", "-c", f"set -o pipefail; {PY} -m sweep.scene {scene} "
                           "--json | head -1"], cwd=tmp_path, env=cli_env(),
                          capture_output=True, text=True, timeout=120)
    assert done.stdout == "{\n"
    assert done.stderr == ""
    assert done.returncode == EXIT_BROKEN_PIPE


@pytest.mark.parametrize("module, data, lines", [
    ("sweep.scene", BOUNCING, 1), ("sweep.estimate", MANY_BODIES, 1)])
def test_json_reader_leaves_after_one_line(tmp_path, module, data, lines):
    path = _write(tmp_path / "input.yaml", data)
    status, err = _reader_leaves(module, [path, "--json"], tmp_path, lines)
    assert (status, err) == (EXIT_BROKEN_PIPE, "")


def test_plot_reader_gone_before_it_writes(tmp_path):
    status, err = _reader_leaves("sweep.plot", ["--figure", "fig17", "-o", "f.png"],
                                 tmp_path, 0)
    assert (status, err) == (EXIT_BROKEN_PIPE, "")
    assert (tmp_path / "f.png").stat().st_size > 0  # the work was done before the print


def test_ctrl_c_is_one_line(tmp_path):
    """SIGINT while the command waits for its input (a FIFO that no one writes yet)."""
    fifo = tmp_path / "bodies.yaml"
    os.mkfifo(fifo)
    child = subprocess.Popen([PY, "-m", "sweep.estimate", fifo], cwd=tmp_path, env=cli_env(),
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             preexec_fn=sigint_default)
    deadline = time.monotonic() + 60
    while True:  # a non-blocking open for writing succeeds once the command opened it
        try:
            writer = os.open(fifo, os.O_WRONLY | os.O_NONBLOCK)
            break
        except OSError as err:
            assert err.errno == errno.ENXIO and time.monotonic() < deadline
            time.sleep(0.05)
    try:
        time.sleep(0.2)
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=60)
    finally:
        os.close(writer)
    assert (child.returncode, out, err) == (EXIT_INTERRUPTED, "", "interrupted\n")


def test_command_returns_the_status_of_main(capsys):
    @command
    def main(argv=None):
        if argv == ["stop"]:
            raise KeyboardInterrupt
        print("done")
        return 3

    assert main([]) == 3 and capsys.readouterr().out == "done\n"
    assert main(["stop"]) == EXIT_INTERRUPTED
    assert capsys.readouterr().err == "interrupted\n"


def test_standard_json(capsys):
    import numpy as np

    value = {"a": float("nan"), "b": [float("inf"), -np.inf, np.float32(1.5)],
             "c": (np.int64(2), np.bool_(True), None, "x"), "d": np.array([1.0, np.nan])}
    assert jsonable(value) == {"a": None, "b": [None, None, 1.5], "c": [2, True, None, "x"],
                               "d": [1.0, None]}
    print_json(value)
    assert json.loads(capsys.readouterr().out) == jsonable(value)
