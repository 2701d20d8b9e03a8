"""The simulations behind a site estimate: one study per body, run or reused.

The bodies of a survey as specimens (``sweep.probability.site``), one study per specimen under
the ensemble, run or reused, their datasets read.

Each distinct body (B, H, i_g, mu) is one study: levels x members, run as ``python -m
sweep.run`` runs it, in this process (``runner.launch.run_file``; :func:`ensemble_datasets`),
into ``<folder>/<key>.nc`` with the study beside it as ``<key>.yaml``; a dataset whose
fingerprint matches the inputs is reused, so a second estimate is instant; one study per body
lets an added body or a second site reuse what is done.  On a cluster:
``python -m sweep.estimate BODIES.yaml --write-study DIR`` writes the studies, ``mpiexec -n N
python -m sweep.run DIR/<key>.yaml`` runs each, and the estimate then reads their datasets.
A body that slides (mu < B/H) is not simulated.  SI units throughout.
"""
import warnings
from collections import namedtuple
from pathlib import Path

import numpy as np

from ..io import records
from ..io.exits import EXIT_BAD_INPUT, EXIT_FAILED
from ..io.problems import InputWarning
from ..io.scene_schema import T_TAIL
from ..paper import estimate as paper_estimate

ARIAS_END = 0.95  # a motion "ends" when 95 % of its Arias intensity has arrived


Specimen = namedtuple("Specimen", "B H i_g mu")
Specimen.__doc__ = """What a simulation of a body needs [SI]: breadth, height, radius of
gyration (None: uniform) and friction coefficient."""


def friction(body, ensemble):
    """The friction coefficient simulated for ``body``: its own, else the ensemble's."""
    return ensemble.mu if body.mu is None else body.mu


def sliding_reason(body, ensemble):
    """Why ``body`` is kept out of the rocking bounds (mu < B/H), or None."""
    mu = friction(body, ensemble)
    if mu >= body.B / body.H:
        return None
    reason = paper_estimate.sliding_reason(mu, body.B, body.H)
    return reason if body.mu is not None else \
        f"{reason} (mu = {mu:g} is the ensemble's default: give the body's own if known)"


def specimen(body, ensemble):
    """The :class:`Specimen` simulated for ``body``."""
    return Specimen(body.B, body.H, body.i_g, friction(body, ensemble))


def specimen_key(spec):
    """A file name for a specimen: ``B24cm_H75cm_mu0.6``."""
    key = f"B{spec.B * 100:.6g}cm_H{spec.H * 100:.6g}cm"
    if spec.i_g is not None:
        key += f"_ig{spec.i_g * 100:.6g}cm"
    return key + f"_mu{spec.mu:.6g}"


def site_specimens(survey):
    """Every distinct specimen simulated for the sites of ``survey`` (sliding bodies left
    out), in order of first appearance."""
    found = {}
    for site in survey.sites:
        for body in site.bodies:
            if sliding_reason(body, survey.ensemble) is None:
                spec = specimen(body, survey.ensemble)
                found.setdefault(specimen_key(spec), spec)
    return found


def member_labels(ensemble):
    """A short label of each member: the record's name or file name, or ``seed k``."""
    if ensemble.records:
        return [r if r in records.NAMES else Path(r).name for r in ensemble.records]
    return [f"seed {k}" for k in range(ensemble.seeds)]


def member_records(ensemble):
    """The accelerogram (``io.records.Record``) of every member, before scaling."""
    if ensemble.records:
        return [records.load_record(r) if r in records.NAMES else records.read_record_file(r)
                for r in ensemble.records]
    from ..groundmotion import stochastic

    scenario = {k: v for k, v in ensemble.synthetic.items() if k != "dt"}
    dt = {} if ensemble.synthetic["dt"] is None else {"dt": ensemble.synthetic["dt"]}
    return [stochastic.generate(**scenario, seed=seed, **dt) for seed in range(ensemble.seeds)]


def arias_end(record, fraction=ARIAS_END):
    """Time [s] at which ``fraction`` of the record's Arias intensity has arrived."""
    husid = np.cumsum(np.square(record.samples))
    return float(np.searchsorted(husid, fraction * husid[-1]) * record.dt)


def simulated_time(ensemble):
    """``t_end`` of the studies: the ensemble's, else the latest time at which a member's
    Arias intensity reaches 95 %, plus ``T_TAIL`` for the body to settle or fall [s]."""
    if ensemble.t_end is not None:
        return ensemble.t_end
    return max(arias_end(r) for r in member_records(ensemble)) + T_TAIL


def study_dict(spec, ensemble, t_end, output, name="site"):
    """The study of one specimen under the ensemble: grid ``pga`` (levels) x ``record`` or
    ``seed`` (members), in that order; SI numbers (the levels with their unit, so that low
    ones are not taken for bare g), absolute paths."""
    body = {"B": spec.B, "H": spec.H, **({} if spec.i_g is None else {"i_g": spec.i_g})}
    contact = {"mu": spec.mu, **{k: v for k, v in (("e_x", ensemble.e_x), ("e_y", ensemble.e_y))
                                 if v is not None}}
    if ensemble.records:
        first = ensemble.records[0]
        excitation = {"kind": "record", **({"name": first} if first in records.NAMES
                                           else {"path": first})}
        members = {"record": list(ensemble.records)}
    else:
        excitation = {"kind": "synthetic", **{k: v for k, v in ensemble.synthetic.items()
                                              if v is not None}, "seed": 0}
        members = {"seed": list(range(ensemble.seeds))}
    return {"name": f"{name}_{specimen_key(spec)}",
            "title": f"B = {spec.B * 100:.4g} cm, H = {spec.H * 100:.4g} cm, mu = {spec.mu:g} "
                     "under a site's ensemble of motions (sweep.estimate)",
            "scene": {"body": body, "contact": contact,
                      "excitation": {"horizontal": excitation}, "solver": {"t_end": t_end}},
            "grid": {"pga": {"values": list(ensemble.levels), "unit": "m/s^2"}, **members},
            "output": str(Path(output).resolve())}


def results_folder(bodies_path):
    """Where the datasets of a bodies file go: ``results/<file stem>/`` beside it."""
    path = Path(bodies_path)
    return path.parent / "results" / path.stem


def write_studies(survey, folder, results):
    """Write the study of every specimen of ``survey`` to ``folder``, its output in
    ``results``; the paths written."""
    import yaml

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    t_end = simulated_time(survey.ensemble)
    name = "site" if survey.source is None else survey.source.stem
    written = []
    for key, spec in site_specimens(survey).items():
        study = study_dict(spec, survey.ensemble, t_end, Path(results) / f"{key}.nc", name)
        path = folder / f"{key}.yaml"
        path.write_text(yaml.safe_dump(study, sort_keys=False))
        written.append(path)
    return written


class RunFailed(RuntimeError):
    """A study of the estimate did not run to its end."""


def _run_study(path):
    """The dataset of the study at ``path`` and whether it was computed now: its output when
    the fingerprint of its inputs matches, else computed in this process as ``python -m
    sweep.run`` computes it (``runner.launch.run_file``; ``--force`` when the output or part
    files hold other inputs).  Its doubts of the PGA levels are not said again for every
    body: they are the bodies file's, said where it was read.

    Raises
    ------
    RunFailed
        The run was refused or failed (said on stderr).
    KeyboardInterrupt
        Ctrl-C during the run (it said what is saved).
    """
    import xarray as xr

    from ..io.study_schema import load_study
    from ..runner import fingerprint, mpi, store
    from ..runner.options import RunOptions

    study = load_study(path)
    stamp = fingerprint.combined(fingerprint.components(study))
    ran = not store.finished_earlier(study.output, stamp)
    if ran:
        parts = store.PartStore(store.parts_dir(study.output)).manifest_stamp()
        stale = study.output.exists() or parts not in (None, stamp)
        options = RunOptions(quiet=True, force=stale,
                             argv=(str(path), "--quiet", *(("--force",) if stale else ())))
        comm = mpi.world_or_say("sweep.run")
        if comm is None:
            raise RunFailed(_ended(path, EXIT_BAD_INPUT))
        from ..runner import launch  # the study machinery once the communicator stands

        with warnings.catch_warnings():  # the levels were checked in the bodies file
            warnings.filterwarnings("ignore", r"grid\.pga\b", InputWarning)
            try:
                launch.run_file(comm, str(path), options)
            except launch.Refused:
                raise RunFailed(_ended(path, EXIT_BAD_INPUT)) from None
            except mpi.JobFailure:
                raise RunFailed(_ended(path, EXIT_FAILED)) from None
    with xr.open_dataset(study.output) as ds:
        return ds.load(), ran


run_study_file = _run_study  # the same for other studies of this layer (sweep.probability.stripes)


def _ended(path, status):
    """Why a study of the estimate did not run to its end: the status its command would
    have ended with."""
    return f"python -m sweep.run {path} ended with status {status}"


def ensemble_datasets(survey, folder, say=None):
    """The dataset of every specimen of ``survey``: {key: xarray.Dataset}.

    The studies are written to ``folder`` (``<key>.yaml``) with their outputs beside them
    (``<key>.nc``) and run, or their outputs reused (:func:`_run_study`).  ``say(text)`` is
    told what was computed.
    """
    import time

    start = time.perf_counter()
    written = write_studies(survey, folder, folder)
    datasets, computed = {}, 0
    for path in written:
        datasets[path.stem], ran = _run_study(path)
        computed += ran
    if say is not None and computed:
        cells = len(survey.ensemble.levels) * survey.ensemble.members
        say(f"{computed} of {len(written)} bodies simulated ({cells} cells each) in "
            f"{time.perf_counter() - start:.1f} s; datasets in {folder}")
    return datasets
