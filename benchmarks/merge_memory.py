"""``python -m benchmarks.merge_memory [N ...]``: the memory rank 0 needs to merge a study's
part files and write its dataset, at several cell counts.

For each count (default 250,000 and 1,000,000 cells) the part files of ``million_cells.yaml``
cut to that many cells are written with made-up results (no cell runs), then a child process
merges and writes them as a run's rank 0 does (``PartStore.merge``, ``store.write_merged``,
the summary's ``outcome`` and ``status``) and reports its peak
resident memory beyond what it held after its imports.  Read with the bytes of every result
of every cell (what a merge holding all cells needs, twice over while the Dataset is built):
the streamed merge holds one group of variables (``runner.merged.BUDGET``) and a few bytes per
cell (ids, outcome, status), so its memory grows far slower than the results.
"""
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
STUDY = ROOT / "benchmarks" / "million_cells.yaml"
SIZES = (250_000, 1_000_000)
PART_CELLS = 1000  # cells per made-up part file

# The child: merge and write as rank 0 does, then print its memory (ru_maxrss is in KiB)
CHILD = """
import json, resource, sys
from sweep.runner import merged, store
from sweep.runner.cell_checks import load_study
from sweep.runner.summary import SUMMARY_VARIABLES
import xarray, netCDF4
study_path, folder, output, budget = sys.argv[1:5]
if int(budget):
    merged.BUDGET = int(budget)
study = load_study(study_path, max_cells=0)
parts = store.PartStore(folder, stamp=store.PartStore(folder).manifest_stamp())
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
result = parts.merge(study.n_cells)
store.write_merged(study, result, output)
result.read(SUMMARY_VARIABLES)
after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print(json.dumps({"before": before * 1024, "peak": after * 1024}))
"""


def study_text(n):
    """``million_cells.yaml`` with its PGA axis cut so that the study has ``n`` cells."""
    per_pga = 100 * 100
    if n % per_pga:
        raise ValueError(f"a cell count of a multiple of {per_pga} is needed, got {n}")
    return STUDY.read_text().replace("num: 100, spacing: log, unit: m/s^2",
                                     f"num: {n // per_pga}, spacing: log, unit: m/s^2")


def fake_parts(study, folder):
    """Part files of every cell of ``study`` with made-up results of the right dtypes."""
    from sweep import cf
    from sweep.runner import store

    parts = store.PartStore(folder)
    parts.prepare(study)
    rng = np.random.default_rng(0)
    for first in range(0, study.n_cells, PART_CELLS):
        cell = np.arange(first, min(first + PART_CELLS, study.n_cells))
        arrays = {name: rng.integers(-1, 3, cf.empty(name, cell.size).shape).astype(var.dtype)
                  for name, var in cf.VARIABLES.items()}
        parts.write_part({**arrays, "cell": cell})
    return parts


def measure(n, folder, budget=0):
    """Bytes of every result of ``n`` cells, and the child's peak memory beyond its imports
    while it merges and writes them (``budget``: bytes of a group, 0: ``merged.BUDGET``)."""
    from sweep import cf
    from sweep.runner import merged
    from sweep.runner.cell_checks import load_study

    folder = Path(folder)
    path = folder / f"cells{n}.yaml"
    path.write_text(study_text(n))
    study = load_study(path, max_cells=0)
    parts = fake_parts(study, folder / f"cells{n}.parts")
    done = subprocess.run([sys.executable, "-c", CHILD, str(path), str(parts.directory),
                           str(folder / f"cells{n}.nc"), str(budget)],
                          cwd=ROOT, capture_output=True, text=True, check=True)
    rss = json.loads(done.stdout.splitlines()[-1])
    results = sum(merged.cell_bytes(name) for name in cf.VARIABLES) * n
    parts.remove()
    return results, rss["peak"] - rss["before"]


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    sizes = [int(k) for k in argv] or list(SIZES)
    print("| cells | results [MiB] | merge and write, beyond imports [MiB] |")
    print("|---|---|---|")
    with tempfile.TemporaryDirectory(prefix="bench_merge_") as tmp:
        for n in sizes:
            results, extra = measure(n, tmp)
            print(f"| {n} | {results / 2**20:.0f} | {extra / 2**20:.0f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
