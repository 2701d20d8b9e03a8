"""The reference of every key of the input files, generated from their models.

Scene, study, bodies and risk files: docs/schema.md and the JSON Schemas.

``python -m sweep.io.reference [--json-schema] [--docs DIR]`` writes ``docs/schema.md``: for
each section of each kind of file, every key with its type, the units a quantity takes
(``units.units_of`` of its dimensions), its default (the model's, else ``kernels.api.DEFAULTS``
where the model leaves None) and a one-line description (the field's).  ``--json-schema``
also writes ``docs/scene.schema.json``, ``docs/study.schema.json`` and
``docs/risk.schema.json``, JSON Schemas (2020-12) that editors check and complete YAML files
with: pydantic's ``model_json_schema()`` with a quantity as a number or a string
``"<number> <unit>"`` (``units.QUANTITY_PATTERN``), its units in its description, an empty
section allowed, and a study's (a risk file's) scene and axes spelled out.
"""
import argparse
import json
import re
import sys
import typing
from collections import namedtuple
from pathlib import Path


from kernels.api import DEFAULTS

from . import bodies_schema as bodies
from . import risk_schema as risk
from . import scene_models as scene
from . import study_schema as study
from . import units, vocabulary

DOCS = Path(__file__).resolve().parents[2] / "docs"
MARKDOWN = "schema.md"
JSON_SCHEMAS = {"scene": "scene.schema.json", "study": "study.schema.json",
                "risk": "risk.schema.json"}
JSON_SCHEMA_DIALECT = "https://json-schema.org/draft/2020-12/schema"

Section = namedtuple("Section", "path model defaults")
Section.__doc__ = """A section of a file: its dotted ``path``, its pydantic ``model`` and the
defaults of the keys the model leaves None (``{key: value in SI}``)."""

_KINDS = typing.get_args(typing.get_args(scene.Ground)[0])  # the ground-motion models
_GROUND = "excitation.horizontal, excitation.vertical"
SCENE = (Section("", scene.Scene, {}),
         Section("body", scene.Body, DEFAULTS["body"]),
         Section("contact", scene.Contact, DEFAULTS["contact"]),
         Section("excitation", scene.Excitation, {}),
         *(Section(f"{_GROUND} (kind: {typing.get_args(kind.model_fields['kind'].annotation)[0]})",
                   kind, DEFAULTS["ground"]) for kind in _KINDS),
         Section(f"{_GROUND} (kind: record, synthetic).sa", scene.SpectralTarget, {}),
         Section(f"{_GROUND} (kind: floor).building", scene.Building, {}),
         Section(f"{_GROUND} (kind: floor).building.modes[i]", scene.BuildingMode, {}),
         Section(f"{_GROUND} (kind: isolated).isolator (kind: linear)", scene.LinearIsolator,
                 {}),
         Section(f"{_GROUND} (kind: isolated).isolator (kind: friction_pendulum)",
                 scene.FrictionPendulum, {}),
         Section("initial", scene.Initial, DEFAULTS["initial"]),
         Section("solver", scene.Solver, DEFAULTS["solver"]),
         Section("restraint", scene.Restraint, {}))
STUDY = (Section("", study.StudyFile, {"output": f"{study.OUTPUT_DIR}/<name>.nc"}),
         Section("grid.<axis> (a mapping)", study.RangeSpec, {"spacing": study.SPACINGS[0]}),
         Section("refine", study.RefineSpec, {}),
         Section("run", study.RunSpec, {"backend": study.BACKENDS[0]}))
BODIES = (Section("", bodies.BodiesFile, {}),
          Section("sites[i]", bodies.SiteEntry, {}),
          Section("bodies[i], sites[i].bodies[j]", bodies.BodyEntry, {}),
          Section("ensemble", bodies.EnsembleEntry,
                  {"probabilities": list(bodies.DEFAULT_PROBABILITIES)}),
          Section("ensemble.motions", bodies.MotionsEntry, {}),
          Section("ensemble.motions.synthetic", bodies.SyntheticEntry, {}),
          Section("ensemble.levels", bodies.LevelsEntry, {}),
          Section("ensemble.levels.pga", bodies.LevelRange, {}),
          Section("ensemble.contact", bodies.ContactEntry,
                  {**DEFAULTS["contact"], "mu": bodies.DEFAULT_MU}))
RISK = (Section("", risk.RiskFile, {}),
        Section("hazard", risk.Hazard, {}),
        Section("hazard.file", risk.CurveFile, {}),
        Section("hazard.source", risk.SourceHazard, {}),
        Section("hazard.source.sources[i] (kind: point)", risk.PointSource, {}),
        Section("hazard.source.sources[i] (kind: area)", risk.AreaSource, {}),
        Section("hazard.source.sources[i].recurrence", risk.Recurrence, {}),
        Section("stripes", risk.Stripes, {}),
        Section("stripes.scenario", risk.Scenario, {}),
        Section("stripes.levels, hazard.source.levels (a mapping)", risk.LevelRange, {}),
        Section("fragility", risk.Fragility, {}))
FILES = (("Scene files", "`python -m sweep.scene SCENE.yaml` reads them; so does "
                         "`sweep.simulate`, and a study's `scene:` is one.", SCENE),
         ("Study files", "`python -m sweep.run STUDY.yaml` runs them (`sweep.run_study`).",
          STUDY),
         ("Bodies files", "`python -m sweep.estimate BODIES.yaml` reads them.", BODIES),
         ("Risk files", "`python -m sweep.risk RISK.yaml` reads them (docs/risk.md).", RISK))

# The bodies models carry no field descriptions; these stand in for them (a description given
# in the model wins).
BODIES_DESCRIPTIONS = {
    "BodiesFile": {"site": "name of the site (one-site format)",
                   "bodies": "the bodies seen at the site (one-site format)",
                   "sites": "the sites, each with its bodies",
                   "ensemble": "the motions the sites may have felt: bounds at stated "
                               "probabilities"},
    "SiteEntry": {"name": "name of the site", "latitude": "degrees north",
                  "longitude": "degrees east", "bodies": "the bodies seen there"},
    "BodyEntry": {"name": "name of the body", "B": "full breadth", "H": "full height",
                  "i_g": "radius of gyration about G (default: a uniform block's)",
                  "overturned": "whether it overturned", "mu": "its friction coefficient",
                  "direction": "any label of the direction it fell"},
    "EnsembleEntry": {"motions": "the motions, each one member", "levels": "the PGA levels "
                      "every member is scaled to", "contact": "friction and restitution of "
                      "the bodies", "t_end": "time simulated (default: from the motions)",
                      "probabilities": "probability levels of the bounds, each in (0, 1)"},
    "MotionsEntry": {"record": "bundled records' names and files' paths, or {glob: pattern}",
                     "synthetic": "an earthquake scenario of sweep.groundmotion.stochastic",
                     "seeds": "synthetic members: seeds 0 .. seeds - 1"},
    "SyntheticEntry": {"model": "the stochastic ground-motion model",
                       "magnitude": "moment magnitude", "distance": "distance to the rupture",
                       "vs30": "mean shear-wave velocity of the site's top 30 m",
                       "dt": "sample step (default: the model's)"},
    "LevelsEntry": {"pga": "the PGA levels: a range or a list"},
    "LevelRange": {"start": "first level", "stop": "last level", "num": "number of levels",
                   "spacing": "log or linear", "values": "the levels themselves, increasing"},
    "ContactEntry": {"mu": "friction of the bodies that give none",
                     "e_x": "tangential restitution", "e_y": "normal restitution"},
}
_BOUNDS = {"ge": "minimum", "gt": "exclusiveMinimum", "le": "maximum", "lt": "exclusiveMaximum"}
_SYMBOLS = {"minimum": ">=", "exclusiveMinimum": ">", "maximum": "<=", "exclusiveMaximum": "<"}


def _plain(text):
    """reStructuredText roles and literals as Markdown code: ``:func:`x``` -> `x`."""
    text = re.sub(r":\w+:`~?\.?([^`]+)`", r"`\1`", text or "")
    return " ".join(text.replace("``", "`").split())


def _summary(model):
    """The first paragraph of a model's docstring, in Markdown."""
    return _plain((model.__doc__ or "").split("\n\n")[0])


def _description(model, key):
    """The one-line description of ``key`` of ``model``."""
    given = model.model_fields[key].description
    return _plain(given or BODIES_DESCRIPTIONS.get(model.__name__, {}).get(key, ""))


def _bounded(schema):
    """Pydantic's ``ge``/``gt``/``le``/``lt`` of a constrained field under their JSON Schema
    names, in the whole ``schema`` (in place)."""
    if isinstance(schema, dict):
        for old, new in _BOUNDS.items():
            if old in schema and "type" in schema:
                schema[new] = schema.pop(old)
        for value in schema.values():
            _bounded(value)
    elif isinstance(schema, list):
        for value in schema:
            _bounded(value)
    return schema


def _without_null(schema):
    """A property's schema without the ``null`` that an optional key allows."""
    options = [s for s in schema.get("anyOf", ()) if s != {"type": "null"}]
    if "anyOf" in schema and len(options) == 1:
        return options[0]
    return {**schema, "anyOf": options} if "anyOf" in schema else schema


def _dimensions(schema):
    """The dimensions of a quantity's schema, or of a list of quantities (``x-dimensions``),
    or ()."""
    schema = _without_null(schema)
    return tuple(schema.get("x-dimensions", ()) or _without_null(schema.get("items", {})).get(
        "x-dimensions", ()))


def _unit_text(dimensions):
    """``length: m, cm, ...; time: s, ms, min`` (one dimension: the units alone)."""
    listed = [", ".join(units.units_of(d)) for d in dimensions]
    if len(dimensions) == 1:
        return listed[0]
    return "; ".join(f"{d.replace('_', ' ')}: {names}" for d, names in zip(dimensions, listed))


def _bound_text(schema):
    return " and ".join(f"{_SYMBOLS[key]} {schema[key]}" for key in _SYMBOLS if key in schema)


def _type_text(schema, sections):
    """A JSON Schema of one key in words: ``quantity (length > 0)``, ``one of: log, linear``,
    ``number >= 0``, ``mapping (body)``; ``sections`` maps a model's name to its path."""
    schema = _without_null(schema)
    if "x-dimensions" in schema:
        number = schema["anyOf"][0]
        dims = " or ".join(d.replace("_", " ") for d in schema["x-dimensions"])
        return f"quantity ({' '.join(filter(None, (dims, _bound_text(number))))})"
    if "$ref" in schema:
        name = schema["$ref"].rsplit("/", 1)[-1]
        return f"mapping ({sections[name]})" if name in sections else "mapping"
    if "oneOf" in schema and "discriminator" in schema:
        return "mapping, one of the kinds below"
    if "oneOf" in schema:
        return " or ".join(_type_text(s, sections) for s in schema["oneOf"])
    if "const" in schema:
        return f"`{schema['const']}`"
    if "enum" in schema:
        return "one of: " + ", ".join(f"`{v}`" for v in schema["enum"])
    if "anyOf" in schema:
        return " or ".join(_type_text(s, sections) for s in schema["anyOf"])
    kind = schema.get("type")
    if isinstance(kind, list):
        return " or ".join(kind)
    if kind == "array":
        items = _type_text(schema.get("items", {}), sections)
        return f"list of {items}" if items != "any" else "list"
    if kind in ("number", "integer"):
        return " ".join(filter(None, (kind, _bound_text(schema))))
    return {"string": "string", "boolean": "true or false", "object": "mapping"}.get(kind, "any")


def _default_text(section, key, schema):
    """The default of a key: required, the model's, or the section's default (in SI units)."""
    field = section.model.model_fields[key]
    if field.is_required():
        return "required"
    if field.default_factory is not None:
        made = field.default_factory()
        return f"`kind: {made.kind}`" if hasattr(made, "kind") else "its defaults"
    value = field.default if field.default is not None else section.defaults.get(key)
    if value is None:
        return ""
    if isinstance(value, str):
        return f"`{value}`" if " " not in value else value
    dims = _dimensions(schema)
    si = units.units_of(dims[0])[0] if dims else ""
    return f"{value:g} {si}".strip() if isinstance(value, float) else f"{value}"


def _cell(text):
    return str(text).replace("|", "\\|")


def _table(section, sections):
    """The Markdown table of a section's keys."""
    schema = _bounded(section.model.model_json_schema())
    lines = ["| key | type | units | default | description |", "|---|---|---|---|---|"]
    for key, prop in schema["properties"].items():
        dims = _dimensions(prop)
        row = (f"`{key}`", _type_text(prop, sections), _unit_text(dims) if dims else "",
               _default_text(section, key, prop), _description(section.model, key))
        lines.append("| " + " | ".join(map(_cell, row)) + " |")
    return lines


def _axes_table():
    """The named axes of a study's grid (``io.vocabulary.AXES``)."""
    lines = ["| axis | sets | units | what |", "|---|---|---|---|"]
    for name, (paths, dimension, long_name) in vocabulary.AXES.items():
        unit = _unit_text((dimension,)) if dimension in units.DIMENSIONS else (
            "names" if dimension == "name" else "those of the scene's field")
        lines.append(f"| `{name}` | {', '.join(f'`{p}`' for p in paths)} | {_cell(unit)} | "
                     f"{_cell(long_name)} |")
    return lines


def heading(title, section):
    """The heading of a section of the files of ``title``: its path, or ``top of a scene
    file``."""
    return section.path or f"top of a {title.lower().removesuffix('s')}"


def markdown():
    """The text of ``docs/schema.md``."""
    out = ["# Input files: every key", "",
           "Written by `python -m sweep.io.reference` from the models of `sweep.io.scene_models`, "
           "`sweep.io.study_schema`, `sweep.io.bodies_schema` and `sweep.io.risk_schema`: edit "
           "those, not this file.  Editors can check and complete scene, study and risk files "
           "with `docs/scene.schema.json`, `docs/study.schema.json` and "
           "`docs/risk.schema.json` (`--json-schema`).", "",
           "## Quantities", "",
           "A quantity is a number in SI units (m, s, rad, Hz and their products) or a string "
           "`\"<number> <unit>\"`: `10 cm`, `0.5 g`, `341.7 gal`, `90 deg`.  Unit names are "
           "case-insensitive; `sec` may stand for `s`, `inch`, `foot` and `feet` for `in` and "
           "`ft`.  The body-relative units are times the body's own West acceleration (B/H) g "
           "(`west`), single-shock overturning velocity (`v_H`, Eq. 9) and slenderness angle "
           "atan(B/H) (`alpha`).  A default in SI units is written with its unit.", "",
           "| dimension | units (SI first) |", "|---|---|",
           *(f"| {d.replace('_', ' ')} | {', '.join(units.units_of(d))} |"
             for d in units.DIMENSIONS if units.units_of(d))]
    for title, intro, sections in FILES:
        names = {s.model.__name__: heading(title, s) for s in sections}
        out += ["", f"## {title}", "", intro]
        for section in sections:
            out += ["", f"### {heading(title, section)}", "", _summary(section.model), "",
                    *_table(section, names)]
            if section.model is study.StudyFile:
                out += ["", "Named axes (any other scene key by its dotted path, e.g. "
                        "`excitation.horizontal.f_stop`); each is a list of values, or a mapping "
                        "below:", "", *_axes_table()]
    return "\n".join(out) + "\n"


# --- JSON Schema ------------------------------------------------------------------------------

def _described_units(schema):
    """Every quantity's units added to its key's description, and the property titles
    pydantic writes (``Mu Edge S``) left out, in the whole ``schema`` (in place)."""
    for definition in [schema, *schema.get("$defs", {}).values()]:
        for prop in definition.get("properties", {}).values():
            prop.pop("title", None)
            dims = _dimensions(prop)
            if dims:
                prop["description"] = (f"{prop.get('description', '')}; a number in "
                                       f"{units.units_of(dims[0])[0]}, or a string "
                                       f"'<number> <unit>' with a unit of: {_unit_text(dims)}")
    return schema


def _nullable_sections(schema):
    """An empty optional section (``contact:``) is an empty mapping, ``vertical: none`` no
    motion."""
    for definition in [schema, *schema.get("$defs", {}).values()]:
        for key, prop in definition.get("properties", {}).items():
            if key in definition.get("required", ()):
                continue
            if "$ref" in prop:
                definition["properties"][key] = {
                    "anyOf": [{"$ref": prop.pop("$ref")}, {"type": "null"}], **prop}
            elif "discriminator" in prop:  # a ground component, by its kind
                choices = {k: prop.pop(k) for k in ("oneOf", "discriminator")}
                definition["properties"][key] = {
                    "anyOf": [choices, {"const": "none"}, {"type": "null"}], **prop}
    return schema


def _finished(schema, title):
    """A model's JSON Schema as written to docs/: dialect, title, plain descriptions."""
    def plain(node):
        if isinstance(node, dict):
            return {k: _plain(v) if isinstance(v, str) and k == "description" else plain(v)
                    for k, v in node.items()}
        return [plain(v) for v in node] if isinstance(node, list) else node
    return {"$schema": JSON_SCHEMA_DIALECT, **plain(schema), "title": title}


def scene_json_schema():
    """The JSON Schema of scene files."""
    schema = _nullable_sections(_described_units(_bounded(scene.Scene.model_json_schema())))
    return _finished(schema, "Scene file (python -m sweep.scene)")


def study_json_schema():
    """The JSON Schema of study files: its scene refers to the scene files' schema, its grid
    names the axes of ``io.vocabulary.AXES`` (any dotted scene path is an axis too)."""
    schema = _described_units(_bounded(study.StudyFile.model_json_schema()))
    schema["$defs"]["RangeSpec"] = _described_units(_bounded(
        study.RangeSpec.model_json_schema()))
    axis = {"anyOf": [{"type": "array", "minItems": 1, "items": study.AXIS_VALUE},
                      {"$ref": "#/$defs/RangeSpec"}]}
    record = {"anyOf": [*axis["anyOf"], {"type": "object", "required": ["glob"],
                                         "additionalProperties": False,
                                         "properties": {"glob": {"type": "string"}}}]}
    properties = schema["properties"]
    properties["scene"] = {"$ref": JSON_SCHEMAS["scene"],
                           "description": properties["scene"]["description"]}
    properties["grid"].update(additionalProperties=axis, minProperties=1, properties={
        name: {**(record if name == "record" else axis), "description": long_name}
        for name, (_, _, long_name) in vocabulary.AXES.items()})
    return _finished(_nullable_sections(schema), "Study file (python -m sweep.run)")


def risk_json_schema():
    """The JSON Schema of risk files: its scene refers to the scene files' schema, its grid
    takes a study's axes (those of ``io.vocabulary.AXES`` that set no motion, or a dotted
    scene path)."""
    schema = _described_units(_bounded(risk.RiskFile.model_json_schema()))
    schema.setdefault("$defs", {})["RangeSpec"] = _described_units(_bounded(
        study.RangeSpec.model_json_schema()))
    properties = schema["properties"]
    sections = {key: {"$ref": f"{JSON_SCHEMAS['scene']}#/properties/{key}"}
                for key in scene.Scene.model_fields if key != "excitation"}
    sections["excitation"] = {  # a floor's or an isolator's ground is the stripes'
        "type": ["object", "string", "null"],
        "description": "horizontal: a building's floor (kind floor) or an isolated platform "
                       "(kind isolated) without the ground motion, which the stripes give"}
    properties["scene"] = {"anyOf": [{"type": "object", "additionalProperties": False,
                                      "properties": sections}, {"type": "null"}],
                           "description": properties["scene"]["description"]}
    axis = {"anyOf": [{"type": "array", "minItems": 1, "items": study.AXIS_VALUE},
                      {"$ref": "#/$defs/RangeSpec"}]}
    named = {name: {**axis, "description": long_name}
             for name, (paths, _, long_name) in vocabulary.AXES.items()
             if not any(p.startswith("excitation") for p in paths)}
    dotted = f"^({'|'.join(vocabulary.SCENE_SECTIONS)})\\."
    properties["grid"] = {"anyOf": [{"type": "object", "additionalProperties": axis,
                                     "minProperties": 1, "properties": named,
                                     "propertyNames": {"anyOf": [{"enum": list(named)},
                                                                 {"pattern": dotted}]}},
                                    {"type": "null"}],
                          "description": properties["grid"]["description"]}
    return _finished(_nullable_sections(schema), "Risk file (python -m sweep.risk)")


def write(folder=DOCS, json_schema=False):
    """Write ``schema.md`` (and, with ``json_schema``, the JSON Schemas) into ``folder``;
    returns the paths written."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    texts = {MARKDOWN: markdown()}
    if json_schema:
        for name, make in (("scene", scene_json_schema), ("study", study_json_schema),
                           ("risk", risk_json_schema)):
            texts[JSON_SCHEMAS[name]] = json.dumps(make(), indent=1, ensure_ascii=False) + "\n"
    for name, text in texts.items():
        (folder / name).write_text(text)
    return [folder / name for name in texts]


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m sweep.io.reference",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--json-schema", action="store_true",
                        help="also write the JSON Schemas of scene, study and risk files")
    parser.add_argument("--docs", default=DOCS, metavar="DIR",
                        help="folder written into (default: the repository's docs/)")
    args = parser.parse_args(argv)
    for path in write(args.docs, args.json_schema):
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
