"""Dimension names of datasets: no dots, no clash with xarray's attributes, the study's own
name kept on the coordinate."""
import xarray as xr
from study_helpers import make_study

import sweep
from sweep import cf
from sweep.runner.cell_checks import load_study


def _names(grid, **extra):
    return cf.dataset_names(load_study(make_study(grid, **extra), check_cells=False))


def test_dotted_paths_take_their_last_key_unless_it_is_ambiguous():
    names = _names({"initial.theta": [0.0, 0.01], "solver.rtol": [1e-6],
                    "excitation.vertical.scale": [0.0], "contact.e_x": [-0.5]})
    assert names["initial.theta"] == "theta" and names["solver.rtol"] == "rtol"
    # 'scale' and 'e_x' are axes of their own (horizontal record scale, e_x): spelled out
    assert names["excitation.vertical.scale"] == "excitation_vertical_scale"
    assert names["contact.e_x"] == "contact_e_x"
    twins = _names({"excitation.horizontal.duration": [1.0], "excitation.vertical.duration":
                    [1.0]})
    assert set(twins.values()) == {"excitation_horizontal_duration",
                                   "excitation_vertical_duration"}


def test_no_name_is_an_xarray_attribute():
    names = _names({"size": [1.0, 2.0], "b_over_h": [0.2], "frequency": [2.0]})
    assert names["size"] == "size_factor"
    for name in names.values():
        assert name.isidentifier() and not hasattr(xr.DataArray, name)


def test_the_dataset_uses_them():
    ds = sweep.run_study(make_study({"size": [1.0, 2.0], "initial.theta": [0.0]}))
    assert ds["outcome"].dims == ("size_factor", "theta")
    assert ds.outcome.size_factor.values.tolist() == [1.0, 2.0]  # the coordinate, not a count
    assert ds["theta"].attrs["study_axis"] == "initial.theta"
