"""Part files, resume, merge, clean-up and the atomic write of a study's merged dataset.

Each finished chunk becomes one part file ``part-<first cell>.npz`` in ``<output>.parts/``,
written under a temporary name, flushed to disk and renamed (``os.replace`` is atomic): a part
either exists whole or not at all, whatever moment a run is killed.  A part holds the ``cell``
ids it covers, so a run resumes from whatever parts exist with any chunk size and rank count,
and their variables packed in one array (``merged.packed``).  ``manifest.json`` records the
fingerprint of the study's inputs (``runner.fingerprint``: the study, the content of its record
files, the program) and every part carries it too: parts of
other inputs are refused with what changed, and a part that disagrees with the manifest stops
the merge, never a mixed dataset.  A refine study keeps the parts of each round in a folder of
its own (``round-000/``, ``round-001/``, ...).  The merge reads the parts a group of
variables at a time (``runner.merged``), and :func:`write_merged` writes a study's dataset one
group after the other.  The dataset is written to a temporary file in
the output's folder and renamed, so a reader never sees half a file; it carries the
fingerprint as its ``input_fingerprint`` attribute, so that a run killed after writing it
finishes its clean-up when started again.  A parts folder is removed by renaming it first
(``.<name>.parts.<pid>.trash``): a kill during the removal leaves only such a folder, which
the next start deletes with the temporary files of killed writes.
"""
import json
import os
import shutil
import zipfile
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from .. import cf, netcdf
from ..io.files import TMP_MARK, replacing, write_atomic
from . import fingerprint
from .merged import MergedParts, packed, placeholder
from .mpi import JobFailure

MANIFEST = "manifest.json"
PART_GLOB = "part-*.npz"
TRASH_MARK = ".trash"
FINGERPRINT_ATTR = "input_fingerprint"  # global attribute of a dataset written by a run


class StoreError(JobFailure):
    """Output or part files that a run cannot use (existing result, stale or foreign parts)."""


def parts_dir(output):
    """Folder of the part files of an output: ``results/x.nc`` -> ``results/x.nc.parts``."""
    output = Path(output)
    return output.with_name(output.name + ".parts")


def round_dir(directory, index):
    """Folder of the parts of a refine study's round ``index`` inside its parts folder."""
    return Path(directory) / f"round-{index:03d}"


def remove_tree(directory):
    """Delete a folder as one step: renamed aside first (atomic), then deleted."""
    directory = Path(directory)
    if not directory.exists():
        return
    trash = directory.with_name(f".{directory.name}.{os.getpid()}{TRASH_MARK}")
    os.replace(directory, trash)
    shutil.rmtree(trash, ignore_errors=True)


def clean_leftovers(output):
    """Delete what killed runs left beside ``output``: temporary files of interrupted writes
    and parts folders caught while being removed.  Only the holder of the output's lock may
    call this.  Returns the names removed."""
    output = Path(output)
    removed = []
    for pattern in (f".{output.name}.*{TMP_MARK}", f".{parts_dir(output).name}.*{TRASH_MARK}"):
        for path in output.parent.glob(pattern):
            if path.is_dir():
                shutil.rmtree(path, ignore_errors=True)
            else:
                path.unlink(missing_ok=True)
            removed.append(path.name)
    return removed


class PartStore:
    """The part files of one run.

    Parameters
    ----------
    directory : str or Path
        The parts folder (:func:`parts_dir` of the output).
    stamp : str, optional
        The fingerprint written into each part (:meth:`prepare` sets it on rank 0; other
        ranks get it with their plan).
    """

    def __init__(self, directory, stamp=None):
        self.directory = Path(directory)
        self.stamp = stamp

    def prepare(self, study, discard=False):
        """Create the folder or check that its parts belong to this study (rank 0 only).

        Leftover temporary files of a killed run are removed.  Parts of other inputs (another
        fingerprint: study, record file content or program changed) raise :class:`StoreError`
        saying what changed, or are deleted when ``discard`` is true.  Returns the fingerprint.
        """
        if self.directory.exists() and not self.directory.is_dir():
            raise StoreError(f"{self.directory} (the folder of the part files) is taken by a "
                             "file; move or delete it")
        manifest = self.directory / MANIFEST
        parts = fingerprint.components(study)
        self.stamp = fingerprint.combined(parts)
        want = {"fingerprint": self.stamp, "components": parts, "n_cells": study.n_cells,
                "study": study.name}
        stale = None
        if manifest.exists():
            have = self._manifest()
            if have.get("fingerprint") != self.stamp:
                said = fingerprint.changes(have.get("components") or {}, parts)
                stale = (f"{self.directory} holds the parts of other inputs "
                         f"({'; '.join(said) or 'an older version of the program'})")
            elif foreign := [p.name for p in self.parts()
                             if _stamp_of(p) not in (self.stamp, None)]:
                stale = (f"{self.directory} holds {len(foreign)} part files of other inputs "
                         f"than its {MANIFEST} states (first: {foreign[0]})")
        elif self.directory.exists() and any(self.directory.glob(PART_GLOB)):
            stale = f"{self.directory} holds part files without a manifest"
        if stale and not discard:
            raise StoreError(f"{stale}; run with --force to discard them and compute every "
                             "cell again, or delete the folder")
        if stale:
            remove_tree(self.directory)
        self.directory.mkdir(parents=True, exist_ok=True)
        for tmp in self.directory.glob(f".*{TMP_MARK}"):
            tmp.unlink(missing_ok=True)
        if not manifest.exists():
            write_atomic(manifest, lambda f: f.write(json.dumps(want, indent=1).encode()))
        return self.stamp

    def _manifest(self):
        """The manifest's content ({} when missing or unreadable)."""
        try:
            have = json.loads((self.directory / MANIFEST).read_text())
        except (OSError, ValueError):
            return {}
        return have if isinstance(have, dict) else {}

    def manifest_stamp(self):
        """The fingerprint its manifest states, or None."""
        return self._manifest().get("fingerprint")

    def parts(self):
        """Paths of the finished part files, sorted."""
        return sorted(self.directory.glob(PART_GLOB))

    def done_cells(self):
        """Ids of the cells that finished part files cover (int64, sorted).

        A part that cannot be read (only a failing disk makes one) is deleted: its cells run
        again.
        """
        done = []
        for path in self.parts():
            try:
                with np.load(path, allow_pickle=False) as npz:
                    done.append(npz["cell"])
            except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
                path.unlink(missing_ok=True)
        return np.unique(np.concatenate(done)) if done else np.zeros(0, dtype=np.int64)

    def write_part(self, arrays):
        """Write one chunk's arrays (``cells.run_chunk``) as a part file, atomically, with the
        fingerprint of the run's inputs."""
        name = f"part-{int(np.min(arrays['cell'])):09d}.npz"
        stamped = {"cell": arrays["cell"], "cells": packed(arrays),
                   "fingerprint": np.array(self.stamp or "")}
        write_atomic(self.directory / name, lambda f: np.savez(f, **stamped))
        return self.directory / name

    def _cells(self, path, n_cells):
        """A part's cell ids, checked against the manifest: its fingerprint and its cells."""
        with np.load(path, allow_pickle=False) as npz:
            stamp = str(npz["fingerprint"]) if "fingerprint" in npz.files else ""
            cell = np.asarray(npz["cell"], dtype=np.int64)
        if stamp != self.stamp:
            raise StoreError(f"{path} was computed from other inputs than {MANIFEST} states; "
                             "nothing was merged. Run again with --force to compute every "
                             "cell again")
        if cell.size and (cell.min() < 0 or cell.max() >= n_cells):
            raise StoreError(f"{path} holds cells outside 0 .. {n_cells - 1}; nothing was merged")
        return cell

    def index(self, n_cells):
        """Every part file with the cell ids it holds, each checked against the manifest and
        together covering all ``n_cells`` cells (else :class:`StoreError`)."""
        index = [(path, self._cells(path, n_cells)) for path in self.parts()]
        _check_covered([cell for _, cell in index], n_cells)
        return index

    def merge(self, n_cells):
        """Every cell's arrays from the part files, in cell order, read a group of variables
        at a time (``merged.MergedParts``); every part is checked against the manifest
        first."""
        return MergedParts(self.index(n_cells), n_cells)

    def remove(self):
        """Delete the parts folder (after the dataset is written)."""
        remove_tree(self.directory)


def _stamp_of(path):
    """The fingerprint a part file carries: '' when none, None when it cannot be read (such a
    part is deleted by ``done_cells``, and its cells run again)."""
    try:
        with np.load(path, allow_pickle=False) as npz:
            return str(npz["fingerprint"]) if "fingerprint" in npz.files else ""
    except (OSError, ValueError, EOFError, zipfile.BadZipFile):
        return None


def merge(parts, n_cells):
    """Arrays of all ``n_cells`` cells, in cell order, from chunk results.

    Parameters
    ----------
    parts : iterable of dict
        Chunk results (``cells.run_chunk``), in any order.
    n_cells : int

    Raises
    ------
    StoreError
        When some cells are covered by no part.
    """
    out = {name: cf.empty(name, n_cells) for name in cf.VARIABLES}
    cells = []
    for part in parts:
        cells.append(np.asarray(part["cell"], dtype=np.int64))
        for name in cf.VARIABLES:
            out[name][cells[-1]] = part[name]
    _check_covered(cells, n_cells)
    return out


def _check_covered(cells, n_cells):
    """:class:`StoreError` when the arrays of cell ids ``cells`` leave some cells out."""
    seen = np.zeros(n_cells, dtype=bool)
    for cell in cells:
        seen[cell] = True
    if not seen.all():
        missing = np.flatnonzero(~seen)
        raise StoreError(f"{missing.size} cells have no results (first: {missing[:5].tolist()})")


def check_output(path, force):
    """Refuse to overwrite an existing result without ``force``."""
    path = Path(path)
    if path.exists() and not force:
        raise StoreError(f"{path} exists; run with --force to overwrite it")


def finished_earlier(path, stamp):
    """True when ``path`` is the dataset of a run of these very inputs (``stamp``): a run
    killed after writing it, before its clean-up ended."""
    path = Path(path)
    if not path.is_file():
        return False
    try:
        import netCDF4

        with netCDF4.Dataset(path) as nc:
            return getattr(nc, FINGERPRINT_ATTR, None) == stamp
    except (OSError, RuntimeError, ValueError):
        return False


def write_merged(study, merged, path, *, history=None, attrs=None):
    """Write the dataset of a study (``cf.to_dataset``) from its part files to ``path``
    atomically, holding one group of variables at a time.

    xarray writes the whole file, its first group of variables read (``merged.groups``) and
    the others as placeholders (``merged.placeholder``): the file's variables, order, encoding
    and attributes are those of ``netcdf.write_netcdf``.  netCDF4 then writes each other group
    into its variables, read one group at a time (``merged`` holds one group: the first stays
    held until the second is read, so a summary of its variables costs no further read).

    Parameters
    ----------
    study : Study
    merged : merged.MergedParts
    path : str or Path
    history : str, optional
        The command for the ``history`` attribute.
    attrs : dict, optional
        Global attributes added to the dataset's.
    """
    import netCDF4

    with replacing(path) as tmp, _no_chunk_cache():
        written = _write_first(study, merged, tmp, history, attrs or {})
        with netCDF4.Dataset(tmp, "a") as nc:
            for group in merged.groups[1:]:
                _fill(nc, {name: merged[name] for name in group if name in written})
    return Path(path)


@contextmanager
def _no_chunk_cache():
    """No chunk cache for the netCDF files opened in the block: netCDF-C keeps up to 64 MiB
    of each variable's chunks until its file is closed, every variable written in full."""
    import netCDF4

    before = netCDF4.get_chunk_cache()
    netCDF4.set_chunk_cache(0, 0, 1.0)
    try:
        yield
    finally:
        netCDF4.set_chunk_cache(*before)


def _write_first(study, merged, tmp, history, attrs):
    """Write the dataset with the first group of variables read and placeholders for the
    others; returns the names of its data variables (an axis's own result is a coordinate)."""
    first = merged.groups[0]   # held by ``merged`` (read once, also for the summary)
    arrays = {name: merged[name] if name in first else placeholder(name, merged.n_cells)
              for name in cf.VARIABLES}
    ds = cf.to_dataset(study, arrays, history=history)
    ds.attrs.update(attrs)
    netcdf.to_netcdf(ds, tmp)
    return set(ds.data_vars)


def _fill(nc, arrays):
    """Write per-cell arrays into the variables of an open netCDF4 Dataset."""
    for name, a in arrays.items():
        nc[name][...] = a.reshape(nc[name].shape)
