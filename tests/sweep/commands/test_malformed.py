"""Every malformed input file gets exit status 2, a message naming where, no traceback, no hang
and nothing written, in ``sweep.scene``, ``sweep.run`` and ``sweep.estimate`` alike.

The cases of ``malformed_corpus`` run in forked children of this process (the kernel compiled
once, before forking), a few at a time, each calling the command's ``main`` with its output
redirected at the file-descriptor level; a child still running after :data:`TIMEOUT` seconds is
killed and counted as a hang.  A handful run as real ``python -m`` subprocesses too.  With
``pytest -s`` one line gives the counts::

    malformed: N cases, T tracebacks, H hangs, exit codes {2: a, 0: b}, W s
"""
import multiprocessing
import os
import re
import subprocess
import sys
import time
import traceback
from collections import Counter, namedtuple
from pathlib import Path

import pytest

import malformed_corpus as corpus
from study_helpers import PY, cli_env

TIMEOUT = 30.0  # seconds a case may take (the slowest valid one takes about two)
WORKERS = 4
ROOT = Path(__file__).resolve().parents[3]
CASES = corpus.cases()
BY_NAME = {case.name: case for case in CASES}
# a problem line: "  <dotted path | (file) | line L, column C>: message"
LOCATED = re.compile(r"^\s+(\(file\)|line \d+, column \d+|[\w\[\]]+(\.[\w\[\]]+)*): ", re.M)
SUBPROCESS_CASES = ("scene:alias_bomb", "scene:deep_list", "record:tiny_step.txt",
                    "record:nan.AT2", "record:dt_1e-300.AT2", "smoke:nul_byte", "grid:1e7_cells", "bodies:key_on",
                    "bodies:binary")

Outcome = namedtuple("Outcome", "code stdout stderr seconds hang before after")


def _main(tool):
    if tool == "scene":
        from sweep.scene import main
    elif tool == "run":
        from sweep.run import main
    else:
        from sweep.estimate import main
    return main


def _child(case, folder):
    """Run one case in this forked child; its exit status is the command's."""
    code = 1
    try:
        os.chdir(folder)
        for fd, name in ((1, ".stdout"), (2, ".stderr")):
            target = os.open(name, os.O_WRONLY | os.O_CREAT | os.O_TRUNC)
            os.dup2(target, fd)
            os.close(target)
        sys.stdout = open(1, "w", closefd=False)
        sys.stderr = open(2, "w", closefd=False)
        for var in [v for v in os.environ if v.startswith(("PMI_", "OMPI_", "PMIX_"))]:
            del os.environ[var]
        os.environ["SWEEP_MPI"] = "0"
        code = _main(case.tool)(["input.yaml", *case.args])
        code = 0 if code is None else code
    except SystemExit as end:
        code = end.code if isinstance(end.code, int) else 0 if end.code is None else 1
    except BaseException:  # noqa: B036 - a traceback is what the test looks for
        traceback.print_exc()
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)


def _listing(folder):
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*")
                  if not p.name.startswith(".std"))


def _write(case, folder):
    folder.mkdir()
    for name, data in case.files.items():
        (folder / name).write_bytes(data)


def run_all(cases, root):
    """{case name: Outcome}, ``WORKERS`` children at a time."""
    context = multiprocessing.get_context("fork")
    pending, running, done = list(enumerate(cases)), {}, {}
    while pending or running:
        while pending and len(running) < WORKERS:
            i, case = pending.pop(0)
            folder = root / f"case{i}"
            _write(case, folder)
            before = _listing(folder)
            child = context.Process(target=_child, args=(case, folder))
            child.start()
            running[case.name] = (child, folder, before, time.perf_counter())
        for name, (child, folder, before, start) in list(running.items()):
            seconds = time.perf_counter() - start
            hang = child.exitcode is None and seconds > TIMEOUT
            if child.exitcode is None and not hang:
                continue
            if hang:
                child.kill()
            child.join()
            read = (lambda n: (folder / n).read_text(errors="replace")
                    if (folder / n).exists() else "")
            done[name] = Outcome(child.exitcode, read(".stdout"), read(".stderr"), seconds,
                                 hang, before, _listing(folder))
            del running[name]
        time.sleep(0.002)
    return done


@pytest.fixture(scope="module")
def outcomes(tmp_path_factory):
    import sweep
    from sweep.runner import cells, launch, store  # noqa: F401  (loaded once, before forking)
    from sweep import estimate, run, scene  # noqa: F401
    import xarray  # noqa: F401
    os.chdir(ROOT)
    sweep.simulate("studies/steady_rocking.yaml")
    cells.warm_up()
    start = time.perf_counter()
    results = run_all(CASES, tmp_path_factory.mktemp("malformed"))
    wall = time.perf_counter() - start
    codes = Counter(o.code for o in results.values() if not o.hang)
    print(f"\nmalformed: {len(results)} cases, "
          f"{sum('Traceback' in o.stderr for o in results.values())} tracebacks, "
          f"{sum(o.hang for o in results.values())} hangs, exit codes {dict(codes)}, "
          f"{wall:.1f} s")
    return results


def _problems(case, outcome):
    """What is wrong with the outcome of a case (empty: right)."""
    if outcome.hang:
        return [f"hangs (still running after {TIMEOUT:g} s)"]
    wrong = []
    if "Traceback" in outcome.stderr:
        wrong.append("traceback")
    if outcome.code not in case.expect:
        wrong.append(f"exit status {outcome.code}, expected {sorted(case.expect)}")
    if outcome.code == 2:
        if not LOCATED.search(outcome.stderr):
            wrong.append("no problem line names a path, (file) or a line and column")
        if case.path and case.path not in outcome.stderr and "line " not in outcome.stderr:
            wrong.append(f"the message does not name {case.path}")
        if outcome.after != outcome.before:
            wrong.append(f"wrote {sorted(set(outcome.after) - set(outcome.before))}")
    return wrong


@pytest.mark.parametrize("name", [c.name for c in CASES])
def test_case(outcomes, name):
    case, outcome = BY_NAME[name], outcomes[name]
    assert not _problems(case, outcome), (_problems(case, outcome), outcome.stderr[-2000:])


def test_corpus_is_large_and_mostly_malformed():
    assert len(CASES) >= 300
    assert sum(case.expect == corpus.BAD for case in CASES) >= 300
    assert {case.tool for case in CASES} == {"scene", "run", "estimate"}


def test_command_line(tmp_path):
    """The same checks through real ``python -m`` processes, started side by side."""
    started = {}
    for name in SUBPROCESS_CASES:
        case = BY_NAME[name]
        folder = tmp_path / re.sub(r"\W", "_", name)
        _write(case, folder)
        started[name] = (subprocess.Popen(
            [PY, "-m", f"sweep.{case.tool}", "input.yaml", *case.args], cwd=folder,
            env=cli_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True),
            folder, _listing(folder))
    for name, (process, folder, before) in started.items():
        out, err = process.communicate(timeout=120)
        outcome = Outcome(process.returncode, out, err, 0.0, False, before, _listing(folder))
        assert not _problems(BY_NAME[name], outcome), (name, outcome.stderr[-2000:])
