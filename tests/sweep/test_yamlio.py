"""Safe YAML reading with duplicate keys refused, and the FileProblems message format."""
import pytest
import yaml

from sweep.io.problems import MISSING, FileProblems, Problem
from sweep.io.yamlio import UniqueKeyLoader, parse_yaml, read_yaml

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
    data, problems = parse_yaml("base: &b {x: 1, y: 2}\nc:\n  <<: *b\n  x: 3\n")
    assert problems == [] and data["c"] == {"x": 3, "y": 2}


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


def test_read_yaml(tmp_path):
    path = tmp_path / "s.yaml"
    path.write_text(TEXT)
    with pytest.raises(FileProblems) as info:
        read_yaml(path)
    assert len(info.value.problems) == 3 and info.value.source == str(path)
    with pytest.raises(FileProblems, match="cannot read"):
        read_yaml(tmp_path / "missing.yaml")
