"""The cells of a run's part files, read one group of variables at a time.

A part file holds a chunk's variables packed into one structured array, ``cells``
(:func:`packed`): an ``.npz`` reads its arrays one by one, at about 0.08 ms each, so one
array in place of one per variable makes a part about five times quicker to read.
Rank 0 never holds every variable of every cell at once: the variables of ``cf.VARIABLES``
are cut, in their order, into groups whose full arrays for all cells fit in ``BUDGET``
(:func:`groups`), and :class:`MergedParts` reads a group by opening each part file and
taking only that group's fields.
``store.write_merged`` writes the dataset a group at a time; :func:`placeholder` stands for
a variable not yet read.
"""
from collections.abc import Mapping

import numpy as np

from .. import cf

BUDGET = 64 * 2**20  # bytes: the full arrays of one group of variables, at most


def cell_bytes(name):
    """Bytes one cell takes in variable ``name`` of ``cf.VARIABLES``."""
    return cf.empty(name, 1).nbytes


def packed(arrays):
    """The variables of ``cf.VARIABLES`` that ``arrays`` holds (first axis = cells; a chunk's
    result holds them all) as one structured array with a field per variable, in their
    order: what a part file holds as ``cells``."""
    names = [name for name in cf.VARIABLES if name in arrays]
    out = np.empty(len(arrays["cell"]), [(name, arrays[name].dtype, arrays[name].shape[1:])
                                         for name in names])
    for name in names:
        out[name] = arrays[name]
    return out


def groups(n_cells, budget=BUDGET):
    """The variables of ``cf.VARIABLES`` in their order, cut into groups (tuples of names)
    whose arrays for ``n_cells`` cells take at most ``budget`` bytes; a variable larger than
    the budget is a group of its own."""
    out, group, size = [], [], 0
    for name in cf.VARIABLES:
        nbytes = cell_bytes(name) * n_cells
        if group and size + nbytes > budget:
            out.append(tuple(group))
            group, size = [], 0
        group.append(name)
        size += nbytes
    return out + [tuple(group)] if group else out


class MergedParts(Mapping):
    """Every cell's arrays from checked part files, read a group of variables at a time.

    A mapping of the names of ``cf.VARIABLES`` to arrays in cell order (as ``store.merge``
    gives); reading a variable reads its group, which is kept until another group is read.

    Parameters
    ----------
    index : list of (path, ndarray)
        Each part file and the cell ids it holds (``store.PartStore.index``), together
        covering every cell.
    n_cells : int
    budget : int, optional
        Bytes of one group's arrays (:func:`groups`); default ``BUDGET``.
    """

    def __init__(self, index, n_cells, budget=None):
        self.index, self.n_cells = index, n_cells
        self.groups = groups(n_cells, BUDGET if budget is None else budget)
        self._held = {}

    def read(self, names):
        """The full arrays of the variables ``names``, in one pass over the part files."""
        out = {name: cf.empty(name, self.n_cells) for name in names}
        for path, cell in self.index:
            with np.load(path, allow_pickle=False) as npz:
                cells = npz["cells"]
            for name in names:
                out[name][cell] = cells[name]
        return out

    def __getitem__(self, name):
        if name not in self._held:
            group = next(g for g in self.groups if name in g)  # KeyError past the end
            self._held = {}  # the group held is let go before the next is read
            self._held = self.read(group)
        return self._held[name]

    def __iter__(self):
        return iter(cf.VARIABLES)

    def __len__(self):
        return len(cf.VARIABLES)


def placeholder(name, n_cells):
    """An array of ``n_cells`` cells of variable ``name`` that takes no memory: every cell
    the value of ``cf.empty``, a broadcast view of one cell."""
    one = cf.empty(name, 1)
    return np.broadcast_to(one, (n_cells, *one.shape[1:]))
