"""A zipped axis may repeat a value (two motions of one magnitude): the zip's dimension is the
member, and its axes are coordinates along it; an axis that is a dimension's coordinate may
not.  The stripes of a risk file keep the magnitudes and distances as drawn."""
import math
import subprocess
import sys

import numpy as np
import pytest
import yaml

import sweep
from sweep.bodies import G
from sweep.io import study_grid
from sweep.io.study_schema import load_study
from sweep.probability import source_hazard, stripes
from sweep.probability.site_studies import run_study_file

MAGNITUDE = "excitation.horizontal.magnitude"
SYNTHETIC = {"kind": "synthetic", "model": "boore2003", "magnitude": 6.0, "distance": "20 km",
             "vs30": "760 m/s", "seed": 0, "pga": "0.3 g"}
SCENE = {"body": {"B": 0.2, "H": 0.6}, "excitation": {"horizontal": SYNTHETIC},
         "solver": {"t_end": 10.0}}
SEEDS, MAGNITUDES = [1, 2, 3], [6.0, 6.0, 6.5]


def _write(tmp_path, zip_groups=None):
    study = {"scene": SCENE, "grid": {"seed": SEEDS, MAGNITUDE: MAGNITUDES},
             "output": str(tmp_path / "repeats.nc")}
    if zip_groups is not None:
        study["zip"] = zip_groups
    path = tmp_path / "repeats.yaml"
    path.write_text(yaml.safe_dump(study, sort_keys=False))
    return path


def test_a_named_zip_runs_with_a_repeated_magnitude_and_is_reused(tmp_path):
    """Each member is the scene of its own seed and magnitude (simulated alone here), the two
    of magnitude 6 are two motions, and the dataset (written, read back, and reused on a second
    run by its fingerprint) holds the magnitudes as written along the member dimension."""
    path = _write(tmp_path, {"member": ["seed", MAGNITUDE]})
    ds, ran = run_study_file(path)
    assert ran and ds["overturned"].dims == ("member",)
    assert ds["magnitude"].dims == ds["seed"].dims == ("member",)
    np.testing.assert_array_equal(ds["magnitude"].values, MAGNITUDES)
    np.testing.assert_array_equal(ds["seed"].values, SEEDS)
    alone = [sweep.simulate({**SCENE, "excitation": {"horizontal": {
        **SYNTHETIC, "seed": seed, "magnitude": magnitude}}})
        for seed, magnitude in zip(SEEDS, MAGNITUDES)]
    np.testing.assert_allclose(ds["pgv"].values, [r.pgv for r in alone], rtol=1e-12)
    np.testing.assert_allclose(ds["pga"].values, 0.3 * G, rtol=1e-12)
    assert ds["pgv"].values[0] != ds["pgv"].values[1]  # one magnitude, two motions
    again, ran_again = run_study_file(path)
    assert not ran_again
    np.testing.assert_array_equal(again["overturned"].values, ds["overturned"].values)


NAME_THE_ZIP = ("; the axis that names a zip group is its dimension's coordinate: name the "
                "group (zip: {member: [...]}) to let its values repeat")


@pytest.mark.parametrize("zip_groups, hint", [
    (None, ""),  # an axis of its own
    ([[MAGNITUDE, "seed"]], NAME_THE_ZIP),  # the first of a listed group names its dimension
])
def test_a_repeated_dimension_coordinate_is_one_line_exit_2(tmp_path, zip_groups, hint):
    path = _write(tmp_path, zip_groups)
    done = subprocess.run([sys.executable, "-m", "sweep.run", str(path), "--dry-run"],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2 and "Traceback" not in done.stderr
    problems = [line.strip() for line in done.stderr.splitlines() if line.startswith("  ")]
    assert problems == [f"grid.{MAGNITUDE}: values repeat: 6.0{hint} (got: {MAGNITUDES})"]


def test_a_listed_zip_may_repeat_its_other_axes_and_cells_are_found_by_both(tmp_path):
    study = load_study(_write(tmp_path, [["seed", MAGNITUDE]]))
    assert [d.name for d in study.dims] == ["seed"] and study.n_cells == 3
    assert study_grid.cell_index(study, {MAGNITUDE: 6.5}) == 2
    assert study_grid.cell_index(study, {"seed": 2, MAGNITUDE: 6.0}) == 1
    with pytest.raises(KeyError):  # magnitude 6 alone is two members
        study_grid.cell_index(study, {MAGNITUDE: 6.0})
    with pytest.raises(KeyError):  # seed 3 is of magnitude 6.5
        study_grid.cell_index(study, {"seed": 3, MAGNITUDE: 6.0})


def test_stripes_keep_the_drawn_magnitudes_and_distances(tmp_path):
    """The plan's earthquakes are the model's draw with the generator of [seed, j], unrounded:
    a point source 10 km away at 8 km depth is hypot(10, 8) km away for every motion."""
    model = source_hazard.SourceModel(
        [source_hazard.point_source(source_hazard.Recurrence(0.02, 5.5, 7.5), 10e3, 8e3)],
        760.0, "BSSA14", "pga")
    levels, motions, seed = [2.0, 6.5], 5, 7
    plan = stripes.plan(levels, motions, seed, model=model)
    for j, (level, stripe) in enumerate(zip(levels, plan)):
        drawn = model.draw(level, motions, np.random.default_rng([seed, j]))
        assert stripe.magnitudes == drawn[:, 0].tolist()
        assert stripe.distances == pytest.approx([math.hypot(10e3, 8e3)] * motions,
                                                 rel=1e-15, abs=0)
        assert stripe.seeds == list(range(seed + j * motions, seed + (j + 1) * motions))


def test_a_stripe_with_repeated_magnitudes_is_a_study(tmp_path):
    """Two motions of one magnitude and at one distance: the stripe's study loads, one member
    dimension, the magnitudes and distances as given."""
    stripe = stripes.Stripe(3.0, [10, 11, 12], [6.25, 6.25, 7.0], [15e3, 15e3, 30e3])
    [path] = stripes.write_studies([stripe], {"body": {"B": 0.15, "H": 0.6}}, 760.0, None,
                                   "repeats", tmp_path)
    study = load_study(path)
    [dim] = study.dims
    assert dim.name == stripes.MEMBER and dim.size == 3
    coords = {axis.name: axis.coords.tolist() for axis in dim.axes}
    assert coords == {"seed": [10, 11, 12], MAGNITUDE: [6.25, 6.25, 7.0],
                      "excitation.horizontal.distance": [15e3, 15e3, 30e3]}
