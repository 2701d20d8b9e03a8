"""Grids: cell index <-> coordinates, zip groups, computed axes, seeded shuffle and dealing."""
import numpy as np
import pytest
from study_helpers import make_study

from sweep.io.scene_schema import load_scene, resolve_scene
from sweep.runner.cell_checks import load_study
from sweep.runner import grid

G = 9.80665


def _study(grid_spec, **extra):
    return load_study(make_study(grid_spec, **extra), check_cells=False)


def test_round_trip_index_coordinates():
    study = _study({"amplitude": {"start": 1.0, "stop": 2.0, "num": 3, "unit": "west"},
                    "frequency": {"start": 1.0, "stop": 8.0, "num": 4, "spacing": "log"},
                    "e_y": [0.0, 0.2]})
    assert study.shape == (3, 4, 2) and study.n_cells == 24
    np.testing.assert_allclose(study.dims[1].axes[0].coords, [1.0, 2.0, 4.0, 8.0])
    seen = set()
    for index in range(study.n_cells):
        coords = grid.cell_coords(study, index)
        assert grid.cell_index(study, coords) == index
        seen.add(tuple(coords.values()))
    assert len(seen) == study.n_cells
    # C order: the last axis varies fastest
    assert grid.cell_coords(study, 1) == {"amplitude": 1.0, "frequency": 1.0, "e_y": 0.2}
    with pytest.raises(IndexError):
        grid.positions(study, 24)


def test_zip_groups_share_a_dimension():
    study = _study({"B": ["10 cm", "20 cm", "40 cm"], "H": [0.3, 0.5, 1.2],
                    "frequency": [2.0, 4.0]}, zip=[["B", "H"]])
    assert [d.name for d in study.dims] == ["B", "frequency"] and study.shape == (3, 2)
    np.testing.assert_allclose(study.dims[0].axes[0].coords, [0.1, 0.2, 0.4])  # in m
    assert [grid.cell_values(study, i)["H"] for i in (0, 2, 4)] == [0.3, 0.5, 1.2]
    assert grid.cell_index(study, {"H": 0.5, "frequency": 4.0}) == 3
    with pytest.raises(KeyError):
        grid.cell_index(study, {"B": 0.1, "H": 0.5, "frequency": 4.0})  # not one position

    named = _study({"B": [0.1, 0.2], "H": [0.3, 0.5], "e_y": [0.0, 0.1]},
                   zip={"specimen": ["B", "H"]})
    assert [d.name for d in named.dims] == ["specimen", "e_y"]


def test_body_relative_units_resolve_per_cell():
    study = _study({"amplitude": {"values": [1.5], "unit": "west"},
                    "b_over_h": [0.5, 0.2]})
    for index, ratio in enumerate([0.5, 0.2]):
        scene = resolve_scene(load_scene(grid.cell_scene(study, index)))
        assert scene["body"]["B"] == 0.1
        assert scene["body"]["H"] == pytest.approx(0.1 / ratio)
        assert scene["excitation"]["horizontal"]["amplitude"] == pytest.approx(1.5 * ratio * G)


def test_size_mu_and_dotted_paths():
    raw = make_study({"size": [2.0], "mu": [0.3], "mu_k": [0.2], "solver.rtol": [1e-6]})
    raw["scene"]["body"]["B"] = "10 cm"
    study = load_study(raw)
    over = grid.cell_overrides(study, 0)
    assert over["body.B"] == pytest.approx(0.2) and over["body.H"] == pytest.approx(0.6)
    assert over["contact.mu_s"] == over["contact.mu_edge_k"] == 0.3
    assert over["contact.mu_k"] == 0.2  # an explicit axis wins over mu
    assert over["solver.rtol"] == 1e-6
    scene = resolve_scene(load_scene(grid.cell_scene(study, 0)))
    assert scene["contact"]["mu_edge_s"] == 0.3 and scene["solver"]["rtol"] == 1e-6


def test_shuffle_is_a_seeded_permutation():
    a, b = grid.shuffled(1000, seed=3), grid.shuffled(1000, seed=3)
    np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(np.sort(a), np.arange(1000))
    assert not np.array_equal(a, grid.shuffled(1000, seed=4))
    assert not np.array_equal(a, np.arange(1000))


@pytest.mark.parametrize("chunk_size", [1, 7, 64])
def test_plan_covers_every_cell_left_once(chunk_size):
    done = np.arange(0, 500, 3)
    chunks = grid.plan(500, done, chunk_size, seed=0)
    assert len(chunks) == -(-(500 - done.size) // chunk_size)
    cells = np.concatenate([chunks[k] for k in range(len(chunks))])
    np.testing.assert_array_equal(np.sort(cells), np.setdiff1d(np.arange(500), done))
    assert all(len(chunks[k]) <= chunk_size and np.all(np.diff(chunks[k]) > 0)
               for k in range(len(chunks)))
    with pytest.raises(IndexError):
        chunks[len(chunks)]


def test_default_chunk_size():
    assert grid.default_chunk_size(384, 2) == 12
    assert grid.default_chunk_size(5, 4) == 1
    assert grid.default_chunk_size(10**6, 2) == grid.MAX_CHUNK
    # on the GPU a rank's share in one launch, at most CUDA_CHUNK
    assert grid.default_chunk_size(4000, 1, "cuda") == 4000
    assert grid.default_chunk_size(4001, 2, "cuda") == 2001
    assert grid.default_chunk_size(10**7, 2, "cuda") == grid.CUDA_CHUNK == 1 << 20
