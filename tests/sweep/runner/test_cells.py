"""``runner.cells.run_chunk``: one cell never stops a study, and what each cell reports.

A cell whose scene cannot be built, or that runs past the wall-time budget, is flagged failed
(with a warning naming it) while the other cells of its chunk give their usual results.
"""
import time

import numpy as np
import pytest
from study_helpers import make_study

import sweep
from kernels import codes
from sweep import cf
from sweep.runner.cell_checks import load_study
from sweep.io.records import load_record
from sweep.runner.cells import CELL_BUDGET, ChunkRunner, run_chunk


def _study(grid, **scene):
    raw = make_study(grid)
    for section, values in scene.items():
        raw["scene"].setdefault(section, {}).update(values)
    return load_study(raw, check_cells=False)


def test_a_cell_that_cannot_be_built_is_flagged_and_the_others_run():
    study = _study({"solver.t_end": [2.0, -1.0, 1.0]})
    with pytest.warns(RuntimeWarning, match=r"cell 1: its scene cannot be built.*t_end"):
        out = run_chunk(study, [2, 1, 0])
    assert out["cell"].tolist() == [2, 1, 0]
    assert out["status"].tolist() == [codes.OK, codes.INVALID_SCENE, codes.OK]
    assert out["outcome"].tolist()[1] == codes.FAILED and out["overturned"][1] == -1
    assert np.isnan(out["max_abs_theta"][1]) and np.isnan(out["mode_time"][1]).all()
    assert out["impact_count"][1] == 0 and out["steps"][1] == 0
    good = run_chunk(study, [2, 0])
    for name in cf.VARIABLES:
        np.testing.assert_array_equal(out[name][[0, 2]], good[name], err_msg=name)


def test_a_cell_over_its_wall_time_budget_is_stopped_and_the_next_runs():
    """A fixed step of 0.1 us over 100 s would run for hours; the step of 1 ms cell after it
    in the same chunk ends normally."""
    study = _study({"solver.dt": [1e-3, 1e-7]},
                   solver={"method": "fixed", "t_end": 100.0})
    assert CELL_BUDGET >= 60
    alone = run_chunk(study, [0])
    t0 = time.perf_counter()
    with pytest.warns(RuntimeWarning, match="cell 1: stopped after the per-cell wall-time "
                                            "budget of 0.5 s"):
        out = run_chunk(study, [1, 0], budget=0.5)
    assert 0.5 <= time.perf_counter() - t0 < 2.0
    assert out["status"].tolist() == [codes.TIME_BUDGET, codes.OK]
    assert out["outcome"][0] == codes.FAILED
    for name in cf.VARIABLES:
        np.testing.assert_array_equal(out[name][1], alone[name][0], err_msg=name)


def test_energy_clamps_per_cell():
    """e_x = e_y = 1 on a block that cannot slide: every impact clamped; e_x = -0.8,
    e_y = 0.2: none.  Counted against the kernel's count for the same scene."""
    study = _study({"e_x": [-0.8, 1.0], "e_y": [0.2, 1.0]}, contact={"mu": 10})
    ds = sweep.run_study(study)
    clamps, impacts = ds["energy_clamps"], ds["impact_count"]
    assert clamps.dtype == np.int32 and clamps.attrs["units"] == "1"
    assert "clamped" in clamps.attrs["long_name"]
    both = {"e_x": 1.0, "e_y": 1.0}
    assert int(clamps.sel(both)) == int(impacts.sel(both)) > 0
    assert int(clamps.sel(e_x=-0.8, e_y=0.2)) == 0 < int(impacts.sel(e_x=-0.8, e_y=0.2))
    scene = make_study({})["scene"]
    scene["contact"] = {"mu": 10, **both}
    one = sweep.simulate(scene)
    assert int(clamps.sel(both)) == one.energy_clamps == one.impact_count


def test_the_records_of_a_study_are_kept_from_chunk_to_chunk():
    """A chunk runner stores each record of a record ensemble once over several chunks and
    gives, byte for byte, the results of chunks that each store their own."""
    raw = make_study({"record": ["elcentro1940_ns", "taft1952_ew_s69e"],
                      "excitation.horizontal.scale": [1.0, 2.0]})
    raw["scene"]["excitation"] = {"horizontal": {"kind": "record", "name": "elcentro1940_ns"}}
    raw["scene"]["solver"] = {"t_end": 1.0}
    study = load_study(raw, check_cells=False)
    runner = ChunkRunner()
    for chunk in ([3], [0, 2], [1]):
        kept, alone = runner(study, chunk), run_chunk(study, chunk)
        for name in alone:
            assert kept[name].tobytes() == alone[name].tobytes(), name
    lengths = [load_record(name).samples.size
               for name in ("elcentro1940_ns", "taft1952_ew_s69e")]
    assert runner.records.size == sum(lengths)
