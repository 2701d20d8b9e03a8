"""What reaches the compiled kernel: read-only, strided and big-endian scene records give the
same results as C-contiguous ones (interpolation.py's input tests), and ``run_cells``
agrees with ``run_scene`` cell by cell."""
from pathlib import Path

import numpy as np
import pytest

from kernels import codes
from kernels.api import record_buffer, run_cells, run_scene, scene_row
from scenes import G, const, pulse, scene, sine

RECORD = np.loadtxt(Path(__file__).resolve().parents[2] / "sweep" / "data" / "records"
                    / "elcentro1940_ns.txt")[:, 1]


def _scenes():
    c = const(0.1, 0.3)
    return [
        scene(horizontal=sine(0.5 * G, 4.0), t_end=5.0),
        scene(initial={"theta": 0.5 * c.alpha}, t_end=3.0),
        scene(0.3, 0.3, mu=0.2, horizontal=pulse(0.5 * G, 0.5), t_end=3.0),
        scene(mu=0.6, e_x=-0.8, e_y=0.2, t_end=20.0,
              horizontal={"kind": "record", "samples": RECORD, "dt": 0.02, "scale": 2.0}),
        scene(0.2, 0.6, mu=0.5, e_x=-0.5, e_y=0.3, horizontal=sine(0.4 * G, 1.5),
              vertical={"kind": "record", "samples": RECORD[::-1], "dt": 0.02}, t_end=8.0),
    ]


@pytest.fixture(scope="module")
def chunk():
    records = []
    rows = np.array([scene_row(sc, records) for sc in _scenes()])
    return rows, record_buffer(records)


@pytest.fixture(scope="module")
def reference(chunk):
    rows, rec = chunk
    return run_cells(np.ascontiguousarray(rows), np.ascontiguousarray(rec))


def _same(results, reference):
    """The result records equal bit for bit (NaN included)."""
    assert results.dtype == reference.dtype and results.tobytes() == reference.tobytes()


def test_read_only(chunk, reference):
    rows, rec = chunk
    rows_ro, rec_ro = rows.copy(), rec.copy()
    rows_ro.setflags(write=False)
    rec_ro.setflags(write=False)
    _same(run_cells(rows_ro, rec_ro), reference)


def test_strided_views(chunk, reference):
    rows, rec = chunk
    wide = np.zeros(2 * rows.shape[0], rows.dtype)
    wide[::2] = rows
    rows_view = wide[::2]
    rec_wide = np.zeros((rec.size, 2))
    rec_wide[:, 1] = rec
    rec_view = rec_wide[:, 1]
    assert not rows_view.flags.c_contiguous and not rec_view.flags.c_contiguous
    _same(run_cells(rows_view, rec_view), reference)


def test_other_dtypes(chunk, reference):
    rows, rec = chunk
    rows_be = rows.astype(codes.SCENE_DTYPE.newbyteorder(">"))
    _same(run_cells(rows_be, list(rec)), reference)
    _same(run_cells(list(rows), rec), reference)


def test_run_cells_matches_run_scene(reference):
    for k, sc in enumerate(_scenes()):
        r = run_scene(sc)
        res = reference[k]
        assert codes.STATUS_NAMES[res["status"]] == r.status
        assert res["impacts"] == len(r.impact_times)
        assert res["max_abs_theta"] == r.max_abs_theta
        assert res["t_end"] == r.t_final
        for m, name in enumerate(codes.MODE_NAMES):
            assert res["mode_time"][m] == r.mode_time[name]


def test_bad_rows_raise():
    with pytest.raises(ValueError, match="rows"):
        run_cells(np.zeros((2, 39)), np.zeros(1))
