"""The hazard of a risk file (``sweep.io.risk_schema``): a curve read from a file or computed
from its source model, and the checks that need it (stripes inside the curve), made by the
file's model (:func:`checked_hazard` in its validation context) and reported as problems of
the file with their dotted paths."""
from pathlib import Path

import numpy as np

from ..bodies import G
from ..io.problems import FieldError
from . import hazard_curve as hc
from . import source_hazard as sh

DEFAULT_LEVELS = {"acceleration": (0.005 * G, 3.0 * G),  # m/s²
                  "velocity": (0.005, 3.0)}  # m/s
DEFAULT_LEVEL_COUNT = 40
DEFAULT_DISTANCE_BINS = (0.0, 10e3, 20e3, 30e3, 50e3, 75e3, 100e3, 150e3, 200e3, 300e3)


def _recurrence(entry):
    return sh.Recurrence(**entry.si())


def source_model(entry):
    """The :class:`~sweep.probability.source_hazard.SourceModel` of ``hazard.source``."""
    sources = []
    for s in entry.sources:
        recurrence = _recurrence(s.recurrence)
        if s.kind == "point":
            sources.append(sh.point_source(recurrence, s.distance.to_si(), s.depth.to_si(),
                                           s.mechanism))
        else:
            sources.append(sh.area_source(recurrence, [q.to_si() for q in s.east],
                                          [q.to_si() for q in s.north], s.spacing.to_si(),
                                          s.depth.to_si(), s.mechanism))
    return sh.SourceModel(sources, entry.vs30.to_si(), entry.model, entry.im)


def hazard_levels(entry):
    """The IM levels [SI] at which a source model's curve is computed."""
    if entry.levels is not None:
        return entry.levels.si()
    lo, hi = DEFAULT_LEVELS[hc.im_dimension(entry.im)]
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
    """The :class:`HazardCurve` of ``hazard.file`` (paths relative to ``folder``)."""
    path = read_path(entry, folder)
    if entry.format == "openquake":
        curve = hc.read_openquake_csv(path, entry.site)
    elif entry.format == "usgs":
        curve = hc.read_usgs_json(path, entry.im)
    else:
        curve = hc.read_columns(path, entry.im, entry.units, entry.kind,
                                entry.investigation_time)
    if entry.im is not None and curve.im != entry.im:
        raise hc.HazardFileError(f"{path}: the curve is of {curve.im}, the risk file says "
                                 f"{entry.im}")
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
