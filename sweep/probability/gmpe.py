"""Ground-motion models by name, from ``pygmm``: the median and sigma of an IM, in SI units.

The median and the lognormal standard deviation of an intensity measure for a magnitude,
distances and a site.

A source of this package is a point (or the points of an area) at a depth: the rupture is the
point itself, so Rjb is the epicentral distance, Rrup = Rhyp = sqrt(Rjb² + depth²), Rx = Rjb,
the fault vertical (dip 90°), its top at the hypocentre and 1 km wide.  The models:

* ``BSSA14``: Boore, Stewart, Seyhan & Atkinson (2014), Earthquake Spectra 30, 1057-1085;
* ``ASK14``: Abrahamson, Silva & Kamai (2014), Earthquake Spectra 30, 1025-1055;
* ``CB14``: Campbell & Bozorgnia (2014), Earthquake Spectra 30, 1087-1115;
* ``CY14``: Chiou & Youngs (2014), Earthquake Spectra 30, 1117-1153.

They predict RotD50 (the median over horizontal orientations), ``sigma`` is the total
standard deviation of ln IM.  pygmm returns g for PGA and spectral accelerations, cm/s for PGV.
All four are models of shallow crustal earthquakes in active regions, fitted to the same
NGA-West2 data (Gregor et al. 2014, Earthquake Spectra 30, 1179-1197, compare their ranges):
Campbell & Bozorgnia (2014) state hypocentres Z_HYP ≤ 20 km and Chiou & Youngs (2014) tops of
rupture Z_TOR ≤ 20 km (pygmm's limits too; here Z_TOR is the depth); ASK14 and BSSA14 (which
has no depth term) rest on the same shallow earthquakes: :data:`MAX_DEPTH`.
"""
from collections import namedtuple

import numpy as np

from ..bodies import G

MODELS = {"BSSA14": "BooreStewartSeyhanAtkinson2014", "ASK14": "AbrahamsonSilvaKamai2014",
          "CB14": "CampbellBozorgnia2014", "CY14": "ChiouYoungs2014"}
MECHANISMS = ("SS", "NS", "RS")  # strike-slip, normal, reverse (pygmm's names)
POINT_WIDTH_KM = 1.0  # down-dip width given to a point rupture
MAX_DEPTH = 20e3  # m: the deepest hypocentre of the models' stated ranges

Prediction = namedtuple("Prediction", "ln_median sigma")
Prediction.__doc__ = """ln of the median IM [ln(m/s²) or ln(m/s)] and the standard deviation of
ln IM."""


def model_class(name):
    """pygmm's class of the model ``name`` (a key of :data:`MODELS`)."""
    import pygmm

    if name not in MODELS:
        raise ValueError(f"unknown ground-motion model {name!r}; models: {', '.join(MODELS)}")
    return getattr(pygmm, MODELS[name])


def scenario(magnitude, rjb, depth, vs30, mechanism="SS"):
    """The ``pygmm.Scenario`` of a point rupture at ``depth`` [m], ``rjb`` [m] from the site."""
    import pygmm

    rjb_km, depth_km = rjb / 1e3, depth / 1e3
    return pygmm.Scenario(mag=float(magnitude), dist_jb=rjb_km,
                          dist_rup=float(np.hypot(rjb_km, depth_km)), dist_x=rjb_km,
                          v_s30=float(vs30), mechanism=mechanism, depth_hyp=depth_km,
                          depth_tor=depth_km, dip=90.0, width=POINT_WIDTH_KM)


def predict(name, im, magnitude, rjb, depth, vs30, mechanism="SS"):
    """:class:`Prediction` of ``im`` (``pga``, ``pgv``, ``sa(T)``) by model ``name``."""
    model = model_class(name)(scenario(magnitude, rjb, depth, vs30, mechanism))
    if im == "pga":
        return Prediction(float(np.log(model.pga * G)), float(model.ln_std_pga))
    if im == "pgv":
        return Prediction(float(np.log(model.pgv / 100.0)), float(model.ln_std_pgv))
    period = float(im[3:-1])
    return Prediction(float(np.log(model.interp_spec_accels([period])[0] * G)),
                      float(model.interp_ln_stds([period])[0]))


def predict_grid(name, im, magnitudes, distances, depth, vs30, mechanism="SS"):
    """ln medians and sigmas over magnitudes x Rjb distances [m], shape (M, R) each."""
    ln_median = np.empty((len(magnitudes), len(distances)))
    sigma = np.empty_like(ln_median)
    for i, m in enumerate(magnitudes):
        for j, r in enumerate(distances):
            ln_median[i, j], sigma[i, j] = predict(name, im, m, r, depth, vs30, mechanism)
    return ln_median, sigma
