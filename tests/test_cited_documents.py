"""Every document the repository cites is in the repository: a clone holds the pages that its
code, tests and docs point at (``docs/physics.md``, ``docs/design.md``, ...), and nothing points
outside it."""
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SKIPPED = {".git", ".venv", "results", "figures", "out", "build", "__pycache__",
           ".pytest_cache", ".numba_cache"}
TEXT = {".py", ".md", ".ipynb", ".yaml", ".yml", ".toml", ".cfg", ".txt", ""}
OUTPUTS = ("results/", "figures/", "out/")  # pages the commands write, not documents cited
WRITTEN = {"bench.md"}  # the benchmarks' report, named where a test writes it
CITED = re.compile(r"(?<![\w/.-])((?:\.\./|[\w-]+/)*[\w-]+\.md)\b")
OUTSIDE = re.compile(r"/work/shared|\.\./shared\b|\.\./\.library")


def _files():
    for path in sorted(ROOT.rglob("*")):
        parts = set(path.relative_to(ROOT).parts)
        if path.is_file() and not parts & SKIPPED and not any(
                p.endswith(".egg-info") for p in parts) and path.suffix in TEXT \
                and path != Path(__file__).resolve():
            yield path


def _found(name, where):
    """Whether the document ``name`` cited in the file ``where`` is in the repository: a
    path relative to the citing file or to the root, or a bare name beside the citing file,
    in docs/ or at the root."""
    if "/" in name:
        candidates = [where.parent / name, ROOT / name.lstrip("./")]
    else:
        candidates = [where.parent / name, ROOT / "docs" / name, ROOT / name]
    return any(c.resolve().is_file() and ROOT in c.resolve().parents for c in candidates)


def _citations():
    out = []
    for path in _files():
        try:
            text = path.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        for number, line in enumerate(text.splitlines(), 1):
            for match in CITED.finditer(line):
                name = match.group(1)
                if not name.startswith(OUTPUTS) and name not in WRITTEN:
                    out.append((path, number, name))
    return out


def test_the_citations_are_found():
    """The scan sees the citations it must check (docs pages cited from code and docs)."""
    names = {name for _, _, name in _citations()}
    assert {"docs/physics.md", "docs/design.md", "docs/probability.md",
            "docs/risk.md"} <= names


@pytest.mark.parametrize("kind", ["missing", "outside"])
def test_every_cited_document_is_in_the_repository(kind):
    if kind == "missing":
        missing = [f"{p.relative_to(ROOT)}:{n}: {name}" for p, n, name in _citations()
                   if not _found(name, p)]
        assert not missing, "cited but not in the repository:\n" + "\n".join(missing)
    else:
        outside = [f"{p.relative_to(ROOT)}:{n}" for p in _files()
                   for n, line in enumerate(p.read_text(encoding="utf-8",
                                                        errors="replace").splitlines(), 1)
                   if OUTSIDE.search(line)]
        assert not outside, "points outside the repository:\n" + "\n".join(outside)
