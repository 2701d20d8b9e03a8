"""The exit statuses of every command and the runner: the one table.

A status means the same whichever command ends with it (``python -m sweep.run``,
``sweep.scene``, ``sweep.plot``, ``sweep.estimate``, ``sweep.fragility``, ``sweep.figures``,
...; docs/runner.md, "Exit statuses")."""

EXIT_OK = 0  # done
EXIT_FAILED = 1  # the work failed (a study's run, a rank stopped), said in words
EXIT_BAD_INPUT = 2  # a bad file or argument, or a refused output: nothing was run
EXIT_INTERRUPTED = 130  # 128 + SIGINT, as a shell reports Ctrl-C
EXIT_BROKEN_PIPE = 141  # 128 + SIGPIPE: the reader of the output went away
