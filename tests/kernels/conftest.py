"""Make the helper module ``scenes`` (next to this file) importable by the kernel tests.

``naive`` lives in ``tests/`` (on the path through pyproject's ``pythonpath``); with
``--import-mode=importlib`` a test's own directory is not put on sys.path, so this does it.
"""
import sys
from pathlib import Path

_HERE = str(Path(__file__).resolve().parent)
if _HERE not in sys.path:
    sys.path.insert(0, _HERE)
