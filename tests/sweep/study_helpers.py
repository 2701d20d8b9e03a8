"""Small studies, a command-line runner and dataset helpers for the study-runner tests."""
import copy
import os
import signal
import subprocess
import sys
import time

import yaml

PY = sys.executable
# the steady-rocking block, with friction high enough that it does not slide
SCENE = {"body": {"B": 0.1, "H": 0.3}, "contact": {"mu": 0.8, "e_x": -0.8, "e_y": 0.2},
         "excitation": {"horizontal": {"kind": "sine", "amplitude": "1.5 west",
                                       "frequency": 4.0}},
         "solver": {"t_end": 2.0}}
# time and coordinate attributes that differ between two runs of the same study
RUN_ATTRS = ("history", "date_created", "input_fingerprint")


def make_study(grid, **extra):
    """A study dict on the shared scene (deep copies, safe to modify)."""
    return {"name": "t", "scene": copy.deepcopy(SCENE), "grid": copy.deepcopy(grid), **extra}


def write_study(path, study):
    path.write_text(yaml.safe_dump(study, sort_keys=False))
    return path


def cli(args, cwd, timeout=120, env=None, module="sweep.run"):
    """Run ``python -m <module> args`` in ``cwd``; the CompletedProcess."""
    return subprocess.run([PY, "-m", module, *map(str, args)], cwd=cwd, env=env or cli_env(),
                          capture_output=True, text=True, timeout=timeout)


def cli_env(**extra):
    """The environment of a child process: no MPI launcher variables, no terminal mode."""
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(("PMI_", "OMPI_", "PMIX_", "MPI_LOCAL", "MV2_"))}
    env.update(CI="1", **extra)
    return env


def without_run_attrs(ds):
    """The dataset without the attributes that record when and how it was made."""
    ds = ds.copy()
    for key in RUN_ATTRS:
        ds.attrs.pop(key, None)
    return ds


# 240 cells of a block rocking to the end: seconds of work, for runs killed or stopped midway
SLOW = {"amplitude": {"start": 1.2, "stop": 2.0, "num": 12, "unit": "west"},
        "frequency": {"start": 6.0, "stop": 10.0, "num": 20}}


def slow_study(folder, t_end, output="r.nc"):
    """The SLOW grid rocking for ``t_end`` seconds, written to ``folder/slow.yaml``:
    (raw dict, path)."""
    raw = make_study(SLOW, output=output)
    raw["scene"]["solver"]["t_end"] = t_end
    return raw, write_study(folder / "slow.yaml", raw)


def wait_for_parts(process, parts_dir, n_parts, timeout=120.0):
    """Wait until ``n_parts`` part files exist while ``process`` still runs."""
    end = time.monotonic() + timeout
    while len(list(parts_dir.glob("part-*.npz"))) < n_parts:
        assert process.poll() is None and time.monotonic() < end, "the run ended too early"
        time.sleep(0.005)


def sigint_default():
    """For ``preexec_fn``: a child started from a shell's background job inherits SIGINT
    ignored, and Python then leaves it ignored; give it the default, as a terminal would, so
    that a test's SIGINT reaches it."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def start(args, cwd, module="sweep.run"):
    """``python -m <module> args`` started in ``cwd`` (pipes for its output): the Popen."""
    return subprocess.Popen([PY, "-m", module, *map(str, args)], cwd=cwd, env=cli_env(),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=sigint_default)
