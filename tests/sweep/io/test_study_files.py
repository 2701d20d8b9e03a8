"""Every file in studies/ still validates, so that none rots as the schemas change.

A file with ``hazard`` is a risk file of ``sweep.risk``, one with ``grid`` a study (checked with every cell's scene, as ``sweep.run`` does before
running), one with ``bodies`` or ``sites`` a bodies file of ``sweep.estimate``, any other YAML
file a scene.
"""
from pathlib import Path

import pytest
import yaml

from sweep.estimate import load_survey
from sweep.io.risk_schema import load_risk
from sweep.io.scene_schema import load_scene
from sweep.probability.risk_inputs import checked_hazard
from sweep.runner.cell_checks import load_study

STUDIES = Path(__file__).resolve().parents[3] / "studies"
FILES = sorted(STUDIES.glob("*.yaml"))


def kind_of(path):
    raw = yaml.safe_load(path.read_text())
    if isinstance(raw, dict) and "hazard" in raw:
        return "risk"
    if isinstance(raw, dict) and "grid" in raw:
        return "study"
    if isinstance(raw, dict) and ("bodies" in raw or "sites" in raw):
        return "bodies"
    return "scene"


def test_studies_folder_has_files_of_every_kind():
    assert {kind_of(p) for p in FILES} == {"study", "bodies", "scene", "risk"}


@pytest.mark.parametrize("path", FILES, ids=[p.name for p in FILES])
def test_file_validates(path):
    kind = kind_of(path)
    if kind == "study":
        study = load_study(path)  # raises FileProblems listing every problem
        assert study.n_cells >= 1
        assert study.output.suffix == ".nc"
    elif kind == "risk":
        spec = load_risk(path, hazard=checked_hazard)  # the stripes inside its curve too
        assert spec.curve.rates.size >= 2
    elif kind == "bodies":
        survey = load_survey(path)
        assert all(site.bodies for site in survey.sites)
    else:
        assert load_scene(path).body.B.value > 0
