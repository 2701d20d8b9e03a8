"""Ishiyama (1982): the closed-form criteria, the estimate of peak ground motion from
overturned bodies, and the classification of the rocking before an overturning."""
