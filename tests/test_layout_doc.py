"""docs/layout.md against the code: every module of ``kernels`` and ``sweep`` listed, nothing
listed that is not there, and each line the summary line of the module's docstring (a
package's line that of its ``__init__.py``), the one-line summary of PEP 257."""
import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LAYOUT = ROOT / "docs" / "layout.md"
PACKAGES = ("kernels", "sweep")


def listing(text):
    """The tree of a layout page, ``{path: description}``: a name indented two spaces per folder
    level, ``/`` ending a folder, its description after the spaces."""
    entries, folders = {}, []
    for line in text.split("```")[1].strip("\n").splitlines():
        depth = (len(line) - len(line.lstrip())) // 2
        name, _, description = line.strip().partition(" ")
        folders = folders[:depth]
        entries["/".join([*folders, name])] = normalise(description)
        if name.endswith("/"):
            folders.append(name.rstrip("/"))
    return entries


def normalise(text):
    """Whitespace collapsed, a trailing period dropped."""
    return " ".join(text.split()).rstrip(".")


def docstring(path):
    return ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""


def entry(module):
    """The listing's path of a module: a package's ``__init__.py`` is its folder's line."""
    return module.removesuffix("__init__.py")


MODULES = sorted(p.relative_to(ROOT).as_posix()
                 for package in PACKAGES for p in (ROOT / package).rglob("*.py"))


def test_listing_reads_the_tree_as_written():
    text = "```\na/           A package\n  b.py       Its module.\n  c/\n    d.py     Deep\ne.py  Top\n```"
    assert listing(text) == {"a/": "A package", "a/b.py": "Its module", "a/c/": "",
                             "a/c/d.py": "Deep", "e.py": "Top"}


def test_every_module_is_listed():
    listed = listing(LAYOUT.read_text(encoding="utf-8"))
    assert [m for m in MODULES if entry(m) not in listed] == []


def test_everything_listed_exists():
    listed = listing(LAYOUT.read_text(encoding="utf-8"))
    assert [path for path in listed if not (ROOT / path).exists()] == []


def test_each_line_is_the_modules_summary_line():
    listed = listing(LAYOUT.read_text(encoding="utf-8"))
    packages = [p.relative_to(ROOT).as_posix() for p in ROOT.glob("*/__init__.py")]
    differing = [(m, listed[entry(m)], docstring(ROOT / m).split("\n", 1)[0])
                 for m in sorted({*MODULES, *packages})
                 if entry(m) in listed
                 and listed[entry(m)] != normalise(docstring(ROOT / m).split("\n", 1)[0])]
    assert differing == []


def test_summaries_are_one_line_sentences():
    """PEP 257: the summary fits on one line and a blank line follows it, so the listing's line
    is a whole sentence."""
    long_or_run_on = [m for m in MODULES
                      if len(docstring(ROOT / m).split("\n", 1)[0]) + 3 > 99
                      or docstring(ROOT / m).split("\n")[1:2] not in ([], [""])]
    assert long_or_run_on == []
