"""Named options of a risk file side by side: each its own scene, all under the same stripes.

A risk file's ``options`` (docs/options.md) name scenes that differ from its ``scene`` by the
dotted paths each sets (``sweep.io.risk_schema.option_scene``).  Every option's stripes are
the studies of the same :class:`~sweep.probability.stripes.Stripe` s (the same seeds,
magnitudes and distances, or records: a paired comparison), written as
``<name>_option<i>_stripe<j>.yaml`` and run, fitted and integrated as one body is; the results
are stacked along one body dimension, ``option``, holding the options' names.
"""
import numpy as np

from ..io.risk_schema import option_scene
from . import stripes as stripe_analysis
from .stripe_results import StripeResults, StripeSides, stripe_results

OPTION = "option"  # the body dimension of named options


def option_scenes(checked):
    """[(name, raw scene)] of a checked risk file's options, in the file's order."""
    return [(name, option_scene(checked.scene, overrides))
            for name, overrides in checked.options.items()]


def _objects(values):
    """A 1-d object array of ``values`` (each kept whole)."""
    out = np.empty(len(values), dtype=object)
    out[:] = values
    return out


def _stacked(per):
    """One :class:`StripeResults` of the options' (each of one body), the option last."""
    sides = [r.sides for r in per]
    if any(s is None for s in sides):
        stacked_sides = None
    else:
        stacked_sides = StripeSides(*(np.stack([getattr(s, key) for s in sides], axis=-1)
                                      for key in StripeSides._fields))
    displacements = [None if r.displacements is None else r.displacements[()] for r in per]
    return StripeResults(
        None, np.stack([r.k for r in per], axis=-1), np.stack([r.n for r in per], axis=-1),
        _objects([r.fits[()] for r in per]), _objects([r.risks[()] for r in per]),
        stacked_sides,
        None if all(d is None for d in displacements) else _objects(displacements))


def placement(scenes):
    """Where the stripes' motions act, in words, for the options that share it: ``as it
    stands, anchored: the ground of a building whose floor ...; ground floor: the ground
    under the body``."""
    shared = {}
    for name, scene in scenes:
        shared.setdefault(stripe_analysis.placement(scene), []).append(name)
    return "; ".join(f"{', '.join(names)}: {said}" for said, names in shared.items())


def run_options(spec, plan, vs30, folder, say=None):
    """Run every option of a checked risk file under the stripes ``plan`` (studies in
    ``folder``): the stacked :class:`StripeResults`, the body dimensions, their coordinates
    and the placement in words."""
    checked = spec.checked
    scenes = option_scenes(checked)
    per = []
    for i, (name, scene) in enumerate(scenes):
        paths = stripe_analysis.write_studies(plan, scene, vs30, None,
                                              f"{spec.name}_option{i}", folder,
                                              checked.stripes.model, spec.curve.im)
        per.append(stripe_results(stripe_analysis.run(paths, say), spec))
    coords = {OPTION: (_objects([name for name, _ in scenes]),
                       {"long_name": "option of the risk file"})}
    return _stacked(per), [OPTION], coords, placement(scenes)
