"""A building's floor over a record read from a file or bundled says how the record was read
as the record on the ground does (the JSON's ``provenance``, the ``--summary`` line, the
``--plot`` caption); the summary names the floor's peaks ``floor PGA``, the ground's
``PGA``."""
import json

import yaml

from sweep import scene
from sweep.plots import scene as scene_plots

GROUND = {"kind": "record", "name": "elcentro1940_ns", "pga": "0.3 g"}
FLOOR = {"kind": "floor", "ground": GROUND,
         "building": {"period": "0.6 s", "height_ratio": 0.667}}


def _scene(tmp_path, name, horizontal):
    path = tmp_path / f"{name}.yaml"
    path.write_text(yaml.safe_dump({"body": {"B": "20 cm", "H": "80 cm"},
                                    "contact": {"mu": 0.5},
                                    "excitation": {"horizontal": horizontal},
                                    "solver": {"t_end": "3 s"}}))
    return path


def _outputs(path, capsys, monkeypatch, tmp_path):
    """The JSON, the ``--summary`` lines and the caption ``--plot`` draws."""
    assert scene.main([str(path), "--json"]) == 0
    said = json.loads(capsys.readouterr().out)
    assert scene.main([str(path), "--summary"]) == 0
    lines = capsys.readouterr().out.splitlines()
    drawn = {}
    draw = scene_plots.draw_scene

    def caught(ds, name="", caption=()):
        drawn["caption"] = list(caption)
        return draw(ds, name, caption)

    monkeypatch.setattr(scene_plots, "draw_scene", caught)
    assert scene.main([str(path), "--plot", str(tmp_path / f"{path.stem}.png")]) == 0
    capsys.readouterr()
    return said, lines, drawn["caption"]


def test_a_floor_says_its_ground_record_as_the_ground_does(tmp_path, capsys, monkeypatch):
    ground, ground_lines, ground_caption = _outputs(_scene(tmp_path, "ground", GROUND),
                                                    capsys, monkeypatch, tmp_path)
    floor, floor_lines, floor_caption = _outputs(_scene(tmp_path, "floor", FLOOR), capsys,
                                                 monkeypatch, tmp_path)
    assert list(ground["provenance"]) == ["horizontal"]
    assert ground["provenance"]["horizontal"]["source"] == "elcentro1940_ns"
    assert floor["provenance"] == ground["provenance"]
    assert floor_lines[2:] == ground_lines[2:] == ground_caption == floor_caption
    assert ground_lines[2].startswith("horizontal record elcentro1940_ns: read as bundled")
    assert len(ground_lines) == 3

    assert "; PGA 0.3 g, PGV" in ground_lines[1] and "floor PGA" not in ground_lines[1]
    assert f"; floor PGA {floor['pga'] / 9.80665:.3g} g, PGV" in floor_lines[1]
    assert floor["pga"] != ground["pga"]  # the building's filter, not the ground's 0.3 g
