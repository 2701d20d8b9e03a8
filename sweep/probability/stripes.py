"""Multiple stripe analysis: motions at each IM level, the body simulated, the fragility fitted.

After Jalayer & Cornell (2009, EESD 38) and Baker (2015, Earthquake Spectra 31): at each IM
level of a stripe list, synthetic motions scaled to that level, the body (or the bodies of a
grid) simulated under them, and the lognormal fragility fitted by maximum likelihood over the
stripes with bootstrap intervals (``sweep.probability.fit``).

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

A scene whose horizontal motion is a building's floor (``kind: floor``, docs/floors.md) keeps
its building: the stripe's motion is the floor's ``ground``, scaled at the ground to the level
of the hazard's IM, and the axes of the motions set the ground's keys
(``excitation.horizontal.ground.seed``, ``.magnitude``, ``.distance``, ``.name`` or ``.path``).
An isolated platform (``kind: isolated``, docs/isolation.md) takes the stripe's motion at its
deepest ``under`` (:func:`ground_keys`): ``under`` itself over the ground, ``under.ground``
over a building's floor (axes ``excitation.horizontal.under.seed``, ``...under.ground.seed``).

Each stripe is an ordinary study (``<folder>/<name>_stripe<j>.yaml`` and ``.nc``): grid = the
axes of the risk map, if any (the body's, its contact's, its solver's or its building's:
``sweep.io.risk_schema`` refuses an axis that sets the motion), × the motions (a zip of
``seed``, magnitude and distance), run through the runner (``runner.launch.run_file``, as
``python -m sweep.run`` runs it; a dataset whose fingerprint matches its inputs is reused).
SI units.
"""
from collections import namedtuple
from pathlib import Path

import numpy as np

from . import fit as fitting

MEMBER = "member"  # the zip dimension of a stripe's motions
HORIZONTAL = "excitation.horizontal."  # the keys of the stripe's motion on the ground
# the study axes of the motions (a dimension of its own when alone; else zipped as MEMBER)
MOTION_AXES = ("seed", "record", *(HORIZONTAL + below + key for below in (
    "ground.", "under.", "under.ground.") for key in ("seed", "name", "path")))

Stripe = namedtuple("Stripe", "level seeds magnitudes distances")
Stripe.__doc__ = """The motions of one stripe: IM ``level`` [SI], and per motion its seed,
magnitude and Rrup [m]; for records (:func:`record_plan`) ``seeds`` and ``magnitudes`` are
None and ``distances`` holds the records."""


def plan(levels, motions, seed, *, model=None, scenario=None):
    """The :class:`Stripe` s: earthquakes drawn from ``model``'s disaggregation at each level
    (``SourceModel``, with ``numpy.random.default_rng([seed, j])`` at level j), used as drawn
    (two motions may share a magnitude or a distance: the zip's dimension is the motion), or
    ``scenario`` = (magnitude, Rrup [m]) for every motion."""
    stripes = []
    for j, level in enumerate(levels):
        seeds = seed + j * motions + np.arange(motions)
        if scenario is not None:
            magnitudes = np.full(motions, float(scenario[0]))
            distances = np.full(motions, float(scenario[1]))
        else:
            magnitudes, distances = model.draw(level, motions, np.random.default_rng([seed, j])).T
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


def _horizontal(scene):
    """The raw horizontal motion of ``scene`` (a mapping, or None)."""
    horizontal = ((scene or {}).get("excitation") or {}).get("horizontal")
    return horizontal if isinstance(horizontal, dict) else None


def ground_keys(scene):
    """The keys below ``excitation.horizontal`` where the stripes' motion goes: none on the
    ground; ``ground`` under a building's floor; ``under`` under an isolated platform on the
    ground, ``under.ground`` under one on a building's floor (the deepest ``under``)."""
    horizontal = _horizontal(scene) or {}
    if horizontal.get("kind") == "floor":
        return ("ground",)
    if horizontal.get("kind") == "isolated":
        under = horizontal.get("under")
        floor = isinstance(under, dict) and under.get("kind") == "floor"
        return ("under", "ground") if floor else ("under",)
    return ()


def _placed(scene, motion):
    """The base ``scene`` (body, contact, solver) with the stripe's horizontal ``motion`` at
    :func:`ground_keys`: the ground of its building's floor, under its isolator, or the
    horizontal motion itself."""
    placed = {k: v for k, v in (scene or {}).items() if k != "excitation"}
    placed["excitation"] = {"horizontal": _nested(_horizontal(scene), ground_keys(scene),
                                                  motion)}
    return placed


def _nested(outer, keys, motion):
    """The raw mapping ``outer`` with ``motion`` at the path ``keys`` below it (``motion``
    itself for no keys)."""
    if not keys:
        return motion
    inner = outer.get(keys[0])
    return {**outer, keys[0]: _nested(inner if isinstance(inner, dict) else {}, keys[1:],
                                      motion)}


def _axis(scene, key):
    """The study axis that sets the key ``key`` of the stripe's motion: ``seed``, a dotted
    path below the horizontal motion, or below the :func:`ground_keys` of a floor or an
    isolator."""
    keys = ground_keys(scene)
    if keys:
        return HORIZONTAL + ".".join(keys) + "." + key
    return key if key == "seed" else HORIZONTAL + key


def _keys_said(entry):
    """``period 0.6 s, height_ratio 0.667`` of a raw mapping (a building, an isolator)."""
    return ", ".join(f"{k} {v}" for k, v in (entry or {}).items())


def placement(scene):
    """Where the stripes' motions act, in words: at the ground under the body, as the
    ground of the building whose floor the body (or its isolated platform) stands on (its
    modes' keys), or under an isolated platform's isolator (its keys)."""
    keys = ground_keys(scene)
    if not keys:
        return "the ground under the body"
    horizontal = _horizontal(scene)
    platform = keys[0] == "under"
    if "ground" in keys:
        building = _keys_said((horizontal["under"] if platform else horizontal).get("building"))
        said = (f"the ground of a building whose floor the "
                f"{'isolated platform' if platform else 'body'} stands on"
                + (f" ({building})" if building else ""))
    else:
        said = "the ground under the isolated platform"
    if platform:
        said += f"; the platform's isolator: {_keys_said(horizontal.get('isolator'))}"
    return said


def _under(scene):
    """What the stripes' motions are under, in a stripe's title: a building's floor, an
    isolator."""
    keys = ground_keys(scene)
    return {(): "", ("ground",): " under a building's floor",
            ("under",): " under an isolator",
            ("under", "ground"): " under a building's floor and an isolator"}[keys]


def _record_study(stripe, scene, grid, name, output, im):
    from ..io import records

    first = stripe.distances[0]
    scaled, said = scaling(im, stripe.level)
    source = "name" if first in records.NAMES else "path"
    excitation = {"kind": "record", source: first, **scaled}
    axis = _axis(scene, source) if ground_keys(scene) else "record"
    return {"name": name,
            "title": f"stripe at {said}: {len(stripe.distances)} records{_under(scene)} "
                     "(sweep.risk)",
            "scene": _placed(scene, excitation),
            "grid": {**(grid or {}), axis: list(stripe.distances)}, "output": str(output)}


def study_dict(stripe, scene, vs30, grid, name, output, motion_model="boore2003", im="pga"):
    """The study of one stripe: the base ``scene`` (body, contact, solver, and a building's
    floor if it has one), a synthetic horizontal motion scaled to the stripe's level of ``im``
    (or the records of a :func:`record_plan`), on the ground or as the floor's ground;
    grid = ``grid`` (the risk map's axes) × the motions."""
    if stripe.seeds is None:
        return _record_study(stripe, scene, grid, name, output, im)
    scaled, said = scaling(im, stripe.level)
    first = {"kind": "synthetic", "model": motion_model, "magnitude": stripe.magnitudes[0],
             "distance": stripe.distances[0], "vs30": vs30, "seed": stripe.seeds[0], **scaled}
    axes = {_axis(scene, "seed"): list(stripe.seeds)}
    for key, values in (("magnitude", stripe.magnitudes), ("distance", stripe.distances)):
        if len(set(values)) > 1:
            axes[_axis(scene, key)] = list(values)
    study = {"name": name,
             "title": f"stripe at {said}: {len(stripe.seeds)} synthetic motions"
                      f"{_under(scene)} (sweep.risk)",
             "scene": _placed(scene, first), "grid": {**(grid or {}), **axes},
             "output": str(output)}
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


def member_dim(ds):
    """The dimension of a stripe dataset's motions: the zip of their axes, or the dimension
    of the one axis that varies (its coordinate's ``study_axis``)."""
    return next(d for d in ds["overturned"].dims if d == MEMBER or (
        d in ds.coords and ds[d].attrs.get("study_axis", d) in MOTION_AXES))


def body_dims(ds):
    """The dimensions of a stripe dataset that are bodies (not the motions)."""
    member = member_dim(ds)
    return [d for d in ds["overturned"].dims if d != member]


def outcomes(datasets):
    """Per stripe, the outcome of every motion and body: overturned (1), standing (0) or
    failed (−1), shape (stripes, motions) + body shape, the motions first."""
    return np.array([ds["overturned"].transpose(member_dim(ds), ...).values
                     for ds in datasets])


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
