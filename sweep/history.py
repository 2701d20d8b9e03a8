"""The time history of one scene as a CF-style xarray Dataset (``--history out.nc``)."""
import numpy as np
import xarray as xr

from kernels.codes import MODE_NAMES

_VARIABLES = {  # name: (units, long_name)
    "x": ("m", "horizontal position of the centroid relative to the floor"),
    "y": ("m", "height of the centroid above the floor"),
    "theta": ("rad", "rotation angle, positive about the left corner"),
    "u": ("m s-1", "horizontal velocity of the centroid relative to the floor"),
    "v": ("m s-1", "vertical velocity of the centroid"),
    "omega": ("rad s-1", "angular velocity"),
    "a_x": ("m s-2", "horizontal floor acceleration"),
    "a_y": ("m s-2", "vertical floor acceleration"),
}


def history_dataset(history, scene):
    """Dataset with dimension ``time`` from the kernel's history dict and the resolved scene."""
    data = {name: ("time", np.asarray(history[name]), {"units": u, "long_name": ln})
            for name, (u, ln) in _VARIABLES.items()}
    data["mode"] = ("time", np.asarray(history["mode"]).astype(np.int8),
                    {"long_name": "motion type", "units": "1",
                     "flag_values": np.arange(len(MODE_NAMES), dtype=np.int8),
                     "flag_meanings": " ".join(MODE_NAMES)})
    body = scene["body"]
    return xr.Dataset(
        data, coords={"time": ("time", np.asarray(history["t"]),
                               {"units": "s", "long_name": "time", "axis": "T"})},
        attrs={"Conventions": "CF-1.11", "title": "rigid block on a moving floor: history",
               "B": body["B"], "H": body["H"]})


def write_netcdf(ds, path):
    """Write a dataset atomically: to a temporary name in the same folder, then rename."""
    import os
    from pathlib import Path
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    encoding = {name: {"_FillValue": None} for name in list(ds.data_vars) + list(ds.coords)}
    try:
        ds.to_netcdf(tmp, encoding=encoding)
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
