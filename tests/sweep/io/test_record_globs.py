"""Record globs of studies and bodies files: the extension matched in any case, as the readers
take ``.AT2`` and ``.at2`` alike, and the other files of the folder named, not silently
skipped."""
import warnings

import numpy as np
import pytest
import yaml

import sweep
from sweep.io.bodies_schema import load_survey
from sweep.io.files import find_files
from sweep.io.problems import FileProblems, InputWarning
from sweep.runner.cell_checks import load_study

G = 9.80665
AT2 = ("PEER NGA STRONG MOTION DATABASE RECORD\nA TEST RECORD\n"
       "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=    5, DT=   .0100 SEC\n{}\n")


def _records(folder, peaks, others=()):
    """PEER files ``{name: peak in g}`` and plain files ``others`` in ``folder``."""
    folder.mkdir()
    for name, peak in peaks.items():
        (folder / name).write_text(AT2.format(f"0.0 {peak / 2} {-peak} {peak / 4} 0.0"))
    for name in others:
        (folder / name).write_text("not a record\n")


def _loaded(raw):
    """The study and the messages of its InputWarnings."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        study = load_study(raw)
    return study, [str(w.message) for w in caught if w.category is InputWarning]


def _study(pattern):
    return {"scene": {"body": {"B": 0.2, "H": 0.6}, "excitation": {"horizontal": {
        "kind": "record", "name": "elcentro1940_ns"}}, "solver": {"t_end": 0.1}},
        "grid": {"record": {"glob": pattern}}}


@pytest.mark.parametrize("pattern", ["recs/*.AT2", "recs/*.at2", "recs/*.At2", "**/*.AT2"])
def test_extension_in_any_case(tmp_path, pattern):
    _records(tmp_path / "recs", {"x.at2": 0.1, "y.AT2": 0.2})
    assert find_files(pattern, tmp_path) == (["recs/x.at2", "recs/y.AT2"], [])


def test_study_glob_finds_both_cases_and_their_peaks(tmp_path, monkeypatch):
    _records(tmp_path / "recs", {"x.at2": 0.1, "y.AT2": 0.2})
    monkeypatch.chdir(tmp_path)
    study, said = _loaded(_study("recs/*.AT2"))
    assert study.axes[0].values == ("recs/x.at2", "recs/y.AT2") and said == []
    ds = sweep.run_study(study)
    np.testing.assert_allclose(ds.pga.values, [0.1 * G, 0.2 * G], rtol=1e-12)


def test_files_left_out_of_the_folder_are_named(tmp_path, monkeypatch):
    _records(tmp_path / "recs", {"x.at2": 0.1, "y.AT2": 0.2},
             others=("x.VT2", "notes.txt", ".hidden"))
    monkeypatch.chdir(tmp_path)
    assert find_files("recs/*.AT2", tmp_path) == (["recs/x.at2", "recs/y.AT2"],
                                                   ["recs/notes.txt", "recs/x.VT2"])
    _, said = _loaded(_study("recs/*.AT2"))
    assert said == ["grid.record.glob: takes 2 files and leaves out 2 others of the same "
                    "folder: notes.txt, x.VT2"]


def test_a_glob_that_matches_nothing_says_what_the_folder_holds(tmp_path, monkeypatch):
    _records(tmp_path / "recs", {}, others=("a.txt", "b.txt"))
    monkeypatch.chdir(tmp_path)
    with pytest.raises(FileProblems) as info:
        load_study(_study("recs/*.AT2"))
    [problem] = info.value.problems
    assert problem.path == "grid.record.glob"
    assert problem.message.endswith("; the folder holds a.txt, b.txt")


def test_many_skipped_files_are_counted(tmp_path):
    _records(tmp_path / "recs", {"x.AT2": 0.1}, others=[f"f{k}.txt" for k in range(8)])
    survey = {"site": "yard", "bodies": [{"name": "s", "B": "20 cm", "H": "80 cm",
                                          "overturned": True}],
              "ensemble": {"motions": {"record": {"glob": "recs/*.at2"}},
                           "levels": {"pga": {"start": "1 m/s^2", "stop": "4 m/s^2",
                                              "num": 3}}}}
    path = tmp_path / "bodies.yaml"
    path.write_text(yaml.safe_dump(survey))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        loaded = load_survey(path)
    assert loaded.ensemble.records == (str((tmp_path / "recs" / "x.AT2").resolve()),)
    assert [str(w.message) for w in caught if w.category is InputWarning] == [
        "ensemble.motions.record.glob: takes 1 file and leaves out 8 others of the same "
        "folder: f0.txt, f1.txt, f2.txt, f3.txt, f4.txt and 3 more"]
