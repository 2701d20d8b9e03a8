"""``kernels.api``: what a result says was cut (the impact log) or changed (restitution),
and how scenes are packed (records by name, records of samples stored once, packing errors
with their paths).

Counts are checked against the kernel's own impact count and against a plastic scene run
without clamping; the steady-rocking scene (docs/design.md 10: 1.5 west at 4 Hz, 10 s) has 79
impacts.
"""
import numpy as np
import pytest

from kernels import api, codes
from kernels.api import not_run, run_scene
from scenes import G, scene, sine

STEADY = {"horizontal": sine(0.5 * G, 4.0), "t_end": 10.0}


def test_impact_log_truncated_against_the_kernel_count():
    full = run_scene(scene(**STEADY))
    cut = run_scene(scene(**STEADY), max_log=10)
    assert full.impact_count == len(full.impact_times) == 79 and not full.impact_log_truncated
    assert "truncated" not in full.message
    assert cut.impact_count == full.impact_count and cut.impact_log_truncated
    assert cut.impact_times == full.impact_times[:10]
    assert cut.omega_after == full.omega_after[:10]
    assert cut.message.endswith("; impact log truncated at 10 of 79 impacts")


def test_every_impact_clamped_is_said_and_equals_plastic():
    """e_x = e_y = 1 gains energy at every rocking impact: each is clamped to the plastic law,
    so the scene is the plastic one (e_x = e_y = 0) bit for bit, and the message says so."""
    plastic = run_scene(scene(**STEADY))
    clamped = run_scene(scene(e_x=1.0, e_y=1.0, **STEADY))
    assert plastic.energy_clamps == 0
    assert clamped.status == "ok" and clamped.energy_clamps == clamped.impact_count == 79
    assert clamped.impact_times == plastic.impact_times
    assert clamped.omega_after == plastic.omega_after
    assert clamped.message == (codes.STATUS_MESSAGES[codes.OK] + "; all 79 impacts had their "
                               "restitution clamped to gain no energy (check e_x, e_y)")
    assert plastic.message == codes.STATUS_MESSAGES[codes.OK]


def test_default_restitution_is_never_clamped():
    r = run_scene(scene(mu=0.8, e_x=-0.8, e_y=0.2, **STEADY))
    assert r.impact_count > 0 and r.energy_clamps == 0


def test_results_of_scenes_that_never_ran():
    results = not_run(2)
    assert results.shape == (2,) and results.dtype == codes.RESULT_DTYPE
    assert (results["status"] == codes.INVALID_SCENE).all()
    counts = ["impacts", "steps", "events", "energy_clamps", "direction"]
    for name in counts:
        assert (results[name] == 0).all(), name
    for name in set(codes.RESULT_DTYPE.names) - {*counts, "status"}:
        assert np.isnan(results[name]).all(), name


def test_records_are_views():
    """``as_records`` of C-contiguous scene records shares their memory."""
    rows = api.scene_rows(3)
    records = api.as_records(rows)
    rows["floor"]["y"]["amp"][2] = 4.5
    assert records[2].floor.y.amp == 4.5 and records.shape == (3,)


def test_a_packing_error_names_its_path():
    with pytest.raises(api.PackingError) as err:
        api.scene_row(scene(horizontal=sine(0.5 * G, -4.0)))
    assert err.value.path == "excitation.horizontal.frequency"
    assert err.value.reason == "must be a positive finite number, got -4.0"
    assert str(err.value) == f"`{err.value.path}` {err.value.reason}"


def test_a_record_of_many_rows_is_stored_once():
    samples = np.sin(np.arange(100.0))
    record = {"kind": "record", "samples": samples, "dt": 0.01}
    records = []
    rows = np.array([api.scene_row(scene(horizontal=record, vertical=other), records)
                     for other in (None, {**record, "samples": 2 * samples}, record)])
    assert len(records) == 2 and records[0] is samples
    assert rows["floor"]["x"]["rec_off"].tolist() == [0, 0, 0]
    assert rows["floor"]["y"]["rec_off"].tolist() == [0, 100, 0]
    assert api.record_buffer(records).size == 200
