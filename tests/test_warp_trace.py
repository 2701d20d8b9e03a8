"""``benchmarks.warp_trace``: a two-lane warp traced on the plain-Python kernel of this tree
and of the loop before one step per pass (c3fab68), its passes against the closed-form rest
scans of a late sine, the kernel's own counts of steps and events, and its lock-step figures
against the same figures counted here, in passes and in units of work."""
import math

import pytest

from benchmarks import warp_trace

G = 9.81
A_REST, A_ROCK, F, START, DURATION = 3.2, 3.5, 2.0, 0.7, 0.5
KAPPA = 1.0 / 3.0                      # min(mu_s, b/h) of the 10 x 30 cm block
# Lane 0 stays at rest (3.2 < kappa g = 3.27 m/s^2), lane 1 rocks (the scene of
# tests/kernels/test_one_step_per_pass.py).
STUDY = f"""name: warp
scene:
  body: {{B: 0.1, H: 0.3}}
  contact: {{mu: 0.8, e_x: -0.8, e_y: 0.2}}
  excitation:
    horizontal: {{kind: sine, amplitude: 3.5, frequency: {F}, start: {START},
                 duration: {DURATION}}}
  solver: {{t_end: 2.0}}
grid:
  excitation.horizontal.amplitude: [{A_REST}, {A_ROCK}]
output: warp.nc
"""
# A scan's intervals are an eighth of the sine's period, 1/16 s, the one holding the start
# cut there: 12 up to 0.7 s, then those up to the exit from rest, or to the sine's end.
BEFORE_START = math.ceil(8 * F * START)
TO_EXIT = BEFORE_START + math.ceil(8 * F * math.asin(KAPPA * G / A_ROCK) / (2 * math.pi * F))
TO_END = BEFORE_START + round(8 * F * DURATION)


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    path = tmp_path_factory.mktemp("warp") / "warp.yaml"
    path.write_text(STUDY)
    return path


@pytest.fixture(scope="module")
def after(study):
    return warp_trace.trace(warp_trace.ROOT, study, 0, 2, 0.0)


@pytest.fixture(scope="module")
def before(study, tmp_path_factory):
    try:
        tree = warp_trace.base_tree(warp_trace.BASE, tmp_path_factory.mktemp("base"))
    except RuntimeError:
        pytest.skip(f"commit {warp_trace.BASE} is not in this checkout")
    return warp_trace.trace(tree, study, 0, 2, 0.0)


def test_a_rest_scanned_one_interval_a_pass(after):
    """One step per pass: the resting lane scans its 20 intervals in 20 passes; the rocking
    lane's first 14 passes are its rest's intervals, the 14th leaving rest."""
    rest, rock = (lane["passes"] for lane in after)
    assert [p.count("R") for p in rest] == [1] * TO_END
    assert [warp_trace.kind(p) for p in rock[:TO_EXIT + 1]] == ["rest"] * TO_EXIT + ["step"]


def test_steps_and_events_against_the_kernels_counts(after):
    """The rocking lane: one step at most a pass; the passes with a step are the kernel's
    ``steps`` and the steps to the events found in steps, each the pass after the find, which
    applies the event's law; those laws and the leaving of rest are the kernel's
    ``events``."""
    lane = after[1]
    passes = lane["passes"]
    assert lane["status"] == 0 and lane["events"] > 10
    assert max(p.count("S") for p in passes) == 1
    found = [i for i, p in enumerate(passes) if "F" in p]
    assert all("E" in passes[i + 1] for i in found)
    resteps = sum("S" in passes[i + 1] for i in found)
    assert sum("S" in p for p in passes) == lane["steps"] + resteps
    assert 0 < resteps <= len(found)
    leavings = sum(warp_trace.kind(p) == "rest" and warp_trace.kind(q) != "rest"
                   for p, q in zip(passes, passes[1:]))
    assert sum("E" in p for p in passes) + leavings == lane["events"]


def test_lock_step_figures(after):
    """The resting lane idles after its 20 passes; both rest until pass 14, so passes 14 to
    19 are the divergent ones; the efficiency is the lanes' passes over 2 x the rocking
    lane's."""
    n = len(after[1]["passes"])
    warp = warp_trace.lock_step(after)
    assert len(warp) == n > TO_END
    assert all(p[0] is None for p in warp[TO_END:])
    f = warp_trace.figures(after)
    assert f["passes"] == n
    assert f["divergent"] == pytest.approx((TO_END - TO_EXIT) / n, rel=1e-15)
    assert f["rest"] == pytest.approx(TO_END / n, rel=1e-15)
    assert f["steps"] == 1 and f["intervals"] == 1
    assert f["efficiency"] == pytest.approx((TO_END + n) / (2 * n), rel=1e-15)
    assert f["efficiency"] <= 1.0
    # one unit a pass; the divergent passes take two, a rest's and a step's one after the other
    assert f["work"] == pytest.approx((TO_END + n) / (2 * (n + TO_END - TO_EXIT)), rel=1e-15)


def test_the_loop_before_took_a_rest_and_an_event_in_one_pass(before):
    """Before: each rest was one pass scanning all its intervals (20 at rest; 14 before the
    rocking lane's exit), a pass whose step held an event stepped again to it, polished it
    and applied its law, and every step still counted in ``steps`` or a re-step."""
    rest, rock = before
    assert rest["passes"] == ["R" * TO_END + "B"]
    assert rock["passes"][0].count("R") == TO_EXIT
    passes = rock["passes"]
    assert max(p.count("S") for p in passes) == 2
    events = [p for p in passes if "F" in p]
    assert events and all("E" in p for p in events)
    assert sum(p.count("S") for p in passes) == rock["steps"] + sum(p.count("S") == 2
                                                                   for p in events)
    f = warp_trace.figures(before)
    assert f["divergent"] == 0.0 and f["intervals"] == TO_END and f["steps"] == 2
    # in units of RK steps and intervals: the first pass lasts the resting lane's 20 intervals
    units = [max(1, p.count("S") + p.count("R")) for p in passes]
    assert f["work"] == pytest.approx((TO_END + sum(units)) / (2 * (TO_END + sum(units[1:]))),
                                      rel=1e-15)


def test_the_command_writes_the_table(study, tmp_path, capsys):
    """``python -m benchmarks.warp_trace`` on the two lanes: the Markdown table, printed and
    written, with the closed-form rows of the warp before and now: the most scan intervals
    of a lane in a pass, 20 and 1, and the most RK steps, 2 and 1."""
    out = tmp_path / "table"
    warp_trace.main(["--cells", "2", "--study", str(study), "-o", str(out)])
    text = out.read_text()
    assert text.strip() == capsys.readouterr().out.strip()
    rows = {line.split(" | ")[0].lstrip("| "): line.rstrip(" |").split(" | ")[1:]
            for line in text.splitlines() if line.startswith("| ")}
    assert rows["most scan intervals of a lane in a pass"] == [str(TO_END), "1"]
    assert rows["most RK steps of a lane in a pass"] == ["2", "1"]


def test_bad_arguments_end_with_one_line(tmp_path, capsys):
    """No such study, no such cell, no such commit: one line each and exit status 2."""
    missing = ["--study", str(tmp_path / "none.yaml")]
    smoke = ["--study", str(warp_trace.ROOT / "studies" / "smoke.yaml"), "--cells", "1"]
    for argv, said in ((missing, "no file"), (smoke + ["--first", "384"], "no cell 384"),
                       (smoke + ["--base", "0" * 40], "--base")):
        with pytest.raises(SystemExit) as stop:
            warp_trace.main(argv + ["-o", str(tmp_path / "table")])
        assert stop.value.code == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert said in err[-1] and "Traceback" not in "".join(err)
