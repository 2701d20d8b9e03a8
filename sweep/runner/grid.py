"""Grids of a study: axes to cells, zip groups, cell ids, chunks and the seeded shuffle.

A study's axes (docs/design.md section 5) are grouped into dimensions: an axis alone is a
dimension of its own, axes of a ``zip`` group share one.  Cells are numbered 0 .. n-1 in C
order over the dimensions (the last one varies fastest), so a cell id is a flat index into the
dataset's arrays.  Each cell's scene is the study's base scene with the cell's axis values set
at their scene paths (``AXES``), before validation, so unit strings such as ``"1.5 west"``
resolve with the cell's own body.

The study's words (``AXES``, ``COMPUTED``, ``FIELD_DIMENSIONS``, ...: ``sweep.io.vocabulary``)
and its cells (``shape``, ``cell_scene``, ``sample``, ...: ``sweep.io.study_grid``) are defined
in ``io``, where the study schema checks them, and imported here under the same names; this
module adds what a run does with the cells: the seeded shuffle and the chunks that the ranks
take one at a time (``runner.mpi``).
"""
import math

import numpy as np

from ..io.study_grid import (DEFAULT_SEED, cell_coords, cell_index, cell_overrides,  # noqa: F401
                             cell_scene, cell_values, n_cells, positions, sample, shape,
                             shape_text)
from ..io.vocabulary import (AXES, COMPUTED, FIELD_DIMENSIONS, MU_PATHS,  # noqa: F401
                             RECORD_PATHS, SCENE_SECTIONS, record_source, targets,
                             value_dimensions)

MAX_CHUNK = 64  # cells per chunk at most by default: a part file every few seconds at worst
CHUNKS_PER_RANK = 16  # default chunk size aims at this many chunks per rank (balance, resume)
CUDA_CHUNK = 1 << 20  # GPU chunk at most: one launch of many waves of resident threads
MIN_GPU_CELLS = 20_000  # a study of fewer cells runs on the CPU: too few for a GPU to win


# --- chunks ---------------------------------------------------------------------

def shuffled(n, seed=DEFAULT_SEED):
    """The cells 0 .. n-1 in a seeded random order (a permutation, the same for any rank count).

    Cost correlates with grid position (high amplitudes overturn early, low ones run to the
    end): a shuffled order gives every rank a fair mix.
    """
    return np.random.default_rng(seed).permutation(n).astype(np.int64)


def default_chunk_size(n, size, backend="cpu"):
    """Chunk size giving about ``CHUNKS_PER_RANK`` chunks per rank, at most ``MAX_CHUNK``; on
    the GPU (``backend="cuda"``) a rank's whole share, at most ``CUDA_CHUNK`` (one launch).

    A GPU launch lasts as long as its slowest cell, and a launch of a few dozen threads leaves
    the GPU all but idle: one GPU thread runs a 60 s sweep cell for many seconds."""
    size = max(1, size)
    if backend == "cuda":
        return max(1, min(CUDA_CHUNK, math.ceil(n / size)))
    return max(1, min(MAX_CHUNK, math.ceil(n / (CHUNKS_PER_RANK * size))))


class Chunks:
    """The chunks of one round: an order of cells cut into consecutive pieces of
    ``chunk_size``, each sorted by cell id; chunk k is ``chunks[k]``.  Every rank holds the same
    order, so a chunk is named by its index alone (``runner.mpi.Dealer``)."""

    def __init__(self, order, chunk_size):
        if chunk_size < 1:
            raise ValueError(f"`chunk_size` must be >= 1, got {chunk_size}")
        self.order = np.asarray(order, dtype=np.int64)
        self.chunk_size = int(chunk_size)

    def __len__(self):
        return -(-self.order.size // self.chunk_size)

    def __getitem__(self, k):
        if not 0 <= k < len(self):
            raise IndexError(k)
        return np.sort(self.order[k * self.chunk_size:(k + 1) * self.chunk_size])

    @property
    def n_cells(self):
        return self.order.size


def plan(n, done, chunk_size, seed=DEFAULT_SEED):
    """The :class:`Chunks` of the cells not yet ``done``, in seeded shuffled order.

    Parameters
    ----------
    n : int
        Number of cells.
    done : ndarray of int
        Cells already computed (from part files); left out.
    chunk_size, seed : int
        Cells per chunk, shuffle seed.
    """
    order = shuffled(n, seed)
    if len(done):
        order = order[~np.isin(order, np.asarray(done, dtype=np.int64))]
    return Chunks(order, chunk_size)
