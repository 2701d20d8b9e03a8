"""Malformed risk and hazard files, as ``test_malformed`` has them for scenes and studies:
exit status 2 (or, loading a risk file, :class:`FileProblems`), one line per problem naming
where, no traceback, no hang.

* Hazard curve files in each format (two columns, OpenQuake CSV, USGS JSON): binary, empty,
  NaN, infinite, negative and duplicate levels, probabilities outside [0, 1], broken OpenQuake
  headers, JSON of the wrong shape; through ``--hazard`` and through a risk file's
  ``hazard.file.path``.
* A mutation of every key of the bundled risk files and of one on a curve file: each value
  replaced by a list, a mapping, ``"zz"``, −1, or deleted, each mapping given an unknown key,
  loaded as the command loads it (``load_risk`` with ``checked_hazard``; a mutation that still
  validates does not run the stripes).
* A handful of each through real ``python -m sweep.risk`` processes.
"""
import subprocess
from pathlib import Path

import pytest
import yaml

from malformed_corpus import _dotted, _nodes, _set
from study_helpers import PY, cli_env
from sweep.io.problems import FileProblems
from sweep.io.risk_schema import load_risk
from sweep.probability.risk_inputs import checked_hazard
from sweep.risk import main

STUDIES = Path(__file__).resolve().parents[3] / "studies"
HEADER = "pga_g,annual_rate\n"
OQ = "#,,,\"generated_by='x', kind='mean', investigation_time=50.0, imt='PGA'\"\n"
OQ_HEADER = "lon,lat,depth,poe-0.1,poe-0.2\n"

# name (its suffix chooses the format) -> contents; every one is malformed
CURVES = {
    "empty.txt": b"",
    "blank.txt": b"  \n\n",
    "comment_only.txt": b"# units: g\n",
    "header_only.txt": HEADER.encode(),
    "binary.txt": bytes(range(256)) * 4,
    "nul.txt": (HEADER + "0.1,1e-2\n\0\n").encode(),
    "latin1.txt": "pga_g,taux \xe9\n0.1 1e-2\n".encode("latin-1"),
    "utf16.txt": (HEADER + "0.1,1e-2\n0.2,1e-3\n").encode("utf-16"),
    "nan_level.txt": (HEADER + "0.1,1e-2\nnan,1e-3\n").encode(),
    "nan_rate.txt": (HEADER + "0.1,nan\n0.2,1e-3\n").encode(),
    "inf_level.txt": (HEADER + "0.1,1e-2\ninf,1e-3\n").encode(),
    "e400_rate.txt": (HEADER + "0.1,1e400\n0.2,1e-3\n").encode(),
    "digits5000.txt": (HEADER + "0.1,1e-2\n" + "9" * 5000 + ",1e-3\n").encode(),
    "negative_level.txt": (HEADER + "-0.1,1e-2\n0.2,1e-3\n").encode(),
    "zero_level.txt": (HEADER + "0,1e-2\n0.2,1e-3\n").encode(),
    "negative_rate.txt": (HEADER + "0.1,1e-2\n0.2,-1e-3\n").encode(),
    "duplicate_levels.txt": (HEADER + "0.1,1e-2\n0.1,1e-3\n0.2,1e-4\n").encode(),
    "decreasing_levels.txt": (HEADER + "0.2,1e-2\n0.1,1e-3\n").encode(),
    "rising_rates.txt": (HEADER + "0.1,1e-3\n0.2,1e-2\n").encode(),
    "one_row.txt": (HEADER + "0.1,1e-2\n").encode(),
    "three_columns.txt": (HEADER + "0.1,1e-2,3\n0.2,1e-3,3\n").encode(),
    "words_after.txt": (HEADER + "0.1,1e-2\nabc,def\n").encode(),
    "three_names.txt": b"pga g rate\n0.1 1e-2\n0.2 1e-3\n",
    "poe_above_1.txt": b"pga_g,poe_50yr\n0.1,1.5\n0.2,0.1\n",
    "poe_nan.txt": b"pga_g,poe_50yr\n0.1,nan\n0.2,0.1\n",
    "poe_negative.txt": b"pga_g,poe_50yr\n0.1,0.5\n0.2,-0.1\n",
    "unit_unknown.txt": b"# units: furlong\npga,annual_rate\n0.1,1e-2\n0.2,1e-3\n",
    "unit_velocity.txt": b"pga [cm/s],annual_rate\n10,1e-2\n20,1e-3\n",
    "two_units.txt": b"# units: g\npga_m/s^2,annual_rate\n1,1e-2\n2,1e-3\n",
    "time_zero.txt": b"# investigation_time: 0\npga_g,poe\n0.1,0.5\n0.2,0.1\n",
    "time_nan.txt": b"# investigation_time: nan\npga_g,poe\n0.1,0.5\n0.2,0.1\n",
    "two_times.txt": b"# investigation_time: 1\npga_g,poe_50yr\n0.1,0.5\n0.2,0.1\n",
    "oq_no_time.csv": ("#,,,\"kind='mean', imt='PGA'\"\n" + OQ_HEADER
                       + "0,0,0,0.5,0.1\n").encode(),
    "oq_time_word.csv": ("# investigation_time=abc, imt='PGA'\n" + OQ_HEADER
                         + "0,0,0,0.5,0.1\n").encode(),
    "oq_time_zero.csv": ("# investigation_time=0.0, imt='PGA'\n" + OQ_HEADER
                         + "0,0,0,0.5,0.1\n").encode(),
    "oq_time_inf.csv": ("# investigation_time=1e400, imt='PGA'\n" + OQ_HEADER
                        + "0,0,0,0.5,0.1\n").encode(),
    "oq_no_imt.csv": ("# investigation_time=50.0\n" + OQ_HEADER + "0,0,0,0.5,0.1\n").encode(),
    "oq_imt_unknown.csv": ("# investigation_time=50.0, imt='PGX'\n" + OQ_HEADER
                           + "0,0,0,0.5,0.1\n").encode(),
    "oq_imt_unclosed.csv": ("# investigation_time=50.0, imt='PGA\n" + OQ_HEADER
                            + "0,0,0,0.5,0.1\n").encode(),
    "oq_no_header.csv": OQ.encode(),
    "oq_no_rows.csv": (OQ + OQ_HEADER).encode(),
    "oq_no_levels.csv": (OQ + "lon,lat,depth,poe-abc\n0,0,0,0.5\n").encode(),
    "oq_short_row.csv": (OQ + OQ_HEADER + "0,0,0,0.5\n").encode(),
    "oq_poe_nan.csv": (OQ + OQ_HEADER + "0,0,0,nan,0.1\n").encode(),
    "oq_poe_word.csv": (OQ + OQ_HEADER + "0,0,0,zz,0.1\n").encode(),
    "oq_poe_above_1.csv": (OQ + OQ_HEADER + "0,0,0,1.5,0.1\n").encode(),
    "oq_duplicate_levels.csv": (OQ + "lon,lat,depth,poe-0.1,poe-0.1,poe-0.2\n"
                                + "0,0,0,0.5,0.4,0.1\n").encode(),
    "oq_rising.csv": (OQ + OQ_HEADER + "0,0,0,0.1,0.5\n").encode(),
    "oq_binary_after.csv": OQ.encode() + bytes(range(1, 256)) * 2,
    "usgs_empty.json": b"",
    "usgs_not_json.json": b"{\"response\": [",
    "usgs_list.json": b"[]",
    "usgs_response_number.json": b"{\"response\": 1}",
    "usgs_imt_unknown.json": b"{\"response\": [{\"metadata\": {\"imt\": {\"value\": \"PGX\"}, "
                             b"\"xvalues\": [0.1, 0.2]}, \"data\": []}]}",
    "usgs_xvalues_words.json": b"{\"response\": [{\"metadata\": {\"imt\": \"PGA\", \"xvalues\": "
                               b"[\"a\", \"b\"]}, \"data\": [{\"component\": \"Total\", "
                               b"\"yvalues\": [1e-2, 1e-3]}]}]}",
    "usgs_data_numbers.json": b"{\"response\": [{\"metadata\": {\"imt\": \"PGA\", \"xvalues\": "
                              b"[0.1, 0.2]}, \"data\": [1, 2]}]}",
    "usgs_ragged.json": b"{\"response\": [{\"metadata\": {\"imt\": \"PGA\", \"xvalues\": "
                        b"[0.1, 0.2]}, \"data\": [{\"component\": \"Total\", "
                        b"\"yvalues\": [1e-2, [1e-3]]}]}]}",
    "usgs_nan.json": b"{\"response\": [{\"metadata\": {\"imt\": \"PGA\", \"xvalues\": "
                     b"[0.1, NaN]}, \"data\": [{\"component\": \"Total\", "
                     b"\"yvalues\": [1e-2, 1e-3]}]}]}",
    "usgs_lengths.json": b"{\"response\": [{\"metadata\": {\"imt\": \"PGA\", \"xvalues\": "
                         b"[0.1, 0.2, 0.4]}, \"data\": [{\"component\": \"Total\", "
                         b"\"yvalues\": [1e-2, 1e-3]}]}]}",
}
PATHS = {"missing.txt": None, "directory": ".", "dev_zero": "/dev/zero"}
FORMATS = {".txt": "columns", ".csv": "openquake", ".json": "usgs"}


def _problem_lines(err):
    return [line for line in err.splitlines() if line.startswith("  ")]


@pytest.fixture(scope="module")
def curves(tmp_path_factory):
    folder = tmp_path_factory.mktemp("curves")
    for name, data in CURVES.items():
        (folder / name).write_bytes(data)
    (folder / "directory").mkdir()
    return folder


def _given(name, curves):
    return PATHS[name] if PATHS.get(name) else str(curves / name)


@pytest.mark.parametrize("name", [*CURVES, *PATHS])
def test_a_malformed_hazard_file_is_one_line_and_status_2(curves, capsys, name):
    try:
        status = main(["--hazard", _given(name, curves), "--median", "0.3g", "--beta", "0.3"])
    except SystemExit as end:
        status = end.code
    out, err = capsys.readouterr()
    assert status == 2 and "Traceback" not in err, err
    [line] = _problem_lines(err)
    assert line.startswith(("  --hazard: ", "  --im: ", "  --units: ", "  --poe: ")), line


@pytest.mark.parametrize("name", [*CURVES, *PATHS])
def test_a_malformed_curve_of_a_risk_file_is_a_problem_of_hazard_file(curves, name):
    suffix = Path(name).suffix or ".txt"
    raw = {"hazard": {"file": {"path": _given(name, curves), "format": FORMATS[suffix]}},
           "fragility": {"median": "0.3 g", "beta": 0.3}}
    if suffix == ".txt" and name not in ("unit_velocity.txt", "two_units.txt"):
        raw["hazard"]["file"].update(im="pga")
    with pytest.raises(FileProblems) as raised:
        load_risk(raw, hazard=checked_hazard)
    assert all(p.path.startswith("hazard.file.") for p in raised.value.problems), \
        str(raised.value)


# --- a mutation of every key of a risk file -------------------------------------------------

CURVE = "# units: g\npga,poe_50yr\n" + "".join(f"{0.01 * 1.5 ** i:.6g},{0.6 * 0.6 ** i:.6g}\n"
                                              for i in range(14))
FILE_BASED = {"name": "file_based", "title": "a block on a curve file", "site": "x",
              "hazard": {"file": {"path": "curve.txt", "format": "columns", "im": "pga",
                                  "units": "g", "kind": "poe", "investigation_time": 50}},
              "scene": {"body": {"B": "15 cm", "H": "60 cm"}, "contact": {"mu": 0.8}},
              "stripes": {"levels": ["2 m/s^2", "4 m/s^2"], "motions": 3,
                          "scenario": {"magnitude": 6.5, "distance": "20 km"},
                          "vs30": "760 m/s"},
              "years": 50, "target": 0.02, "output": "out.nc"}
TEXT = ("name", "title", "site", "output", "stripes.model")  # free text: "zz" is valid
# below: a scene is checked as a scene (its own tests); a grid's values when its studies load
LENIENT = ("scene.",)


def _bases(folder):
    (folder / "curve.txt").write_text(CURVE)
    file_based = _set(FILE_BASED, ("hazard", "file", "path"), str(folder / "curve.txt"))
    return {"risk_example": yaml.safe_load((STUDIES / "risk_example.yaml").read_text()),
            "risk_map_example": yaml.safe_load((STUDIES / "risk_map_example.yaml").read_text()),
            "file_based": file_based}


def _mutations(data):
    """(label, keys, value or None to delete, surely malformed) of every node of ``data``."""
    for keys, node in _nodes(data):
        if not keys:
            continue
        path = _dotted(keys)
        lenient = (path + ".").startswith(LENIENT) or (keys[0] == "grid" and len(keys) > 2)
        if isinstance(node, dict):
            yield "unknown", keys + ("zz_unknown",), 1, not lenient
            changes = (("zz", "zz", True), ("number", 3.5, True), ("list", [1, 2], False))
        elif isinstance(node, list):
            changes = (("zz", "zz", True), ("number", 3.5, True))
        else:
            changes = (("list", [1, 2], True), ("mapping", {"a": 1}, True),
                       ("zz", "zz", path not in TEXT), ("negative", -1, False))
        for label, value, bad in changes:
            yield label, keys, value, bad and not lenient
        yield "delete", keys, None, False


def _named(problems, keys):
    """Whether a problem is at the mutated key or below it."""
    path = _dotted(keys)
    return any(p.path == path or p.path.startswith((path + ".", path + "[")) for p in problems)


def test_a_mutation_of_every_key_of_a_risk_file(tmp_path):
    checked, wrong = 0, []
    for base, data in _bases(tmp_path).items():
        for label, keys, value, bad in _mutations(data):
            mutated = _set(data, keys, value)
            name = f"{base}:{_dotted(keys)}={label}"
            try:
                load_risk(mutated, hazard=checked_hazard)
                if bad:
                    wrong.append(f"{name}: loaded")
            except FileProblems as problems:  # a valid value may upset another key
                if (bad and not _named(problems.problems, keys)) or \
                        not all(p.path for p in problems.problems):
                    wrong.append(f"{name}: {problems}")
            except Exception as err:  # noqa: BLE001 - any other exception is the failure
                wrong.append(f"{name}: {type(err).__name__}: {err}")
            checked += 1
    assert checked > 500
    assert not wrong, "\n".join(wrong[:20])


# --- real processes -------------------------------------------------------------------------

def _mutated_file(folder, name, keys, value):
    data = _bases(folder)[name]
    path = folder / f"{name}-{_dotted(keys)}.yaml"
    path.write_text(yaml.safe_dump(_set(data, keys, value), sort_keys=False))
    return path


def test_the_command_line(tmp_path, curves):
    """Risk files and curve files through ``python -m sweep.risk``, side by side."""
    (tmp_path / "curve.txt").write_text(CURVE)
    runs = {
        "years=zz": ([str(_mutated_file(tmp_path, "risk_example", ("years",), "zz"))],
                     "years"),
        "m_max deleted": ([str(_mutated_file(tmp_path, "risk_example", (
            "hazard", "source", "sources", 0, "recurrence", "m_max"), None))],
            "hazard.source.sources[0].recurrence.m_max"),
        "grid axis=zz": ([str(_mutated_file(tmp_path, "risk_map_example", ("grid", "B"),
                                            "zz"))], "grid.B"),
        "curve binary": ([str(_mutated_file(tmp_path, "file_based", (
            "hazard", "file", "path"), str(curves / "binary.txt")))], "hazard.file.path"),
        "units contradict": ([str(_mutated_file(tmp_path, "file_based", (
            "hazard", "file", "units"), "m/s^2"))], "hazard.file.units"),
        "--hazard nan": (["--hazard", str(curves / "nan_level.txt"), "--median", "0.3g",
                          "--beta", "0.3"], "--hazard"),
        "--hazard openquake header": (["--hazard", str(curves / "oq_no_time.csv"),
                                       "--median", "0.3g", "--beta", "0.3"], "--hazard"),
    }
    started = {name: (subprocess.Popen([PY, "-m", "sweep.risk", *args], cwd=tmp_path,
                                       env=cli_env(), stdout=subprocess.PIPE,
                                       stderr=subprocess.PIPE, text=True), where)
               for name, (args, where) in runs.items()}
    for name, (process, where) in started.items():
        _, err = process.communicate(timeout=120)
        assert process.returncode == 2 and "Traceback" not in err, (name, err)
        assert any(line.startswith(f"  {where}") for line in _problem_lines(err)), (name, err)
