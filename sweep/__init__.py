"""Studies of rigid blocks rocking, sliding and overturning on a shaking floor (Ishiyama 1982).

Scene and study files, grids, the MPI runner, the netCDF store, closed-form criteria and plots
around the ``kernels`` package.
"""
__version__ = "0.1.0"
