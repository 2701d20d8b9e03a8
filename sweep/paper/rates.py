"""How the overturning points of frequency sweeps move with the sweep rate, and their slow limit.

A rate study (``studies/rate_study_*.yaml``) sweeps the same levels over several durations,
each from several starting phases (``phase`` or ``seed``, the ensemble), and may vary other
axes (``solver.method``: adaptive or the paper's fixed 1 ms step).  The rate is given as the
octave duration T = duration / log2(f_start/f_stop) [s per octave].  For each level and T the
quantity swept through at overturning (v/v_H for constant-acceleration sweeps, whose velocity
amplitude grows; a/((B/H) g) for constant velocity or displacement) is summarized over the
ensemble, and ``fit_slow_limit`` extrapolates it to T -> infinity with
y(T) = y_inf + c (T/T_0)^-k (``scipy.optimize.curve_fit``, its covariance for the interval).
``python -m sweep.paper.rates RESULT.nc ...`` prints the tables of ``docs/reproduction.md``.
"""
import sys
from collections import namedtuple

import numpy as np
from scipy import optimize, stats

from ..cli import report_command
from ..io import units
from . import classify, plane

ENSEMBLE_AXES = ("phase", "seed")  # axes whose cells are members of one ensemble
REPORTED_LEVELS = {"acceleration": (1.1, 1.5, 2.0)}  # levels of the per-rate table
CONFIDENCE = 0.95
K_BOUNDS = (0.05, 3.0)  # exponent k of the fit; a saddle-node passed slowly gives 2/3
MISFIT_P = 0.05  # chi2 above its (1 - MISFIT_P) quantile: the scatter is more than sigma says

RateCells = namedtuple("RateCells", "hold body unit level octave_time series labels value "
                                    "point")
RateCells.__doc__ = """The cells of one rate study.

hold : the amplitude held; body : text naming the body; unit : the unit of the levels as
written ('west', 'v_H', 'mm'); level, octave_time : ndarray, shape (n,), the held level (as
written) and T [s per octave]; series : int array, the combination of the axes other than
amplitude, duration and the ensemble; labels : one text per series; value : ndarray, shape
(n,), the swept quantity at overturning during the sweep (v for constant acceleration, a
otherwise), NaN if the body stood or overturned after the sweep; point : ndarray, shape (n, 2),
(v, a) at overturning (NaN likewise)."""

Summary = namedtuple("Summary", "levels octave_times count overturned median mean sem low high")
Summary.__doc__ = """The swept quantity at overturning per series, level and T.

levels, octave_times : the sorted values; count, overturned : int arrays, shape
(n_series, n_levels, n_T), cells and overturnings; median, mean, sem (standard error of the
mean, NaN with fewer than two overturnings), low, high (smallest and largest) : float arrays of
that shape over the overturned members."""

SlowLimit = namedtuple("SlowLimit", "value se low high k k_se c residuals chi2 dof scaled")
SlowLimit.__doc__ = """Fit y(T) = value + c (T/T_0)^-k.

value, se : the limit y(T -> inf) and its standard error; low, high : its ``CONFIDENCE``
interval; k, k_se : the exponent and its standard error; c : the coefficient at T_0 (the
shortest T); residuals : (y - fit)/sigma (or y - fit without sigma); chi2 : sum of the
squared normalized residuals (NaN without sigma); dof : n - 3; scaled : True when the
standard errors were scaled by the residuals (no sigma given, or a chi2 that the given sigma
cannot explain, p < ``MISFIT_P``)."""


def swept_quantity(hold):
    """'v' for a constant-acceleration sweep (the velocity amplitude it sweeps through),
    else 'a'."""
    return "v" if hold == "acceleration" else "a"


def _dims_of(study):
    """Position of the amplitude, duration and ensemble dimensions, and of the others."""
    roles = {}
    for k, dim in enumerate(study.dims):
        names = [axis.name for axis in dim.axes]
        if names == ["amplitude"]:
            roles[k] = "amplitude"
        elif any(name.endswith("duration") for name in names):
            roles[k] = "duration"
        elif any(name in ENSEMBLE_AXES for name in names):
            roles[k] = "ensemble"
    return roles, [k for k in range(len(study.dims)) if k not in roles]


def rate_cells(ds):
    """The cells of a rate study's dataset (a ``RateCells``)."""
    study = classify.study_of(ds)
    if classify.amplitude_dim(study) is None:
        raise ValueError(f"{study.name} has no amplitude axis of its own: not a rate study")
    cells = plane.sweep_cells(ds)
    group, scenes = classify.scene_groups(study)
    grounds = [scene["excitation"]["horizontal"] for scene in scenes]
    octave = np.array([g["duration"] / abs(np.log2(g["f_start"] / g["f_stop"]))
                       for g in grounds])[group]
    positions = np.indices(study.shape).reshape(len(study.dims), -1)
    _, others = _dims_of(study)
    sizes = [study.dims[k].size for k in others]
    series = (np.ravel_multi_index(positions[others], sizes) if others
              else np.zeros(study.n_cells, dtype=int))
    labels = [", ".join(plane.value_text(axis.name, axis.values[i])
                        for k, i in zip(others, combo) for axis in study.dims[k].axes)
              for combo in np.ndindex(*sizes)] if others else [""]
    level_axis = study.dims[classify.amplitude_dim(study)].axes[0]
    level = ds["amplitude"].values[positions[classify.amplitude_dim(study)]]
    if level_axis.unit and not level_axis.body_relative:  # SI coordinates back to the unit
        level = level / units.parse_quantity(f"1 {level_axis.unit}", level_axis.dimension).to_si()
    value = cells.point[:, 0 if swept_quantity(cells.hold) == "v" else 1]
    return RateCells(cells.hold, cells.body, level_axis.unit, np.asarray(level, dtype=float),
                     octave, series, labels, value, cells.point)


def summarize(cells):
    """The swept quantity at overturning per series, level and T over the ensemble."""
    levels, octave_times = np.unique(cells.level), np.unique(cells.octave_time)
    shape = (len(cells.labels), levels.size, octave_times.size)
    count, overturned = np.zeros(shape, dtype=int), np.zeros(shape, dtype=int)
    median, mean, sem, low, high = (np.full(shape, np.nan) for _ in range(5))
    for index in np.ndindex(*shape):
        s, i, j = index
        pick = ((cells.series == s) & (cells.level == levels[i])
                & (cells.octave_time == octave_times[j]))
        values = cells.value[pick]
        values = values[~np.isnan(values)]
        count[index], overturned[index] = pick.sum(), values.size
        if values.size:
            median[index], mean[index] = np.median(values), values.mean()
            low[index], high[index] = values.min(), values.max()
        if values.size > 1:
            sem[index] = values.std(ddof=1) / np.sqrt(values.size)
    return Summary(levels, octave_times, count, overturned, median, mean, sem, low, high)


def _power_law(T, value, c, k):
    return value + c * T ** -k


def fit_slow_limit(T, y, sigma=None, confidence=CONFIDENCE):
    """Fit y(T) = y_inf + c (T/T_0)^-k and extrapolate to T -> infinity.

    Parameters
    ----------
    T : array_like, shape (n,)
        Octave durations [s], n >= 4.
    y : array_like, shape (n,)
        The quantity at overturning (e.g. the ensemble mean of v/v_H).
    sigma : array_like, shape (n,), optional
        Standard errors of ``y`` (e.g. of the ensemble mean).  Taken as absolute (normal
        quantile for the interval) unless the residuals exceed them (chi2 p-value below
        ``MISFIT_P``: the points scatter about the power law by more than their errors);
        then, as without ``sigma``, the covariance is scaled by chi2/dof and the interval
        uses Student's t with n - 3 degrees of freedom.
    confidence : float
        Level of the interval of the limit.

    Returns
    -------
    SlowLimit
    """
    T, y = np.asarray(T, dtype=float), np.asarray(y, dtype=float)
    if T.size < 4:
        raise ValueError(f"fit_slow_limit needs at least 4 rates, got {T.size}")
    x = T / T.min()
    order = np.argsort(x)
    step = y[order][-2] - y[order][-1]  # last change: the tail of a 2/3 power law
    k0 = 2.0 / 3.0
    ratio = (x[order][-1] / x[order][-2]) ** -k0
    guess_value = y[order][-1] - step * ratio / (1.0 - ratio)
    guess = (guess_value, y[order][0] - guess_value, k0)
    bounds = ([-np.inf, -np.inf, K_BOUNDS[0]], [np.inf, np.inf, K_BOUNDS[1]])
    params, cov = optimize.curve_fit(_power_law, x, y, p0=guess, sigma=sigma,
                                     absolute_sigma=sigma is not None, bounds=bounds)
    residuals = y - _power_law(x, *params)
    dof = T.size - 3
    chi2, scaled = np.nan, True
    if sigma is not None:
        residuals = residuals / np.asarray(sigma, dtype=float)
        chi2 = float(np.sum(residuals ** 2))
        scaled = bool(stats.chi2.sf(chi2, dof) < MISFIT_P)
        if scaled:
            cov = cov * chi2 / dof
    quantile = (stats.t.ppf(0.5 + confidence / 2.0, dof) if scaled
                else stats.norm.ppf(0.5 + confidence / 2.0))
    se = np.sqrt(np.diag(cov))
    return SlowLimit(float(params[0]), float(se[0]), float(params[0] - quantile * se[0]),
                     float(params[0] + quantile * se[0]), float(params[2]), float(se[2]),
                     float(params[1]), residuals, chi2, dof, scaled)


def level_fits(summary, series=0):
    """{level: SlowLimit} of every level overturned by every member at every rate, fitted to
    the ensemble means with their standard errors (none with fewer than 4 rates)."""
    fits = {}
    if summary.octave_times.size < 4:
        return fits
    for i, level in enumerate(summary.levels):
        mean, sem = summary.mean[series, i], summary.sem[series, i]
        complete = np.all(summary.overturned[series, i] == summary.count[series, i])
        if complete and np.all(np.isfinite(sem)) and np.all(sem > 0):
            fits[float(level)] = fit_slow_limit(summary.octave_times, mean, sem)
    return fits


def lowest_per_rate(cells, series=0):
    """Per T: (T, (v, a) of the overturning with the lowest swept quantity, the lowest level
    at which some member overturned, how many of how many members did, and the median (v, a)
    of their overturnings)."""
    rows = []
    for T in np.unique(cells.octave_time):
        pick = (cells.series == series) & (cells.octave_time == T)
        value, level, point = cells.value[pick], cells.level[pick], cells.point[pick]
        over = ~np.isnan(value)
        if not np.any(over):
            rows.append((float(T), (np.nan, np.nan), np.nan, 0, 0, (np.nan, np.nan)))
            continue
        best = np.flatnonzero(over)[np.argmin(value[over])]
        lowest = level[over].min()
        at = level == lowest
        rows.append((float(T), tuple(point[best]), float(lowest), int(over[at].sum()),
                     int(at.sum()), tuple(np.median(point[at & over], axis=0))))
    return rows


# --- tables -----------------------------------------------------------------------------------

def _cell(median, low, high):
    return "–" if np.isnan(median) else f"{median:.3f} ({low:.3f}–{high:.3f})"


def report(ds):
    """Markdown tables of one rate study: per series and rate the lowest overturning and the
    swept quantity at the reported levels (median over the ensemble, range), then the
    slow-limit fit of every level."""
    cells = rate_cells(ds)
    summary = summarize(cells)
    q = swept_quantity(cells.hold)
    name = {"v": "v/v_H", "a": "a/((B/H) g)"}[q]
    reported = [lv for lv in REPORTED_LEVELS.get(cells.hold, summary.levels)
                if lv in summary.levels]
    lines = [f"## {ds.attrs.get('title', '')}", ""]
    for s, label in enumerate(cells.labels):
        lines += [f"### {label or 'all cells'}: {name} at overturning", "",
                  f"| T [s/octave] | lowest {q}: (v, a) | lowest level overturning: members, "
                  "median (v, a) | "
                  + " | ".join(f"{lv:g} {cells.unit}" for lv in reported) + " |",
                  "|---" * (3 + len(reported)) + "|"]
        for j, (T, (v, a), lowest, over, n, (v_low, a_low)) in enumerate(
                lowest_per_rate(cells, s)):
            values = [_cell(summary.median[s, i, j], summary.low[s, i, j], summary.high[s, i, j])
                      for i, lv in enumerate(summary.levels) if lv in reported]
            lines.append(f"| {T:g} | ({v:.3f}, {a:.3f}) | {lowest:g} {cells.unit}: {over} of "
                         f"{n}, ({v_low:.3f}, {a_low:.3f}) | " + " | ".join(values) + " |")
        lines += ["", f"Fit {name} = y_inf + c (T/{summary.octave_times[0]:g} s)^-k to the "
                      "ensemble means (their standard errors as sigma):", "",
                  f"| level [{cells.unit}] | y_inf | {CONFIDENCE:.0%} interval | k | "
                  "chi2 / dof | largest residual | mean of the 3 slowest (range) |",
                  "|---|---|---|---|---|---|---|"]
        for level, fit in level_fits(summary, s).items():
            slowest = summary.mean[s, np.searchsorted(summary.levels, level), -3:]
            lines.append(f"| {level:g} | {fit.value:.3f} ± {fit.se:.3f}"
                         f"{' (scaled)' if fit.scaled else ''} | {fit.low:.3f}–{fit.high:.3f} "
                         f"| {fit.k:.2f} ± {fit.k_se:.2f} | {fit.chi2:.1f} / {fit.dof} | "
                         f"{np.max(np.abs(fit.residuals)):.1f} σ | {slowest.mean():.3f} "
                         f"({slowest.min():.3f}–{slowest.max():.3f}) |")
        lines.append("")
    return "\n".join(lines)


main = report_command(
    "sweep.paper.rates",
    "Tables and slow-limit fits of rate studies.",
    report)


if __name__ == "__main__":
    sys.exit(main())
