"""Studies of rigid blocks rocking, sliding and overturning on a shaking floor (Ishiyama 1982).

Scene and study files, grids, the MPI runner, the netCDF store, closed-form criteria and plots
around the ``kernels`` package.
"""
__version__ = "0.1.0"


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
