"""A dataset of the package written to a netCDF file with ``cf.encoding``, atomically.

The dataset comes from ``cf``'s builders, the file is NETCDF4 through netCDF4, written whole (a
temporary file in the same folder, flushed and renamed: a reader never sees half a file)."""
from pathlib import Path

from . import cf
from .io.files import replacing


def to_netcdf(ds, path):
    """Write ``ds`` to ``path`` in place: NETCDF4, encoding ``cf.encoding``."""
    ds.to_netcdf(path, format="NETCDF4", engine="netcdf4", encoding=cf.encoding(ds))


def write_netcdf(ds, path):
    """Write a Dataset of the package (a study's, a scene's history) to ``path`` atomically:
    a temporary file in the same folder, flushed and renamed; encoding ``cf.encoding``."""
    with replacing(path) as tmp:
        to_netcdf(ds, tmp)
    return Path(path)
