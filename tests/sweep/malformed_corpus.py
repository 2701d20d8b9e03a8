"""Malformed input files for ``sweep.scene``, ``sweep.run`` and ``sweep.estimate``.

:func:`cases` builds several hundred cases, deterministically (seeded), from the bundled examples
(``studies/steady_rocking.yaml``, ``smoke.yaml``, ``fig18_elcentro_ns.yaml``,
``refine_example.yaml`` with ``run: {backend: cpu}``, ``bodies_example.yaml``), shrunk to a
few short cells so that a case that turns out valid runs in a blink:

* every leaf replaced by hostile values (huge integers, 1e400, NaN, inf, -0, negative, bool,
  null, list, mapping, a very long string, control characters, a bad timestamp, ...);
* keys deleted, unknown keys added, keys repeated or not strings, mappings replaced by scalars;
* whole-file damage: empty, binary, truncated, BOM, CRLF, tabs, NUL bytes, deep nesting, alias
  bombs, several documents;
* record files referenced from a scene (two columns and PEER ``.AT2``) with NaN, inf, 1e400,
  a tiny median step, bad headers; records that are not regular files;
* grids of too many cells (and one of 1e7 cells dry-run with the limit lifted).

Each case says which exit statuses are right: ``{2}`` when the file is malformed by
construction, ``{0}`` when it is valid by construction (BOM, CRLF, comments), ``{0, 2}`` when it
depends on the field (a negative number, null for an optional key).
"""
import copy
import random
import re
from collections import namedtuple
from pathlib import Path

import yaml

from sweep.runner import grid

STUDIES = Path(__file__).resolve().parents[2] / "studies"
SEED = 20240611
HOSTILE_PER_LEAF = 5  # hostile values tried per leaf (a seeded choice, the sure ones first)

Case = namedtuple("Case", "name tool args files expect path")
Case.__doc__ = """One run: ``tool`` (scene, run, estimate) with ``args`` on ``files`` ({name:
bytes}, the first is the input file); ``expect`` the right exit statuses; ``path`` the dotted
path a message must name (None: any)."""

BAD, VALID, EITHER = frozenset({2}), frozenset({0}), frozenset({0, 2})
NUMBER, TEXT, FLAG, CHOICE = "number", "text", "flag", "choice"
EVERY = frozenset({NUMBER, TEXT, FLAG, CHOICE})
NOT_TEXT = frozenset({NUMBER, FLAG, CHOICE})

# (label, YAML text of the value, leaf kinds for which it is surely malformed)
HOSTILE = [
    ("digits5000", "9" * 5000, EVERY),  # beyond Python's int-from-string limit
    ("control", '"a\\x07b"', EVERY),
    ("nul", '"x\\0y"', EVERY),
    ("timestamp", "2001-13-45", EVERY),
    ("int1e400", "1" + "0" * 400, NOT_TEXT),
    ("float1e400", "1.0e+400", NOT_TEXT),
    ("str1e400", "'1e400 m'", NOT_TEXT),
    ("nan", ".nan", NOT_TEXT),
    ("inf", ".inf", NOT_TEXT),
    ("minus_inf", "-.inf", NOT_TEXT),
    ("list", "[1, 2]", EVERY),
    ("mapping", "{a: 1}", EVERY),
    ("bool", "true", {NUMBER, CHOICE}),
    ("word", "abc", {NUMBER, FLAG, CHOICE}),
    ("long", "x" * 100_000, {NUMBER, FLAG, CHOICE}),
    ("binary", "!!binary aGVsbG8=", EVERY),
    ("minus_zero", "-0", frozenset({FLAG, CHOICE})),
    ("negative", "-1", frozenset({FLAG, CHOICE})),
    ("null", "null", frozenset()),
    ("empty", "''", frozenset({NUMBER, FLAG})),
]
SURE_FIRST = ("digits5000", "control", "int1e400", "nan")  # one of them on every leaf

# Whole-file texts that are malformed whatever the tool
ALIAS_BOMB = "".join(f"{c}: &{c} [{', '.join(['*' + p] * 9) if p else ', '.join('x' * 9)}]\n"
                     for p, c in zip(" abcdefgh", "abcdefghi"))


def _kind(path, value):
    """The kind of a leaf, from its path and value."""
    last = re.sub(r"\[\d+\]$", "", path).split(".")[-1]
    if last in ("name", "title", "site", "direction", "description", "output"):
        return TEXT if not path.startswith("scene.excitation") else CHOICE
    if isinstance(value, bool):
        return FLAG
    if last in ("kind", "method", "hold", "law", "shape", "spacing", "unit", "axis", "units",
                "backend"):
        return CHOICE
    return NUMBER


def _dotted(keys):
    """The dotted path of a tuple of keys, as messages write it (``bodies[0].B``)."""
    return "".join(f"[{k}]" if isinstance(k, int) else f".{k}" for k in keys).lstrip(".")


def _nodes(data, keys=()):
    """(keys, value) of every node below ``data``, the top first."""
    yield keys, data
    items = data.items() if isinstance(data, dict) else \
        enumerate(data) if isinstance(data, list) else ()
    for key, value in items:
        yield from _nodes(value, keys + (key,))


def _set(data, keys, value):
    """A copy of ``data`` with ``value`` at ``keys`` (None as value: the key deleted)."""
    data = copy.deepcopy(data)
    node = data
    for key in keys[:-1]:
        node = node[key]
    if value is None:
        del node[keys[-1]]
    else:
        node[keys[-1]] = value
    return data


def _text(data, raw=None):
    """YAML text of ``data``; the placeholder value ``@HOSTILE@`` replaced by ``raw`` as is."""
    text = yaml.safe_dump(data, sort_keys=False, width=10_000)
    return text if raw is None else text.replace("'@HOSTILE@'", raw).replace("@HOSTILE@", raw)


# --- bases: bundled examples, shrunk to a few short cells ---------------------------------

def _load(name):
    return yaml.safe_load((STUDIES / name).read_text())


def _short_scene(scene, t_end=0.5):
    scene = copy.deepcopy(scene)
    scene.setdefault("solver", {}).update(t_end=t_end, max_steps=20_000)
    return scene


def _small_grid(study):
    for spec in study["grid"].values():
        if isinstance(spec, dict) and "num" in spec:
            spec["num"] = 2
    study["scene"] = _short_scene(study["scene"])
    study["output"] = "out.nc"
    return study


def _bases():
    """{name: (tool, args, data, scene paths an axis overrides)}."""
    smoke = _small_grid(_load("smoke.yaml"))
    fig18 = _small_grid(_load("fig18_elcentro_ns.yaml"))
    fig18["scene"]["solver"]["t_end"] = 0.5
    refine = _small_grid(_load("refine_example.yaml"))
    refine["grid"]["amplitude"]["num"] = 3
    refine["run"] = {"backend": "cpu"}
    bodies = _load("bodies_example.yaml")
    bodies["bodies"] = [bodies["bodies"][0], bodies["bodies"][4]]

    def overridden(study):
        return {f"scene.{p}" for name in study["grid"] for p in grid.targets(name)} | \
            ({"scene.body.B", "scene.body.H"} if "b_over_h" in study["grid"] else set())

    return {"scene": ("scene", ["--json"], _short_scene(_load("steady_rocking.yaml")), set()),
            "smoke": ("run", [], smoke, overridden(smoke)),
            "smoke_dry": ("run", ["--dry-run"], smoke, overridden(smoke)),
            "fig18": ("run", ["--dry-run"], fig18, overridden(fig18)),
            "refine": ("run", ["--dry-run"], refine, overridden(refine)),
            "bodies": ("estimate", [], bodies, set())}


# --- cases --------------------------------------------------------------------------------

def _case(name, tool, args, text, expect, path=None, files=None):
    body = text.encode() if isinstance(text, str) else text
    return Case(name, tool, list(args), {"input.yaml": body, **(files or {})}, expect, path)


def _leaf_cases(base, tool, args, data, overridden, rng):
    out = []
    leaves = [(keys, v) for keys, v in _nodes(data) if not isinstance(v, (dict, list))]
    if base == "smoke_dry":  # its scene leaves are the smoke study's: run the grid ones only
        leaves = [(k, v) for k, v in leaves if k[0] == "grid"]
    if base == "fig18":  # the record study: its axes and records
        leaves = [(k, v) for k, v in leaves if k[0] == "grid" or k[:2] == ("scene", "excitation")]
    if base == "refine":  # the refine study: its refined axis and tolerance, its backend
        leaves = [(k, v) for k, v in leaves
                  if k[0] in ("refine", "run") or k[:2] == ("grid", "amplitude")]
    for keys, value in leaves:
        path = _dotted(keys)
        kind = _kind(path, value)
        sure = rng.choice(SURE_FIRST)
        others = rng.sample([h for h in HOSTILE if h[0] != sure], HOSTILE_PER_LEAF - 1)
        for label, raw, bad_for in [h for h in HOSTILE if h[0] == sure] + others:
            hidden = any(path == p or path.startswith(p + ".") for p in overridden)
            yaml_level = label in ("digits5000", "control", "nul", "timestamp")
            bad = yaml_level or (kind in bad_for and not hidden)
            text = _text(_set(data, keys, "@HOSTILE@"), raw)
            out.append(_case(f"{base}:{path}={label}", tool, args, text,
                             BAD if bad else EITHER, path if bad else None))
    return out


def _structure_cases(base, tool, args, data, overridden):
    """Unknown keys, deleted keys, and mappings replaced by a list, a string or a number."""
    out = []
    for keys, node in _nodes(data):
        if not isinstance(node, dict):
            continue
        path = _dotted(keys)
        unknown = _dotted(keys + ("zz_unknown",))
        text = _text(_set(data, keys + ("zz_unknown",), 1))
        out.append(_case(f"{base}:{unknown}", tool, args, text, BAD, unknown))
        for key in node:
            out.append(_case(f"{base}:-{_dotted(keys + (key,))}", tool, args,
                             _text(_set(data, keys + (key,), None)), EITHER))
        if keys:  # a message at an axis set below it may name the axis instead
            named = None if any(p.startswith(path + ".") for p in overridden) else path
            axis = keys[0] == "grid" and len(keys) == 2  # an axis may be a list
            for label, raw in (("list", "[1, 2]"), ("scalar", "just words"),
                               ("number", "3.5")):
                bad = not (axis and label == "list")
                out.append(_case(f"{base}:{path}=~{label}", tool, args,
                                 _text(_set(data, keys, "@HOSTILE@"), raw),
                                 BAD if bad else EITHER, named if bad else None))
    top = _text(data)
    first_key = next(iter(data))
    for label, text in (
            ("duplicate", top + f"{first_key}: 1\n"),
            ("key_int", top + "1: x\n"),
            ("key_on", top + "on: x\n"),
            ("key_null", top + "null: x\n"),
            ("key_list", top + "[1, 2]: x\n"),
            ("key_long", top + "k" * 200_000 + ": 1\n")):
        out.append(_case(f"{base}:{label}", tool, args, text, BAD))
    return out


def _file_cases(base, tool, args, data, rng):
    """Damage to the whole text: every case is malformed but BOM, CRLF and comments."""
    top = _text(data)
    nested = "a: " + "{a: " * 10_000 + "1" + "}" * 10_000 + "\n"
    out = [_case(f"{base}:{label}", tool, args, text, expect) for label, text, expect in (
        ("empty", "", BAD),
        ("blank", " \n\n", BAD),
        ("comment_only", "# nothing\n", BAD),
        ("document_marker", "---\n", BAD),
        ("two_documents", top + "---\n" + top, BAD),
        ("top_list", "- 1\n- 2\n", BAD),
        ("top_scalar", "hello\n", BAD),
        ("top_number", "1" + "0" * 400 + "\n", BAD),
        ("deep_list", "a: " + "[" * 10_000 + "]" * 10_000 + "\n", BAD),
        ("deep_mapping", nested, BAD),
        ("alias_bomb", ALIAS_BOMB, BAD),
        ("alias", top + "zz: &a 1\nzy: *a\n", BAD),
        ("nul_byte", top[:len(top) // 2] + "\0" + top[len(top) // 2:], BAD),
        ("escape_char", top + "# \x1b[31m\n", BAD),
        ("tabs", top.replace("\n  ", "\n\t"), BAD if "\n  " in top else EITHER),
        ("unclosed", top + "zz: [1, 2\n", BAD),
        ("bom", "\ufeff" + top, VALID),
        ("crlf", top.replace("\n", "\r\n"), VALID),
        ("comments", "# a comment\n" + top + "# the end\n", VALID),
        ("unchanged", top, VALID))]
    out.append(_case(f"{base}:utf16", tool, args, top.encode("utf-16"), BAD))
    out.append(_case(f"{base}:latin1", tool, args, (top + "# caf\xe9\n").encode("latin-1"), BAD))
    garbage = bytes(rng.randrange(256) for _ in range(300)) + b"\xff\xfe"
    out.append(_case(f"{base}:binary", tool, args, garbage, BAD))
    for cut in sorted(rng.sample(range(1, len(top)), 3)):
        out.append(_case(f"{base}:truncated@{cut}", tool, args, top[:cut], EITHER))
    return out


# --- records ------------------------------------------------------------------------------

def _at2(npts_dt, values):
    return ("PEER NGA STRONG MOTION DATABASE RECORD\nTEST 1940, station, 0\n"
            f"ACCELERATION TIME SERIES IN UNITS OF G\n{npts_dt}\n{values}\n").encode()


RECORDS = {  # file name, contents, expected exit
    "valid.txt": (b"# t a\n0 0.1\n0.01 -0.2\n0.02 0.3\n0.03 0.0\n", VALID),
    "valid.AT2": (_at2("NPTS=    4, DT=   .0100 SEC", "0.01 -0.02 0.03 0.0"), VALID),
    "nan.txt": (b"0 0.1\n0.01 nan\n0.02 0.3\n", BAD),
    "inf.txt": (b"0 0.1\n0.01 inf\n0.02 0.3\n", BAD),
    "e400.txt": (b"0 0.1\n0.01 1e400\n0.02 0.3\n", BAD),
    "nan_time.txt": (b"0 0.1\nnan 0.2\n0.02 0.3\n", BAD),
    "huge_span.txt": (b"-1e308 0.1\n0 0.2\n1e308 0.3\n", BAD),
    "tiny_step.txt": (b"0 0.1\n1e-12 0.2\n2e-12 0.3\n3e-12 0.1\n1000 0.0\n", BAD),
    "one_row.txt": (b"0 0.1\n", BAD),
    "empty.txt": (b"", BAD),
    "three_columns.txt": (b"0 0.1 1\n0.01 0.2 1\n", BAD),
    "decreasing.txt": (b"0 0.1\n0.02 0.2\n0.01 0.3\n", BAD),
    "words.txt": (b"time accel\n0 a\n", BAD),
    "binary.txt": (bytes(range(256)) * 4, BAD),
    "zeros.txt": (b"0 0\n0.01 0\n0.02 0\n", VALID),
    "nan.AT2": (_at2("NPTS= 3, DT= .01 SEC", "0.1 nan 0.2"), BAD),
    "inf.AT2": (_at2("NPTS= 3, DT= .01 SEC", "0.1 1e400 0.2"), BAD),
    "dt_inf.AT2": (_at2("NPTS= 3, DT= 1e400 SEC", "0.1 0.2 0.3"), BAD),
    "dt_zero.AT2": (_at2("NPTS= 3, DT= 0 SEC", "0.1 0.2 0.3"), BAD),
    "dt_nan.AT2": (_at2("NPTS= 3, DT= nan SEC", "0.1 0.2 0.3"), BAD),
    "dt_1e-300.AT2": (_at2("NPTS= 3, DT= 1e-300 SEC", "0.1 0.2 0.3"), BAD),
    "dt_1e6.AT2": (_at2("NPTS= 3, DT= 1e6 SEC", "0.1 0.2 0.3"), BAD),
    "npts_huge.AT2": (_at2("NPTS= " + "9" * 5000 + ", DT= .01 SEC", "0.1 0.2"), BAD),
    "npts_mismatch.AT2": (_at2("NPTS= 1000000000000, DT= .01 SEC", "0.1 0.2"), BAD),
    "short.AT2": (b"only\ntwo lines\n", BAD),
    "velocity.AT2": (_at2("NPTS= 2, DT= .01", "1 2").replace(b"ACCELERATION", b"VELOCITY"),
                     BAD),
    "garbage.AT2": (_at2("NPTS= 2, DT= .01", "1 zz"), BAD),
}


def _record_cases(base_scene):
    out = []
    for name, (content, expect) in RECORDS.items():
        for extra in ({}, {"pga": "0.3 g"}):
            scene = copy.deepcopy(base_scene)
            scene["excitation"]["horizontal"] = {"kind": "record", "path": name, **extra}
            right = BAD if name == "zeros.txt" and extra else expect
            out.append(_case(f"record:{name}{'+pga' if extra else ''}", "scene", ["--json"],
                             _text(scene), right,
                             None if right != BAD else "excitation.horizontal",
                             files={name: content}))
    for label, path in (("directory", "."), ("missing", "nope.txt"), ("dev_zero", "/dev/zero"),
                        ("dev_null", "/dev/null"), ("long_name", "r" * 5000 + ".txt"),
                        ("proc", "/proc/self/status")):
        scene = copy.deepcopy(base_scene)
        scene["excitation"]["horizontal"] = {"kind": "record", "path": path}
        out.append(_case(f"record:path={label}", "scene", ["--json"], _text(scene), BAD,
                         "excitation.horizontal.path"))
    return out


# --- grids --------------------------------------------------------------------------------

def _grid_cases(smoke):
    def study(**axes):
        data = copy.deepcopy(smoke)
        data["grid"] = axes
        return _text(data)

    def long_list(value, n):  # written out: dumping two million values takes a minute
        return _text({**smoke, "grid": {"mu": "@HOSTILE@"}}, f"[{', '.join([value] * n)}]")

    big = {"amplitude": {"start": 0.8, "stop": 3.0, "num": 1000, "unit": "west"},
           "frequency": {"start": 1.0, "stop": 10.0, "num": 100, "spacing": "log"},
           "mu": {"start": 0.1, "stop": 1.0, "num": 100}}
    out = [_case("grid:1e7_cells", "run", ["--dry-run"], study(**big), BAD, "grid"),
           _case("grid:1e7_cells_run", "run", [], study(**big), BAD, "grid"),
           _case("grid:1e7_cells_unlimited", "run", ["--dry-run", "--max-cells", "0"],
                 study(**big), VALID)]
    for label, num in (("num_1e7", 10_000_000), ("num_1e12", 10**12), ("num_1e400", 10**400),
                       ("num_float", 2.5), ("num_zero", 0)):
        axes = copy.deepcopy(big)
        axes["amplitude"]["num"] = num
        out.append(_case(f"grid:{label}", "run", ["--dry-run"], study(**axes), BAD,
                         "grid.amplitude.num"))
    many = {f"excitation.horizontal.{k}": {"start": 1, "stop": 2, "num": 1000}
            for k in ("start", "phase")}
    many.update({f"initial.{k}": {"start": 0, "stop": 0.1, "num": 1000}
                 for k in ("theta", "omega", "x_dot", "y_dot", "lift")})
    out += [
        _case("grid:1e21_cells", "run", ["--dry-run", "--max-cells", "0"], study(**many), BAD,
              "grid"),
        _case("grid:repeats_1e5", "run", ["--dry-run"], long_list("0.5", 100_000), BAD,
              "grid.mu"),
        _case("grid:list_2e6", "run", ["--dry-run"], long_list("0.5", 2_000_000), BAD,
              "(file)"),
        _case("grid:empty", "run", ["--dry-run"], study(), BAD, "grid"),
        _case("grid:axis_empty_list", "run", ["--dry-run"], study(mu=[]), BAD, "grid.mu"),
        _case("grid:axis_int_key", "run", ["--dry-run"],
              _text(smoke).replace("grid:\n", "grid:\n  1: [1, 2]\n"), BAD, "grid"),
        _case("grid:zip_bad", "run", ["--dry-run"],
              _text({**smoke, "zip": [["amplitude", 3]]}), BAD, "zip"),
        _case("grid:zip_mapping_int", "run", ["--dry-run"],
              _text({**smoke, "zip": {"d": "amplitude"}}), BAD, "zip"),
    ]
    for label, output in (("proc", "/proc/x.nc"), ("below_file", "input.yaml/x.nc"),
                          ("directory", "."), ("long", "o" * 5000 + ".nc"),
                          ("dev_null_dir", "/dev/null/x.nc")):
        out.append(_case(f"output:{label}", "run", [], _text({**smoke, "output": output}), BAD,
                         "output"))
    return out


def cases():
    """Every case, in a fixed order (names are unique)."""
    rng = random.Random(SEED)
    bases = _bases()
    out = []
    for base, (tool, args, data, overridden) in bases.items():
        out += _leaf_cases(base, tool, args, data, overridden, rng)
        if base in ("scene", "smoke", "bodies"):
            out += _structure_cases(base, tool, args, data, overridden)
            out += _file_cases(base, tool, args, data, rng)
    out += _record_cases(bases["scene"][2])
    out += _grid_cases(bases["smoke"][2])
    names = [c.name for c in out]
    assert len(names) == len(set(names)), "case names must be unique"
    return out

