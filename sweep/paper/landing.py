"""What a body does after landing from a translation jump (Ishiyama 1982, Fig. 5).

Every cell of a landing study classified as sliding, tilting forward or back and standing, or
overturning forward or back, for ``sweep.plots.landing`` to draw (docs/landing.md).

"Forward" is the direction of the horizontal velocity at release: theta < 0 for x_dot >= 0
(rotation about the right corner, docs/physics.md 1.1).  The dataset says whether and to which
side a body overturned (``overturned``, ``overturn_direction``) and how far it tilted
(``max_abs_theta``), not to which side a body that stood tilted: those cells are simulated
again with their history (as ``sweep.paper.classify`` does for Figs 11-16) and the side of
their first tilt beyond 0.05 alpha is read from it.
"""
import math

import numpy as np
import xarray as xr

from kernels.api import run_scene

from . import classify

FAILED, SLIDES, TILTS_FORWARD, TILTS_BACK, OVERTURNS_FORWARD, OVERTURNS_BACK = range(-1, 5)
CLASSES = {  # code -> flag meaning
    FAILED: "failed",
    SLIDES: "slides",
    TILTS_FORWARD: "tilts_forward",
    TILTS_BACK: "tilts_back",
    OVERTURNS_FORWARD: "overturns_forward",
    OVERTURNS_BACK: "overturns_back",
}


def first_tilt(scene, alpha):
    """Sign of theta at the first tilt beyond ``classify.EPSILON`` alpha of a resolved scene,
    simulated again with its history every ``classify.DT_OUT`` s (at its largest |theta| if no
    sample lies beyond)."""
    scene["solver"]["dt_out"] = classify.DT_OUT  # output sampling only: the same trajectory
    theta = run_scene(scene, history=True).history["theta"]
    beyond = np.flatnonzero(np.abs(theta) >= classify.EPSILON * alpha)
    return np.sign(theta[beyond[0] if beyond.size else np.argmax(np.abs(theta))])


def landing_classes(ds):
    """The class of every cell of a landing study's dataset.

    Parameters
    ----------
    ds : xarray.Dataset
        A dataset of ``sweep.run`` (its ``study`` attribute holds the study's text).

    Returns
    -------
    xarray.DataArray
        int8 on the dimensions of ``outcome``: one of ``CLASSES`` (``flag_values``,
        ``flag_meanings``).  A cell slides when its largest |theta| stays below
        ``classify.EPSILON`` alpha; a cell that stood is classed by its first tilt
        (:func:`first_tilt`).
    """
    study = classify.study_of(ds)
    outcome = ds["outcome"]
    failed = outcome.values.ravel() < 0
    overturned = ds["overturned"].values.ravel() == 1
    direction = ds["overturn_direction"].values.ravel()
    theta_max = ds["max_abs_theta"].values.ravel()
    classes = np.full(outcome.size, FAILED, dtype=np.int8)
    for index in np.flatnonzero(~failed):
        scene = classify.resolved_cell(study, index)
        forward = -1 if scene["initial"]["x_dot"] >= 0 else 1  # sign of theta tilting forward
        alpha = math.atan2(scene["body"]["B"], scene["body"]["H"])
        if overturned[index]:
            classes[index] = OVERTURNS_FORWARD if direction[index] == forward else OVERTURNS_BACK
        elif theta_max[index] < classify.EPSILON * alpha:
            classes[index] = SLIDES
        else:
            classes[index] = (TILTS_FORWARD if first_tilt(scene, alpha) == forward
                              else TILTS_BACK)
    codes = sorted(CLASSES)
    return xr.DataArray(classes.reshape(outcome.shape), coords=outcome.coords, dims=outcome.dims,
                        name="landing_class",
                        attrs={"long_name": "what the body did after landing", "units": "1",
                               "flag_values": np.array(codes, dtype=np.int8),
                               "flag_meanings": " ".join(CLASSES[c] for c in codes)})
