"""The :class:`Record`: a uniformly sampled acceleration, from a file or a synthetic motion.

It is a motion as numbers, so it lives in ``groundmotion``, below ``io``: the record readers of
``sweep.io.formats`` return it (``sweep.io.formats.base`` and ``sweep.io.records`` import it
under the same name) and ``stochastic`` builds it without reaching up to ``io``.  How a file was
read is ``io``'s :class:`~sweep.io.formats.base.Reading`, which a record only carries.
"""
import functools
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True, eq=False)
class Record:
    """A uniformly sampled acceleration record.

    Attributes
    ----------
    name : str
        Bundled name, or the file's path.
    dt : float
        Sample step [s].
    samples : ndarray, shape (n,)
        Acceleration [m/s^2], read-only.
    provenance : str
        Where the data come from and what was done to them.
    units : str
        Acceleration unit the file's numbers were read in (m/s^2 for the bundled records).
    reading : Reading or None
        How the file was read (:class:`sweep.io.formats.base.Reading`); None for a record
        that no file gave (a synthetic motion).
    """

    name: str
    dt: float
    samples: np.ndarray
    provenance: str
    units: str = "m/s^2"
    reading: "Reading" = None  # noqa: F821  (sweep.io.formats.base.Reading, above this layer)

    @property
    def pga(self):
        """Peak absolute acceleration [m/s^2]."""
        return float(np.max(np.abs(self.samples)))

    @functools.cached_property
    def intensity(self):
        """:class:`~sweep.groundmotion.intensity.Intensity` of the samples (scale 1)."""
        from .intensity import measures
        return measures(self.samples, self.dt)

    @property
    def duration(self):
        """Time from the first to the last sample [s]."""
        return self.dt * (len(self.samples) - 1)
