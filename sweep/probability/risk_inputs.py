"""The hazard of a risk file, and the checks that need it.

A curve read from a file or computed from its source model (``sweep.io.risk_schema``), and the
checks that need it (stripes inside the curve), made by the file's model
(:func:`checked_hazard` in its validation context) and reported as problems of the file with
their dotted paths."""
from pathlib import Path

import numpy as np

from ..bodies import G
from ..io.imt import im_dimension
from ..io.problems import MISSING, FieldError, Problem, warn
from ..io.risk_schema import im_problems
from . import gmpe
from . import hazard_curve as hc
from . import hazard_files as hf
from . import source_hazard as sh

DEFAULT_LEVELS = {"acceleration": (0.005 * G, 3.0 * G),  # m/s²
                  "velocity": (0.005, 3.0)}  # m/s
DEFAULT_LEVEL_COUNT = 40
DEFAULT_DISTANCE_BINS = (0.0, 10e3, 20e3, 30e3, 50e3, 75e3, 100e3, 150e3, 200e3, 300e3)


def _recurrence(entry):
    """A ``recurrence``'s :class:`~sweep.probability.source_hazard.Recurrence`: its rate, or
    its ``a`` as OpenQuake's a-value."""
    if entry.a is None:
        return sh.Recurrence(float(entry.rate), **entry.si())
    return sh.Recurrence.from_a_value(float(entry.a), **entry.si())


def _caution_depth(entry, path):
    """Warn of a source deeper than the ground-motion models' range (``path``: dotted)."""
    if entry.depth.to_si() > gmpe.MAX_DEPTH:
        warn([Problem(f"{path}.depth", str(entry.depth),
                      f"deeper than the ground-motion model's range (shallow crustal "
                      f"earthquakes, hypocentres to {gmpe.MAX_DEPTH / 1e3:g} km): its "
                      f"predictions are extrapolated")])


def source_model(entry):
    """The :class:`~sweep.probability.source_hazard.SourceModel` of ``hazard.source``; a
    source deeper than the models' range is warned (an ``InputWarning``)."""
    sources = []
    for i, s in enumerate(entry.sources):
        _caution_depth(s, f"hazard.source.sources[{i}]")
        recurrence = _recurrence(s.recurrence)
        if s.kind == "point":
            sources.append(sh.point_source(recurrence, s.distance.to_si(), s.depth.to_si(),
                                           s.mechanism))
        else:
            sources.append(sh.area_source(recurrence, [q.to_si() for q in s.east],
                                          [q.to_si() for q in s.north],
                                          None if s.spacing is None else s.spacing.to_si(),
                                          s.depth.to_si(), s.mechanism))
    return sh.SourceModel(sources, entry.vs30.to_si(), entry.model, entry.im,
                          truncation=entry.truncation_level)


def hazard_levels(entry):
    """The IM levels [SI] at which a source model's curve is computed."""
    if entry.levels is not None:
        return entry.levels.si()
    lo, hi = DEFAULT_LEVELS[im_dimension(entry.im)]
    return np.geomspace(lo, hi, DEFAULT_LEVEL_COUNT)


def distance_bins(entry):
    """Rrup bin edges [m] of the disaggregation."""
    if entry.distance_bins is not None:
        return np.array([q.to_si() for q in entry.distance_bins])
    return np.array(DEFAULT_DISTANCE_BINS)


def read_path(entry, folder):
    """The path of ``hazard.file`` (relative to ``folder``)."""
    path = Path(entry.path)
    return path if path.is_absolute() else Path(folder) / path


def read_curve(entry, folder):
    """The :class:`HazardCurve` of ``hazard.file`` (paths relative to ``folder``).

    Raises
    ------
    FieldError
        A setting of ``hazard.file`` (``im``, ``units``, ``kind``, ``investigation_time``)
        that contradicts the file, or that neither gives; a ``site`` the file has not.
    HazardFileError, OSError
        A file that cannot be read or used.
    """
    path = read_path(entry, folder)
    try:
        if entry.format == "columns":
            curve = hf.read_columns(path, entry.im, entry.units, entry.kind,
                                    entry.investigation_time)
        else:
            curve = hf.read_openquake_csv(path, entry.site, entry.im) \
                if entry.format == "openquake" else hf.read_usgs_json(path, entry.im)
            hf.check_given_units(curve, entry.units, path)
        if entry.im is not None and curve.im != entry.im:
            raise hc.HazardFileError(f"{path}: the curve is of {curve.im}", key="im")
    except hc.HazardFileError as err:
        if err.key is None:
            raise
        value = getattr(entry, err.key)
        raise FieldError(("hazard", "file", err.key), MISSING if value is None else value,
                         str(err).removeprefix(f"{path}: ")) from None
    return curve


def checked_hazard(checked, folder):
    """The hazard curve of a risk file's model (``RiskFile``), its paths relative to
    ``folder``.

    Raises
    ------
    FieldError
        An unreadable or unusable curve (``hazard.file.path``), stripe levels outside the
        curve (``stripes.levels``).
    """
    try:
        if checked.hazard.file is not None:
            curve = read_curve(checked.hazard.file, folder)
        else:
            entry = checked.hazard.source
            curve = source_model(entry).curve(hazard_levels(entry))
    except (hc.HazardFileError, OSError) as err:
        message = str(err) if isinstance(err, hc.HazardFileError) else \
            f"cannot read: {err.strerror or err}"
        if checked.hazard.file is None:
            raise FieldError(("hazard", "source"), "...", message) from None
        raise FieldError(("hazard", "file", "path"), checked.hazard.file.path,
                         message.removeprefix(f"{read_path(checked.hazard.file, folder)}: ")) \
            from None
    if checked.im is None and im_problems(checked, curve.im):
        raise FieldError.several(im_problems(checked, curve.im))
    if checked.stripes is not None:
        levels = stripe_levels(checked.stripes)
        outside = [i for i, x in enumerate(levels)
                   if not curve.levels[0] <= x <= curve.levels[-1]]
        if outside:
            raise FieldError(("stripes", "levels", outside[0]) if len(outside) == 1
                             else ("stripes", "levels"),
                             f"{levels[outside[0]]:.4g} {curve.units}",
                             f"outside the hazard curve ({curve.levels[0]:.4g} to "
                             f"{curve.levels[-1]:.4g} {curve.units})")
    return curve


def stripe_levels(stripes):
    """The stripes' IM levels [SI]."""
    return np.asarray(stripes.levels.si(), dtype=float)
