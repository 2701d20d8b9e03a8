"""Where sweeps overturn a body from subharmonic rocking (Ishiyama 1982, curve b, Fig. 14).

A search study (``studies/curve_b_scan_*.yaml``) varies the level, the body, the sweep's
start, direction and rate, the starting phase and the initial disturbance (tilt, angular
velocity).  Its overturnings are classified by ``sweep.paper.classify`` (each simulated again
with its history); ``counts`` tallies them per value of every axis, and ``robustness``
classifies a cell again with the classifier's window, tolerance and sampling changed, the
integrator's tolerance changed and the amplitude changed by a relative 1e-6.
``python -m sweep.paper.subharmonic RESULT.nc ...`` prints both as markdown tables.
"""
import contextlib
import sys
from collections import namedtuple

import numpy as np

from kernels import run_scene

from ..cli import report_command
from .. import cf
from ..runner import grid
from . import classify

# Changes under which a classification is repeated: (name, classifier constants, scene
# changes as {dotted path: factor or value})
VARIANTS = (
    ("as run", {}, {}),
    ("6 half-cycles", {"HALF_CYCLES": 6}, {}),
    ("16 half-cycles", {"HALF_CYCLES": 16}, {}),
    ("tolerance 0.15", {"TOLERANCE": 0.15}, {}),
    ("regular share 0.8", {"REGULAR": 0.8}, {}),
    ("sampled every 1 ms", {}, {"solver.dt_out": 0.001}),
    ("rtol 1e-7", {}, {"solver.rtol": 1e-7}),
    ("rtol 1e-10", {}, {"solver.rtol": 1e-10}),
    ("amplitude × (1 + 1e-6)", {}, {"excitation.horizontal.amplitude": ("scale", 1 + 1e-6)}),
    ("amplitude × (1 − 1e-6)", {}, {"excitation.horizontal.amplitude": ("scale", 1 - 1e-6)}),
)

Tally = namedtuple("Tally", "axis value cells overturned subharmonic ratios")
Tally.__doc__ = """Overturnings of the cells that share one value of one axis.

axis, value : the axis and its value as written; cells, overturned, subharmonic : counts;
ratios : the period ratios n of the subharmonic ones, sorted."""


def counts(ds, rockings):
    """A ``Tally`` per value of every axis of a study (``rockings``: ``classify_dataset``)."""
    study = classify.study_of(ds)
    positions = np.indices(study.shape).reshape(len(study.dims), -1)
    over = np.zeros(study.n_cells, dtype=bool)
    over[list(rockings)] = True
    sub = {i: r.period_ratio for i, r in rockings.items() if r.kind == "subharmonic"}
    tallies = []
    for k, dim in enumerate(study.dims):
        for j in range(dim.size):
            cells = np.flatnonzero(positions[k] == j)
            ratios = sorted(round(sub[i], 2) for i in cells if i in sub)
            value = ", ".join(str(axis.values[j]) for axis in dim.axes)
            tallies.append(Tally(dim.name, value, cells.size, int(over[cells].sum()),
                                 len(ratios), ratios))
    return tallies


@contextlib.contextmanager
def classifier_constants(**values):
    """The rule constants of ``sweep.paper.classify`` set to ``values`` for the block."""
    saved = {name: getattr(classify, name) for name in values}
    for name, value in values.items():
        setattr(classify, name, value)
    try:
        yield
    finally:
        for name, value in saved.items():
            setattr(classify, name, value)


def _changed(scene, changes):
    """A copy of a resolved scene with ``changes`` ({dotted path: value or ('scale', f)})."""
    scene = {key: dict(value) if isinstance(value, dict) else value
             for key, value in scene.items()}
    for path, change in changes.items():
        section, *middle, key = path.split(".")
        node = scene[section]
        for part in middle:
            node[part] = dict(node[part])
            node = node[part]
        node[key] = node[key] * change[1] if isinstance(change, tuple) else change
    return scene


def robustness(ds, index, variants=VARIANTS):
    """The classification of cell ``index`` under each of ``variants``.

    Returns
    -------
    list of (str, Rocking or None)
        The variant's name and the rocking before the overturning (None: the body stood).
    """
    scene = classify.resolved_cell(classify.study_of(ds), index)
    scene["solver"]["dt_out"] = classify.DT_OUT
    found = []
    for name, constants, changes in variants:
        changed = _changed(scene, changes)
        result = run_scene(changed, history=True)
        result = result._replace(history=cf.history_dataset(result.history, changed))
        with classifier_constants(**constants):
            found.append((name, classify.classify_result(result)))
    return found


def _rocking_text(rocking):
    if rocking is None:
        return "stood"
    ratio = "" if np.isnan(rocking.period_ratio) else f" n = {rocking.period_ratio:.2f}"
    return f"{rocking.kind.replace('_', ' ')}{ratio}"


def report(ds, rockings=None):
    """Markdown: overturnings and subharmonic ones per axis value, each subharmonic cell with
    its point, and the classification of each under the ``VARIANTS``."""
    rockings = classify.classify_dataset(ds) if rockings is None else rockings
    study = classify.study_of(ds)
    v = ds["v_norm_at_overturn"].values.ravel()
    a = ds["a_norm_at_overturn"].values.ravel()
    kinds = [r.kind for r in rockings.values()]
    lines = [f"## {ds.attrs.get('title', '')}", "",
             f"{study.n_cells} cells, {len(rockings)} overturned during the sweep: "
             + ", ".join(f"{kinds.count(k)} {k.replace('_', ' ')}" for k in classify.KINDS),
             "", "| axis | value | cells | overturned | subharmonic | n |",
             "|---|---|---|---|---|---|"]
    for t in counts(ds, rockings):
        lines.append(f"| {t.axis} | {t.value} | {t.cells} | {t.overturned} | {t.subharmonic} "
                     f"| {', '.join(f'{n:g}' for n in t.ratios)} |")
    subharmonic = [i for i, r in rockings.items() if r.kind == "subharmonic"]
    if subharmonic:
        names = [name for name, _, _ in VARIANTS]
        lines += ["", "| cell | values | (v, a) | " + " | ".join(names) + " |",
                  "|---" * (3 + len(names)) + "|"]
        for i in subharmonic:
            values = "; ".join(f"{k} = {val}" for k, val in grid.cell_values(study, i).items())
            kinds = [_rocking_text(r) for _, r in robustness(ds, i)]
            lines.append(f"| {i} | {values} | ({v[i]:.3f}, {a[i]:.3f}) | "
                         + " | ".join(kinds) + " |")
    return "\n".join(lines + [""])


main = report_command(
    "sweep.paper.subharmonic",
    "Overturnings of sweep studies by the rocking before them, counted per condition.",
    report)


if __name__ == "__main__":
    sys.exit(main())
