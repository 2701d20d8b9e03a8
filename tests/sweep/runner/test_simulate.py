"""``sweep.simulate``: one scene from Python, from a dict in file units or a file path."""
import json
import math
from pathlib import Path

import pytest
from study_helpers import cli

import sweep
from sweep.runner.simulate import simulate, summary, to_json_dict

ROOT = Path(__file__).resolve().parents[3]

# docs/physics.md A4: B x H = 10 x 30 cm released from theta0 = 0.5 alpha, Housner impacts
A4_FIRST_IMPACTS = (0.19368, 0.47162, 0.68867)

FREE_ROCKING = {"body": {"B": "10 cm", "H": "30 cm"},
                "contact": {"mu": 10, "e_x": 0.0, "e_y": 0.0},
                "initial": {"theta": "0.5 alpha"},
                "solver": {"t_end": 0.8}}


def test_simulate_twice_from_a_dict():
    """The package-level function stays callable after its first use, and a dict with
    units gives the A4 impact times."""
    first = sweep.simulate(FREE_ROCKING)
    second = sweep.simulate(FREE_ROCKING)
    assert first.impact_times == second.impact_times
    assert first.impact_times[:3] == pytest.approx(A4_FIRST_IMPACTS, abs=1e-5)
    assert first.status == "ok" and not first.overturned


def test_simulate_history_is_a_dataset():
    """history=True gives an xarray Dataset whose theta starts at 0.5 alpha."""
    r = sweep.simulate(FREE_ROCKING, history=True)
    theta0 = float(r.history["theta"].isel(time=0))
    assert theta0 == pytest.approx(0.5 * math.atan(1 / 3), rel=1e-12)


# docs/design.md 10's steady rocking: 79 impacts in 10 s
STEADY = {"body": {"B": "10 cm", "H": "30 cm"}, "contact": {"mu": 10, "e_x": 0.0, "e_y": 0.0},
          "excitation": {"horizontal": {"kind": "sine", "amplitude": "1.5 west",
                                        "frequency": 4.0}},
          "solver": {"t_end": 10.0}}


def _no_constant(name):
    raise ValueError(f"not standard JSON: {name}")


def test_truncated_impact_log_is_flagged():
    """A log of 10 impacts keeps the first 10 of the kernel's 79; the JSON, the message, the
    summary line and the history say so."""
    full = simulate(STEADY)
    cut = simulate(STEADY, history=True, max_log=10)
    data = json.loads(json.dumps(to_json_dict(cut), allow_nan=False),
                      parse_constant=_no_constant)
    assert data["impact_count"] == full.impact_count == 79
    assert data["impact_log_truncated"] is True and len(data["impact_times"]) == 10
    assert data["impact_times"] == full.impact_times[:10]
    assert "impact log truncated at 10 of 79 impacts" in data["message"]
    assert "79 impacts" in summary(cut)
    assert cut.history.attrs["impact_count"] == 79
    assert cut.history.attrs["impact_log_truncated"] == 1
    whole = to_json_dict(full)
    assert whole["impact_log_truncated"] is False and whole["impact_count"] == 79
    assert "truncated" not in whole["message"]


def test_restitution_clamped_at_every_impact_is_said():
    clamped = to_json_dict(simulate({**STEADY, "contact": {"mu": 10, "e_x": 1, "e_y": 1}}))
    assert clamped["status"] == "ok" and clamped["energy_clamps"] == 79
    assert "all 79 impacts had their restitution clamped" in clamped["message"]
    assert to_json_dict(simulate(STEADY))["energy_clamps"] == 0


def test_scene_outputs_are_checked_before_any_work(tmp_path):
    (tmp_path / "file").write_text("a file")
    done = cli(["studies/steady_rocking.yaml", "--plot", "/proc/x.png", "--history",
                str(tmp_path / "file" / "h.nc"), "--animate", str(tmp_path / "ok.gif")],
               cwd=ROOT, timeout=60, module="sweep.scene")
    assert done.returncode == 2 and "Traceback" not in done.stderr, done.stderr
    assert "--plot: its folder /proc is not writable" in done.stderr
    assert f"--history: {tmp_path / 'file'} is a file, not a folder" in done.stderr
    assert "--animate" not in done.stderr and done.stdout == ""  # nothing was run
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]


def test_a_history_too_long_to_hold_is_refused_before_the_run():
    from sweep.io.problems import FileProblems
    from sweep.runner.simulate import MAX_HISTORY
    # dt_out given: a default dt_out would be coarsened to fit (test_outputs.py)
    scene = {"body": {"B": 0.1, "H": 0.3}, "solver": {"t_end": 1e7, "dt_out": 0.02}}  # 5e8
    with pytest.raises(FileProblems, match="solver.dt_out: a history over t_end = 1e.07 s"):
        simulate(scene, history=True)
    assert 1e7 / 0.02 > MAX_HISTORY
    assert simulate(scene).status == "ok"  # without a history it runs (at rest: at once)
