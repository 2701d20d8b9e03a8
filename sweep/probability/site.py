"""What bodies seen at a site tell of its shaking, in probability (PROBABILITY.md section 6).

Every body of a site is simulated under an ensemble of motions (records, or synthetic motions
of a scenario), each motion scaled to a set of PGA levels x_j.  o_ijm in {0, 1} says whether
body i overturned under member m scaled to x_j.  The bodies seen overturned (set O) bound the
shaking from below, those left standing (set S) from above:

* **Site likelihood.**  The observation as a whole is reproduced by member m at level x_j when
  c_jm = prod_{i in O} o_ijm prod_{i in S} (1 - o_ijm) = 1.  The likelihood of x_j is the
  ensemble average L(x_j) = mean_m c_jm, taken directly from the simulations: the bodies
  shaken by the same motion are not independent, and the product of their marginal
  probabilities is not the likelihood (PROBABILITY.md section 6).
* **Posterior.**  Prior uniform in ln x over the levels; L linear in ln x between them, and 0
  at and below West's level of the most demanding overturned body, a_o = (B/H) g, below which
  no body rocks without vertical motion (a knot added there).  The posterior density in ln x
  is L normalised; its quantiles at the stated probabilities are the site's PGA bounds.  The
  PGV bounds are quantiles of the same posterior carried over to each member's PGV (its
  PGV/PGA is fixed by the record; ln PGV is linear in ln x between levels), so they hold for
  the ensemble's mix of PGV/PGA.  Where the likelihood is not 0 at the lowest (highest)
  level, the posterior is cut there by the range of levels, not by the bodies:
  ``cut_below`` and ``cut_above`` say so.
* **Support.**  The posterior is only as good as the simulations that reproduce every
  observation (c_jm = 1).  With one such simulation its shape is the triangle of the linear
  interpolation between the two levels around it, and its percentiles restate the spacing of
  the levels: with 12 levels and with 24 they differ by a factor 1.5.  The estimate says how
  many simulations, at how many levels, carry the likelihood (:class:`Support`), and gives no
  percentiles below :data:`MIN_MATCHES` simulations or :data:`MIN_LEVELS` levels; it says
  where more levels would help (between the levels around those with L > 0) and that more
  members would.
* **Per body.**  Fragility P_i(x_j) = fraction of the members that overturned it, with a 95 %
  Wilson interval; with the same knot at its own a_o.  An overturned body bounds x from below:
  x_lo(q) is the lowest x with P_i(x) = q (overturning below it had probability < q).  A
  standing body bounds x from above: x_hi(q) is the highest x with 1 - P_i(x) = q (above it,
  it survives with probability < q): the precarious-rock argument (Brune 1996; Purvance,
  Anooshehpoor & Brune 2008, EESD 37).  Both are
  interpolated in ln x; a bound outside the levels is said so (``beyond``: ``below`` the
  lowest level, ``above`` the highest).
* **(PGA, PGV) map.**  Each (member, level) is a point (PGA, PGV) of the scaled motion; its
  indicator c_jm.  The probability that a motion of (PGA, PGV) is consistent with every
  observation is the Gaussian-kernel (Nadaraya-Watson) average of c in (ln PGA, ln PGV/PGA),
  bandwidths the spacing of ln x and max(that, 1.06 sigma M^-1/5) (sigma: the spread of
  ln PGV/PGA over the M members), left blank where the kernel weights sum to less than
  :data:`MAP_SUPPORT`.  The region at level q is where it is at least q.  A probit surface
  cannot hold a band bounded on both sides (overturned below, standing above): hence the
  kernel average.
* **Sliding.**  A body whose friction coefficient (given, or the ensemble's default) is below
  B/H slides before it rocks (Ishiyama 1982, conclusion 1): it is kept out of the likelihood,
  not simulated, and listed with the reason.  A body that slid (``slid`` = 1) in most of the
  simulations at the two levels around its 50 % bound is flagged.

Each distinct body (B, H, i_g, mu) is one study: levels x members, run by ``python -m
sweep.run`` in this process (:func:`ensemble_datasets`) into ``<folder>/<key>.nc`` with the
study beside it as ``<key>.yaml``; a dataset whose fingerprint matches the inputs is reused,
so a second estimate is instant.  The study schema wants distinct values along every axis, and
bodies of one site often share B, H or mu, so the bodies cannot be one zipped dimension; one
study per body also lets an added body or a second site reuse what is done.  On a cluster:
``python -m sweep.estimate BODIES.yaml --write-study DIR`` writes the studies, ``mpiexec -n N
python -m sweep.run DIR/<key>.yaml`` runs each, and the estimate then reads their datasets.
SI units throughout.
"""
import math
import warnings
from collections import namedtuple
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..io import records
from ..io.problems import InputWarning
from ..io.scene_schema import T_TAIL
from ..paper import criteria
from ..paper import estimate as paper_estimate
from .fragility import counted

ARIAS_END = 0.95  # a motion "ends" when 95 % of its Arias intensity has arrived
MAP_POINTS = 121  # grid points along each axis of the (PGA, PGV) map
MAP_SUPPORT = 0.5  # the map is blank where the kernel weights (1 at a point) sum below this
SILVERMAN = 1.06  # normal-reference factor of the bandwidth in ln PGV/PGA
SLID_MOST = 0.5  # a body is flagged when more than this fraction of the cells near its bound slid
# The fewest simulations reproducing every body, and the fewest levels with L > 0, that give
# posterior percentiles: fewer, and the percentiles restate the spacing of the levels.
MIN_MATCHES = 5
MIN_LEVELS = 3
WILSON_CONFIDENCE = 0.95

Specimen = namedtuple("Specimen", "B H i_g mu")
Specimen.__doc__ = """What a simulation of a body needs [SI]: breadth, height, radius of
gyration (None: uniform) and friction coefficient."""

Bound = namedtuple("Bound", "value beyond")
Bound.__doc__ = """A bound [SI]: ``value``, or None when it lies above the highest level;
``beyond`` None inside the levels, ``"below"`` when it is at or below the lowest level (then
``value`` is that level), ``"above"`` when no level reaches it."""


# --- the bodies and their studies -------------------------------------------------------------

def friction(body, ensemble):
    """The friction coefficient simulated for ``body``: its own, else the ensemble's."""
    return ensemble.mu if body.mu is None else body.mu


def sliding_reason(body, ensemble):
    """Why ``body`` is kept out of the rocking bounds (mu < B/H), or None."""
    mu = friction(body, ensemble)
    if mu >= body.B / body.H:
        return None
    reason = paper_estimate.sliding_reason(mu, body.B, body.H)
    return reason if body.mu is not None else \
        f"{reason} (mu = {mu:g} is the ensemble's default: give the body's own if known)"


def specimen(body, ensemble):
    """The :class:`Specimen` simulated for ``body``."""
    return Specimen(body.B, body.H, body.i_g, friction(body, ensemble))


def specimen_key(spec):
    """A file name for a specimen: ``B24cm_H75cm_mu0.6``."""
    key = f"B{spec.B * 100:.6g}cm_H{spec.H * 100:.6g}cm"
    if spec.i_g is not None:
        key += f"_ig{spec.i_g * 100:.6g}cm"
    return key + f"_mu{spec.mu:.6g}"


def site_specimens(survey):
    """Every distinct specimen simulated for the sites of ``survey`` (sliding bodies left
    out), in order of first appearance."""
    found = {}
    for site in survey.sites:
        for body in site.bodies:
            if sliding_reason(body, survey.ensemble) is None:
                spec = specimen(body, survey.ensemble)
                found.setdefault(specimen_key(spec), spec)
    return found


def member_labels(ensemble):
    """A short label of each member: the record's name or file name, or ``seed k``."""
    if ensemble.records:
        return [r if r in records.NAMES else Path(r).name for r in ensemble.records]
    return [f"seed {k}" for k in range(ensemble.seeds)]


def member_records(ensemble):
    """The accelerogram (``io.records.Record``) of every member, before scaling."""
    if ensemble.records:
        return [records.load_record(r) if r in records.NAMES else records.read_record_file(r)
                for r in ensemble.records]
    from ..groundmotion import stochastic

    scenario = {k: v for k, v in ensemble.synthetic.items() if k != "dt"}
    dt = {} if ensemble.synthetic["dt"] is None else {"dt": ensemble.synthetic["dt"]}
    return [stochastic.generate(**scenario, seed=seed, **dt) for seed in range(ensemble.seeds)]


def arias_end(record, fraction=ARIAS_END):
    """Time [s] at which ``fraction`` of the record's Arias intensity has arrived."""
    husid = np.cumsum(np.square(record.samples))
    return float(np.searchsorted(husid, fraction * husid[-1]) * record.dt)


def simulated_time(ensemble):
    """``t_end`` of the studies: the ensemble's, else the latest time at which a member's
    Arias intensity reaches 95 %, plus ``T_TAIL`` for the body to settle or fall [s]."""
    if ensemble.t_end is not None:
        return ensemble.t_end
    return max(arias_end(r) for r in member_records(ensemble)) + T_TAIL


def study_dict(spec, ensemble, t_end, output, name="site"):
    """The study of one specimen under the ensemble: grid ``pga`` (levels) x ``record`` or
    ``seed`` (members), in that order; SI numbers (the levels with their unit, so that low
    ones are not taken for bare g), absolute paths."""
    body = {"B": spec.B, "H": spec.H, **({} if spec.i_g is None else {"i_g": spec.i_g})}
    contact = {"mu": spec.mu, **{k: v for k, v in (("e_x", ensemble.e_x), ("e_y", ensemble.e_y))
                                 if v is not None}}
    if ensemble.records:
        first = ensemble.records[0]
        excitation = {"kind": "record", **({"name": first} if first in records.NAMES
                                           else {"path": first})}
        members = {"record": list(ensemble.records)}
    else:
        excitation = {"kind": "synthetic", **{k: v for k, v in ensemble.synthetic.items()
                                              if v is not None}, "seed": 0}
        members = {"seed": list(range(ensemble.seeds))}
    return {"name": f"{name}_{specimen_key(spec)}",
            "title": f"B = {spec.B * 100:.4g} cm, H = {spec.H * 100:.4g} cm, mu = {spec.mu:g} "
                     "under a site's ensemble of motions (sweep.estimate)",
            "scene": {"body": body, "contact": contact,
                      "excitation": {"horizontal": excitation}, "solver": {"t_end": t_end}},
            "grid": {"pga": {"values": list(ensemble.levels), "unit": "m/s^2"}, **members},
            "output": str(Path(output).resolve())}


def results_folder(bodies_path):
    """Where the datasets of a bodies file go: ``results/<file stem>/`` beside it."""
    path = Path(bodies_path)
    return path.parent / "results" / path.stem


def write_studies(survey, folder, results):
    """Write the study of every specimen of ``survey`` to ``folder``, its output in
    ``results``; the paths written."""
    import yaml

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    t_end = simulated_time(survey.ensemble)
    name = "site" if survey.source is None else survey.source.stem
    written = []
    for key, spec in site_specimens(survey).items():
        study = study_dict(spec, survey.ensemble, t_end, Path(results) / f"{key}.nc", name)
        path = folder / f"{key}.yaml"
        path.write_text(yaml.safe_dump(study, sort_keys=False))
        written.append(path)
    return written


class RunFailed(RuntimeError):
    """A study of the estimate did not run to its end."""


def _run_study(path):
    """The dataset of the study at ``path`` and whether it was computed now: its output when
    the fingerprint of its inputs matches, else computed by ``python -m sweep.run`` in this
    process (``--force`` when the output or part files hold other inputs).  Its doubts of
    the PGA levels are not said again for every body: they are the bodies file's, said where
    it was read."""
    import xarray as xr

    from ..io.study_schema import load_study
    from ..runner import fingerprint, store
    from ..runner.command import main as run_command

    study = load_study(path, check_cells=False)
    stamp = fingerprint.combined(fingerprint.components(study))
    ran = not store.finished_earlier(study.output, stamp)
    if ran:
        parts = store.PartStore(store.parts_dir(study.output)).manifest_stamp()
        stale = study.output.exists() or parts not in (None, stamp)
        with warnings.catch_warnings():  # the levels were checked in the bodies file
            warnings.filterwarnings("ignore", r"grid\.pga\b", InputWarning)
            status = run_command([str(path), "--quiet", *(["--force"] if stale else [])])
        if status == 130:
            raise KeyboardInterrupt
        if status != 0:
            raise RunFailed(f"python -m sweep.run {path} ended with status {status}")
    with xr.open_dataset(study.output) as ds:
        return ds.load(), ran


def ensemble_datasets(survey, folder, say=None):
    """The dataset of every specimen of ``survey``: {key: xarray.Dataset}.

    The studies are written to ``folder`` (``<key>.yaml``) with their outputs beside them
    (``<key>.nc``) and run, or their outputs reused (:func:`_run_study`).  ``say(text)`` is
    told what was computed.
    """
    import time

    start = time.perf_counter()
    written = write_studies(survey, folder, folder)
    datasets, computed = {}, 0
    for path in written:
        datasets[path.stem], ran = _run_study(path)
        computed += ran
    if say is not None and computed:
        cells = len(survey.ensemble.levels) * survey.ensemble.members
        say(f"{computed} of {len(written)} bodies simulated ({cells} cells each) in "
            f"{time.perf_counter() - start:.1f} s; datasets in {folder}")
    return datasets


# --- the likelihood and the posterior ---------------------------------------------------------

def consistency(overturned, observed):
    """c_jm = prod_{i in O} o_ijm prod_{i in S} (1 - o_ijm): member m at level j reproduces
    every observation.

    Parameters
    ----------
    overturned : ndarray, shape (bodies, levels, members)
        o_ijm: 1 overturned, 0 standing, NaN failed.
    observed : array_like of bool, shape (bodies,)
        True for the bodies seen overturned.

    Returns
    -------
    ndarray, shape (levels, members)
        1 or 0; NaN where a body's simulation failed.
    """
    o = np.asarray(overturned, dtype=float)
    seen = np.asarray(observed, dtype=bool)[:, None, None]
    return np.prod(np.where(seen, o, 1.0 - o), axis=0)


def likelihood(consistent):
    """L(x_j) = mean over the members of c_jm, failed cells left out; and the members
    counted at each level.  NaN where none counts."""
    c = np.asarray(consistent, dtype=float)
    counted = np.sum(np.isfinite(c), axis=1)
    with np.errstate(invalid="ignore"):
        return np.nansum(c, axis=1) / counted, counted


def with_floor(u, values, floor):
    """Knots ``u`` and ``values`` (along axis 0) with a knot at ``floor`` of value 0 added when
    it lies strictly between two knots: the quantity is 0 there (West's level).  ``values``
    may have more axes (members); their knot is 0 too."""
    u = np.asarray(u, dtype=float)
    values = np.asarray(values, dtype=float)
    if floor is None or not u[0] < floor < u[-1] or np.any(u == floor):
        return u, values
    k = int(np.searchsorted(u, floor))
    return np.insert(u, k, floor), np.insert(values, k, 0.0, axis=0)


@dataclass(frozen=True)
class Pieces:
    """A density in ln x, linear between knots, carried over to a measure w (ln PGA or
    ln PGV) linear in ln x between the same knots: one trapezoid per member and segment.

    ``w0``, ``w1``: ends of each piece in w; ``d0``, ``d1``: density at its ends per unit
    ln x; ``du``: its width in ln x.  Mass of a piece: du (d0 + d1)/2.
    """

    w0: np.ndarray
    w1: np.ndarray
    d0: np.ndarray
    d1: np.ndarray
    du: np.ndarray

    @classmethod
    def build(cls, u, density, measure):
        """Pieces from knots ``u`` (K,), ``density`` (K, M) and ``measure`` w (K, M)."""
        du = np.diff(u)[:, None] * np.ones_like(density[1:])
        return cls(measure[:-1].ravel(), measure[1:].ravel(), density[:-1].ravel(),
                   density[1:].ravel(), du.ravel())

    @property
    def total(self):
        return float(np.sum(self.du * (self.d0 + self.d1)) / 2.0)

    def cdf(self, t):
        """Mass below ``t`` over the total (w increasing within each piece)."""
        f = np.clip((t - self.w0) / (self.w1 - self.w0), 0.0, 1.0)
        return float(np.sum(self.du * (self.d0 * f + (self.d1 - self.d0) * f * f / 2.0))
                     / self.total)

    def quantiles(self, probabilities):
        """The w at which the cdf reaches each probability (exact: within a bracket of
        breakpoints the cdf is a quadratic, solved by Brent's method)."""
        from scipy.optimize import brentq

        edges = np.unique(np.concatenate([self.w0, self.w1]))
        at = np.array([self.cdf(t) for t in edges])
        out = []
        for q in probabilities:
            k = int(np.searchsorted(at, q))
            if k == 0:
                out.append(edges[0])
            elif k == len(edges) or at[k] == q:
                out.append(edges[min(k, len(edges) - 1)])
            else:
                out.append(brentq(lambda t: self.cdf(t) - q, edges[k - 1], edges[k],
                                  xtol=1e-13, rtol=1e-14))
        return np.array(out, dtype=float)


@dataclass(frozen=True)
class Posterior:
    """The posterior of the level (PGA) given every observation at a site.

    Attributes
    ----------
    knots : ndarray, shape (K,)
        PGA [m/s^2] of the levels and of the West knot.
    density : ndarray, shape (K,)
        Posterior density per unit ln PGA at the knots (linear in ln PGA between them).
    pga, pgv : ndarray, shape (Q,)
        Quantiles [m/s^2, m/s] at the probabilities.
    cut_below, cut_above : bool
        The likelihood is not 0 at the lowest (highest) level: the lower (upper) quantiles
        are set by the range of levels, not by the observations.
    """

    knots: np.ndarray
    density: np.ndarray
    pga: np.ndarray
    pgv: np.ndarray
    cut_below: bool
    cut_above: bool


def posterior(levels, consistent, pgv, probabilities, floor=None):
    """The posterior of the level given the observations, and its quantiles.

    Parameters
    ----------
    levels : ndarray, shape (J,)
        PGA levels x_j [m/s^2], increasing.
    consistent : ndarray, shape (J, M)
        c_jm (:func:`consistency`); NaN for failed cells, which take the average of the
        others at their level (they neither add nor remove evidence).
    pgv : ndarray, shape (J, M)
        PGV of member m at level j [m/s].
    probabilities : sequence of float
    floor : float, optional
        West's level [m/s^2] of the most demanding overturned body: the likelihood is 0 at
        and below it.

    Returns
    -------
    Posterior or None
        None when no member reproduces the observations at any level.
    """
    u = np.log(np.asarray(levels, dtype=float))
    c = np.asarray(consistent, dtype=float)
    mean, _ = likelihood(c)
    if not np.nansum(mean) > 0:
        return None
    c = np.where(np.isfinite(c), c, np.nan_to_num(mean)[:, None])
    knots, density = with_floor(u, c, None if floor is None else math.log(floor))
    ln_pga = np.repeat(knots[:, None], c.shape[1], axis=1)
    ln_pgv = np.column_stack([np.interp(knots, u, np.log(pgv[:, m]))
                              for m in range(c.shape[1])])
    by_pga = Pieces.build(knots, density, ln_pga)
    by_pgv = Pieces.build(knots, density, ln_pgv)
    return Posterior(knots=np.exp(knots), density=density.sum(axis=1) / by_pga.total,
                     pga=np.exp(by_pga.quantiles(probabilities)),
                     pgv=np.exp(by_pgv.quantiles(probabilities)),
                     cut_below=bool(mean[0] > 0), cut_above=bool(mean[-1] > 0))


@dataclass(frozen=True)
class Support:
    """What carries the likelihood of a site.

    Attributes
    ----------
    matches : int
        Simulations (member, level) that reproduce every observation (c_jm = 1).
    cells : int
        Simulations counted (failed ones left out).
    levels : int
        Levels at which the likelihood is not 0; ``of_levels``: the levels simulated.
    between : tuple of float or None
        (low, high) [m/s^2]: the levels around those with L > 0, where more levels would
        resolve the posterior; None when no level has L > 0.
    """

    matches: int
    cells: int
    levels: int
    of_levels: int
    between: tuple

    @property
    def sufficient(self):
        """Enough to give percentiles (:data:`MIN_MATCHES`, :data:`MIN_LEVELS`)."""
        return self.matches >= MIN_MATCHES and self.levels >= MIN_LEVELS

    def text(self):
        """'3 of 48 simulations (at 2 of 12 levels)'."""
        return (f"{self.matches} of {self.cells} simulation{'s' if self.cells != 1 else ''} "
                f"(at {self.levels} of {self.of_levels} level{'s' if self.of_levels != 1 else ''})")


def support(levels, consistent):
    """The :class:`Support` of the likelihood of ``consistent`` (J, M) at ``levels`` (J,)."""
    c = np.asarray(consistent, dtype=float)
    hit = np.nansum(c, axis=1) > 0
    where = np.flatnonzero(hit)
    between = None if where.size == 0 else (float(levels[max(where[0] - 1, 0)]),
                                            float(levels[min(where[-1] + 1, len(levels) - 1)]))
    return Support(int(np.nansum(c)), int(np.sum(np.isfinite(c))), int(hit.sum()), len(levels),
                   between)


def support_advice(sup):
    """Why the percentiles are withheld, and what to do (or '' when they are given)."""
    if sup.sufficient:
        return ""
    low, high = sup.between
    return (f"only {sup.text()} reproduce every body; percentiles need at least "
            f"{MIN_MATCHES} simulations at {MIN_LEVELS} levels, else they restate the spacing "
            f"of the levels: add levels between {low * 100:.0f} and {high * 100:.0f} gal, or "
            "more motions")


# --- one body ---------------------------------------------------------------------------------

def _crossing(u, p, q, first):
    """Where ``p`` (at knots ``u``) crosses ``q``, interpolated in u.

    ``first``: the lowest u at which p reaches q (a fragility rising through q: a lower
    bound); else the highest u at which p still reaches q (a survival falling through q: an
    upper bound), so that p stays below q above it.  Returns ``(u or None, beyond, (k0, k1))``
    with ``beyond`` as in :class:`Bound` and the knots bracketing the crossing (None above).
    """
    p = np.asarray(p, dtype=float)
    if first:
        reached = np.flatnonzero(p >= q)
        if reached.size == 0:
            return None, "above", None
        k = int(reached[0])
        if k == 0:
            return u[0], "below", (0, 0)
        t = (q - p[k - 1]) / (p[k] - p[k - 1])
        return u[k - 1] + t * (u[k] - u[k - 1]), None, (k - 1, k)
    held = np.flatnonzero(p >= q)  # p is the survival here: the last knot where it holds
    if held.size == 0:
        return u[0], "below", (0, 0)
    k = int(held[-1])
    if k == len(u) - 1:
        return None, "above", None
    t = (p[k] - q) / (p[k] - p[k + 1])
    return u[k] + t * (u[k + 1] - u[k]), None, (k, k + 1)


def body_bound(levels, fragility, q, overturned, west=None):
    """The bound on the level that one body gives at probability ``q``.

    Parameters
    ----------
    levels : ndarray, shape (J,)
        PGA levels [m/s^2], increasing.
    fragility : ndarray, shape (J,)
        P_i(x_j), the fraction of members that overturned the body.
    q : float
    overturned : bool
        Seen overturned: the lower bound x_lo(q), the lowest x with P_i(x) = q; seen
        standing: the upper bound x_hi(q), the highest x with 1 - P_i(x) = q.
    west : float, optional
        The body's a_o = (B/H) g: P_i is 0 at and below it (a knot of value 0).

    Returns
    -------
    Bound
    """
    counted = np.isfinite(fragility)  # a level whose every simulation failed says nothing
    u, p = with_floor(np.log(levels)[counted], np.asarray(fragility)[counted],
                      None if west is None else math.log(west))
    if overturned:
        x, beyond, _ = _crossing(u, p, q, first=True)
    else:
        x, beyond, _ = _crossing(u, 1.0 - p, q, first=False)
    return Bound(None if x is None else float(math.exp(x)), beyond)


@dataclass(frozen=True)
class BodyEstimate:
    """One body of a site under the ensemble.

    Attributes
    ----------
    name : str
    overturned : bool
        As seen.
    B, H, mu : float
        Size [m] and the friction coefficient simulated.
    mu_given : bool
        ``mu`` is the body's own, not the ensemble's default.
    west : float
        a_o = (B/H) g [m/s^2].
    fragility, lower, upper : ndarray, shape (J,)
        P_i(x_j) and its 95 % Wilson interval.
    members : ndarray of int, shape (J,)
        Members counted at each level (failed cells left out).
    bounds : tuple of Bound
        At each probability: x_lo(q) for an overturned body, x_hi(q) for a standing one.
    slid : float
        Fraction of the cells at the two levels around the 50 % bound in which the body slid
        (NaN without such a bound).
    """

    name: str
    overturned: bool
    B: float
    H: float
    mu: float
    mu_given: bool
    west: float
    fragility: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    members: np.ndarray
    bounds: tuple
    slid: float

    @property
    def slid_near_bound(self):
        """True when the body slid in most of the simulations near its bound."""
        return bool(self.slid > SLID_MOST)


def body_estimate(body, ensemble, overturned, slid):
    """A :class:`BodyEstimate` from the body's outcomes.

    Parameters
    ----------
    body : io.bodies_schema.Body
    ensemble : io.bodies_schema.Ensemble
    overturned, slid : ndarray, shape (J, M)
        1/0 per level and member, NaN for failed cells.
    """
    from .intervals import wilson_interval

    levels = np.asarray(ensemble.levels)
    k = np.nansum(overturned, axis=1)
    n = np.sum(np.isfinite(overturned), axis=1)
    with np.errstate(invalid="ignore"):
        p = k / n
    lower, upper = wilson_interval(k, n, WILSON_CONFIDENCE)
    west = float(criteria.west_acceleration(body.B, body.H))
    bounds = tuple(body_bound(levels, p, q, body.overturned, west)
                   for q in ensemble.probabilities)
    u = np.log(levels)
    target = p if body.overturned else 1.0 - p
    _, _, bracket = _crossing(u, target, 0.5, first=body.overturned)
    near = np.nan if bracket is None else float(np.nanmean(slid[list(set(bracket))]))
    return BodyEstimate(name=body.name, overturned=body.overturned, B=body.B, H=body.H,
                        mu=friction(body, ensemble), mu_given=body.mu is not None, west=west,
                        fragility=p, lower=np.asarray(lower, float),
                        upper=np.asarray(upper, float), members=n, bounds=bounds, slid=near)


# --- the (PGA, PGV) map -----------------------------------------------------------------------

@dataclass(frozen=True)
class ConsistencyMap:
    """The probability that a motion of (PGA, PGV) reproduces every observation.

    Attributes
    ----------
    pga, pgv : ndarray, shape (A,), (V,)
        The map's axes [m/s^2, m/s], log-spaced over the simulated points.
    probability : ndarray, shape (V, A)
        Kernel average of the indicator; NaN where the points are too few (see the module).
    bandwidth : tuple of float
        In ln PGA and in ln PGV/PGA.
    points_pga, points_pgv, consistent : ndarray, shape (J, M)
        The simulated points and their indicator c_jm (NaN: failed).
    regions : tuple
        At each probability q: ``(pga_min, pga_max, pgv_min, pgv_max)`` of the map where the
        probability is at least q, or None where it never is.
    """

    pga: np.ndarray
    pgv: np.ndarray
    probability: np.ndarray
    bandwidth: tuple
    points_pga: np.ndarray
    points_pgv: np.ndarray
    consistent: np.ndarray
    regions: tuple


def bandwidths(levels, pga, pgv):
    """Kernel bandwidths in ln PGA (the spacing of ln x) and in ln PGV/PGA (Silverman's
    normal reference over the members' mean ln PGV/PGA, no narrower than the first)."""
    h_pga = float(np.median(np.diff(np.log(levels))))
    ratio = np.nanmean(np.log(pgv / pga), axis=0)
    spread = float(np.std(ratio, ddof=1)) if ratio.size > 1 else 0.0
    return h_pga, max(h_pga, SILVERMAN * spread * ratio.size ** -0.2)


def consistency_map(levels, pga, pgv, consistent, probabilities, points=MAP_POINTS):
    """The :class:`ConsistencyMap` of the points (pga, pgv) with indicators ``consistent``,
    all of shape (J, M)."""
    h_a, h_r = bandwidths(levels, pga, pgv)
    keep = np.isfinite(consistent)
    s_i, r_i = np.log(pga[keep]), np.log(pgv[keep] / pga[keep])
    c_i = consistent[keep]
    axis_a = np.geomspace(np.min(pga), np.max(pga), points)
    axis_v = np.geomspace(np.min(pgv), np.max(pgv), points)
    s = np.log(axis_a)[None, :, None]
    r = np.log(axis_v)[:, None, None] - s
    weight = np.exp(-0.5 * ((s - s_i) / h_a) ** 2 - 0.5 * ((r - r_i) / h_r) ** 2)
    total = weight.sum(axis=2)
    with np.errstate(invalid="ignore", divide="ignore"):
        probability = np.where(total >= MAP_SUPPORT, (weight * c_i).sum(axis=2) / total, np.nan)
    regions = []
    for q in probabilities:
        inside = probability >= q
        if not inside.any():
            regions.append(None)
            continue
        rows, cols = np.nonzero(inside)
        regions.append((axis_a[cols.min()], axis_a[cols.max()], axis_v[rows.min()],
                        axis_v[rows.max()]))
    return ConsistencyMap(axis_a, axis_v, probability, (h_a, h_r), pga, pgv, consistent,
                          tuple(regions))


# --- a site -----------------------------------------------------------------------------------

@dataclass(frozen=True)
class SiteEstimate:
    """What the bodies of one site tell under the ensemble (see the module).

    Attributes
    ----------
    site : io.bodies_schema.Site
    ensemble : io.bodies_schema.Ensemble
    members : list of str
        Labels of the motions.
    bodies : list of BodyEstimate
        The bodies that rock (kept in the likelihood), in the file's order.
    excluded : list of (str, str)
        Name and reason of the bodies kept out (they slide).
    likelihood : ndarray, shape (J,)
        L(x_j); ``counted``: the members counted at each level.
    posterior : Posterior or None
    reason : str
        Why there is no posterior ('' when there is one).
    west_floor : float or None
        a_o of the most demanding overturned body [m/s^2].
    map : ConsistencyMap or None
    support : Support or None
        What carries the likelihood (None: no body rocks).
    failed_cells : int
    t_end : float
        Simulated time [s].
    datasets : list of str
        The datasets read, one per body that rocks.
    """

    site: object
    ensemble: object
    members: list
    bodies: list
    excluded: list
    likelihood: np.ndarray
    counted: np.ndarray
    posterior: Posterior
    reason: str
    west_floor: float
    map: ConsistencyMap
    support: Support
    failed_cells: int
    t_end: float
    datasets: list = field(default_factory=list)

    @property
    def quantiles(self):
        """The posterior's (pga, pgv) at the probabilities, or None when there is no
        posterior or too little :class:`Support` for percentiles."""
        if self.posterior is None or not self.support.sufficient:
            return None
        return self.posterior.pga, self.posterior.pgv


def _cells(ds, name):
    """A variable of a specimen's dataset as float (levels, members), NaN where failed."""
    values = ds[name].transpose("pga", ...).values.astype(float)
    return np.where(values < 0, np.nan, values)


def estimate_site(site, ensemble, datasets):
    """The probabilistic estimate of one site from the datasets of its specimens.

    Parameters
    ----------
    site : io.bodies_schema.Site
    ensemble : io.bodies_schema.Ensemble
    datasets : dict of str to xarray.Dataset
        {specimen key: dataset} (:func:`ensemble_datasets`), with dimensions ``pga`` and the
        members' (``record`` or ``seed``).

    Returns
    -------
    SiteEstimate
    """
    excluded, rocking = [], []
    for body in site.bodies:
        reason = sliding_reason(body, ensemble)
        if reason is None:
            rocking.append(body)
        else:
            excluded.append((body.name, reason))
    levels = np.asarray(ensemble.levels)
    common = {"site": site, "ensemble": ensemble, "members": member_labels(ensemble),
              "excluded": excluded, "t_end": simulated_time(ensemble)}
    if not rocking:
        return SiteEstimate(**common, bodies=[], likelihood=np.full(levels.size, np.nan),
                            counted=np.zeros(levels.size, int), posterior=None,
                            reason="no body that rocks: every body slides (mu < B/H)",
                            west_floor=None, map=None, support=None, failed_cells=0)
    keys = [specimen_key(specimen(b, ensemble)) for b in rocking]
    overturned = np.stack([_cells(datasets[k], "overturned") for k in keys])
    slid = np.stack([_cells(datasets[k], "slid") for k in keys])
    bodies = [body_estimate(b, ensemble, o, s) for b, o, s in zip(rocking, overturned, slid)]
    consistent = consistency(overturned, [b.overturned for b in rocking])
    mean, counted = likelihood(consistent)
    pgv = _cells(datasets[keys[0]], "pgv")
    pga = np.broadcast_to(levels[:, None], pgv.shape).copy()
    floor = max((b.west for b in bodies if b.overturned), default=None)
    post = posterior(levels, consistent, pgv, ensemble.probabilities, floor)
    reason = "" if post is not None else (
        "no member reproduces every observation at any level: the bodies seen contradict "
        "each other under this ensemble (or the levels miss the band where they agree)")
    return SiteEstimate(**common, bodies=bodies, likelihood=mean, counted=counted,
                        posterior=post, reason=reason, west_floor=floor,
                        support=support(levels, consistent),
                        map=consistency_map(levels, pga, pgv, consistent,
                                            ensemble.probabilities),
                        failed_cells=int(np.sum(~np.isfinite(overturned))),
                        datasets=[str(datasets[k].encoding.get("source", k)) for k in keys])


# --- output -----------------------------------------------------------------------------------

MAP_METHOD = ("Gaussian-kernel average of the consistency indicator in (ln PGA, ln PGV/PGA); "
              "the region at q is where it is at least q")
PRIOR = "uniform in ln PGA over the levels"


def _peak(consistency_map):
    """The largest probability of the map (NaN when it is blank)."""
    finite = consistency_map.probability[np.isfinite(consistency_map.probability)]
    return float(finite.max()) if finite.size else math.nan


def _bounds_json(bounds, probabilities):
    return [{"probability": q, "value": b.value, "beyond": b.beyond}
            for q, b in zip(probabilities, bounds)]


def summary(estimate):
    """The estimate of a site as a JSON-ready dict, SI units; lists of probabilities are in
    the order of ``probabilities``."""
    ens = estimate.ensemble
    post, m, sup = estimate.posterior, estimate.map, estimate.support
    quantiles = estimate.quantiles
    return {
        "members": estimate.members, "levels": list(ens.levels), "t_end": estimate.t_end,
        "probabilities": list(ens.probabilities), "mu_default": ens.mu,
        "failed_cells": estimate.failed_cells,
        "excluded": [{"name": name, "reason": reason} for name, reason in estimate.excluded],
        "bodies": [{"name": b.name, "overturned": b.overturned, "B": b.B, "H": b.H, "mu": b.mu,
                    "mu_given": b.mu_given, "a_o": b.west, "fragility": b.fragility,
                    "fragility_lower": b.lower, "fragility_upper": b.upper,
                    "members_counted": b.members,
                    "bound": "lower" if b.overturned else "upper",
                    "bounds": _bounds_json(b.bounds, ens.probabilities),
                    "slid_near_bound": b.slid, "slid_flag": b.slid_near_bound}
                   for b in estimate.bodies],
        "likelihood": estimate.likelihood, "members_counted": estimate.counted,
        "support": None if sup is None else {
            "simulations_reproducing": sup.matches, "simulations": sup.cells,
            "levels_with_likelihood": sup.levels, "levels": sup.of_levels,
            "sufficient": sup.sufficient, "minimum": {"simulations": MIN_MATCHES,
                                                      "levels": MIN_LEVELS},
            "add_levels_between": None if sup.between is None else list(sup.between)},
        "posterior": None if post is None else {
            "prior": PRIOR, "pga": None if quantiles is None else quantiles[0],
            "pgv": None if quantiles is None else quantiles[1], "cut_below": post.cut_below,
            "cut_above": post.cut_above, "west_floor": estimate.west_floor,
            "percentiles_withheld": support_advice(sup)},
        "posterior_note": estimate.reason,
        "region": None if m is None else {
            "method": MAP_METHOD, "bandwidth_ln_pga": m.bandwidth[0],
            "bandwidth_ln_pgv_over_pga": m.bandwidth[1],
            "peak": _peak(m),
            "levels": [{"probability": q, "pga": None if r is None else [r[0], r[1]],
                        "pgv": None if r is None else [r[2], r[3]]}
                       for q, r in zip(ens.probabilities, m.regions)]},
        "datasets": estimate.datasets,
    }


def _gal(a):
    return f"{a * 100:.0f}"


def _bound_text(bound, levels):
    if bound.beyond == "above":
        return f"> {_gal(levels[-1])}"
    if bound.beyond == "below":
        return f"<= {_gal(bound.value)}"
    return _gal(bound.value)


def format_text(estimate, lower_limits=None, width=92):
    """The estimate as tables and sentences, in the paper's units (gal, cm/s); with the
    deterministic ``lower_limits`` (``sweep.paper.estimate``) side by side."""
    import textwrap

    ens = estimate.ensemble
    levels = ens.levels
    qs = " / ".join(f"{q:.0%}" for q in ens.probabilities)
    lines = [textwrap.fill(
        f"Ensemble: {counted(len(estimate.members), 'motion')} "
        f"({', '.join(estimate.members[:6])}"
        f"{', ...' if len(estimate.members) > 6 else ''}) scaled to {len(levels)} PGA levels "
        f"from {_gal(levels[0])} to {_gal(levels[-1])} gal, simulated for "
        f"{estimate.t_end:.1f} s; mu = {ens.mu:g} for the bodies that give none.", width)]
    if estimate.failed_cells:
        lines.append(f"{counted(estimate.failed_cells, 'simulation')} failed; left out of the "
                     "counts.")
    for name, reason in estimate.excluded:
        lines.append(textwrap.fill(f"Kept out: {name}: {reason}.", width,
                                   subsequent_indent="  "))
    if estimate.bodies:
        header = (f"{'body':<18} {'state':<10} {'a_o [gal]':>9}  {'slid':>4}  "
                  f"bound at {qs} [gal]")
        lines += ["", header, "-" * len(header)]
        note = ("slid: share of the simulations at the two levels around the body's 50 % "
                "bound in which it slid")
    for b in estimate.bodies:
        kind = "lower" if b.overturned else "upper"
        bounds = " / ".join(_bound_text(x, levels) for x in b.bounds)
        slid = "most" if b.slid_near_bound else "" if np.isnan(b.slid) else f"{b.slid:.0%}"
        lines.append(f"{b.name[:18]:<18} {'overturned' if b.overturned else 'standing':<10} "
                     f"{_gal(b.west):>9}  {slid:>4}  {kind}: {bounds}")
    if estimate.bodies:
        lines.append(note)
    flagged = [b.name for b in estimate.bodies if b.slid_near_bound]
    if flagged:
        lines.append(textwrap.fill(
            f"Slid in most of the simulations near their bound: {', '.join(flagged)} (the "
            "bound mixes sliding with rocking; a known mu would help).", width))
    lines.append("")
    post = estimate.posterior
    if post is None:
        lines.append(textwrap.fill(f"No posterior: {estimate.reason}.", width))
        return "\n".join(lines)
    lines.append(textwrap.fill(
        f"The site's shaking given every body (posterior, prior {PRIOR}), carried by "
        f"{estimate.support.text()} that reproduce every body:", width))
    quantiles = estimate.quantiles
    head = f"{'':<12} {'deterministic':>16}  " + ("  ".join(
        f"{q:>7.0%}" for q in ens.probabilities) if quantiles else "")
    lines.append(head.rstrip())
    for k, (key, unit, shown) in enumerate((("pga", "gal", _gal),
                                            ("pgv", "cm/s", lambda v: f"{v * 100:.3g}"))):
        limit = "" if lower_limits is None else f">= {shown(lower_limits[key]['value'])}"
        values = "  ".join(f"{shown(v):>7}" for v in quantiles[k]) if quantiles else ""
        lines.append(f"{key.upper() + ' [' + unit + ']':<12} {limit:>16}  {values}".rstrip())
    if not quantiles:
        lines.append(textwrap.fill(f"  Percentiles withheld: {support_advice(estimate.support)}.",
                                   width, subsequent_indent="  "))
    if post.cut_below or post.cut_above:
        ends = [end for end, cut in (("lowest", post.cut_below), ("highest", post.cut_above))
                if cut]
        lines.append(textwrap.fill(
            f"  The likelihood is not 0 at the {' and '.join(ends)} level: the quantiles on "
            "that side are set by the range of levels, not by the bodies.", width,
            subsequent_indent="  "))
    m = estimate.map
    lines.append("Motions consistent with every body, in (PGA, PGV):")
    for q, region in zip(ens.probabilities, m.regions):
        if region is None:
            lines.append(f"  at >= {q:.0%}: nowhere (at most {_peak(m):.0%})")
        else:
            lines.append(f"  at >= {q:.0%}: PGA {_gal(region[0])}-{_gal(region[1])} gal, "
                         f"PGV {region[2] * 100:.3g}-{region[3] * 100:.3g} cm/s")
    return "\n".join(lines)
