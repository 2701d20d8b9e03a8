"""studies/explore.ipynb runs from a clean clone in the project's own kernel and shows real results.

The notebook is executed with nbclient in ``studies/`` (as Jupyter does), its parameters cell
pointed at a temporary folder so that it runs its small study itself, as it does without
``results/smoke.nc``.
"""
import base64
import json
import sys
from pathlib import Path

import pytest

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")

NOTEBOOK = Path(__file__).resolve().parents[2] / "studies" / "explore.ipynb"
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def executed(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("notebook")
    nb = nbformat.read(NOTEBOOK, as_version=4)
    params = next(c for c in nb.cells if "parameters" in c.metadata.get("tags", []))
    params.source = (f"from pathlib import Path\nRESULT = Path({str(tmp / 'absent.nc')!r})\n"
                     f"STUDY = Path('smoke.yaml')\nTINY = Path({str(tmp / 'tiny.nc')!r})")
    # "python3": jupyter_client starts the kernel with this interpreter (sys.executable)
    client = nbclient.NotebookClient(nb, timeout=300, kernel_name="python3",
                                     resources={"metadata": {"path": str(NOTEBOOK.parent)}})
    client.execute()
    return nb, tmp


def _summary(nb):
    for cell in nb.cells:
        for out in cell.get("outputs", []):
            if out.get("name") == "stdout" and '"rocked_below_west"' in out.get("text", ""):
                return json.loads(out["text"])
    raise AssertionError("the summary cell printed no JSON")


def test_runs_in_this_environment_and_writes_its_result(executed):
    nb, tmp = executed
    summary = _summary(nb)
    assert summary["kernel_prefix"] == sys.prefix  # the kernel is the project's interpreter
    assert summary["result"].endswith("tiny.nc") and (tmp / "tiny.nc").is_file()
    assert summary["cells"] == 30


def test_summary_obeys_west_threshold(executed):
    # PHYSICS.md A2: below (B/H) g the block stays at rest (mu = 0.8 > b/h: no sliding)
    summary = _summary(executed[0])
    assert summary["rocked_below_west"] == 0
    assert summary["failed"] == 0
    assert summary["at_rest"] >= 5  # amplitude 0.8 and 0.95 west at every frequency
    assert summary["overturned"] > 0
    assert summary["at_rest"] + summary["rocked"] + summary["overturned"] == 30
    # overturning needs at least West's acceleration (Eq. 14)
    lowest = [a for a in summary["lowest_overturning_amplitude"].values() if a is not None]
    assert lowest and min(lowest) >= 1.0


def test_draws_the_map(executed):
    pngs = [base64.b64decode(out["data"]["image/png"])
            for cell in executed[0].cells for out in cell.get("outputs", [])
            if "image/png" in out.get("data", {})]
    assert len(pngs) == 1
    assert pngs[0].startswith(PNG_SIGNATURE) and len(pngs[0]) > 10_000
