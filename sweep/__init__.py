"""Studies of rigid blocks rocking, sliding and overturning on a shaking floor (Ishiyama 1982).

Around the ``kernels`` package, one folder per layer: ``io`` (YAML, units, the scene, study and
bodies schemas, records, problems, atomic writes), ``runner`` (one scene; grids of cells over
MPI ranks, part files, refine, progress), ``paper`` (criteria, estimate, classification, the
normalized plane), ``plots`` (figures from datasets) and ``cf`` (the metadata of every
dataset).  ``run``, ``scene``, ``plot`` and ``estimate`` are the ``python -m`` commands;
:func:`simulate` and :func:`run_study` the Python entry points.
"""
from ._version import __version__


def run_study(study, **options):
    """Run a study in this process and return its xarray Dataset (``runner.launch.run_study``).

    ``study`` is a study file or a dict of the same schema; nothing is written.
    """
    from .runner.launch import run_study as _run_study  # heavy imports only when called
    return _run_study(study, **options)


def simulate(scene, history=False):
    """Run one scene (a file or a dict of the scene schema); see ``sweep.runner.simulate``."""
    from .runner.simulate import simulate as _simulate
    return _simulate(scene, history=history)
