"""Figures drawn from datasets (and histories) already computed: one module per figure family.

Nothing here simulates or sets a matplotlib backend; ``python -m sweep.plot`` chooses ``Agg``.
"""
