"""Risk files load as scene, study and bodies files do (``io.loader.load_file``): a file and
its dict give one model, every problem comes at once with its dotted path, and the checks
that need the hazard (stripes inside the curve) are the model's, through its context."""
import pytest
import yaml

from sweep.io.problems import FileProblems
from sweep.io.risk_schema import load_risk
from sweep.probability.risk_inputs import checked_hazard

SOURCE = {"model": "BSSA14", "im": "pga", "vs30": "760 m/s",
          "levels": {"start": "0.02 g", "stop": "2 g", "num": 10},
          "sources": [{"kind": "point", "distance": "10 km", "depth": "8 km",
                       "recurrence": {"rate": 0.02, "m_min": 5.5, "m_max": 7.5}}]}
RISK = {"name": "r", "hazard": {"source": SOURCE},
        "scene": {"body": {"B": "15 cm", "H": "60 cm"}},
        "stripes": {"levels": ["2 m/s^2", "4 m/s^2"], "motions": 3}}


def _problems(source, **options):
    with pytest.raises(FileProblems) as raised:
        load_risk(source, **options)
    return [(p.path, p.message) for p in raised.value.problems]


def test_a_file_and_its_dict_give_one_model(tmp_path):
    path = tmp_path / "r.yaml"
    path.write_text(yaml.safe_dump(RISK))
    from_file, from_dict = load_risk(path, hazard=checked_hazard), load_risk(RISK)
    assert from_file.checked.model_dump(warnings=False) == \
        from_dict.checked.model_dump(warnings=False)
    assert from_dict.curve is None  # no hazard function: no curve built
    assert from_file.curve.levels.size == 10 and from_file.folder == tmp_path


def test_every_problem_at_once_with_dotted_paths():
    raw = {**RISK, "yeras": 50, "hazard": {"source": {**SOURCE, "sources": [
        {**SOURCE["sources"][0], "recurrence": {"rate": 0.02, "m_min": 5.5, "m_max": 5.0}}]}},
        "stripes": {"levels": ["2 m/s^2", "1 m/s^2"]}}
    assert _problems(raw) == [
        ("yeras", "unknown key; did you mean 'years'?"),
        ("hazard.source.sources[0].recurrence.m_max", "must be greater than m_min"),
        ("stripes.levels[1]", "levels must increase")]


def test_the_hazard_checks_are_the_model_s():
    raw = {**RISK, "stripes": {"levels": ["2 m/s^2", "40 m/s^2"], "motions": 3}}
    assert load_risk(raw).curve is None
    [(path, message)] = _problems(raw, hazard=checked_hazard)
    assert path == "stripes.levels[1]" and message.startswith("outside the hazard curve")
    missing = {**RISK, "hazard": {"file": {"path": "nowhere.csv", "format": "openquake"}},
               "stripes": {**RISK["stripes"], "scenario": {"magnitude": 6, "distance": "10 km"},
                           "vs30": "760 m/s"}}
    [(path, message)] = _problems(missing, hazard=checked_hazard)
    assert path == "hazard.file.path" and message.startswith("cannot read")


@pytest.mark.parametrize("text, message", [
    ("", "the risk file is empty"),
    ("- 1\n", "a risk file must be a mapping of hazard, scene, stripes, years, ..."),
    ("years: 50\nyears: 40\n", "duplicate key"),
])
def test_top_level_and_yaml_problems_as_other_files(tmp_path, text, message):
    path = tmp_path / "r.yaml"
    path.write_text(text)
    assert any(m.startswith(message) for _, m in _problems(path))


def test_the_choice_of_sections_shows_with_the_fields_problems():
    raw = {"hazard": {"file": {"path": "c.csv", "format": "columns"}}, "years": 0,
           "stripes": {"levels": ["2 m/s^2", "4 m/s^2"]}}
    assert _problems(raw) == [  # im and units may be the file's (test_hazard_files.py)
        ("years", "must be greater than 0"),
        ("scene", "required with stripes: the body simulated"),
        ("stripes.scenario", "required with a hazard curve file (no disaggregation)"),
        ("stripes.vs30", "required with a hazard curve file")]
    assert _problems({"hazard": {"source": SOURCE}, "replicates": -1}) == [
        ("replicates", "must be greater than or equal to 0"),
        ("stripes", "required (or a known fragility)")]
