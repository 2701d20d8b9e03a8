"""What decides a study's results, hashed: the study, the record files it reads, the program.

A run's part files are kept only while all three are unchanged, so that a resumed run never
mixes cells computed from other inputs.  The components are hashed apart, so that a refusal
can say what changed:

``study``
    the base scene, every axis with its values, the refine settings;
``records``
    the content (SHA-256 of the bytes) of every record file a cell can read: bundled records
    by name and the user's files by path, from the base scene and from the axes that set a
    record's ``name`` or ``path``;
``program``
    the package version and the sources that turn a cell into results (``PROGRAM_SOURCES``:
    the kernel, the body's scales, the input checks, the cell runner, the dataset's
    variables, the part files' layout).
"""
import hashlib
import importlib.resources
import json
from pathlib import Path

from .._version import __version__
from ..io import records
from . import grid

_ROOT = Path(__file__).resolve().parents[2]
# Source files whose edit can change what a cell's part holds, or how (the part's layout).
PROGRAM_SOURCES = ("kernels/*.py", "sweep/bodies.py", "sweep/io/*.py", "sweep/io/formats/*.py",
                   "sweep/groundmotion/*.py",
                   "sweep/runner/grid.py", "sweep/runner/store.py", "sweep/runner/merged.py",
                   "sweep/runner/cells.py", "sweep/runner/cell_rows.py",
                   "sweep/paper/criteria.py", "sweep/cf.py",
                   "sweep/netcdf.py")
_RECORD_KEYS = ("name", "path")
_EXCITATIONS = ("horizontal", "vertical")


def _sha(data):
    return hashlib.sha256(data).hexdigest()


def source_digest(patterns=PROGRAM_SOURCES, root=_ROOT):
    """SHA-256 over the names and bytes of the files matching ``patterns`` below ``root``."""
    digest = hashlib.sha256()
    for pattern in patterns:
        for path in sorted(root.glob(pattern)):
            digest.update(str(path.relative_to(root)).encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()


def _record_file(key, value, base_dir):
    """The file a record ``name`` or ``path`` reads, or None for a name that is not bundled."""
    if key == "path":
        return (Path(base_dir) / Path(value).expanduser()).resolve()
    name = records.ALIASES.get(value, value)
    if name not in records.BUNDLED:
        return None
    with importlib.resources.as_file(
            importlib.resources.files("sweep.data") / "records" / f"{name}.txt") as path:
        return Path(path)


def record_references(study):
    """``{(key, value)}``: every record name and path the study's cells can read."""
    found = set()
    excitation = study.scene.get("excitation")
    for which in _EXCITATIONS:
        ground = excitation.get(which) if isinstance(excitation, dict) else None
        if isinstance(ground, dict) and isinstance(ground.get("ground"), dict):
            ground = ground["ground"]  # a floor reads its ground's record
        if isinstance(ground, dict):
            found |= {(key, ground[key]) for key in _RECORD_KEYS
                      if isinstance(ground.get(key), str)}
    for axis in study.axes:
        if axis.name == "record":
            found |= {grid.record_source(v) for v in axis.values if isinstance(v, str)}
            continue
        for target in grid.targets(axis.name):
            section, *_, key = target.split(".")
            if section == "excitation" and key in _RECORD_KEYS:
                found |= {(key, v) for v in axis.values if isinstance(v, str)}
    return found


def record_digests(study):
    """``{"name: elcentro1940_ns" or "path: my.AT2": SHA-256 of the file, or "missing"}``."""
    out = {}
    for key, value in sorted(record_references(study)):
        path = _record_file(key, value, study.base_dir)
        if path is None:
            continue
        try:
            out[f"{key}: {value}"] = _sha(path.read_bytes())
        except OSError:
            out[f"{key}: {value}"] = "missing"
    return out


def study_digest(study):
    """SHA-256 of the base scene, the axes and their values, and the refine settings."""
    content = {"scene": study.scene,
               "dims": [[dim.name, [[a.name, list(a.values)] for a in dim.axes]]
                        for dim in study.dims],
               "refine": None if study.refine is None else [study.refine.axis,
                                                            study.refine.tolerance]}
    return _sha(json.dumps(content, sort_keys=True, default=str).encode())


def components(study):
    """The hashed components of a study's inputs: ``{"study", "records", "program"}``."""
    return {"study": study_digest(study), "records": record_digests(study),
            "program": f"{__version__}:{source_digest()}"}


def combined(parts):
    """One fingerprint of the components (what part files and the dataset carry)."""
    return _sha(json.dumps(parts, sort_keys=True).encode())


def changes(old, new):
    """What differs between two sets of components, in words (empty when nothing does)."""
    said = []
    if old.get("study") != new.get("study"):
        said.append("the study's scene, grid or refine settings changed")
    old_rec, new_rec = old.get("records", {}), new.get("records", {})
    for ref in sorted(set(old_rec) | set(new_rec)):
        if old_rec.get(ref) != new_rec.get(ref):
            what = ("is no longer read" if ref not in new_rec else
                    "is read now but was not" if ref not in old_rec else
                    "changed content")
            said.append(f"record file ({ref}) {what}")
    if old.get("program") != new.get("program"):
        said.append("the program (kernel or cell code) changed")
    return said
