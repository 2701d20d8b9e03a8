"""The schema reference: docs/schema.md and the JSON Schemas are the generator's output, name
every field of every model with its units and default, and accept every bundled file; every
command's --help lists the units and points to docs/schema.md."""
import contextlib
import io
import json
import re
from pathlib import Path

import pytest
import yaml

from kernels.api import DEFAULTS
from sweep.io import bodies_schema, reference, risk_schema, scene_schema, study_schema

ROOT = Path(__file__).resolve().parents[3]
DOCS = ROOT / "docs"
REGENERATE = "python -m sweep.io.reference --json-schema"


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    folder = tmp_path_factory.mktemp("docs")
    return {path.name: path.read_text() for path in reference.write(folder, json_schema=True)}


@pytest.mark.parametrize("name", ["schema.md", "scene.schema.json", "study.schema.json",
                                  "risk.schema.json"])
def test_docs_are_up_to_date(written, name):
    assert (DOCS / name).read_text() == written[name], f"docs/{name} is stale: run {REGENERATE}"


def _sections(markdown):
    """{section heading: its table of keys} of docs/schema.md."""
    parts = re.split(r"^### (.+)$", markdown, flags=re.M)
    return {heading: re.search(r"^\| key \|.*?(?=^$)", text, flags=re.M | re.S)[0]
            for heading, text in zip(parts[1::2], parts[2::2])}


def test_every_field_of_every_model_is_described(written):
    """Each model of the three schemas (the lists their modules keep for "did you mean") has a
    section that has a row for each of its fields."""
    sections = _sections(written["schema.md"])
    models = {section.model: reference.heading(title, section)
              for title, _, file_sections in reference.FILES for section in file_sections}
    expected = {*scene_schema._MODELS, *bodies_schema._MODELS, study_schema.StudyFile,
                study_schema.RangeSpec, study_schema.RefineSpec,
                *set(risk_schema._MODELS) - {risk_schema.LevelList}}  # levels: a plain list
    assert expected <= set(models)
    rows = 0
    for model, heading in models.items():
        keys = re.findall(r"^\| `([^`]+)` \|", sections[heading], flags=re.M)
        assert keys == list(model.model_fields), heading
        rows += len(keys)
    assert rows == sum(len(model.model_fields) for model in models)


def _row(sections, heading, key):
    return next(line.split(" | ") for line in sections[heading].splitlines()
                if line.startswith(f"| `{key}` |"))


def test_rows_give_type_units_default_and_description(written):
    sections = _sections(written["schema.md"])
    key, kind, units, default, description = _row(sections, "body", "B")
    assert kind == "quantity (length > 0)" and units == "m, cm, mm, km, in, ft, yd, mi"
    assert default == "" and description.startswith("full breadth")  # or the rock form
    assert _row(sections, "solver", "zeno_dt")[3] == "1e-06 s" == \
        f"{DEFAULTS['solver']['zeno_dt']:g} s"
    assert _row(sections, "contact", "e_x")[1:4] == ["number >= -1 and <= 1", "", "-0.8"]
    assert _row(sections, "initial", "omega")[2:4] == ["rad/s, deg/s", "0 rad/s"]
    scale_with = "excitation.horizontal, excitation.vertical (kind: record)"
    assert _row(sections, scale_with, "scale_with")[1] == "`horizontal`"
    assert "in/s^2, ft/s^2" in written["schema.md"]


def test_scene_study_and_risk_fields_have_descriptions(written):
    for title, _, file_sections in reference.FILES:
        for section in file_sections if title != "Bodies files" else ():
            for key in section.model.model_fields:
                assert reference._description(section.model, key), (section.path, key)


def _validator(written, kind):
    jsonschema = pytest.importorskip("jsonschema")
    referencing = pytest.importorskip("referencing")
    scene = json.loads(written["scene.schema.json"])
    registry = referencing.Registry().with_resource(
        reference.JSON_SCHEMAS["scene"], referencing.Resource.from_contents(scene))
    schema = json.loads(written[reference.JSON_SCHEMAS[kind]])
    jsonschema.Draft202012Validator.check_schema(schema)
    return jsonschema.Draft202012Validator(schema, registry=registry)


def test_json_schemas_accept_every_bundled_file(written):
    validators = {kind: _validator(written, kind) for kind in ("scene", "study", "risk")}
    checked = 0
    for path in sorted((ROOT / "studies").glob("*.yaml")):
        raw = yaml.safe_load(path.read_text())
        if "body" in raw or "grid" in raw or "hazard" in raw:
            kind = "risk" if "hazard" in raw else "study" if "grid" in raw else "scene"
            errors = list(validators[kind].iter_errors(raw))
            assert not errors, (path.name, errors[0].message)
            checked += 1
    assert checked >= 32


@pytest.mark.parametrize("kind, raw, where", [
    ("scene", {"body": {"B": 0.1, "H": 0.3, "weight": 2}}, "weight"),
    ("scene", {"body": {"B": "ten cm", "H": 0.3}}, "ten cm"),
    ("scene", {"body": {"B": -0.1, "H": 0.3}}, "-0.1"),
    ("scene", {"body": {"B": 0.1, "H": 0.3}, "excitation": {"horizontal": {"kind": "sin"}}},
     "sin"),
    ("study", {"scene": {"body": {"B": 0.1}}, "grid": {"mu": [0.2]}}, "H"),
    ("study", {"scene": {"body": {"B": 0.1, "H": 0.3}}, "grid": {"mu": {"num": 0}}}, "0"),
    ("risk", {"hazard": {"file": {"path": "c.csv", "format": "csv"}}}, "csv"),
    ("risk", {"hazard": {}, "grid": {"depth": [1]}}, "depth"),
    ("risk", {"hazard": {}, "years": 0}, "0"),
])
def test_json_schemas_refuse(written, kind, raw, where):
    errors = list(_validator(written, kind).iter_errors(raw))
    assert errors and any(where in error.message for error in errors), errors


def test_empty_sections_and_no_motion_shorthand(written):
    raw = {"body": {"B": 0.1, "H": 0.3}, "contact": None, "excitation": {"vertical": "none"}}
    assert not list(_validator(written, "scene").iter_errors(raw))


@pytest.mark.parametrize("command", ["scene", "run", "estimate"])  # those reading quantities
def test_help_lists_units_and_the_reference(command):
    main = __import__(f"sweep.{command}", fromlist=["main"]).main
    out = io.StringIO()
    with contextlib.redirect_stdout(out), pytest.raises(SystemExit) as end:
        main(["--help"])
    text = " ".join(out.getvalue().split())
    assert end.value.code == 0
    assert "length: m, cm, mm, km, in, ft, yd, mi" in text
    assert "m/s^2, cm/s^2, mm/s^2, gal, g" in text and "docs/schema.md" in text
