"""Readers of accelerogram files, one module per format.

PEER ``.AT2`` (:mod:`.at2`), K-NET and KiK-net ASCII (:mod:`.knet`), COSMOS and CSMIP Volume 2
(:mod:`.cosmos`) and plain columns of numbers (:mod:`.columns`); :mod:`.base` holds the
:class:`~.base.Record` they return and the checks they share.
``sweep.io.records.read_record_file`` picks the reader."""
