"""A study's record samples in one growing buffer, each record stored once at a fixed offset.

``api.scene_row`` places a scene's records in a :class:`RecordCache` (``api.place_record``) as
it does in a chunk's list; the cache outlives the chunk, so that a rank running many chunks of
one study stores each record once and a GPU receives each once (``cuda_batch.DeviceRecords``).
Records are found by their content (equal samples share an offset, whichever array holds
them).  Past ``limit`` samples the cache starts over before the next chunk
(:meth:`RecordCache.restart_if_full`), which bounds its memory; ``generation`` counts the
restarts, for a device copy to follow.
"""
import hashlib

import numpy as np

LIMIT = 1 << 24  # samples kept at most between chunks: 128 MiB (an ensemble of unique records)


class RecordCache:
    """Record samples shared by the scene rows of many chunks (see the module)."""

    def __init__(self, limit=LIMIT):
        self.limit = limit
        self.generation = 0
        self._start()

    def _start(self):
        self._offsets = {}                 # digest of the samples -> offset
        self._buffer = np.zeros(1)         # capacity; never empty, as api.record_buffer
        self.size = 0

    def place(self, samples):
        """Offset of ``samples`` (contiguous float64) in :meth:`buffer`, stored if new."""
        key = hashlib.blake2b(samples, digest_size=16).digest()
        offset = self._offsets.get(key)
        if offset is None:
            offset, self.size = self.size, self.size + samples.size
            if self.size > self._buffer.size:
                grown = np.zeros(max(self.size, 2 * self._buffer.size))
                grown[:offset] = self._buffer[:offset]
                self._buffer = grown
            self._buffer[offset:self.size] = samples
            self._offsets[key] = offset
        return offset

    def buffer(self):
        """The samples stored so far, one contiguous float64 array (never empty)."""
        return self._buffer[:max(self.size, 1)]

    def restart_if_full(self):
        """Forget every record when more than ``limit`` samples are stored (between chunks)."""
        if self.size > self.limit:
            self._start()
            self.generation += 1
