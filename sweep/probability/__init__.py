"""Probabilities from ensembles of simulations (docs/probability.md sections 3-4).

The fragility layer: ``intervals``, binomial proportion intervals (Wilson, Clopper-Pearson);
``fit``, lognormal fragility functions and the two-parameter (PGA, PGV) surface fitted by
maximum likelihood; ``bootstrap``, the bootstrap over ensemble members behind the intervals of
a fit; ``fragility``, a study's dataset turned into probabilities of overturning, rocking and
sliding over its ensemble dimensions, with the fitted fragility of every body.
"""
