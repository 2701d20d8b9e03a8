"""Part files, resume, merge and the atomic netCDF write.

Each finished chunk becomes one part file ``part-<first cell>.npz`` in ``<output>.parts/``,
written under a temporary name, flushed to disk and renamed (``os.replace`` is atomic): a part
either exists whole or not at all, whatever moment a run is killed.  A part holds the ``cell``
ids it covers, so a run resumes from whatever parts exist with any chunk size and rank count.
``manifest.json`` records a fingerprint of the study (base scene, axes, refine settings, kernel
sources), so that parts of another version of a study are never merged.  A refine study keeps
the parts of each round in a folder of its own (``round-000/``, ``round-001/``, ...).  The
dataset is written to a temporary file in the output's folder and renamed, so a reader never
sees half a file.
"""
import hashlib
import json
import shutil
import zipfile
from pathlib import Path

import numpy as np

from .. import __version__, cf
from ..io.files import TMP_MARK, replacing, write_atomic
from .cells import kernel_digest

MANIFEST = "manifest.json"
PART_GLOB = "part-*.npz"


class StoreError(Exception):
    """Output or part files that a run cannot use (existing result, stale parts)."""


def parts_dir(output):
    """Folder of the part files of an output: ``results/x.nc`` -> ``results/x.nc.parts``."""
    output = Path(output)
    return output.with_name(output.name + ".parts")


def round_dir(directory, index):
    """Folder of the parts of a refine study's round ``index`` inside its parts folder."""
    return Path(directory) / f"round-{index:03d}"


def fingerprint(study):
    """Hash of what decides a study's results: base scene, axes and their values, refine
    settings, kernel."""
    content = {"scene": study.scene,
               "dims": [[dim.name, [[a.name, list(a.values)] for a in dim.axes]]
                        for dim in study.dims],
               "version": __version__, "kernel": kernel_digest()}
    if study.refine is not None:
        content["refine"] = [study.refine.axis, study.refine.tolerance]
    text = json.dumps(content, sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()


class PartStore:
    """The part files of one run.

    Parameters
    ----------
    directory : str or Path
        The parts folder (:func:`parts_dir` of the output).
    """

    def __init__(self, directory):
        self.directory = Path(directory)

    def prepare(self, study, discard=False):
        """Create the folder or check that its parts belong to this study (rank 0 only).

        Leftover temporary files of a killed run are removed.  Parts of another study (another
        fingerprint) raise :class:`StoreError`, or are deleted when ``discard`` is true.
        """
        manifest = self.directory / MANIFEST
        want = {"fingerprint": fingerprint(study), "n_cells": study.n_cells,
                "study": study.name}
        if manifest.exists():
            try:
                have = json.loads(manifest.read_text())
            except (OSError, ValueError):
                have = {}
            if have.get("fingerprint") != want["fingerprint"]:
                if not discard:
                    raise StoreError(
                        f"{self.directory} holds the parts of a different version of this "
                        "study (its scene, grid or the kernel changed); run with --force to "
                        "discard them, or delete the folder")
                shutil.rmtree(self.directory)
        elif self.directory.exists() and any(self.directory.glob(PART_GLOB)):
            if not discard:
                raise StoreError(f"{self.directory} holds part files without a manifest; "
                                 "run with --force to discard them, or delete the folder")
            shutil.rmtree(self.directory)
        self.directory.mkdir(parents=True, exist_ok=True)
        for tmp in self.directory.glob(f".*{TMP_MARK}"):
            tmp.unlink(missing_ok=True)
        if not manifest.exists():
            write_atomic(manifest, lambda f: f.write(json.dumps(want, indent=1).encode()))

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
            except (OSError, ValueError, KeyError, zipfile.BadZipFile):
                path.unlink(missing_ok=True)
        return np.unique(np.concatenate(done)) if done else np.zeros(0, dtype=np.int64)

    def write_part(self, arrays):
        """Write one chunk's arrays (``cells.run_chunk``) as a part file, atomically."""
        name = f"part-{int(np.min(arrays['cell'])):09d}.npz"
        write_atomic(self.directory / name, lambda f: np.savez(f, **arrays))
        return self.directory / name

    @staticmethod
    def _load(path):
        with np.load(path, allow_pickle=False) as npz:
            return {key: npz[key] for key in npz.files}

    def merge(self, n_cells):
        """Every cell's arrays from the part files, in cell order (see :func:`merge`)."""
        return merge((self._load(p) for p in self.parts()), n_cells)

    def remove(self):
        """Delete the parts folder (after the dataset is written)."""
        shutil.rmtree(self.directory, ignore_errors=True)


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
    seen = np.zeros(n_cells, dtype=bool)
    for part in parts:
        cell = np.asarray(part["cell"], dtype=np.int64)
        seen[cell] = True
        for name in cf.VARIABLES:
            out[name][cell] = part[name]
    if not seen.all():
        missing = np.flatnonzero(~seen)
        raise StoreError(f"{missing.size} cells have no results (first: {missing[:5].tolist()})")
    return out


def check_output(path, force):
    """Refuse to overwrite an existing result without ``force``."""
    path = Path(path)
    if path.exists() and not force:
        raise StoreError(f"{path} exists; run with --force to overwrite it")
    if path.exists() and path.is_dir():
        raise StoreError(f"{path} is a folder, not a file")


def write_netcdf(ds, path):
    """Write a Dataset of the package (a study's, a scene's history) to ``path`` atomically:
    a temporary file in the same folder, flushed and renamed; encoding ``cf.encoding``."""
    with replacing(path) as tmp:
        ds.to_netcdf(tmp, format="NETCDF4", engine="netcdf4", encoding=cf.encoding(ds))
    return Path(path)
