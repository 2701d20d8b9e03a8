"""Safe YAML reading with duplicate keys refused, and the FileProblems message format."""
import pytest
import yaml

from sweep.io.problems import MISSING, FileProblems, Problem
from sweep.io.yamlio import MAX_DEPTH, UniqueKeyLoader, parse_yaml

TEXT = """\
a: 1
b:
  c: 2
  c: 3
  d: [{e: 1, e: 2}]
a: 4
"""


def test_duplicates_with_dotted_paths_and_lines():
    data, problems = parse_yaml(TEXT)
    assert data == {"a": 4, "b": {"c": 3, "d": [{"e": 2}]}}  # last value kept to check on
    assert [(p.path, p.value) for p in problems] == [("b.c", "c"), ("b.d[0].e", "e"),
                                                      ("a", "a")]  # in file order
    assert "first at line 1, again at line 6" in problems[2].message


def test_loader_for_yaml_load():
    with pytest.raises(FileProblems, match="b.c: duplicate key"):
        yaml.load(TEXT, Loader=UniqueKeyLoader)
    assert yaml.load("x: [1, 2]\ny: {z: 1.5}", Loader=UniqueKeyLoader) == \
        {"x": [1, 2], "y": {"z": 1.5}}


def test_merge_keys_may_be_overridden():
    data, problems = parse_yaml("c:\n  <<: {x: 1, y: 2}\n  x: 3\n")
    assert problems == [] and data["c"] == {"x": 3, "y": 2}


@pytest.mark.parametrize("text, column", [
    ("base: &b {x: 1, y: 2}\nc:\n  <<: *b\n", 7),
    ("a: &a [x, x, x, x, x, x, x, x, x]\nb: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a]\n", 4)])
def test_anchors_and_aliases_refused(text, column):
    data, problems = parse_yaml(text)
    assert data is None and problems[0].path == f"line 1, column {column}"
    assert "anchors (&name) and aliases (*name) are not accepted" in problems[0].message


@pytest.mark.parametrize("text, where, message", [
    ("a: 1\nb: x\x00\n", "line 2, column 5", "character U+0000 is not allowed"),
    ("a: " + "[" * 10_000, "line 1, column 67", f"nested deeper than {MAX_DEPTH} levels"),
    ("a: " + "9" * 5000, "line 1, column 4", "cannot read this value (Exceeds the limit"),
    ("t: 2001-13-01\n", "line 1, column 4", "cannot read this value (month must be in 1..12)"),
])
def test_hostile_text_located(text, where, message):
    data, problems = parse_yaml(text)
    assert data is None and len(problems) == 1
    assert problems[0].path == where and message in problems[0].message


def test_keys_are_strings_and_strings_have_no_control_characters():
    data, problems = parse_yaml('on: 1\n2: x\nb: {c: ["ok\\tok", "bell\\a"]}\n')
    assert [(p.path, p.value) for p in problems] == [("True", True), ("2", 2),
                                                      ("b.c[1]", "bell\a")]
    assert "a key must be a string" in problems[0].message
    assert problems[2].message == "contains the control character U+0007"


def test_safe_only():
    _, problems = parse_yaml("a: !!python/object/apply:os.system ['true']\n")
    assert len(problems) == 1 and "YAML error" in problems[0].message


def test_syntax_error_located():
    _, problems = parse_yaml("a: [1, 2\n")
    assert problems[0].path.startswith("line 2, column")


def test_format_one_per_line():
    err = FileProblems([("body.H", -0.3, "must be greater than 0"),
                        Problem("body.B", MISSING, "required"),
                        ("excitation.horizontal.amplitude", "1.5 wset", "unknown unit")])
    assert str(err).splitlines() == [
        "body.H: must be greater than 0 (got: -0.3)",
        "body.B: required",
        "excitation.horizontal.amplitude: unknown unit (got: '1.5 wset')",
    ]
    assert str(err.with_prefix("scene")).splitlines()[0] == \
        "scene.body.H: must be greater than 0 (got: -0.3)"
