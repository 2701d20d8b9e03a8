"""How a record file was read, said by the scene's outputs (issue 20, point 8): the reader,
the unit and where it came from, dt, sample count and the header lines, in ``--json``
(``provenance``), ``--summary`` and the ``--plot`` caption.

The expected values are read here from the files themselves (the AT2 header's NPTS and DT, the
bundled file's rows), not from the readers."""
import json
import re
from pathlib import Path

import numpy as np
import pytest
from test_record_formats import _cosmos_channel, _knet_text, _signal

from sweep import scene
from sweep.io.records import load_record, provenance_line, read_record_file
from sweep.plots.scene import draw_scene
from sweep.runner.simulate import simulate

G = 9.80665
BUNDLED = Path(__file__).resolve().parents[3] / "sweep" / "data" / "records"


def _elcentro_at2(path):
    """The bundled El Centro NS written as a PEER .AT2 file (g, 5 values a line)."""
    rows = np.loadtxt(BUNDLED / "elcentro1940_ns.txt")
    g = rows[:, 1] / G
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD",
             "IMPERIAL VALLEY 05/19/40 0439, EL CENTRO ARRAY #9, 180",
             "ACCELERATION TIME SERIES IN UNITS OF G",
             f"NPTS=  {len(g)}, DT=   .0200 SEC"]
    lines += ["".join(f"{v:15.7E}" for v in g[k:k + 5]) for k in range(0, len(g), 5)]
    path.write_text("\n".join(lines) + "\n")
    return path


def _scene(tmp_path, horizontal):
    path = tmp_path / "scene.yaml"
    path.write_text(json.dumps({"body": {"B": 0.2, "H": 0.8}, "contact": {"mu": 0.5},
                                "excitation": {"horizontal": horizontal},
                                "solver": {"t_end": 0.5}}))
    return path


def _json(path, capsys):
    assert scene.main([str(path), "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_at2_provenance_names_the_reader_the_header_unit_and_its_npts_dt(tmp_path, capsys):
    at2 = _elcentro_at2(tmp_path / "RSN6_ELC180.AT2")
    header = at2.read_text().splitlines()[:4]
    npts, dt = re.search(r"NPTS=\s*(\d+), DT=\s*([.\d]+)", header[3]).groups()
    path = _scene(tmp_path, {"kind": "record", "path": at2.name, "pga": "0.3 g"})
    said = _json(path, capsys)["provenance"]
    assert list(said) == ["horizontal"]
    said = said["horizontal"]
    assert said["source"] == str(at2) and said["format"] == "at2"
    assert "AT2" in said["reader"]
    assert said["units"] == "g" and said["units_from"] == "header"
    assert said["units_line"] == f"line 3: {header[2]}"
    assert said["npts"] == int(npts) and said["dt"] == float(dt)
    assert said["header"] == header and said["title"] == header[1]

    assert scene.main([str(path), "--summary"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 3
    assert lines[2] == (f"horizontal record {at2}: read as PEER NGA AT2, in g (from the "
                        f"header, line 3), dt {float(dt):g} s, {npts} samples; {header[1]}")


def test_at2_naming_another_unit_is_refused(tmp_path):
    at2 = _elcentro_at2(tmp_path / "a.AT2")
    at2.write_text(at2.read_text().replace("UNITS OF G", "UNITS OF CM/S/S"))
    with pytest.raises(ValueError, match="line 3: names the unit CM/S/S"):
        read_record_file(at2)


@pytest.mark.parametrize("comment, units, unit, origin", [
    ("# acceleration in cm/s^2\n", None, "cm/s^2", "comment"),
    ("# a quiet floor\n", "gal", "gal", "units:"),
    ("", None, "m/s^2", "default")])
def test_two_column_units_and_where_they_came_from(tmp_path, capsys, comment, units, unit,
                                                   origin):
    data = tmp_path / "floor.txt"
    data.write_text(comment + "".join(f"{0.01 * k:.2f} {v:.3f}\n"
                                      for k, v in enumerate([0.0, 50.0, -80.0, 20.0, 0.0])))
    horizontal = {"kind": "record", "path": data.name, **({"units": units} if units else {})}
    said = _json(_scene(tmp_path, horizontal), capsys)["provenance"]["horizontal"]
    assert said["format"] == "columns" and said["reader"].startswith("two columns")
    assert (said["units"], said["units_from"]) == (unit, origin)
    assert said["units_line"] == ("line 1: # acceleration in cm/s^2" if origin == "comment"
                                  else None)
    assert said["dt"] == 0.01 and said["npts"] == 5
    assert said["header"] == ([comment[1:].strip()] if comment else [])
    factor = {"cm/s^2": 0.01, "gal": 0.01, "m/s^2": 1.0}[unit]
    np.testing.assert_allclose(read_record_file(data, units).samples,
                               factor * np.array([0.0, 50.0, -80.0, 20.0, 0.0]))


def test_one_column_dt_from_the_scene(tmp_path, capsys):
    data = tmp_path / "floor.dat"
    data.write_text("# units: g\n0.0\n0.1\n-0.2\n0.0\n")
    path = _scene(tmp_path, {"kind": "record", "path": data.name, "format": "column",
                             "dt": "10 ms"})
    said = _json(path, capsys)["provenance"]["horizontal"]
    assert (said["format"], said["units"], said["units_from"]) == ("column", "g", "comment")
    assert said["dt"] == 0.01 and said["npts"] == 4


def test_knet_and_cosmos_units_from_their_headers(tmp_path):
    knet = tmp_path / "MYG0041103111446.NS"
    knet.write_text(_knet_text(_signal()))
    read = read_record_file(knet).reading
    assert (read.format, read.reader, read.units_from) == ("knet", "K-NET/KiK-net ASCII",
                                                           "header")
    assert read.units_line.startswith("line 14: Scale Factor")
    assert "MYG004" in read.title and len(read.header) == 17
    assert any("mean" in note for note in read.notes)

    cosmos = tmp_path / "test.V2"
    cosmos.write_text("\n".join(_cosmos_channel(_signal(n=40), 0.01, "360 Deg")) + "\n")
    rec = read_record_file(cosmos)
    announced = next(k for k, line in enumerate(cosmos.read_text().splitlines(), 1)
                     if "acceleration pts" in line)
    assert rec.reading.reader == "COSMOS V2" and rec.units == "cm/s^2"
    assert (rec.reading.units_from, rec.reading.units_line.split(":")[0]) == (
        "header", f"line {announced}")
    assert "Test Station" in rec.reading.title


def test_bundled_record_and_a_scene_without_records(capsys):
    rows = np.loadtxt(BUNDLED / "elcentro1940_ns.txt")
    rec = load_record("elcentro1940_ns")
    assert rec.reading.units_from == "bundled" and rec.units == "m/s^2"
    result = simulate({"body": {"B": 0.2, "H": 0.8},
                       "excitation": {"horizontal": {"kind": "record",
                                                     "name": "elcentro1940_ns"}},
                       "solver": {"t_end": 0.2}})
    said = result.provenance["horizontal"]
    assert said["source"] == "elcentro1940_ns" and said["npts"] == len(rows)
    assert said["dt"] == pytest.approx(rows[1, 0] - rows[0, 0])
    still = simulate({"body": {"B": 0.2, "H": 0.8}, "solver": {"t_end": 0.1}})
    assert still.provenance == {}


def test_plot_caption_says_how_each_record_was_read(tmp_path):
    at2 = _elcentro_at2(tmp_path / "RSN6_ELC180.AT2")
    path = _scene(tmp_path, {"kind": "record", "path": at2.name, "pga": "0.3 g"})
    result = simulate(path, history=True)
    lines = [provenance_line(c, said) for c, said in result.provenance.items()]
    caption = draw_scene(result.history, str(path), lines)._supxlabel.get_text()
    assert "read as PEER NGA AT2, in g (from the header, line 3)" in caption
    assert "2688 samples" in " ".join(caption.split())
