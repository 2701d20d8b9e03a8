"""The package version, alone in a module at the bottom of ``sweep``.

The datasets' ``source`` and ``history`` attributes (``sweep.cf``,
``sweep.probability.fragility``) and the program's fingerprint (``sweep.runner.fingerprint``)
read it here, not from the package root, which stands above every layer.  Keep it equal to
``version`` in pyproject.toml."""
__version__ = "0.1.0"
