"""studies/explore.ipynb, the tutorial: it runs top to bottom in the project's kernel, prints
what its text says, reads flags by name, and is stored without its outputs.

The notebook is executed with nbclient from a copy in a temporary folder, which is also its
working folder: the record file it writes goes to a temporary folder of its own, never beside
the notebook, and the stored notebook is never rewritten.  Cells whose printed lines are
checked carry a tag (cell metadata, not shown).
"""
import base64
import importlib.util
import re
import shutil
import sys
from pathlib import Path

import pytest

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")

NOTEBOOK = Path(__file__).resolve().parents[3] / "studies" / "explore.ipynb"
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
FIGURES = 6         # history, scene, line at 2 Hz, xarray map, package map, fragility
STUDY_CELLS = 17 * 12 * 2  # amplitude x frequency x b_over_h of section 3
MAX_BYTES = 50_000  # the stored notebook: its source, without outputs
CELL_TIMEOUT = 300  # s; the whole notebook takes about 10 s once the kernel is compiled
PREFIX_TAG = "test_prefix"
MOTION_TAG = "test_motion_file"


@pytest.fixture(scope="module")
def executed(tmp_path_factory):
    if importlib.util.find_spec("cf_xarray") is None:
        pytest.fail("cf_xarray is not installed: the notebook reads flags with it "
                    "(a dependency of the project: pip install -e .)")
    tmp = tmp_path_factory.mktemp("notebook")
    stored = NOTEBOOK.read_bytes()
    copy = tmp / NOTEBOOK.name
    shutil.copyfile(NOTEBOOK, copy)
    nb = nbformat.read(copy, as_version=4)
    probe = nbformat.v4.new_code_cell("import sys\nprint(sys.prefix)")
    probe.metadata["tags"] = [PREFIX_TAG]
    nb.cells.append(probe)
    # the record file of section 2, read while the kernel (and its temporary folder) lives
    motion = nbformat.v4.new_code_cell(
        "print(motion_file.resolve())\n"
        "rows = [line.split() for line in motion_file.read_text().splitlines()\n"
        "        if not line.startswith('#')]\n"
        "print(len(rows), sorted({len(row) for row in rows}))")
    motion.metadata["tags"] = [MOTION_TAG]
    nb.cells.append(motion)
    # "python3": jupyter_client starts the kernel with this interpreter (sys.executable)
    client = nbclient.NotebookClient(nb, timeout=CELL_TIMEOUT, kernel_name="python3",
                                     resources={"metadata": {"path": str(tmp)}})
    client.execute()
    assert NOTEBOOK.read_bytes() == stored  # executing never rewrites the stored notebook
    return nb, tmp


def _code_cells(nb):
    return [cell for cell in nb.cells if cell.cell_type == "code"]


def _stdout(nb, tag):
    """The standard output of the cell tagged ``tag``."""
    cell = next((c for c in nb.cells if tag in c.metadata.get("tags", [])), None)
    assert cell is not None, f"no cell tagged {tag!r}"
    return "".join(out["text"] for out in cell.get("outputs", [])
                   if out.get("output_type") == "stream" and out.get("name") == "stdout")


def _number(pattern, text):
    match = re.search(pattern, text)
    assert match, f"{pattern!r} not in {text!r}"
    return float(match.group(1))


def _pngs(nb):
    return [base64.b64decode(out["data"]["image/png"]) for cell in _code_cells(nb)
            for out in cell.get("outputs", []) if "image/png" in out.get("data", {})]


def test_runs_in_the_projects_kernel_without_errors(executed):
    nb, _ = executed
    assert _stdout(nb, PREFIX_TAG).strip() == sys.prefix
    errors = [out for cell in _code_cells(nb) for out in cell.get("outputs", [])
              if out.get("output_type") == "error"]
    assert not errors


def test_one_scene_verdict(executed):
    # section 1: El Centro NS at 0.4 g rocks the 20 x 80 cm body to 0.9 alpha; 0.5 g overturns it
    nb, _ = executed
    verdict = _stdout(nb, "verdict")
    assert "status: ok" in verdict and "overturned: False" in verdict
    assert _number(r"= ([\d.]+) α", verdict) == pytest.approx(0.9, abs=0.05)  # "nine tenths"
    assert _number(r"= ([\d.]+) g,", verdict) == pytest.approx(0.40)
    levels = _stdout(nb, "levels").splitlines()
    assert [line.split(":")[0] for line in levels] == ["PGA 0.3 g", "PGA 0.4 g", "PGA 0.5 g"]
    assert "stood" in levels[0] and "stood" in levels[1] and "overturned at" in levels[2]
    moving = _stdout(nb, "moving")
    start, end = re.search(r"from t = ([\d.]+) s to t = ([\d.]+) s", moving).groups()
    assert 0 < float(start) < float(end) < 20


def test_own_record(executed):
    # section 2: a two-column file in gal, as written it stands, scaled to 0.6 g it overturns
    nb, tmp = executed
    path, shape = _stdout(nb, MOTION_TAG).splitlines()
    assert Path(path).name == "burst_2hz.txt" and tmp not in Path(path).parents
    assert shape == "601 [2]"  # rows, columns
    assert not Path(path).exists()  # its temporary folder went with the kernel
    assert sorted(p.name for p in tmp.iterdir()) == [NOTEBOOK.name]  # nothing beside it
    lines = _stdout(nb, "own_record").splitlines()
    assert lines[0].startswith("as written (PGA 2.9") and "stood" in lines[0]
    assert lines[-1].startswith("scaled to PGA 0.6 g: overturned at")


def test_study_counts_by_flag_name(executed):
    # section 3: every cell counted once by name; none moved below West's acceleration
    counts = dict(re.findall(r"^\s*(\w+): (\d+) cells$", _stdout(executed[0], "counts"),
                             re.MULTILINE))
    assert set(counts) == {"failed", "no_rocking", "rocked", "overturned"}
    assert sum(map(int, counts.values())) == STUDY_CELLS
    assert counts["failed"] == "0" and int(counts["overturned"]) > 0
    assert int(counts["no_rocking"]) >= 12 * 2  # 0.8 west at every frequency and body
    assert "below West's acceleration: 0" in _stdout(executed[0], "counts")


def test_fragility_fit(executed):
    # section 4: theta and beta inside their intervals; theta more than twice West's
    fit = _stdout(executed[0], "fit")
    theta, lower, upper = (float(x) for x in re.search(
        r"θ = ([\d.]+) m/s²  \(95 %: ([\d.]+) to ([\d.]+)\)", fit).groups())
    assert lower < theta < upper
    beta, b_lower, b_upper = (float(x) for x in re.search(
        r"β = ([\d.]+)  \(95 %: ([\d.]+) to ([\d.]+)\)", fit).groups())
    assert 0 < b_lower < beta < b_upper
    assert theta > 2 * _number(r"\(B/H\) g = ([\d.]+) m/s²", fit)  # "more than twice"


def test_draws_every_figure(executed):
    pngs = _pngs(executed[0])
    assert len(pngs) == FIGURES
    assert all(png.startswith(PNG_SIGNATURE) and len(png) > 10_000 for png in pngs)


def test_reads_flags_by_name_and_shows_no_internals():
    nb = nbformat.read(NOTEBOOK, as_version=4)
    source = "\n".join(cell.source for cell in _code_cells(nb))
    assert not re.search(r"\b(outcome|mode|status|overturned|slid)\s*(==|!=|<=|>=|<|>)\s*-?\d",
                         source), "compare flags by name (cf_xarray), not by code"
    assert ".cf ==" in source and ".cf.isin" in source
    assert "kernel_prefix" not in source and "sys.prefix" not in source


def test_stored_without_outputs():
    # what a clone holds: the source alone (outputs stripped, no execution counts), small;
    # the tests above run it
    assert NOTEBOOK.stat().st_size < MAX_BYTES
    nb = nbformat.read(NOTEBOOK, as_version=4)
    cells = _code_cells(nb)
    assert cells and all(cell.execution_count is None and not cell.get("outputs")
                         for cell in cells)
