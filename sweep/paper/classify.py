"""Kind of rocking that preceded an overturning (Ishiyama 1982, Figs 11-16).

The paper names three: *inverse phase* rocking (mostly in constant-acceleration sweeps, its
curve a), *subharmonic* rocking (curve b) and *in phase* rocking, repeated "only a few times"
(constant velocity or displacement sweeps, line c).  A study's dataset does not keep
histories, so a cell is simulated again with its history (``simulate_cell``; the run is
deterministic and overturns at the same instant) and the rocking before the overturning is
classified (``classify_history``).  ``find_overturning`` picks, for a panel of Figs 12-16, the
overturning of a kind nearest to point P and returns it with its history, for
``sweep.plots.histories`` to draw.

Rule (θ > 0 is rotation about the left corner, which a floor acceleration a_x > 0 drives):

1. Tilt side: s(t) = +1 once θ > ε α, -1 once θ < -ε α, unchanged in between (hysteresis
   ε = ``EPSILON``: chatter and small bounces near θ = 0 are not rocking).  The body rocks
   a half-cycle from one change of s to the next.  The final excursion starts when |θ| last
   rises through ε α and ends in the overturning.
2. The rocking episode before it starts after the last stretch of |θ| <= ε α longer than one
   floor period (the body stood still); the window is its last ``HALF_CYCLES`` half-cycles.
3. Fewer than ``MIN_HALF_CYCLES`` (a few cycles at most): the phase c = Σ a_x s / Σ |a_x| over
   the final excursion, until |θ| reaches α (beyond it gravity alone throws the body over),
   decides: ``in_phase`` if c > 0 (the floor acceleration pushes the body over), else
   ``inverse_phase``; the period ratio is NaN.
4. Otherwise: period ratio n = T_body/T_floor, with T_body the median length of the body
   cycles in the window (each two successive half-cycles, so that rocking lopsided by a
   vertical floor motion is still steady) and T_floor twice the mean spacing of the zero
   crossings of a_x in the window.  Fewer than ``REGULAR`` of the cycles within ``TOLERANCE``
   of the median length, or n < ``HARMONIC[0]`` (the body rocks faster than the floor):
   ``irregular``.
   n >= ``HARMONIC[1]``: ``subharmonic`` (one body cycle over about n floor cycles).
   Else (one body cycle per floor cycle) the phase c over the window decides: c > 0
   ``in_phase`` (the body leans to the side the floor acceleration drives it to), c <= 0
   ``inverse_phase`` (it leans against it).
"""
from collections import namedtuple

import numpy as np

from kernels import run_scene

from .. import cf
from ..io.scene_schema import load_scene, resolve_scene
from ..io.study_schema import load_study
from ..runner import grid
from .criteria import POINT_P, body_constants

KINDS = ("in_phase", "inverse_phase", "subharmonic", "irregular")
EPSILON = 0.05      # |θ|/α above which the body counts as tilted to one side (step 1)
HALF_CYCLES = 10    # rocking half-cycles (five body cycles) examined before the final one
MIN_HALF_CYCLES = 4  # fewer: "a few times" (the paper's in phase overturning), step 3
HARMONIC = (0.75, 1.5)  # period ratios of one body cycle per floor cycle
TOLERANCE = 0.25    # relative distance from the median of a regular cycle length
REGULAR = 0.6       # share of regular cycles that makes the rocking steady (the escape
                    # itself disturbs the last two or three)
DT_OUT = 0.002      # s, history sampling of a re-simulated cell (>= 39 samples per 12.8 Hz cycle)

Rocking = namedtuple("Rocking", "kind period_ratio phase half_cycles t_start t_final")
Rocking.__doc__ = """Classification of the rocking before an overturning.

kind : one of ``KINDS``; period_ratio : T_body/T_floor (NaN after a few cycles at most);
phase : c of the rule, in [-1, 1]; half_cycles : number of half-cycles in the window;
t_start : start of the window [s]; t_final : start of the final excursion [s]."""


def tilt_side(theta, alpha, epsilon=EPSILON):
    """Side s(t) = +1/-1 to which the body leans, with hysteresis ε α (0 before any tilt)."""
    side = np.where(theta > epsilon * alpha, 1, np.where(theta < -epsilon * alpha, -1, 0))
    index = np.where(side != 0, np.arange(side.size), -1)
    last = np.maximum.accumulate(index)  # the latest sample that was clearly tilted
    return np.where(last >= 0, side[np.maximum(last, 0)], 0)


def _zero_crossings(t, a):
    """Times at which ``a`` changes sign (linear interpolation between samples)."""
    k = np.flatnonzero((a[1:] > 0.0) != (a[:-1] > 0.0))
    return t[k] - a[k] * (t[k + 1] - t[k]) / (a[k + 1] - a[k])


def _phase(a_x, side):
    """c = Σ a_x s / Σ |a_x|: +1 when the floor always drives the body to its side."""
    total = np.sum(np.abs(a_x))
    return float(np.sum(a_x * side) / total) if total > 0.0 else 0.0


def _episode_start(t, tilted, rises, final, t_floor):
    """First rise of |θ| through ε α after the last still stretch longer than ``t_floor``."""
    edges = np.diff(np.concatenate([[0], (~tilted).astype(np.int8), [0]]))
    starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    long = (ends <= final) & (t[ends - 1] - t[starts] > t_floor)
    begin = ends[long][-1] if np.any(long) else 0
    return rises[rises >= begin][0]


def classify_history(t, theta, a_x, alpha, t_overturn=None):
    """Classify the rocking before an overturning from sampled histories.

    Parameters
    ----------
    t, theta, a_x : ndarray, shape (n,)
        Times [s] (uniform sampling), rotation [rad] and horizontal floor acceleration
        [m/s^2].
    alpha : float
        Slenderness angle [rad].
    t_overturn : float, optional
        Time of overturning; samples after it are left out (default: the whole history).

    Returns
    -------
    Rocking
    """
    t, theta, a_x = (np.asarray(v, dtype=float) for v in (t, theta, a_x))
    if t_overturn is not None:
        keep = t <= t_overturn
        t, theta, a_x = t[keep], theta[keep], a_x[keep]
    tilted = np.abs(theta) > EPSILON * alpha
    rises = np.flatnonzero(tilted & ~np.concatenate([[False], tilted[:-1]]))
    if rises.size == 0:
        raise ValueError("the body never tilted by more than "
                         f"{EPSILON} alpha: no rocking to classify")
    final = rises[-1]
    side = tilt_side(theta, alpha)
    floor = _zero_crossings(t[:final + 1], a_x[:final + 1])[-9:]
    first = _episode_start(t, tilted, rises, final,
                           2.0 * np.median(np.diff(floor)) if floor.size >= 2 else np.inf)
    switches = np.flatnonzero(side[1:] != side[:-1]) + 1
    bounds = np.unique(np.concatenate([[first], switches[(switches > first) & (switches < final)],
                                       [final]]))[-HALF_CYCLES - 1:]
    half_cycles = bounds.size - 1
    if half_cycles < MIN_HALF_CYCLES:  # step 3: pushed over after a few cycles at most
        over = final + max(1, int(np.argmax(np.abs(theta[final:]) >= alpha)))
        phase = _phase(a_x[final:over], side[final:over])
        kind = "in_phase" if phase > 0.0 else "inverse_phase"
        return Rocking(kind, np.nan, phase, int(half_cycles), float(t[bounds[0]]),
                       float(t[final]))
    i0 = bounds[0]
    crossings = _zero_crossings(t[i0:final + 1], a_x[i0:final + 1])
    cycles = t[bounds[2:]] - t[bounds[:-2]]
    t_body = np.median(cycles)
    t_floor = (2.0 * (crossings[-1] - crossings[0]) / (crossings.size - 1)
               if crossings.size >= 2 else np.inf)
    ratio = t_body / t_floor
    phase = _phase(a_x[i0:final], side[i0:final])
    regular = np.mean(np.abs(cycles / t_body - 1.0) <= TOLERANCE)
    if regular < REGULAR or ratio < HARMONIC[0]:
        kind = "irregular"
    elif ratio >= HARMONIC[1]:
        kind = "subharmonic"
    else:
        kind = "in_phase" if phase > 0.0 else "inverse_phase"
    return Rocking(kind, float(ratio), phase, int(half_cycles), float(t[i0]), float(t[final]))


# --- cells of a study -------------------------------------------------------------------------

def study_of(ds):
    """The study a dataset was run from (``sweep.run`` keeps its text in ``ds.attrs``)."""
    return load_study(ds.attrs.get("study_file") or "study.yaml", text=ds.attrs["study"])


def simulate_cell(study, index, dt_out=DT_OUT):
    """Simulate cell ``index`` of a study again, with its history sampled every ``dt_out`` s.

    Returns the kernel's ``SceneResult`` with ``history`` as a Dataset (``cf.history_dataset``).
    """
    scene = resolved_cell(study, index)
    scene["solver"]["dt_out"] = dt_out  # output sampling only: the trajectory is the same
    result = run_scene(scene, history=True)
    return result._replace(history=cf.history_dataset(result.history, scene))


def classify_result(result):
    """The :class:`Rocking` before the overturning of a simulated scene (None if it stood)."""
    if not result.overturned:
        return None
    h = result.history
    alpha = float(body_constants(h.attrs["B"], h.attrs["H"]).alpha)
    return classify_history(h["time"].values, h["theta"].values, h["a_x"].values, alpha,
                            result.t_overturn)


def resolved_cell(study, index):
    """The resolved SI scene of cell ``index`` of a study (``io.scene_schema.resolve_scene``)."""
    return resolve_scene(load_scene(grid.cell_scene(study, int(index)), base_dir=study.base_dir))


def excitation_end(scene):
    """Time [s] at which the horizontal excitation of a resolved scene stops (inf: never)."""
    ground = scene["excitation"]["horizontal"]
    if ground["kind"] == "none" or ground["duration"] is None:
        return np.inf
    return ground["start"] + ground["duration"]


def amplitude_dim(study):
    """Position of the dimension that is the ``amplitude`` axis alone, or None."""
    return next((k for k, dim in enumerate(study.dims)
                 if len(dim.axes) == 1 and dim.axes[0].name == "amplitude"), None)


def scene_groups(study):
    """Cells that differ only in the amplitude of the horizontal motion, and their scene.

    Every axis but a lone ``amplitude`` changes the body, the contact or the timing of the
    motion, so one resolved scene per combination of those axes describes the cells of that
    combination but for their amplitude (which the dataset's ``amplitude`` coordinate gives).

    Returns
    -------
    group : ndarray of int, shape (n_cells,)
        The group of each cell.
    scenes : list of dict
        The resolved scene of each group's first cell.
    """
    k = amplitude_dim(study)
    if k is None:
        group = np.arange(study.n_cells)
    else:
        others = [d for d in range(len(study.dims)) if d != k]
        positions = np.indices(study.shape).reshape(len(study.dims), -1)[others]
        group = (np.ravel_multi_index(positions, [study.dims[d].size for d in others])
                 if others else np.zeros(study.n_cells, dtype=int))
    first = np.unique(group, return_index=True)[1]
    return group, [resolved_cell(study, i) for i in first]


def overturned_cells(ds):
    """Cell ids (flat indices in the study's order) of the cells that overturned while the
    floor was shaking; an overturning after the excitation stopped is left out."""
    group, scenes = scene_groups(study_of(ds))
    end = np.array([excitation_end(scene) for scene in scenes])[group]
    t_overturn = ds["t_overturn"].values.ravel()
    cells = np.flatnonzero(ds["overturned"].values.ravel() == 1)
    return cells[t_overturn[cells] <= end[cells]].astype(int)


def classify_dataset(ds, cells=None):
    """Classify the overturned cells of a study's dataset by simulating them again.

    Parameters
    ----------
    ds : xarray.Dataset
        A dataset of ``sweep.run`` (its ``study`` attribute gives the cells' scenes).
    cells : array_like of int, optional
        Cell ids to classify; default ``overturned_cells(ds)``.

    Returns
    -------
    dict of int to Rocking
        One entry per overturned cell id; a cell that stood in the second simulation
        (a chaotic trajectory can differ) is left out.
    """
    study = study_of(ds)
    cells = overturned_cells(ds) if cells is None else cells
    found = {}
    for index in cells:
        rocking = classify_result(simulate_cell(study, index))
        if rocking is not None:
            found[int(index)] = rocking
    return found


def dataset_key(ds):
    """What the classification of a dataset's cells depends on: the study it was run from."""
    return ds.attrs.get("study_file"), ds.attrs["study"]


def classifications(datasets, known=None):
    """``classify_dataset`` of each dataset, taken from ``known`` ({``dataset_key``: its
    classification}) where it is there."""
    known = known or {}
    return [known[dataset_key(ds)] if dataset_key(ds) in known else classify_dataset(ds)
            for ds in datasets]


# --- the histories of Figs 12-16 -----------------------------------------------------------

Panel = namedtuple("Panel", "kind holds steady title")
Panel.__doc__ = """A history to draw: the rocking ``kind``, the sweeps (``holds``) it may come
from, whether it must come from steady rocking (a finite period ratio, not a few cycles), and
the panel's title."""

INVERSE = Panel("inverse_phase", ("acceleration",), True,
                "overturning from inverse phase rocking (constant acceleration)")
SUBHARMONIC = Panel("subharmonic", ("acceleration", "velocity", "displacement"), True,
                    "overturning from subharmonic rocking")
FIGURE_PANELS = {  # figure: (title, panels); a one-panel title is completed by the sweep
    "fig12": ("Fig. 12: three kinds of rocking motion before overturning",
              (INVERSE, SUBHARMONIC,
               Panel("in_phase", ("velocity", "displacement"), False,
                     "overturning from in phase rocking (constant velocity or displacement)"))),
    "fig13": ("Fig. 13", (INVERSE,)),
    "fig14": ("Fig. 14", (SUBHARMONIC,)),
    "fig15": ("Fig. 15", (Panel("in_phase", ("velocity",), False, ""),)),
    "fig16": ("Fig. 16", (Panel("in_phase", ("displacement",), False, ""),)),
}
Found = namedtuple("Found", "ds study index values result rocking")
Found.__doc__ = """An overturning of the wanted kind: its dataset, study, cell id, the raw value
of every axis in that cell, the scene result with its history, and the classification."""


def _distance_to_p(ds, cells):
    """Log distance of the cells' overturning points from P in the normalized plane."""
    v = ds["v_norm_at_overturn"].values.ravel()[cells]
    a = ds["a_norm_at_overturn"].values.ravel()[cells]
    return np.hypot(np.log(v / POINT_P[0]), np.log(a / POINT_P[1]))


def find_overturning(datasets, panel, known=None):
    """The overturning of ``panel.kind`` nearest to P among the sweeps holding one of
    ``panel.holds`` (a ``Found``, or None), and the number of overturnings examined.

    A candidate of a dataset in ``known`` ({``dataset_key``: ``classify_dataset``}) is not
    simulated again to be classified; only the overturning found is, for its history.
    """
    known = known or {}
    candidates = []
    for k, ds in enumerate(datasets):
        study = study_of(ds)
        if study.excitation.get("hold", "acceleration") not in panel.holds:
            continue
        cells = overturned_cells(ds)
        candidates += [(d, k, int(i), study) for d, i in zip(_distance_to_p(ds, cells), cells)]
    for examined, (_, k, index, study) in enumerate(sorted(candidates, key=lambda c: c[:3])):
        classified = known.get(dataset_key(datasets[k]))
        result = None if classified is not None else simulate_cell(study, index)
        rocking = classify_result(result) if classified is None else classified.get(index)
        steady = rocking is not None and not np.isnan(rocking.period_ratio)
        if rocking is not None and rocking.kind == panel.kind and (steady or not panel.steady):
            if result is None:
                result = simulate_cell(study, index)
            return Found(datasets[k], study, index, grid.cell_values(study, index), result,
                         rocking), examined + 1
    return None, len(candidates)


def figure_overturnings(datasets, figure, known=None):
    """The overturning of each panel of ``figure`` (a key of ``FIGURE_PANELS``): a list of
    ``(Found or None, overturnings examined)``, one per panel (``known`` as for
    :func:`find_overturning`)."""
    return [find_overturning(datasets, panel, known) for panel in FIGURE_PANELS[figure][1]]
