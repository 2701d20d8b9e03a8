"""``kernels.record_cache.RecordCache``: a study's records stored once, at fixed offsets."""
import numpy as np

from kernels import api
from kernels.record_cache import RecordCache


def _scene(samples):
    return {"body": {"B": 0.1, "H": 0.3},
            "excitation": {"horizontal": {"kind": "record", "samples": samples, "dt": 0.01}}}


def test_records_are_found_by_content_and_keep_their_offsets():
    cache = RecordCache()
    assert cache.buffer().tolist() == [0.0]          # never empty, as api.record_buffer([])
    a, b = np.sin(np.arange(100.0)), np.cos(np.arange(30.0))
    rows = [api.scene_row(_scene(s), cache) for s in (a, b, a.copy(), b)]
    assert [row["floor"]["x"]["rec_off"] for row in rows] == [0, 100, 0, 100]
    assert cache.size == 130
    np.testing.assert_array_equal(cache.buffer(), np.concatenate([a, b]))


def test_a_full_cache_starts_over_between_chunks():
    cache = RecordCache(limit=150)
    cache.place(np.arange(100.0))
    cache.restart_if_full()
    assert (cache.size, cache.generation) == (100, 0)
    cache.place(np.arange(60.0) + 0.5)
    cache.restart_if_full()
    assert (cache.size, cache.generation) == (0, 1)
    assert cache.place(np.arange(60.0) + 0.5) == 0
