"""Ishiyama (1982): closed-form criteria, limits from overturned bodies, rocking and landing.

The closed-form criteria, the estimate of peak ground motion from overturned bodies, the
classification of the rocking before an overturning, and of what a body does after landing from
a translation jump."""
