"""Multiple stripe analysis (Jalayer & Cornell 2009, EESD 38; Baker 2015, Earthquake Spectra
31): at each IM level of a stripe list, synthetic motions scaled to that level, the body (or
the bodies of a grid) simulated under them, and the lognormal fragility fitted by maximum
likelihood over the stripes with bootstrap intervals (``sweep.probability.fit``).

The motions of stripe j are Boore's (2003) stochastic motions (``sweep.groundmotion``) of
earthquakes drawn from the disaggregation of the hazard at that level
(``SourceModel.draw``: the (M, R) that dominate it, so that each stripe carries the frequency
content of the shaking that produces it), or of one stated scenario, each scaled to the level
of the hazard's IM: its PGA, its PGV or its 5 %-damped Sa(T) (the scene's ``pga``, ``pgv`` or
``sa`` key, ``sweep.io.scene_schema``), as the site ensembles are scaled to a PGA.  Seeds:
``seed + j × motions + i`` for motion i of stripe j, so that no two motions share their
noise.

A user's records (``stripes.records``) are the motions of every stripe instead, each scaled
to the level (the same records at every level, as in Baker 2015's multiple stripes).

Each stripe is an ordinary study (``<folder>/<name>_stripe<j>.yaml`` and ``.nc``): grid = the
body axes of the risk map, if any, × the motions (a zip of ``seed``, magnitude and distance),
run through the runner (``runner.launch.run_file``, as ``python -m sweep.run`` runs it; a
dataset whose fingerprint matches its inputs is reused).  SI units.
"""
from collections import namedtuple
from pathlib import Path

import numpy as np

from . import fit as fitting

MEMBER = "member"  # the zip dimension of a stripe's motions
MEMBER_DIMS = (MEMBER, "seed", "record")  # the dimension of the motions, whichever it is
MAGNITUDE_AXIS = "excitation.horizontal.magnitude"
DISTANCE_AXIS = "excitation.horizontal.distance"
MAGNITUDE_DIGITS = 4  # decimals of a drawn magnitude
DISTANCE_STEP = 1.0  # m: drawn distances are rounded to this

Stripe = namedtuple("Stripe", "level seeds magnitudes distances")
Stripe.__doc__ = """The motions of one stripe: IM ``level`` [SI], and per motion its seed,
magnitude and Rrup [m]; for records (:func:`record_plan`) ``seeds`` and ``magnitudes`` are
None and ``distances`` holds the records."""


def _distinct(values, draw, rounding, rng, tries=100):
    """``values`` rounded, redrawn (``draw(count, rng)``) where a value repeats: the study
    schema wants distinct values along an axis."""
    values = rounding(values)
    for _ in range(tries):
        _, first = np.unique(values, return_index=True)
        repeated = np.setdiff1d(np.arange(values.size), first)
        if not repeated.size:
            return values
        values[repeated] = rounding(draw(repeated.size, rng))
    raise RuntimeError("could not draw distinct values")


def plan(levels, motions, seed, *, model=None, scenario=None):
    """The :class:`Stripe` s: earthquakes drawn from ``model``'s disaggregation at each level
    (``SourceModel``), or ``scenario`` = (magnitude, Rrup [m]) for every motion."""
    stripes = []
    for j, level in enumerate(levels):
        seeds = seed + j * motions + np.arange(motions)
        if scenario is not None:
            magnitudes = np.full(motions, float(scenario[0]))
            distances = np.full(motions, float(scenario[1]))
        else:
            rng = np.random.default_rng([seed, j])
            drawn = model.draw(level, motions, rng)
            magnitudes = _distinct(drawn[:, 0], lambda n, r: model.draw(level, n, r)[:, 0],
                                   lambda v: np.round(v, MAGNITUDE_DIGITS), rng)
            distances = np.round(drawn[:, 1] / DISTANCE_STEP) * DISTANCE_STEP
            if np.unique(distances).size > 1:
                distances = _distinct(distances, lambda n, r: model.draw(level, n, r)[:, 1],
                                      lambda v: np.round(v / DISTANCE_STEP) * DISTANCE_STEP,
                                      rng)
        stripes.append(Stripe(float(level), seeds.tolist(), magnitudes.tolist(),
                              distances.tolist()))
    return stripes


def record_plan(levels, records):
    """The :class:`Stripe` s of an ensemble of ``records`` (bundled names, or absolute paths)
    scaled to each level: no seed, magnitude or distance."""
    return [Stripe(float(level), None, None, list(records)) for level in levels]


def scaling(im, level):
    """The scene keys that scale a motion to ``level`` [SI] of the IM ``im`` (``pga``,
    ``pgv``, ``sa(T)``), and the level in words."""
    if im == "pgv":
        return {"pgv": f"{level!r} m/s"}, f"PGV {level:.4g} m/s"
    if im.startswith("sa("):
        period = float(im[3:-1])
        return ({"sa": {"period": period, "value": f"{level!r} m/s^2"}},
                f"Sa({period:g} s) {level:.4g} m/s^2")
    return {"pga": f"{level!r} m/s^2"}, f"PGA {level:.4g} m/s^2"


def _record_study(stripe, scene, grid, name, output, im):
    from ..io import records

    first = stripe.distances[0]
    scaled, said = scaling(im, stripe.level)
    excitation = {"kind": "record", **({"name": first} if first in records.NAMES
                                       else {"path": first}), **scaled}
    scene = {k: v for k, v in (scene or {}).items() if k != "excitation"}
    scene["excitation"] = {"horizontal": excitation}
    return {"name": name,
            "title": f"stripe at {said}: {len(stripe.distances)} records (sweep.risk)",
            "scene": scene, "grid": {**(grid or {}), "record": list(stripe.distances)},
            "output": str(output)}


def study_dict(stripe, scene, vs30, grid, name, output, motion_model="boore2003", im="pga"):
    """The study of one stripe: the base ``scene`` (body, contact, solver), a synthetic
    horizontal motion scaled to the stripe's level of ``im`` (or the records of a
    :func:`record_plan`); grid = ``grid`` (body axes) × the motions."""
    if stripe.seeds is None:
        return _record_study(stripe, scene, grid, name, output, im)
    scaled, said = scaling(im, stripe.level)
    first = {"kind": "synthetic", "model": motion_model, "magnitude": stripe.magnitudes[0],
             "distance": stripe.distances[0], "vs30": vs30, "seed": stripe.seeds[0], **scaled}
    scene = {k: v for k, v in (scene or {}).items() if k != "excitation"}
    scene["excitation"] = {"horizontal": first}
    axes = {"seed": list(stripe.seeds)}
    if len(set(stripe.magnitudes)) > 1:
        axes[MAGNITUDE_AXIS] = list(stripe.magnitudes)
    if len(set(stripe.distances)) > 1:
        axes[DISTANCE_AXIS] = list(stripe.distances)
    study = {"name": name,
             "title": f"stripe at {said}: {len(stripe.seeds)} synthetic motions (sweep.risk)",
             "scene": scene, "grid": {**(grid or {}), **axes}, "output": str(output)}
    if len(axes) > 1:
        study["zip"] = {MEMBER: list(axes)}
    return study


def write_studies(stripes, scene, vs30, grid, name, folder, motion_model="boore2003", im="pga"):
    """Write the study of every stripe (motions scaled to its level of ``im``) to ``folder``
    (``<name>_stripe<j>.yaml``, output beside it); the paths."""
    import yaml

    folder = Path(folder).resolve()
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for j, stripe in enumerate(stripes):
        path = folder / f"{name}_stripe{j}.yaml"
        study = study_dict(stripe, scene, vs30, grid, f"{name}_stripe{j}",
                           folder / f"{name}_stripe{j}.nc", motion_model, im)
        text = yaml.safe_dump(study, sort_keys=False)
        if not path.is_file() or path.read_text() != text:
            path.write_text(text)
        paths.append(path)
    return paths


def run(paths, say=None):
    """The dataset of every stripe study, computed or reused (``site_studies.run_study_file``);
    ``say(text)`` is told what was computed."""
    import time

    from .site_studies import run_study_file

    start = time.perf_counter()
    datasets, computed = [], 0
    for path in paths:
        ds, ran = run_study_file(path)
        datasets.append(ds)
        computed += ran
    if say is not None and computed:
        say(f"{computed} of {len(paths)} stripes simulated in {time.perf_counter() - start:.1f}"
            f" s; datasets in {Path(paths[0]).parent}")
    return datasets


def body_dims(ds):
    """The dimensions of a stripe dataset that are bodies (not the motions)."""
    return [d for d in ds["overturned"].dims if d not in MEMBER_DIMS]


def outcomes(datasets):
    """Per stripe, the outcome of every motion and body: overturned (1), standing (0) or
    failed (−1), shape (stripes, motions) + body shape, the motions first."""
    out = []
    for ds in datasets:
        over = ds["overturned"]
        member = next(d for d in MEMBER_DIMS if d in over.dims)
        out.append(over.transpose(member, ...).values)
    return np.array(out)


def counts(datasets):
    """Overturned and simulated motions per stripe and body: ``k``, ``n``, shape
    (stripes,) + body shape; failed cells (−1) left out."""
    o = outcomes(datasets)
    return (o == 1).sum(axis=1), (o >= 0).sum(axis=1)


def fit(levels, outcome, *, shared_members=False, confidence=0.95,
        replicates=fitting.DEFAULT_REPLICATES, seed=0):
    """The lognormal fit of every body over the stripes: an object array of body shape of
    ``fit.LognormalFit``.

    ``outcome`` is :func:`outcomes`.  The bootstrap resamples members: with
    ``shared_members`` (the same records scaled to every stripe) a member is one record with
    its outcomes at every level (a cluster bootstrap); otherwise every motion is its own
    member (the stripes' synthetic motions all differ).
    """
    levels = np.asarray(levels, dtype=float)
    stripes, motions = outcome.shape[:2]
    x = np.repeat(levels, motions)
    labels = np.tile(np.arange(motions), stripes) if shared_members else np.arange(x.size)
    shape = outcome.shape[2:]
    fits = np.empty(shape, dtype=object)
    for index in np.ndindex(*shape):
        o = outcome[(slice(None), slice(None)) + index].ravel()
        fits[index] = fitting.fit_lognormal(x, (o == 1).astype(float), (o >= 0).astype(float),
                                            members=labels, confidence=confidence,
                                            replicates=replicates, seed=seed)
    return fits
