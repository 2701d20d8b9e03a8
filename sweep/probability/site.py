"""What bodies seen at a site tell of its shaking, in probability (docs/probability.md section 6).

Every body of a site is simulated under an ensemble of motions (records, or synthetic motions
of a scenario), each motion scaled to a set of PGA levels x_j.  o_ijm in {0, 1} says whether
body i overturned under member m scaled to x_j.  The bodies seen overturned (set O) bound the
shaking from below, those left standing (set S) from above.  The estimate gathers

* the likelihood L(x_j) of each level, the posterior of the level and what carries it
  (``site_posterior``);
* each body's fragility and the bound it gives (``site_bodies``);
* the probability that a motion of (PGA, PGV) reproduces every observation
  (``site_map``);
* the bodies that slide: a body whose friction coefficient (given, or the ensemble's default)
  is below B/H slides before it rocks (Ishiyama 1982, conclusion 1); it is kept out of the
  likelihood, not simulated, and listed with the reason.

The simulations (one study per distinct body, run or reused: ``site_studies``) give o_ijm;
the text and JSON of an estimate are ``site_report``'s.  SI units throughout.
"""
from dataclasses import dataclass, field

import numpy as np

from .site_bodies import body_estimate
from .site_map import ConsistencyMap, consistency_map
from .site_posterior import Posterior, Support, consistency, likelihood, posterior, support
from .site_studies import member_labels, simulated_time, sliding_reason, specimen, specimen_key


@dataclass(frozen=True)
class SiteEstimate:
    """What the bodies of one site tell under the ensemble (see the module).

    Attributes
    ----------
    site : io.bodies_schema.Site
    ensemble : io.bodies_schema.Ensemble
    members : list of str
        Labels of the motions.
    bodies : list of BodyEstimate
        The bodies that rock (kept in the likelihood), in the file's order.
    excluded : list of (str, str)
        Name and reason of the bodies kept out (they slide).
    likelihood : ndarray, shape (J,)
        L(x_j); ``counted``: the members counted at each level.
    posterior : Posterior or None
    reason : str
        Why there is no posterior ('' when there is one).
    west_floor : float or None
        a_o of the most demanding overturned body [m/s^2].
    map : ConsistencyMap or None
    support : Support or None
        What carries the likelihood (None: no body rocks).
    failed_cells : int
    t_end : float
        Simulated time [s].
    datasets : list of str
        The datasets read, one per body that rocks.
    """

    site: object
    ensemble: object
    members: list
    bodies: list
    excluded: list
    likelihood: np.ndarray
    counted: np.ndarray
    posterior: Posterior
    reason: str
    west_floor: float
    map: ConsistencyMap
    support: Support
    failed_cells: int
    t_end: float
    datasets: list = field(default_factory=list)

    @property
    def quantiles(self):
        """The posterior's (pga, pgv) at the probabilities, or None when there is no
        posterior or too little :class:`Support` for percentiles."""
        if self.posterior is None or not self.support.sufficient:
            return None
        return self.posterior.pga, self.posterior.pgv


def _cells(ds, name):
    """A variable of a specimen's dataset as float (levels, members), NaN where failed."""
    values = ds[name].transpose("pga", ...).values.astype(float)
    return np.where(values < 0, np.nan, values)


def estimate_site(site, ensemble, datasets):
    """The probabilistic estimate of one site from the datasets of its specimens.

    Parameters
    ----------
    site : io.bodies_schema.Site
    ensemble : io.bodies_schema.Ensemble
    datasets : dict of str to xarray.Dataset
        {specimen key: dataset} (``site_studies.ensemble_datasets``), with dimensions
        ``pga`` and the members' (``record`` or ``seed``).

    Returns
    -------
    SiteEstimate
    """
    excluded, rocking = [], []
    for body in site.bodies:
        reason = sliding_reason(body, ensemble)
        if reason is None:
            rocking.append(body)
        else:
            excluded.append((body.name, reason))
    levels = np.asarray(ensemble.levels)
    common = {"site": site, "ensemble": ensemble, "members": member_labels(ensemble),
              "excluded": excluded, "t_end": simulated_time(ensemble)}
    if not rocking:
        return SiteEstimate(**common, bodies=[], likelihood=np.full(levels.size, np.nan),
                            counted=np.zeros(levels.size, int), posterior=None,
                            reason="no body that rocks: every body slides (mu < B/H)",
                            west_floor=None, map=None, support=None, failed_cells=0)
    keys = [specimen_key(specimen(b, ensemble)) for b in rocking]
    overturned = np.stack([_cells(datasets[k], "overturned") for k in keys])
    slid = np.stack([_cells(datasets[k], "slid") for k in keys])
    bodies = [body_estimate(b, ensemble, o, s) for b, o, s in zip(rocking, overturned, slid)]
    consistent = consistency(overturned, [b.overturned for b in rocking])
    mean, counted = likelihood(consistent)
    pgv = _cells(datasets[keys[0]], "pgv")
    pga = np.broadcast_to(levels[:, None], pgv.shape).copy()
    floor = max((b.west for b in bodies if b.overturned), default=None)
    post = posterior(levels, consistent, pgv, ensemble.probabilities, floor)
    reason = "" if post is not None else (
        "no member reproduces every observation at any level: the bodies seen contradict "
        "each other under this ensemble (or the levels miss the band where they agree)")
    return SiteEstimate(**common, bodies=bodies, likelihood=mean, counted=counted,
                        posterior=post, reason=reason, west_floor=floor,
                        support=support(levels, consistent),
                        map=consistency_map(levels, pga, pgv, consistent,
                                            ensemble.probabilities),
                        failed_cells=int(np.sum(~np.isfinite(overturned))),
                        datasets=[str(datasets[k].encoding.get("source", k)) for k in keys])
