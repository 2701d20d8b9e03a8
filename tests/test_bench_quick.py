"""The benchmark harness: its error measure, interpolation, statistics and floor motions, and a
quick run of ``python -m benchmarks`` end to end (slow: about 25 s, two mpiexec launches)."""
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

import hard_cases
from benchmarks import floor, scenes, throughput, work_precision
from kernels.api import run_scene

ROOT = Path(__file__).resolve().parents[1]


def _outcome(times, omega=1.0, t_overturn=None):
    times = np.asarray(times, dtype=float)
    return scenes.Outcome(times, np.full(times.size, omega), t_overturn, math.nan)


def test_impact_error_matches_one_to_one():
    scene = scenes.SCENES[0]
    ref = _outcome([1.0, 2.0, 3.0])
    assert scenes.error(_outcome([1.0, 2.0001, 3.0]), ref, scene)[0] == pytest.approx(1e-4)
    err, note = scenes.error(_outcome([1.0, 3.0]), ref, scene)       # one impact missed
    assert err == math.inf and "2 impacts, reference 3" in note
    err, note = scenes.error(_outcome([1.0, 1.2, 2.0, 3.0]), ref, scene)   # one too many
    assert err == math.inf
    err, note = scenes.error(_outcome([1.0, 2.0, 3.0], t_overturn=4.0), ref, scene)
    assert err == math.inf and "overturned" in note


def test_impact_error_skips_the_final_accumulation():
    """Impacts after the reference's last one with |omega+| >= OMEGA_CHATTER are not
    compared; the count before the midpoint to the next reference impact must agree."""
    ref = scenes.Outcome(np.array([1.0, 2.0, 2.5, 2.6]), np.array([0.5, 0.3, 1e-4, 1e-5]),
                         None, math.nan)
    run = _outcome([1.0 + 1e-6, 2.0, 2.51])
    assert scenes.error(run, ref, scenes.SCENES[0]) == (pytest.approx(1e-6), "")
    assert scenes.error(_outcome([1.0, 2.0, 2.2]), ref, scenes.SCENES[0])[0] == math.inf


def test_cpu_to_reach_interpolates_in_log_log():
    """Between runs (1e-4, 1 ms) and (1e-6, 4 ms) the CPU for 1e-5 is their geometric mean;
    a run that is both slower and less accurate than another is ignored."""
    points = [work_precision.Point("adaptive", 0, 0, cpu, 1, err)
              for err, cpu in ((1e-4, 1e-3), (1e-6, 4e-3), (1e-5, 9e-3), (math.inf, 1e-4))]
    assert work_precision.cpu_to_reach(points, 1e-5) == (pytest.approx(2e-3), "=")
    assert work_precision.cpu_to_reach(points, 1e-2) == (pytest.approx(1e-3), "<=")
    assert work_precision.cpu_to_reach(points, 1e-8) == (pytest.approx(9e-3), ">")


def test_wilson_and_paired_fractions():
    """Wilson's 95 % interval of 0/10 is [0, 0.2775]; two runs that disagree once each
    way have equal fractions and McNemar p = 1."""
    low, high = hard_cases.wilson(0, 10)
    assert low == pytest.approx(0.0, abs=1e-12) and high == pytest.approx(0.2775, abs=1e-4)
    stats = hard_cases.compare_fractions([1, 1, 0, 0], [1, 0, 1, 0])
    assert (stats.only_a, stats.only_b, stats.difference, stats.p_value) == (1, 1, 0.0, 1.0)


def test_gpu_report_names_the_status_changes():
    """Statuses of two runs of four cells: one overturned cell and one rocking cell ran out
    of their budget in the second; counted per pair of names, the most frequent first."""
    from benchmarks.gpu import status_changes
    from kernels import codes
    cpu = np.zeros(5, codes.RESULT_DTYPE)
    other = np.zeros(5, codes.RESULT_DTYPE)
    cpu["status"] = [codes.OVERTURNED, codes.OVERTURNED, codes.OK, codes.OVERTURNED, codes.OK]
    other["status"] = [codes.BUDGET_EXHAUSTED, codes.BUDGET_EXHAUSTED, codes.BUDGET_EXHAUSTED,
                       codes.OVERTURNED, codes.OK]
    assert status_changes(other, cpu) == ("2 overturned -> budget_exhausted, "
                                          "1 ok -> budget_exhausted")
    assert status_changes(cpu, cpu) == "none"


def test_quick_study_keeps_two_values_per_axis():
    raw = {"name": "m", "grid": {"a": {"start": 1, "stop": 2, "num": 40}, "b": [1, 2, 3],
                                 "c": {"values": [4, 5, 6]}}}
    grid = throughput.quick_study(raw)["grid"]
    assert grid == {"a": {"start": 1, "stop": 2, "num": 2}, "b": [1, 3],
                    "c": {"values": [4, 6]}}


@pytest.mark.parametrize("key", ["sweep", "el_centro"])
def test_scipy_floor_motion_is_the_kernels(key):
    """The scipy program's floor motion (written from docs/design.md 4) equals the kernel's
    a_x, a_y in the history to 1e-12 m/s^2 on the sweep and on El Centro NS + UD."""
    scene = next(s for s in scenes.SCENES if s.key == key)
    resolved = {**scene.resolved, "solver": {**scene.resolved["solver"], "t_end": 10.0,
                                             "dt_out": 0.013}}
    hist = run_scene(resolved, history=True).history
    problem = scenes.scipy_problem(resolved)
    for name, a in (("a_x", problem["a_x"]), ("a_y", problem["a_y"])):
        np.testing.assert_allclose([a(t) for t in hist["t"]], hist[name], rtol=0, atol=1e-12)


@pytest.mark.slow
@pytest.mark.mpi
def test_quick_benchmark_run(tmp_path):
    """``python -m benchmarks --quick`` writes the report, its headline tables first, with every
    section and a PNG plot; the quick map gives identical datasets on 1 and 2 ranks."""
    report, figure = tmp_path / "bench.md", tmp_path / "wp.png"
    done = subprocess.run([sys.executable, "-m", "benchmarks", "--quick", "-o", str(report),
                           "--figure", str(figure)], cwd=ROOT, capture_output=True, text=True,
                          timeout=600)
    assert done.returncode == 0, done.stderr
    text = report.read_text()
    assert text.index("## Headline: cells per second") < text.index("## Targets, side by side")
    assert "| CPU, 1 rank |" in text and "| floor, same cells |" in text
    for heading in ("## Work-precision", "## Throughput", "## Stability on hard cases",
                    "### Steady rocking", "### Chaotic rocking"):
        assert heading in text
    assert "datasets identical" in text
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_floor_loop_meets_the_free_rocking_anchor_and_the_kernel():
    """The floor (the kernel's tableau, rocking only) against docs/physics.md A4's quadrature on
    free rocking, and against the kernel's impact times on steady rocking and on the 60 s log sweep
    (Housner's impact)."""
    free = next(s for s in scenes.SCENES if s.key == "free_rocking")
    out = floor.run(free.resolved, 1e-10, 1e-12)
    assert scenes.error(scenes.Outcome.of_scipy(out), free.anchor(), free)[0] < 1e-9
    steady = next(s for s in scenes.SCENES if s.key == "steady_rocking")
    kernel = run_scene({**steady.resolved, "solver": {**steady.resolved["solver"],
                                                      "rtol": 1e-12, "atol": 1e-14}})
    out = floor.run(steady.resolved, 1e-10, 1e-12)
    assert len(out["impact_times"]) == len(kernel.impact_times) == 79
    np.testing.assert_allclose(out["impact_times"], kernel.impact_times, rtol=0, atol=1e-9)
    sweep = next(s for s in scenes.SCENES if s.key == "sweep").resolved
    out = floor.run(sweep, 1e-10, 1e-12)
    kernel = run_scene({**sweep, "solver": {**sweep["solver"], "rtol": 1e-12, "atol": 1e-14}})
    assert len(out["impact_times"]) == len(kernel.impact_times) > 500
    np.testing.assert_allclose(out["impact_times"], kernel.impact_times, rtol=0, atol=1e-7)
    assert not floor.takes(next(s for s in scenes.SCENES if s.key == "el_centro").resolved)


def test_floor_loop_closes_bursts_within_zeno_dt():
    """On a cell of the throughput map whose rocking dies out in bursts of impacts, the map's
    zeno_dt ends each burst in rest: less than half the impacts of the classical closure
    alone."""
    from sweep.io.scene_schema import load_scene, resolve_scene
    from sweep.io.study_schema import load_study
    from sweep.runner import grid
    study = load_study(throughput.quick_study(yaml.safe_load(throughput.STUDY.read_text())))
    cell = resolve_scene(load_scene(grid.cell_scene(study, 2)))
    plain, closed = (floor.run(cell, 1e-6, 1e-8, zeno_dt=z) for z in (0.0, 1e-4))
    assert len(closed["impact_times"]) < len(plain["impact_times"]) / 2
